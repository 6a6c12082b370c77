#include "json_output.h"

namespace probelights::cli {

nlohmann::json bakeToJson(const std::string& sourcePath, const Probe& probe, const BakeOptions& options,
                          const BakeResult& result, double loadMs, const Evaluation& ev) {
  using nlohmann::json;
  json lights = json::array();
  for (const Light& l : result.lights) {
    lights.push_back({{"direction", {l.direction.x, l.direction.y, l.direction.z}},
                      {"rgb", l.rgb},
                      {"solid_angle", l.solidAngle},
                      {"angular_radius", l.angularRadius},
                      {"rect", {l.rect.x0, l.rect.y0, l.rect.x1, l.rect.y1}},
                      {"energy_share", l.energyShare}});
  }
  std::vector<std::string> notes = probe.report().notes;
  notes.insert(notes.end(), result.notes.begin(), result.notes.end());
  nlohmann::json evaluation = nullptr;
  if (ev.done) {
    evaluation = {{"effects", effectsToString(ev.effects)},
                  {"refit", ev.refit},
                  {"error", "relative RMS of luminance vs the probe"}};
    if (ev.effects & kDiffuse) evaluation["diffuse"] = ev.errors.diffuse;
    if (ev.effects & kShadow) evaluation["shadow"] = ev.errors.shadow;
    if (ev.effects & kGlossy) evaluation["glossy"] = ev.errors.glossy;
    if (ev.refit && !ev.autoCount) evaluation["energy_shift"] = ev.energyShift;
    if (ev.autoCount) {
      json tried = json::array();
      for (auto [n, e] : ev.tried) tried.push_back({{"lights", n}, {"worst_error", e}});
      evaluation["auto_count"] = {{"met", ev.met}, {"lights", options.lights}, {"tried", tried}};
    }
  }
  return {
      {"evaluation", evaluation},
      {"source",
       {{"path", sourcePath},
        {"width", probe.width()},
        {"height", probe.height()},
        {"projection", toString(probe.projection().kind())},
        {"negative_samples", probe.report().negativeSamples},
        {"non_finite_samples", probe.report().nonFiniteSamples}}},
      {"method", toString(options.method)},
      {"sh", options.method == Method::SphericalHarmonics ? nlohmann::json{{"bands", options.shBands},
                                                                           {"epsilon", options.shEpsilon},
                                                                           {"depth", options.shDepth}}
                                                          : nlohmann::json(nullptr)},
      {"centroid", options.centroid == CentroidWeight::Energy ? "energy" : "energy2"},
      {"requested_lights", options.lights},
      {"horizon_split", result.horizonSplit},
      {"working_resolution", {{"setting", options.resolution.toString()}, {"cell_size", result.cellSize}}},
      {"lights", lights},
      {"total_rgb", result.totalRgb},
      {"timings_ms",
       {{"load", loadMs},
        {"tables", result.timings.tablesMs},
        {"partition", result.timings.partitionMs},
        {"lights", result.timings.lightsMs}}},
      {"notes", notes},
  };
}

}  // namespace probelights::cli
