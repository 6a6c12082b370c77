// probelights sh and probelights sample: the probe's SH coefficients, and samples of its SH importance
// sampler (Jarosz et al. 2009 warping, Berger 2011 epsilon clamping). Usage in main.cpp.
#include "commands.h"
#include "json_output.h"
#include "options.h"
#include "probelights/image_file.h"
#include "probelights/sh_request.h"

namespace probelights::cli {

namespace {

constexpr const char* kConvention =
    "real SH, index l(l+1)+m, orthonormal, Condon-Shortley phase (Sloan 2008); theta from +Z, phi = atan2(y, "
    "x)";

// A command of a table (sh_request.h): its options, --projection and -o; the probe, loaded as they say.
template <class Request>
struct Asked {
  Request request;
  std::string probe, output = "-";
};

template <class Request>
Asked<Request> parseAsked(const std::vector<std::string>& argv,
                          const std::vector<TableOption<Request>>& options, const std::string& command) {
  Asked<Request> a;
  TableOptions<Request> given(options);
  std::vector<Option> table;
  given.addTo(table);
  table.push_back({{"--projection"},
                   [&](const std::string& v) { a.request.probe.projection = parseProjectionChoice(v); }});
  table.push_back({{"-o", "--output"}, [&](const std::string& v) { a.output = nonEmpty("-o", v); }});
  a.probe = oneProbe(parseOptions(argv, table), command);
  given.apply(a.request);
  refuseOverwritingProbe(a.probe, {a.output});
  return a;
}

}  // namespace

std::string shOptionsUsage() { return tableUsage(shOptions(), ShRequest{}); }
std::string sampleOptionsUsage() { return tableUsage(sampleOptions(), SampleRequest{}); }

int shCommand(const std::vector<std::string>& argv) {
  const auto a = parseAsked(argv, shOptions(), "sh");
  const ShRequest& r = a.request;
  requireBands(r.bands);  // before the probe is read
  const Probe probe = loadProbe(a.probe, r.probe);
  const ShCoefficients sh = shProject(probe, r);
  nlohmann::json c = nlohmann::json::array();
  for (const Rgb& v : sh.c) c.push_back(v);
  writeJson({{"source", sourceToJson(a.probe, probe)},
             {"bands", r.bands},
             {"convention", kConvention},
             {"quantity", r.irradiance ? "irradiance" : "radiance"},
             {"window", toString(r.window)},
             {"coefficients", c}},
            a.output);
  return 0;
}

int sampleCommand(const std::vector<std::string>& argv) {
  const auto a = parseAsked(argv, sampleOptions(), "sample");
  const SampleRequest& r = a.request;
  requireBands(r.bands);
  const Probe probe = loadProbe(a.probe, r.probe);
  nlohmann::json dirs = nlohmann::json::array(), pdfs = nlohmann::json::array();
  for (const auto& s : shSamples(probe, r)) {
    dirs.push_back({s.direction.x, s.direction.y, s.direction.z});
    pdfs.push_back(s.pdf);
  }
  writeJson({{"source", sourceToJson(a.probe, probe)},
             {"bands", r.bands},
             {"epsilon", r.epsilon},
             {"depth", r.depth},
             {"seed", r.seed},
             {"convention", kConvention},
             {"directions", dirs},
             {"pdf", pdfs}},
            a.output);
  return 0;
}

}  // namespace probelights::cli
