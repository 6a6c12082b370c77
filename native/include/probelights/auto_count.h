// The auto count: the fewest lights whose errors meet a tolerance (bake.h runs it for `maxError`).
#pragma once

#include <utility>
#include <vector>

#include "probelights/evaluate.h"
#include "probelights/placement.h"
#include "probelights/sun_angles.h"

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
// up to maxLights; with refit, each candidate is refit first. When none meets it: the count with the lowest
// error tried (the doubling stops two doublings past it without improvement), so a miss never costs more
// lights than a count that did better. `grid`: the probe's working grid for these options if the caller has
// built it, else autoCount builds it.
// `angles`: each candidate's sun angles (sun_angles.h) before it is evaluated.
AutoCountResult autoCount(const Probe& probe, const Evaluator& evaluator, BakeOptions options,
                          double tolerance, bool refit, int maxLights = 1024, bool moveDirections = false,
                          const WorkingGrid* grid = nullptr, SunAngles angles = SunAngles::Spread);

}  // namespace probelights
