// A bake, the whole path from a probe to lights ready to render, with its accuracy measured. The steps, each
// in its own room:
//   placement.h      the probe divided into N regions by a method, a light each (the working grid, the cuts)
//   finish_lights.h  the sun angles and the irradiance refit
//   cut_choice.h     both cuts tried and the better kept
//   auto_count.h     the fewest lights that meet a tolerance
//   evaluate.h       the errors of the lights on the effects asked for
// bakeEvaluated runs them as AccuracyOptions ask. Shells fill a request (request.h) rather than call it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "probelights/auto_count.h"
#include "probelights/cut_choice.h"
#include "probelights/evaluate.h"
#include "probelights/finish_lights.h"
#include "probelights/placement.h"
#include "probelights/sources.h"
#include "probelights/sun_angles.h"

namespace probelights {

// One bake with the accuracy options the CLI and the add-on offer: `maxError` > 0 picks the count
// (autoCount), `refit` refits the lights' colours (up to kMaxRefitLights lights: a bake of more is made
// without it and says so in a note, whether the count was asked or chosen), and any of them (or `evaluate`)
// measures the errors on `effects`.
struct AccuracyOptions {
  Effects effects = kDiffuse;
  bool evaluate = false, refit = false;
  double maxError = 0;
  int evaluatorWidth = EvaluatorOptions{}.maxWidth;  // the add-on's quick estimate uses 512 (its preset)
  bool moveDirections = false;                       // the refit also moves directions (refit.h)
  // The lights' angles (sun_angles.h), fitted when shadows are evaluated, and the renderer's sun they are
  // judged and fitted as (cone.h).
  SunAngles sunAngles = SunAngles::Fit;
  SunProfile sunProfile = SunProfile::Cone;
  SunCones sunCones = SunCones::Free;  // how wide a cone may be (cone.h), fitted or not
  // Which cut's lights (CutChoice) when the bake's method is variance or median cut. Not with a tolerance.
  CutChoice cuts = CutChoice::One;
  FinishOptions finish() const { return {sunAngles, refit, moveDirections}; }  // how the lights are finished
};

struct EvaluatedBake {
  BakeResult bake;
  bool evaluated = false, autoCount = false, met = false, refit = false;
  Effects effects;
  EffectErrors errors;
  EffectErrors truthNorms;  // when evaluated: the probe's own response per effect (Evaluator::truthNorms)
  double energyShift = 0;   // of the refit
  SunAngles sunAngles = SunAngles::Spread;   // what the lights' angles are: fit only when they were fitted
  SunProfile sunProfile = SunProfile::Cone;  // the sun they were judged as
  SunCones sunCones = SunCones::Free;        // how wide their cones could be
  int count = 0;  // the light count asked for, or chosen when autoCount (bake.lights may hold fewer)
  Method cut = Method::Variance;              // the method the lights were cut with (the one kept)
  std::vector<std::pair<int, double>> tried;  // autoCount: (count, worst error) of every count tried
  // The lamps took the probe's sources alone (request.h: sources): the residual the world keeps, and the
  // split's level and share; the errors are then those of the lamps plus the residual against the probe.
  std::optional<SourceSplit> sources;
};

// `grid`: the probe's working grid for these options if the caller has built it.
EvaluatedBake bakeEvaluated(const Probe& probe, BakeOptions options, AccuracyOptions accuracy,
                            const WorkingGrid* grid = nullptr);

// bakeEvaluated on a caller's buffer (Probe(view, projection, nonFinite)), its pixels checked in the working
// grid's pass rather than a pass of their own (Probe::unchecked: a second read of the whole buffer): the same
// lights, notes and errors, the same Error for NaN/Inf before any light is made.
// `probe` receives the probe (its report's notes), set also when the check refuses it.
EvaluatedBake bakeBuffer(ImageView view, ProjectionKind projection, NonFinitePolicy nonFinite,
                         const BakeOptions& options, const AccuracyOptions& accuracy,
                         std::optional<Probe>& probe);

// Whether bakeEvaluated needs nothing of the probe but its working grid: a grid method, and no evaluation,
// refit or tolerance. Then a file can be read band by band into the grid (grid_load.h) and baked with
// bakeOnGrid, never holding the image whole.
bool bakesOnGridAlone(const BakeOptions& options, const AccuracyOptions& accuracy);

// bakeEvaluated for such a bake, on the grid loadGrid built (tablesMs: its build time, within the load).
EvaluatedBake bakeOnGrid(const Probe& probe, const MomentTable& table, double tablesMs,
                         const BakeOptions& options, SunAngles angles, SunCones cones = SunCones::Free);

}  // namespace probelights
