#include "probelights/auto_count.h"

#include <limits>
#include <optional>

#include "probelights/error.h"
#include "probelights/finish_lights.h"

namespace probelights {

AutoCountResult autoCount(const Probe& probe, const Evaluator& evaluator, BakeOptions options,
                          double tolerance, const FinishOptions& finish, int maxLights,
                          const WorkingGrid* grid) {
  if (!(tolerance > 0)) throw Error("the error tolerance must be positive");
  AutoCountResult best;
  // One working grid for every count tried (the grid does not depend on the count).
  std::optional<WorkingGrid> own;
  if (!grid) grid = &own.emplace(probe, options);
  auto attempt = [&](int n) {
    options.lights = n;
    BakeResult r = grid->bake(probe, options);
    r.lights = finishLights(evaluator, std::move(r.lights), finish);
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

}  // namespace probelights
