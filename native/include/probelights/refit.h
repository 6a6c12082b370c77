// Refitting baked lights to the probe's diffuse light: colours by non-negative least squares, and optionally
// directions by coordinate descent (used by bakeEvaluated, accuracy.h, and the tradeoff grid).
#pragma once

#include <vector>

#include "probelights/evaluate.h"
#include "probelights/lights.h"

namespace probelights {

// Irradiance-exact intensities: keeps each light's direction and re-solves its non-negative colour, per
// channel, by non-negative least squares (Lawson & Hanson 1974) so the lights' diffuse irradiance matches the
// probe's on the evaluator's fit receivers: its 1024 fit normals and, with shadows, its 1024 refit ground
// points (Evaluator::fitReceivers(true)). Returns the refit lights; `energyShift` (if given) gets
// sum(new) / sum(old) - 1. At most kMaxRefitLights lights (the active-set solve grows with the cube of the
// count; beyond it the plain lights are already within a fraction of a percent).
inline constexpr std::size_t kMaxRefitLights = 256;
// moveDirections: also moves each light's direction (coordinate descent: steps of 4, 2, 1 and 0.5 degrees
// along two tangent axes, kept when the fit improves; three rounds, each followed by the NNLS colours).
// Measured at 16 lights on studiolights: diffuse error 1.8 -> 1.3 % (city), 2.3 -> 1.5 % (sunset), 3.0 -> 1.9
// % (Kerner), shadows unchanged or better.
std::vector<Light> refitIrradiance(const Evaluator& evaluator, const std::vector<Light>& lights,
                                   double* energyShift = nullptr, bool moveDirections = false);

}  // namespace probelights
