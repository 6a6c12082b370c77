#include "probelights/median_cut.h"

#include <cmath>

namespace probelights {

std::optional<Cut> MedianCutRule::chooseCut(const RegionSweep& region) const {
  // Debevec 2005: cut across the longer side, measured on the sphere. If every lit cell lies in one column
  // (row), only the other axis can be cut.
  auto extent = projection_.extentOnSphere(region.pixels());
  Axis axis = extent[0] >= extent[1] ? Axis::X : Axis::Y;
  auto p = positionAlong(region, axis);
  if (!p) {
    axis = axis == Axis::X ? Axis::Y : Axis::X;
    p = positionAlong(region, axis);
    if (!p) return std::nullopt;
  }
  return Cut{region.cells(), axis, *p};
}

std::optional<int> MedianCutRule::positionAlong(const RegionSweep& region, Axis axis) const {
  auto range = litCutRange(region, axis);
  if (!range) return std::nullopt;
  // The energy left of a cut grows with its position: binary search the first position holding half, then
  // keep whichever of it and its predecessor is closer to half.
  const double half = 0.5 * region.total().energy;
  auto energyBefore = [&](int p) { return region.before(axis, p).energy; };
  const auto [lo, hi] = *range;
  int p = firstTrue(lo, hi, [&](int q) { return energyBefore(q) >= half; });
  if (p > hi) p = hi;
  if (p > lo && std::abs(energyBefore(p - 1) - half) <= std::abs(energyBefore(p) - half)) --p;
  return p;
}

}  // namespace probelights
