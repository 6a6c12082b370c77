// The auto count: the fewest lights whose errors meet a tolerance (bake.h runs it for `maxError`).
#pragma once

#include <utility>
#include <vector>

#include "probelights/evaluate.h"
#include "probelights/finish_lights.h"
#include "probelights/placement.h"

namespace probelights {

struct AutoCountResult {
  BakeResult bake;
  EffectErrors errors;
  int lights = 0;
  // false: no count tried met the tolerance; then the one with the lowest error (fewest on a tie)
  bool met = false;
  std::vector<std::pair<int, double>> tried;  // (lights, worst error)
};

// The smallest N (doubling, then bisecting) whose worst error over the evaluator's effects is <= tolerance,
// up to maxLights; each candidate is finished first (finishLights: its angles, its refit if asked). When
// none meets it: the count with the lowest error tried (the doubling stops two doublings past it without
// improvement), so a miss never costs more lights than a count that did better. `grid`: the probe's working
// grid for these options if the caller has built it, else autoCount builds it.
AutoCountResult autoCount(const Probe& probe, const Evaluator& evaluator, BakeOptions options,
                          double tolerance, const FinishOptions& finish = {}, int maxLights = 1024,
                          const WorkingGrid* grid = nullptr);

}  // namespace probelights
