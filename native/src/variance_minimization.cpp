#include "probelights/variance_minimization.h"

#include <algorithm>
#include <limits>

namespace probelights {

namespace {

// A cut's cost: the larger part's variance, then (for ties, e.g. two parts with no spread at all) how
// unequal the parts' energies are.
std::pair<double, double> cutCost(const RegionSweep& region, Axis axis, int p) {
  RegionMoments a = region.before(axis, p), b = region.after(axis, p);
  return {std::max(a.variance(), b.variance()), std::abs(a.energy - b.energy)};
}

}  // namespace

std::optional<int> VarianceMinimizationRule::positionAlong(const RegionSweep& region, Axis axis) const {
  auto range = litCutRange(region, axis);
  if (!range) return std::nullopt;
  int best = (*range)[0];
  auto bestCost = cutCost(region, axis, best);
  for (int p = best + 1; p <= (*range)[1]; ++p)
    if (auto cost = cutCost(region, axis, p); cost < bestCost) bestCost = cost, best = p;
  return best;
}

std::optional<Cut> VarianceMinimizationRule::chooseCut(const RegionSweep& region) const {
  // Viriyothai & Debevec 2009: try every cut on both axes; keep the one whose worse part has the least
  // variance. Ties go to the cut that balances energy best, then to the first found (x before y).
  std::optional<Cut> best;
  std::pair<double, double> bestCost{std::numeric_limits<double>::infinity(), 0};
  for (Axis axis : {Axis::X, Axis::Y}) {
    auto p = positionAlong(region, axis);
    if (!p) continue;
    if (auto cost = cutCost(region, axis, *p); !best || cost < bestCost)
      bestCost = cost, best = Cut{region.cells(), axis, *p};
  }
  return best;
}

}  // namespace probelights
