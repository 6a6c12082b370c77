// Variance minimization light probe sampling (Viriyothai & Debevec 2009): among every cut of a region (both
// axes, every position), take the one that minimizes the larger of the two parts' sum of L_p d_p^2, each
// evaluated in O(1) from the moment tables (RegionMoments::variance). Unlike median cut it does not cut
// through the brighter of two unequal sources; it cuts between them.
#pragma once

#include "probelights/partition.h"

namespace probelights {

class VarianceMinimizationRule final : public CutRule {
 public:
  std::string name() const override { return "variance"; }
  std::optional<Cut> chooseCut(const RegionSweep& region) const override;
  std::optional<int> positionAlong(const RegionSweep& region, Axis axis) const override;
  // The most spread-out region is split first.
  double priority(const RegionMoments& region) const override { return region.variance(); }
};

}  // namespace probelights
