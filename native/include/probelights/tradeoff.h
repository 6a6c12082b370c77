// What accuracy costs in time: bakes over a grid of knobs (methods x light counts x working resolutions x
// with and without the irradiance refit), each evaluated on the effects asked for.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "probelights/bake.h"
#include "probelights/evaluate.h"
#include "probelights/placement.h"

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
  std::vector<WorkingResolution> resolutions{{WorkingResolution::Mode::Full, 0},
                                             {WorkingResolution::Mode::Width, 256}};
  bool refit = true;  // also evaluate each bake refit, colours and directions (counts up to kMaxRefitLights)
  SunAngles sunAngles = SunAngles::Fit;  // every row's lights get these angles before they are evaluated
};

std::vector<TradeoffRow> tradeoff(const Probe& probe, const Evaluator& evaluator,
                                  const TradeoffOptions& options);

}  // namespace probelights
