// probelights evaluate PROBE LIGHTS.json [options]: the errors of any lights against the probe (a bake's
// JSON, or anybody's lights in its layout), judged as the module's evaluate() judges them (request.h's
// table).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>

#include "commands.h"
#include "options.h"
#include "probelights/image_file.h"
#include "write_whole.h"

namespace probelights::cli {

namespace {

// A number array of `n` items at `key` of a light, or an Error naming the light and the file.
std::vector<double> numbers(const nlohmann::json& light, const char* key, std::size_t n,
                            const std::string& which) {
  const auto it = light.find(key);
  if (it == light.end() || !it->is_array() || it->size() != n)
    throw Error(which + " has no " + key + " of " + std::to_string(n) + " numbers");
  std::vector<double> out;
  for (const auto& v : *it) {
    if (!v.is_number()) throw Error(which + " has a " + key + " that is not numbers");
    out.push_back(v.get<double>());
  }
  return out;
}

// The lights of a bake's JSON ({"lights": [{"direction": [x, y, z], "rgb": [r, g, b], "angle": a}, ...]}, the
// angle optional), or of a bare list of them.
std::vector<Light> readLights(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read '" + path + "': " + std::strerror(errno));
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    throw Error("'" + path + "' is not JSON: give a bake's JSON (probelights bake PROBE -o lights.json)");
  }
  const nlohmann::json* list = doc.is_array() ? &doc : nullptr;
  if (doc.is_object() && doc.contains("lights") && doc["lights"].is_array()) list = &doc["lights"];
  if (!list)
    throw Error("'" + path +
                "' holds no lights: give a bake's JSON, {\"lights\": [{\"direction\": [x, y, z], "
                "\"rgb\": [r, g, b], \"angle\": radians}, ...]}");
  std::vector<Light> lights;
  for (std::size_t i = 0; i < list->size(); ++i) {
    const nlohmann::json& l = (*list)[i];
    const std::string which = "light " + std::to_string(i) + " of '" + path + "'";
    if (!l.is_object()) throw Error(which + " is not an object with direction and rgb");
    Light light;
    const auto d = numbers(l, "direction", 3, which), c = numbers(l, "rgb", 3, which);
    light.direction = {d[0], d[1], d[2]};
    light.rgb = {c[0], c[1], c[2]};
    if (l.contains("angle")) {
      if (!l["angle"].is_number()) throw Error(which + " has an angle that is not a number");
      light.angle = l["angle"].get<double>();
    }
    lights.push_back(light);
  }
  return lights;
}

}  // namespace

std::string evaluateOptionsUsage() { return tableUsage(evaluateOptions(), EvaluateRequest{}); }

int evaluateCommand(const std::vector<std::string>& argv) {
  EvaluateRequest request;
  TableOptions<EvaluateRequest> given(evaluateOptions());
  std::vector<Option> table;
  given.addTo(table);
  std::string output;
  table.push_back({{"--projection"}, [&](const std::string& v) {
                     request.judging.probe.projection = parseProjectionChoice(v);
                   }});
  table.push_back({{"-o", "--output"}, [&](const std::string& v) { output = nonEmpty("-o", v); }});
  const std::vector<std::string> positional = parseOptions(argv, table);
  if (positional.size() != 2)
    throw UsageError("evaluate takes a probe and its lights: probelights evaluate PROBE LIGHTS.json");
  given.apply(request);
  const std::string& probePath = positional[0];
  refuseOverwritingProbe(probePath, {output});
  if (output == positional[1] || sameFile(output, positional[1]))
    throw UsageError("'" + output + "' is the lights' file: write the errors elsewhere");
  const std::vector<Light> lights = readLights(positional[1]);
  const Probe probe = loadProbe(probePath, request.judging.probe);
  const EffectErrors errors = evaluateGiven(probe, lights, request);
  const Effects effects = request.judging.accuracy.effects;
  // The module's dict: {effect: error}, the effects asked for.
  const std::vector<std::tuple<Effect, const char*, double>> asked{{kDiffuse, "diffuse", errors.diffuse},
                                                                   {kShadow, "shadow", errors.shadow},
                                                                   {kGlossy, "glossy", errors.glossy}};
  nlohmann::json doc = nlohmann::json::object();
  for (const auto& [bit, name, value] : asked)
    if (effects & bit) doc[name] = value;
  if (!output.empty()) writeJson(doc, output, 2);
  if (output != "-") {
    std::printf("probe      %s  %dx%d %s\n", probePath.c_str(), probe.width(), probe.height(),
                toString(probe.projection().kind()).c_str());
    for (const auto& note : probe.report().notes) std::printf("note       %s\n", note.line().c_str());
    std::printf("lights     %zu from %s\nerror      ", lights.size(), positional[1].c_str());
    for (const auto& [bit, name, value] : asked)
      if (effects & bit) std::printf("%s %.2f%%  ", name, 100 * value);
    std::printf("(relative RMS of luminance vs the probe)\n");
  }
  return 0;
}

}  // namespace probelights::cli
