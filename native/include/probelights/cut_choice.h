// Whose lights a bake keeps when both cuts are tried (bake.h runs it for AccuracyOptions::cuts).
#pragma once

#include <cstddef>
#include <string>

#include "probelights/evaluate.h"
#include "probelights/finish_lights.h"
#include "probelights/placement.h"

namespace probelights {

// Neither cut wins everywhere (median cut fits a third of the probes here better), so both can be tried,
// each judged by how its diffuse light and shadows fit the probe (Evaluator::fitError on the fit receivers,
// not the points the errors are measured on):
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

// The choices a menu of methods offers (the Blender add-on's, which lists them from this): the cut choices
// that try both cuts (auto, both), then every registered method (placement.h), each a name as the options
// take it, a label and what it does in one line.
struct MethodChoice {
  std::string name, label, help;
};
std::vector<MethodChoice> methodMenu();

// The cut kept of a CutChoice other than one: its lights finished, a note saying which and why.
struct ChosenCut {
  BakeResult bake;
  Method cut = Method::Variance;
  double energyShift = 0;  // of its refit (finishLights)
};

// `first`: the lights of options.method (variance or median cut) as cut on `grid`; the other cut's are cut on
// the same grid, and the better of the two kept. Finishing as finishLights with `refit`, `moveDirections`
// and `angles`.
ChosenCut chooseCut(const Probe& probe, const WorkingGrid& grid, const Evaluator& evaluator,
                    const BakeOptions& options, BakeResult first, CutChoice cuts,
                    const FinishOptions& finish);

}  // namespace probelights
