// What accuracy costs in time: bakes over a grid of knobs (methods x light counts x working resolutions x
// with and without the irradiance refit), each evaluated on the effects asked for.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "probelights/bake.h"
#include "probelights/evaluate.h"
#include "probelights/placement.h"
#include "probelights/request.h"

namespace probelights {

struct TradeoffRow {
  Method method;
  int lights = 0;                               // asked for
  int made = 0;                                 // made
  std::optional<WorkingResolution> resolution;  // none for a method that cuts no working grid (sh)
  bool refit = false;
  double bakeMs = 0;  // tables + partition + lights (+ refit)
  EffectErrors errors;
};

struct TradeoffOptions {
  std::vector<Method> methods = everyMethod();
  std::vector<int> counts{1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024};
  CentroidWeight centroid = CentroidWeight::Energy;  // where each row's lights stand in their regions
  std::vector<WorkingResolution> resolutions{{WorkingResolution::Mode::Full, 0},
                                             {WorkingResolution::Mode::Width, 256}};
  bool refit = true;  // also evaluate each bake refit, colours and directions (counts up to kMaxRefitLights)
  SunAngles sunAngles = SunAngles::Fit;  // every row's lights get these angles before they are evaluated
};

std::vector<TradeoffRow> tradeoff(const Probe& probe, const Evaluator& evaluator,
                                  const TradeoffOptions& options);

// A tradeoff as every shell asks for it (the CLI's tradeoff, the module's tradeoff()), filled by the names
// of tradeoffOptions(): the grid (counts, methods, resolutions) and, in `judging`, how each row's lights are
// made and judged, by the bake request's options (request.h) of the same names: preset, effects, refit,
// evaluator_width, centroid, sun_angles, sun_profile, sun_cones, nonfinite. So `preset` makes each row as
// that recipe's bake would (the Blender add-on's tradeoff asks for its bake's preset).
BakeRequest tradeoffJudging();  // the bake's defaults but effects diffuse and shadow, refit on
struct TradeoffRequest {
  TradeoffOptions grid;
  BakeRequest judging = tradeoffJudging();
};
using TradeoffOption = TableOption<TradeoffRequest>;
const std::vector<TradeoffOption>& tradeoffOptions();
const TradeoffOption& tradeoffOption(const std::string& name);

// The tradeoff a request asks for: its evaluator built on the probe, then every row. `evaluatorMs`, when
// given, receives the time the evaluator's truths took.
std::vector<TradeoffRow> tradeoff(const Probe& probe, const TradeoffRequest& request,
                                  double* evaluatorMs = nullptr);

}  // namespace probelights
