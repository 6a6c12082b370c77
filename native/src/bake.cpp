#include "probelights/bake.h"

#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "probelights/error.h"

namespace probelights {

bool bakesOnGridAlone(const BakeOptions& options, const AccuracyOptions& a) {
  return usesWorkingGrid(options.method) && !a.evaluate && !a.refit && !(a.maxError > 0) &&
         a.cuts == CutChoice::One;
}

EvaluatedBake bakeOnGrid(const Probe& probe, const MomentTable& table, double tablesMs,
                         const BakeOptions& options, SunAngles angles, SunCones cones) {
  EvaluatedBake out;
  out.cut = options.method;
  out.bake = bake(probe, table, options);
  applySunAngles(angles, nullptr, out.bake.lights);
  keepSunCones(cones, out.bake.lights);
  out.sunCones = cones;
  out.sunAngles = angles == SunAngles::Points ? SunAngles::Points : SunAngles::Spread;
  out.bake.timings.tablesMs = tablesMs;
  out.count = options.lights;
  if (!probe.hasPixels())
    out.bake.notes.insert(out.bake.notes.begin(),
                          {NoteKind::Reading,
                           "read band by band into a working grid of " + std::to_string(table.width()) + "x" +
                               std::to_string(table.height()) + " cells, never whole",
                           "tables built during the load"});
  return out;
}

namespace {

// The one rule of the refit's limit (refit.h: kMaxRefitLights), for a fixed count and a chosen one alike:
// more lights are baked without it, and the bake says so in one line. Turns `a`'s refit off when it does.
void keepRefitWithinItsLimit(AccuracyOptions& a, std::size_t lights, std::vector<Note>& notes) {
  if (!a.refit || lights <= kMaxRefitLights) return;
  a.refit = false, a.moveDirections = false;
  notes.push_back({NoteKind::Warning, "the refit takes at most " + std::to_string(kMaxRefitLights) +
                                          " lights: " + std::to_string(lights) + " lights baked without it"});
}

}  // namespace

EvaluatedBake bakeEvaluated(const Probe& probe, BakeOptions options, AccuracyOptions a,
                            const WorkingGrid* prebuilt) {
  if (!(a.maxError >= 0 && a.maxError < 1)) {
    char got[32];
    std::snprintf(got, sizeof got, "%g", a.maxError);
    throw Error(std::string("the error tolerance is a fraction in (0, 1), e.g. 0.01 for 1 %; got ") + got);
  }
  EvaluatedBake out;
  out.cut = options.method;
  const bool twoCuts = a.cuts != CutChoice::One;
  if (twoCuts && options.method != Method::Variance && options.method != Method::MedianCut)
    throw Error("both cuts are variance and median cut: bake with one of them");
  if (twoCuts && a.maxError > 0) throw Error("both cuts take a light count, not an error tolerance");
  const bool evaluating = a.evaluate || a.refit || a.maxError > 0 || twoCuts;
  if (a.refit) a.effects |= kDiffuse;
  if (!evaluating) {
    out.bake = prebuilt ? prebuilt->bake(probe, options) : bake(probe, options);
    out.count = options.lights;
    applySunAngles(a.sunAngles, nullptr, out.bake.lights);
    keepSunCones(a.sunCones, out.bake.lights);
    out.sunAngles = a.sunAngles == SunAngles::Points ? SunAngles::Points : SunAngles::Spread;
    out.sunCones = a.sunCones;
    return out;
  }
  // One working grid for the bakes and the evaluator's samples (no second pass over the pixels).
  std::optional<WorkingGrid> built;
  const WorkingGrid& grid = prebuilt ? *prebuilt : built.emplace(probe, options);
  const EvaluatorOptions evaluatorOptions{a.evaluatorWidth, a.refit, a.sunProfile, a.sunCones};
  const Evaluator evaluator = grid.table() ? Evaluator(probe, *grid.table(), a.effects, evaluatorOptions)
                                           : Evaluator(probe, a.effects, evaluatorOptions);
  if (a.maxError > 0) {
    AutoCountResult chosen = autoCount(probe, evaluator, options, a.maxError, a.finish(), 1024, &grid);
    out.bake = std::move(chosen.bake);
    out.autoCount = true, out.met = chosen.met, out.tried = std::move(chosen.tried),
    out.count = chosen.lights;
    char line[200], detail[80];
    if (chosen.met) {
      std::snprintf(line, sizeof line, "auto count: %d lights, worst error %.2f%%", chosen.lights,
                    100 * chosen.errors.worst(a.effects));
      std::snprintf(detail, sizeof detail, "asked at most %.2f%%", 100 * a.maxError);
    } else {
      std::snprintf(line, sizeof line,
                    "no count met the tolerance of %.2f%%: using %d lights, the lowest error found",
                    100 * a.maxError, chosen.lights);
      std::snprintf(detail, sizeof detail, "%.2f%%", 100 * chosen.errors.worst(a.effects));
    }
    out.bake.notes.push_back({chosen.met ? NoteKind::Chosen : NoteKind::Warning, line, detail});
    keepRefitWithinItsLimit(a, out.bake.lights.size(), out.bake.notes);  // autoCount refit those within it
  } else {
    out.bake = grid.bake(probe, options);
    out.count = options.lights;
    std::vector<Note> limit;  // the note goes on the bake kept (chooseCut returns another)
    keepRefitWithinItsLimit(a, out.bake.lights.size(), limit);
    if (twoCuts) {
      ChosenCut chosen = chooseCut(probe, grid, evaluator, options, std::move(out.bake), a.cuts, a.finish());
      out.bake = std::move(chosen.bake), out.cut = chosen.cut, out.energyShift = chosen.energyShift;
    } else {
      out.bake.lights = finishLights(evaluator, std::move(out.bake.lights), a.finish(), &out.energyShift);
    }
    out.bake.notes.insert(out.bake.notes.end(), limit.begin(), limit.end());
  }
  out.evaluated = true;
  out.refit = a.refit;
  out.effects = a.effects;
  out.sunAngles = a.sunAngles == SunAngles::Fit && !(a.effects & kShadow) ? SunAngles::Spread : a.sunAngles;
  out.sunProfile = a.sunProfile;
  out.sunCones = a.sunCones;
  out.errors = evaluator.evaluate(out.bake.lights);
  out.truthNorms = evaluator.truthNorms();
  return out;
}

EvaluatedBake bakeBuffer(ImageView view, ProjectionKind projection, NonFinitePolicy nonFinite,
                         const BakeOptions& options, const AccuracyOptions& accuracy,
                         std::optional<Probe>& probe) {
  probe.emplace(Probe::unchecked(view, projection));
  PixelReport counts;
  const WorkingGrid grid(*probe, options, &counts);
  probe->settle(counts, nonFinite);
  return bakeEvaluated(*probe, options, accuracy, &grid);
}

}  // namespace probelights
