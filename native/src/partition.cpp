#include "probelights/partition.h"

#include <bit>
#include <queue>
#include <tuple>

#include "probelights/error.h"
#include "probelights/lights.h"

namespace probelights {

std::array<Rect, 2> splitRect(const Rect& r, Axis axis, int position) {
  if (axis == Axis::X) return {Rect{r.x0, r.y0, position, r.y1}, Rect{position, r.y0, r.x1, r.y1}};
  return {Rect{r.x0, r.y0, r.x1, position}, Rect{r.x0, position, r.x1, r.y1}};
}

std::optional<std::array<int, 2>> litCutRange(const MomentTable& table, const Rect& cells, Axis axis) {
  const int start = axis == Axis::X ? cells.x0 : cells.y0, end = axis == Axis::X ? cells.x1 : cells.y1;
  const long long total = table.moments(cells).litCells;
  auto litBefore = [&](int p) { return table.moments(splitRect(cells, axis, p)[0]).litCells; };
  // Valid p: the first part [start, p) has a lit cell and the second [p, end) has one, i.e. 1 <= litBefore(p)
  // < total.
  int first = firstTrue(start + 1, end - 1, [&](int p) { return litBefore(p) >= 1; });
  int last = firstTrue(start + 1, end - 1, [&](int p) { return litBefore(p) >= total; }) - 1;
  if (first > last) return std::nullopt;
  return std::array<int, 2>{first, last};
}

Partition partitionSphere(const MomentTable& table, const CutRule& rule, int count, int horizonRow) {
  checkLightCount(count);
  Partition p;
  p.regions.push_back(table.wholeGrid());
  if (table.litCells() == 0) {
    p.notes.push_back("the probe is black: no lights");
    return p;
  }

  // Splits region i in place (first part) and appends the second; false if the rule cannot cut it. A region
  // is cut only where both parts keep a lit cell (CutRule contract), so every split adds exactly one lit
  // region.
  auto split = [&](std::size_t i) {
    const Rect r = p.regions[i];
    if (table.moments(r).litCells < 2) return false;
    auto cut = rule.chooseCut(table, r);
    if (!cut) return false;
    auto parts = splitRect(r, cut->axis, cut->position);
    p.cuts.push_back(*cut);
    p.regions[i] = parts[0];
    p.regions.push_back(parts[1]);
    return true;
  };

  // A horizon cut first, where it leaves light on both sides; then only splits by priority.
  bool horizon = false;
  if (count >= 2 && horizonRow > 0 && horizonRow < table.height()) {
    auto parts = splitRect(p.regions[0], Axis::Y, horizonRow);
    if (table.moments(parts[0]).litCells > 0 && table.moments(parts[1]).litCells > 0) {
      p.cuts.push_back(Cut{p.regions[0], Axis::Y, horizonRow});
      p.regions = {parts[0], parts[1]};
      horizon = p.horizonCut = true;
    }
  }

  // N = 2^n: n rounds that split every region (the papers' algorithm exactly, when nothing stops a split).
  if (!horizon && std::has_single_bit(static_cast<unsigned>(count))) {
    for (int round = 0; round < std::countr_zero(static_cast<unsigned>(count)); ++round) {
      std::size_t n = p.regions.size();
      for (std::size_t i = 0; i < n; ++i) split(i);
    }
  }

  // Otherwise (or to make up for regions that could not be split): split the region of largest priority.
  using Entry = std::tuple<double, long long, std::size_t>;  // priority, -creation order, index
  std::priority_queue<Entry> queue;
  long long order = 0;
  auto push = [&](std::size_t i) {
    if (table.moments(p.regions[i]).litCells >= 2)
      queue.emplace(rule.priority(table, p.regions[i]), -order++, i);
  };
  for (std::size_t i = 0; i < p.regions.size(); ++i) push(i);
  while (static_cast<int>(p.regions.size()) < count && !queue.empty()) {
    std::size_t i = std::get<2>(queue.top());
    queue.pop();
    if (!split(i)) continue;
    push(i);
    push(p.regions.size() - 1);
  }

  if (static_cast<int>(p.regions.size()) < count) {
    std::string cells = table.cellSize() == 1 ? "pixels" : "cells of the working grid";
    p.notes.push_back("made " + std::to_string(p.regions.size()) + " lights, not " + std::to_string(count) +
                      ": the probe has only " + std::to_string(table.litCells()) + " lit " + cells);
  }
  return p;
}

}  // namespace probelights
