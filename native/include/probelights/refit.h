// Refitting baked lights to the probe's diffuse light: colours by non-negative least squares, and optionally
// directions by coordinate descent (used by finishLights, finish_lights.h, and the tradeoff grid).
#pragma once

#include <vector>

#include "probelights/evaluate.h"
#include "probelights/lights.h"

namespace probelights {

// Irradiance-exact intensities: keeps each light's direction and re-solves its non-negative colour, per
// channel, by non-negative least squares (Lawson & Hanson 1974) so the lights' diffuse irradiance matches the
// probe's on the evaluator's fit receivers: its fit normals (1024 unless asked) and, with shadows, its 1024
// refit ground points (Evaluator::fitReceivers(true)). Returns the refit lights; `energyShift` (if given)
// gets sum(new) / sum(old) - 1. At most kMaxRefitLights lights (the active-set solve grows with the cube of
// the count; beyond it the plain lights are already within a fraction of a percent). A light the solve
// leaves dark is placed anew (placeDarkLights) and the colours solved again; its rect stays the region it
// was made from.
inline constexpr std::size_t kMaxRefitLights = 256;
// How the refit goes beyond the colours.
struct RefitOptions {
  // Also moves each light's direction (coordinate descent: steps of 4, 2, 1 and 0.5 degrees along two
  // tangent axes, kept when the fit improves; three rounds up to 16 lights, two above, each followed by the
  // NNLS colours): lower diffuse error at few lights, shadows unchanged or better (docs/results/shadows.md).
  bool moveDirections = false;
  // Holds the lights' sum per channel (each channel's sum of rgb, the probe's integral for cut lights) where
  // it is positive: the colours solved with that sum weighted far above the receivers, then scaled to it
  // exactly. The fit then cannot trade energy for its receivers (energyShift is rounding).
  bool keepEnergy = false;
  // Rounds of moves; 0: three up to kThreeMoveRoundsUpTo lights, two above (the single bake's rule).
  int moveRounds = 0;
};
// Up to this many lights the refit's moves take three rounds, above it two: with many suns a third round
// changes the errors by nothing measurable and costs time; with few it still lowers them (docs/decisions.md).
inline constexpr std::size_t kThreeMoveRoundsUpTo = 16;
std::vector<Light> refitIrradiance(const Evaluator& evaluator, const std::vector<Light>& lights,
                                   double* energyShift = nullptr, const RefitOptions& options = {});

// The colour solve alone (refitIrradiance's first step): each light's non-negative colour, per channel, so
// the lights as they are fit `receivers` best; no light is placed anew. With `total`: each channel's sum
// held to it where it is positive (RefitOptions::keepEnergy).
void solveColours(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
                  std::vector<Light>& lights, const Rgb* total = nullptr);

// Lights the colour solve left dark (luminance 0: their region's light is better carried by their
// neighbours, as on a few probes here) are placed anew where the fit
// wants light most: each in turn at the candidate direction (the probe's 256 brightest samples and the
// evaluator's 256 evenly spread normals) whose point kernel k best explains the remaining residual r on the
// receivers, i.e. the largest (k . r)^2 / (k . k) with k . r > 0 (weights as the fit's), as a point (angle 0:
// the angle fit, if any, comes after). refitIrradiance solves the colours again after; that can only lower
// the fit's error (the old colours, the moved lights' zero, are still a solution). Returns whether any light
// moved. Probes with no dark light are unchanged.
bool placeDarkLights(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
                     std::vector<Light>& lights);

}  // namespace probelights
