#include "probelights/accuracy.h"

#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "probelights/error.h"
#include "probelights/names.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {

// finishLights after its first step, the angles (`fitted`: whether they were fitted).
std::vector<Light> finishAngled(const Evaluator& evaluator, std::vector<Light> lights, bool fitted,
                                bool refit, bool moveDirections, SunAngles angles, double* energyShift) {
  double before = 0;  // (the angles do not change the colours)
  for (const Light& l : lights) before += l.rgb[0] + l.rgb[1] + l.rgb[2];
  // The directions move for the shadows the angled lights cast; then the angles again for the moved lights,
  // and their colours for those angles. The refit is kept only if it fits the fit receivers better (the joint
  // fit can lose on shadows what it wins on shading).
  if (refit) {
    std::vector<Light> moved = refitIrradiance(evaluator, lights, nullptr, moveDirections);
    if (fitted) {
      applySunAngles(angles, &evaluator, moved, true);
      moved = refitIrradiance(evaluator, moved);
    }
    const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
    if (evaluator.fitError(receivers, moved) <= evaluator.fitError(receivers, lights))
      lights = std::move(moved);
  }
  if (energyShift) {
    double after = 0;
    for (const Light& l : lights) after += l.rgb[0] + l.rgb[1] + l.rgb[2];
    *energyShift = before > 0 ? after / before - 1.0 : 0.0;
  }
  return lights;
}

}  // namespace

std::vector<Light> finishLights(const Evaluator& evaluator, std::vector<Light> lights, bool refit,
                                bool moveDirections, SunAngles angles, double* energyShift) {
  // Angles first, so the directions move for the shadows the lights will cast.
  const bool fitted = applySunAngles(angles, &evaluator, lights, refit);
  return finishAngled(evaluator, std::move(lights), fitted, refit, moveDirections, angles, energyShift);
}

AutoCountResult autoCount(const Probe& probe, const Evaluator& evaluator, BakeOptions options,
                          double tolerance, bool refit, int maxLights, bool moveDirections,
                          const WorkingGrid* grid, SunAngles angles) {
  if (!(tolerance > 0)) throw Error("the error tolerance must be positive");
  AutoCountResult best;
  // One working grid for every count tried (the grid does not depend on the count).
  std::optional<WorkingGrid> own;
  if (!grid) grid = &own.emplace(probe, options);
  auto attempt = [&](int n) {
    options.lights = n;
    BakeResult r = grid->bake(probe, options);
    // Decided before the call: its by-value parameter may be moved into before the other arguments are read
    // (clang evaluates them left to right, GCC right to left; the Windows and macOS builds are clang's).
    const bool refitThese = refit && r.lights.size() <= kMaxRefitLights;
    r.lights = finishLights(evaluator, std::move(r.lights), refitThese, moveDirections, angles);
    EffectErrors e = evaluator.evaluate(r.lights);
    best.tried.push_back({n, e.worst(evaluator.effects())});
    return std::pair{std::move(r), e};
  };
  // Doubling until the tolerance is met, then bisection between the last miss and the first hit. The error is
  // not monotonic in the count (shadows of many small lights can be worse than of a few), so a miss keeps the
  // count with the lowest error seen (fewest lights on a tie), and the doubling stops once two doublings past
  // that count did not improve on it: a miss never costs more lights than a count that did better.
  int lo = 0, hi = 0;
  double bestError = std::numeric_limits<double>::infinity();
  for (int n = 1; n <= maxLights; n *= 2) {
    auto [r, e] = attempt(n);
    const double worst = e.worst(evaluator.effects());
    const bool fewerLit =
        static_cast<int>(r.lights.size()) < n;  // more lights than lit pixels: more cannot help
    if (worst <= tolerance) {
      hi = n;
      best.bake = std::move(r), best.errors = e, best.lights = n, best.met = true;
      break;
    }
    lo = n;
    if (worst < bestError) {
      bestError = worst;
      best.bake = std::move(r), best.errors = e, best.lights = n;
    }
    if (fewerLit || n >= 4 * best.lights) break;
  }
  if (!best.met) return best;
  while (hi - lo > 1) {
    int mid = lo + (hi - lo) / 2;
    auto [r, e] = attempt(mid);
    if (e.worst(evaluator.effects()) <= tolerance) {
      hi = mid;
      best.bake = std::move(r), best.errors = e, best.lights = mid;
    } else {
      lo = mid;
    }
  }
  return best;
}

bool bakesOnGridAlone(const BakeOptions& options, const AccuracyOptions& a) {
  return usesWorkingGrid(options.method) && !a.evaluate && !a.refit && !(a.maxError > 0) &&
         a.cuts == CutChoice::One;
}

EvaluatedBake bakeOnGrid(const Probe& probe, const MomentTable& table, double tablesMs,
                         const BakeOptions& options, SunAngles angles) {
  EvaluatedBake out;
  out.cut = options.method;
  out.bake = bake(probe, table, options);
  applySunAngles(angles, nullptr, out.bake.lights);
  out.sunAngles = angles == SunAngles::Points ? SunAngles::Points : SunAngles::Spread;
  out.bake.timings.tablesMs = tablesMs;
  out.count = options.lights;
  if (!probe.hasPixels())
    out.bake.notes.insert(out.bake.notes.begin(), "read band by band into a working grid of " +
                                                      std::to_string(table.width()) + "x" +
                                                      std::to_string(table.height()) +
                                                      " cells, never whole (tables built during the load)");
  return out;
}

namespace {

constexpr NameTable<CutChoice, 3> kCutChoices{
    {{CutChoice::One, "one"}, {CutChoice::Both, "both"}, {CutChoice::Auto, "auto"}}};

// The cuts of a CutChoice other than one (accuracy.h): `out` holds the bake's method's lights as cut; the
// other cut's lights are cut on the same grid, and the better of the two kept in `out`, finished, with a
// note.
void chooseCut(const Probe& probe, const WorkingGrid& grid, const Evaluator& evaluator,
               const BakeOptions& options, const AccuracyOptions& a, EvaluatedBake& out) {
  BakeOptions other = options;
  other.method = options.method == Method::Variance ? Method::MedianCut : Method::Variance;
  BakeResult second = grid.bake(probe, other);
  const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
  const bool finishBoth =
      a.cuts == CutChoice::Both || !a.refit || out.bake.lights.size() <= kBothFinishedUpTo;
  double shifts[2] = {0, 0}, errors[2];
  std::vector<Light>* lights[2] = {&out.bake.lights, &second.lights};
  if (finishBoth) {
    for (int c = 0; c < 2; ++c) {
      *lights[c] =
          finishLights(evaluator, std::move(*lights[c]), a.refit, a.moveDirections, a.sunAngles, &shifts[c]);
      errors[c] = evaluator.fitError(receivers, *lights[c]);
    }
  } else {
    // Each started (finishLights' first step, the angles) and judged with its colours solved for them (the
    // solve alone: placing dark lights too picked worse at 64 suns, 0.324 against 0.320 % mean shadow error).
    bool fitted[2];
    for (int c = 0; c < 2; ++c) {
      fitted[c] = applySunAngles(a.sunAngles, &evaluator, *lights[c], true);
      std::vector<Light> judged = *lights[c];
      solveColours(evaluator, receivers, judged);
      errors[c] = evaluator.fitError(receivers, judged);
    }
    const int keep = errors[1] < errors[0] ? 1 : 0;
    *lights[keep] = finishAngled(evaluator, std::move(*lights[keep]), fitted[keep], a.refit, a.moveDirections,
                                 a.sunAngles, &shifts[keep]);
  }
  const bool swap = errors[1] < errors[0];
  const Method kept = swap ? other.method : options.method, left = swap ? options.method : other.method;
  char line[240];
  std::snprintf(line, sizeof line,
                finishBoth ? "both cuts fitted: %s kept (fit error %.4g against %s's %.4g)"
                           : "both cuts started: %s kept and finished (fit error with colours solved %.4g "
                             "against %s's %.4g)",
                toString(kept).c_str(), errors[swap ? 1 : 0], toString(left).c_str(), errors[swap ? 0 : 1]);
  out.energyShift = shifts[swap ? 1 : 0];
  if (swap) {
    second.timings.tablesMs = out.bake.timings.tablesMs;
    out.bake = std::move(second), out.cut = other.method;
  }
  out.bake.notes.push_back(line);
}

}  // namespace

std::string toString(CutChoice cuts) { return std::string(nameOf(kCutChoices, cuts)); }
CutChoice parseCutChoice(const std::string& name) { return parseName(kCutChoices, "cuts", name); }

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
    out.sunAngles = a.sunAngles == SunAngles::Points ? SunAngles::Points : SunAngles::Spread;
    return out;
  }
  // One working grid for the bakes and the evaluator's samples (no second pass over the pixels).
  std::optional<WorkingGrid> built;
  const WorkingGrid& grid = prebuilt ? *prebuilt : built.emplace(probe, options);
  const EvaluatorOptions evaluatorOptions{a.evaluatorWidth, a.refit, a.sunProfile};
  const Evaluator evaluator = grid.table() ? Evaluator(probe, *grid.table(), a.effects, evaluatorOptions)
                                           : Evaluator(probe, a.effects, evaluatorOptions);
  if (a.maxError > 0) {
    AutoCountResult chosen =
        autoCount(probe, evaluator, options, a.maxError, a.refit, 1024, a.moveDirections, &grid, a.sunAngles);
    out.bake = std::move(chosen.bake);
    out.autoCount = true, out.met = chosen.met, out.tried = std::move(chosen.tried),
    out.count = chosen.lights;
    char line[200];
    if (chosen.met)
      std::snprintf(line, sizeof line, "auto count: %d lights, worst error %.2f%% (asked at most %.2f%%)",
                    chosen.lights, 100 * chosen.errors.worst(a.effects), 100 * a.maxError);
    else
      std::snprintf(line, sizeof line,
                    "no count met the tolerance of %.2f%%: using %d lights, the lowest error found (%.2f%%)",
                    100 * a.maxError, chosen.lights, 100 * chosen.errors.worst(a.effects));
    out.bake.notes.push_back(line);
  } else {
    out.bake = grid.bake(probe, options);
    out.count = options.lights;
    if (a.refit && out.bake.lights.size() > kMaxRefitLights)
      throw Error("the refit takes at most " + std::to_string(kMaxRefitLights) + " lights");
    if (twoCuts)
      chooseCut(probe, grid, evaluator, options, a, out);
    else
      out.bake.lights = finishLights(evaluator, std::move(out.bake.lights), a.refit, a.moveDirections,
                                     a.sunAngles, &out.energyShift);
  }
  out.evaluated = true;
  out.refit = a.refit;
  out.effects = a.effects;
  out.sunAngles = a.sunAngles == SunAngles::Fit && !(a.effects & kShadow) ? SunAngles::Spread : a.sunAngles;
  out.sunProfile = a.sunProfile;
  out.errors = evaluator.evaluate(out.bake.lights);
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
