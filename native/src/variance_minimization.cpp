#include "probelights/variance_minimization.h"

#include <algorithm>
#include <limits>

namespace probelights {

std::optional<Cut> VarianceMinimizationRule::chooseCut(const RegionSweep& region) const {
  // Viriyothai & Debevec 2009: try every cut on both axes; keep the one whose worse part has the least
  // variance. Ties (e.g. two parts with no spread at all) go to the cut that balances energy best, then to
  // the first found.
  std::optional<Cut> best;
  double bestCost = std::numeric_limits<double>::infinity(), bestImbalance = bestCost;
  for (Axis axis : {Axis::X, Axis::Y}) {
    auto range = litCutRange(region, axis);
    if (!range) continue;
    for (int p = (*range)[0]; p <= (*range)[1]; ++p) {
      RegionMoments a = region.before(axis, p), b = region.after(axis, p);
      double cost = std::max(a.variance(), b.variance());
      double imbalance = std::abs(a.energy - b.energy);
      if (cost < bestCost || (cost == bestCost && imbalance < bestImbalance)) {
        bestCost = cost;
        bestImbalance = imbalance;
        best = Cut{region.cells(), axis, p};
      }
    }
  }
  return best;
}

}  // namespace probelights
