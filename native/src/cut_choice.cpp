#include "probelights/cut_choice.h"

#include <cstdio>
#include <utility>
#include <vector>

#include "probelights/finish_lights.h"
#include "probelights/names.h"

namespace probelights {

namespace {
constexpr NameTable<CutChoice, 3> kCutChoices{
    {{CutChoice::One, "one"}, {CutChoice::Both, "both"}, {CutChoice::Auto, "auto"}}};
}  // namespace

std::string toString(CutChoice cuts) { return std::string(nameOf(kCutChoices, cuts)); }

std::vector<MethodChoice> methodMenu() {
  std::vector<MethodChoice> menu{
      {"auto", "Auto",
       "Variance minimization and median cut: at " + std::to_string(kBothFinishedUpTo) +
           " lights or fewer each fitted and the lights that fit the world's light better kept; above, each "
           "started and the better fitted alone"},
      {"both", "Both cuts",
       "Variance minimization and median cut, each fitted, and the lights that fit the world's light better "
       "kept (a second fit: slower)"}};
  for (const PlacementMethod& m : placementMethods()) {
    std::string label = m.label;
    if (!label.empty() && label[0] >= 'a' && label[0] <= 'z')
      label[0] = static_cast<char>(label[0] - 'a' + 'A');
    menu.push_back({m.name, label, m.help});
  }
  return menu;
}
CutChoice parseCutChoice(const std::string& name) { return parseName(kCutChoices, "cuts", name); }

ChosenCut chooseCut(const Probe& probe, const WorkingGrid& grid, const Evaluator& evaluator,
                    const BakeOptions& options, BakeResult first, CutChoice cuts,
                    const FinishOptions& finish) {
  BakeOptions other = options;
  other.method = options.method == Method::Variance ? Method::MedianCut : Method::Variance;
  BakeResult second = grid.bake(probe, other);
  const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
  const bool finishBoth = cuts == CutChoice::Both || !finish.refits(first.lights.size()) ||
                          first.lights.size() <= kBothFinishedUpTo;
  double shifts[2] = {0, 0}, errors[2];
  std::vector<Light>* lights[2] = {&first.lights, &second.lights};
  if (finishBoth) {
    for (int c = 0; c < 2; ++c) {
      *lights[c] = finishLights(evaluator, std::move(*lights[c]), finish, &shifts[c]);
      errors[c] = evaluator.fitError(receivers, *lights[c]);
    }
  } else {
    // Each started (finishLights' first step, the angles) and judged with its colours solved for them (the
    // solve alone: placing dark lights too picked worse at 64 suns).
    bool fitted[2];
    for (int c = 0; c < 2; ++c) {
      fitted[c] = applySunAngles(finish.angles, &evaluator, *lights[c], true);
      std::vector<Light> judged = *lights[c];
      solveColours(evaluator, receivers, judged);
      errors[c] = evaluator.fitError(receivers, judged);
    }
    const int keep = errors[1] < errors[0] ? 1 : 0;
    *lights[keep] = finishAngled(evaluator, std::move(*lights[keep]), fitted[keep], finish, &shifts[keep]);
  }
  const bool swap = errors[1] < errors[0];
  const Method kept = swap ? other.method : options.method, left = swap ? options.method : other.method;
  char detail[160];
  std::snprintf(detail, sizeof detail,
                finishBoth ? "fit error %.4g against %s's %.4g"
                           : "and finished; fit error with colours solved %.4g against %s's %.4g",
                errors[swap ? 1 : 0], toString(left).c_str(), errors[swap ? 0 : 1]);
  const Note note{
      NoteKind::Chosen,
      std::string(finishBoth ? "both cuts fitted: " : "both cuts started: ") + toString(kept) + " kept",
      detail};
  ChosenCut out;
  out.energyShift = shifts[swap ? 1 : 0];
  out.cut = kept;
  if (swap) {
    second.timings.tablesMs = first.timings.tablesMs;
    out.bake = std::move(second);
  } else {
    out.bake = std::move(first);
  }
  out.bake.notes.push_back(note);
  return out;
}

}  // namespace probelights
