// Median cut light probe sampling (Debevec 2005): cut each region across its longer side, measured on the
// sphere (lat-long width scaled by cos latitude), at the position that leaves equal energy on both sides.
#pragma once

#include "probelights/partition.h"
#include "probelights/projection.h"

namespace probelights {

class MedianCutRule final : public CutRule {
 public:
  explicit MedianCutRule(const Projection& projection) : projection_(projection) {}
  std::string name() const override { return "median-cut"; }
  std::optional<Cut> chooseCut(const RegionSweep& region) const override;
  std::optional<int> positionAlong(const RegionSweep& region, Axis axis) const override;
  // The brightest region is split first: median cut aims at equal energy per light.
  double priority(const RegionMoments& region) const override { return region.energy; }

 private:
  const Projection& projection_;
};

}  // namespace probelights
