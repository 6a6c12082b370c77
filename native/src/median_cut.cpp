#include "probelights/median_cut.h"

#include <cmath>

namespace probelights {

std::optional<Cut> MedianCutRule::chooseCut(const MomentTable& table, const Rect& cells) const {
  // Debevec 2005: cut across the longer side, measured on the sphere. If every lit cell lies in one column
  // (row), only the other axis can be cut.
  auto extent = projection_.extentOnSphere(table.toPixels(cells));
  Axis axis = extent[0] >= extent[1] ? Axis::X : Axis::Y;
  auto range = litCutRange(table, cells, axis);
  if (!range) {
    axis = axis == Axis::X ? Axis::Y : Axis::X;
    range = litCutRange(table, cells, axis);
    if (!range) return std::nullopt;
  }
  // The energy left of a cut grows with its position: binary search the first position holding half, then
  // keep whichever of it and its predecessor is closer to half.
  const double half = 0.5 * table.moments(cells).energy;
  auto energyBefore = [&](int p) { return table.moments(splitRect(cells, axis, p)[0]).energy; };
  const auto [lo, hi] = *range;
  int p = firstTrue(lo, hi, [&](int q) { return energyBefore(q) >= half; });
  if (p > hi) p = hi;
  if (p > lo && std::abs(energyBefore(p - 1) - half) <= std::abs(energyBefore(p) - half)) --p;
  return Cut{cells, axis, p};
}

}  // namespace probelights
