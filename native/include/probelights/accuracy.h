// A bake with its accuracy measured: the errors of the lights on the effects asked for, the irradiance refit,
// and the auto count (the fewest lights that meet a tolerance). What the CLI's bake and the add-on run.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "probelights/bake.h"
#include "probelights/evaluate.h"
#include "probelights/refit.h"
#include "probelights/sun_angles.h"

namespace probelights {

// A bake's lights made ready to render and be judged: the refit (colours, and directions if asked; refit.h)
// and the sun angles (sun_angles.h); with both, the colours are solved again for the fitted angles.
// `energyShift` (if given): the lights' total rgb after / before - 1.
std::vector<Light> finishLights(const Evaluator& evaluator, std::vector<Light> lights, bool refit,
                                bool moveDirections, SunAngles angles, double* energyShift = nullptr);

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

// Whose lights a bake keeps. Neither cut wins everywhere (median cut fits a third of the probes here better),
// so both can be tried, each judged by how its diffuse light and shadows fit the probe
// (Evaluator::fitError on the fit receivers, not the points the errors are measured on):
// - one: the bake's method's lights.
// - both: the lights of variance minimization and of median cut each made ready (finishLights) and the
//   better kept (the pick agrees with the lower estimated shadow error on most probes: docs/cli.md). Costs a
//   second finishLights.
// - auto: both up to kBothFinishedUpTo lights (or without the refit, where finishing is only the angles);
//   above, both cuts are started (their angles fitted, finishLights' first step, and their colours solved:
//   solveColours) and only the better is finished: most of both's gain for a fraction of its cost
//   (docs/cli.md, "Methods and knobs").
// The kept lights are those that cut alone, finished as finishLights finishes them, gives (the same bits).
enum class CutChoice { One, Both, Auto };
inline constexpr std::size_t kBothFinishedUpTo = 16;
std::string toString(CutChoice cuts);
CutChoice parseCutChoice(const std::string& name);  // throws Error naming the choices

// One bake with the accuracy options the CLI and the add-on offer: `maxError` > 0 picks the count
// (autoCount), `refit` refits the lights' colours, and any of them (or `evaluate`) measures the errors on
// `effects`.
struct AccuracyOptions {
  Effects effects = kDiffuse;
  bool evaluate = false, refit = false;
  double maxError = 0;
  int evaluatorWidth = 2048;    // EvaluatorOptions::maxWidth (the add-on's quick estimate uses 512)
  bool moveDirections = false;  // the refit also moves directions (refit.h)
  // The lights' angles (sun_angles.h), fitted when shadows are evaluated, and the renderer's sun they are
  // judged and fitted as (cone.h).
  SunAngles sunAngles = SunAngles::Fit;
  SunProfile sunProfile = SunProfile::Cone;
  // Which cut's lights (CutChoice) when the bake's method is variance or median cut. Not with a tolerance.
  CutChoice cuts = CutChoice::One;
};

struct EvaluatedBake {
  BakeResult bake;
  bool evaluated = false, autoCount = false, met = false, refit = false;
  Effects effects;
  EffectErrors errors;
  double energyShift = 0;                    // of the refit
  SunAngles sunAngles = SunAngles::Spread;   // what the lights' angles are: fit only when they were fitted
  SunProfile sunProfile = SunProfile::Cone;  // the sun they were judged as
  int count = 0;  // the light count asked for, or chosen when autoCount (bake.lights may hold fewer)
  Method cut = Method::Variance;              // the method the lights were cut with (the one kept)
  std::vector<std::pair<int, double>> tried;  // autoCount: (count, worst error) of every count tried
};

// `grid`: the probe's working grid for these options if the caller has built it.
EvaluatedBake bakeEvaluated(const Probe& probe, BakeOptions options, AccuracyOptions accuracy,
                            const WorkingGrid* grid = nullptr);

// bakeEvaluated on a caller's buffer (Probe(view, projection, nonFinite)), its pixels checked in the working
// grid's pass rather than a pass of their own (Probe::unchecked; at 8K the own pass read 537 MB of Blender's
// RGBA again): the same lights, notes and errors, the same Error for NaN/Inf before any light is made.
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
                         const BakeOptions& options, SunAngles angles);

}  // namespace probelights
