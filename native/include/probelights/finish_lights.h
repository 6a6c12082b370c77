// A bake's lights made ready to render and be judged: the sun angles (sun_angles.h) and the irradiance refit
// (refit.h). The step of a bake (bake.h) after placement (placement.h).
#pragma once

#include <vector>

#include "probelights/evaluate.h"
#include "probelights/lights.h"
#include "probelights/refit.h"
#include "probelights/sun_angles.h"

namespace probelights {

// How a bake's lights are finished: their sun angles (sun_angles.h), then the irradiance refit (refit.h).
struct FinishOptions {
  SunAngles angles = SunAngles::Spread;
  bool refit = false;           // up to kMaxRefitLights lights: more are finished without it
  bool moveDirections = false;  // the refit also moves the lights' directions
  bool keepEnergy = false;      // the refit holds the lights' sum per channel (RefitOptions)
  int moveRounds = 0;           // RefitOptions
  // Rounds of the angle fit after the moves (fitSunAngles), which starts from the angles fitted before them.
  int refitAngleRounds = 2;
  // Whether `lights` lights are refit: the one rule of the refit's limit (a bake says so in a note).
  bool refits(std::size_t lights) const { return refit && lights <= kMaxRefitLights; }
  RefitOptions refitOptions() const { return {moveDirections, keepEnergy, moveRounds}; }
};

// The sun angles, then the refit (colours, and directions if asked); with both, the colours are solved again
// for the fitted angles. `energyShift` (if given): the lights' total rgb after / before - 1.
std::vector<Light> finishLights(const Evaluator& evaluator, std::vector<Light> lights,
                                const FinishOptions& finish, double* energyShift = nullptr);

// finishLights after its first step, the angles (applySunAngles; `fitted`: what it returned), for a caller
// that judged the angled lights before finishing them (cut_choice.h).
std::vector<Light> finishAngled(const Evaluator& evaluator, std::vector<Light> lights, bool fitted,
                                const FinishOptions& finish, double* energyShift);

}  // namespace probelights
