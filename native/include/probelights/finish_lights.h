// A bake's lights made ready to render and be judged: the sun angles (sun_angles.h) and the irradiance refit
// (refit.h). The step of a bake (bake.h) after placement (placement.h).
#pragma once

#include <vector>

#include "probelights/evaluate.h"
#include "probelights/lights.h"
#include "probelights/refit.h"
#include "probelights/sun_angles.h"

namespace probelights {

// The refit (colours, and directions if asked) and the sun angles; with both, the colours are solved again
// for the fitted angles. `energyShift` (if given): the lights' total rgb after / before - 1.
std::vector<Light> finishLights(const Evaluator& evaluator, std::vector<Light> lights, bool refit,
                                bool moveDirections, SunAngles angles, double* energyShift = nullptr);

// finishLights after its first step, the angles (applySunAngles; `fitted`: what it returned), for a caller
// that judged the angled lights before finishing them (cut_choice.h).
std::vector<Light> finishAngled(const Evaluator& evaluator, std::vector<Light> lights, bool fitted,
                                bool refit, bool moveDirections, SunAngles angles, double* energyShift);

}  // namespace probelights
