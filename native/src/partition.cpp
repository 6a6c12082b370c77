#include "probelights/partition.h"

#include <algorithm>
#include <bit>
#include <queue>
#include <tuple>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/lights.h"

namespace probelights {

std::array<Rect, 2> splitRect(const Rect& r, Axis axis, int position) {
  if (axis == Axis::X) return {Rect{r.x0, r.y0, position, r.y1}, Rect{position, r.y0, r.x1, r.y1}};
  return {Rect{r.x0, r.y0, r.x1, position}, Rect{r.x0, position, r.x1, r.y1}};
}

RegionSweep::RegionSweep(const MomentTable& table, const Rect& cells, const RegionMoments& total)
    : table_(table), cells_(cells), pixels_(table.toPixels(cells)), total_(total) {
  if (table.hasTables()) return;  // answered from the tables when asked
  // From the region's column and row sums: the parts' moments summed in order from either end (lit counts
  // are whole numbers, exact in a double).
  std::vector<MomentTable::Sums> columns, rows;
  table.marginals(cells, columns, rows);
  auto sweepAxis = [](const std::vector<MomentTable::Sums>& sums, std::vector<RegionMoments>& before,
                      std::vector<RegionMoments>& after) {
    const std::size_t n = sums.size();
    auto moments = [](const MomentTable::Sums& s) {
      return RegionMoments{s[0], {s[1], s[2], s[3]}, std::llround(s[4])};
    };
    before.resize(n + 1), after.resize(n + 1);
    MomentTable::Sums run{};
    for (std::size_t i = 0; i <= n; ++i) {
      before[i] = moments(run);
      if (i < n)
        for (int k = 0; k < 5; ++k) run[k] += sums[i][k];
    }
    run = {};
    for (std::size_t i = n + 1; i-- > 0;) {
      after[i] = moments(run);
      if (i > 0)
        for (int k = 0; k < 5; ++k) run[k] += sums[i - 1][k];
    }
  };
  sweepAxis(columns, before_[0], after_[0]);
  sweepAxis(rows, before_[1], after_[1]);
}

RegionMoments RegionSweep::before(Axis axis, int p) const {
  if (table_.hasTables()) return table_.moments(splitRect(cells_, axis, p)[0]);
  return axis == Axis::X ? before_[0][p - cells_.x0] : before_[1][p - cells_.y0];
}

RegionMoments RegionSweep::after(Axis axis, int p) const {
  if (table_.hasTables()) return table_.moments(splitRect(cells_, axis, p)[1]);
  return axis == Axis::X ? after_[0][p - cells_.x0] : after_[1][p - cells_.y0];
}

std::optional<std::array<int, 2>> litCutRange(const RegionSweep& region, Axis axis) {
  const Rect& cells = region.cells();
  const int start = axis == Axis::X ? cells.x0 : cells.y0, end = axis == Axis::X ? cells.x1 : cells.y1;
  const long long total = region.total().litCells;
  auto litBefore = [&](int p) { return region.before(axis, p).litCells; };
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
  // Each region's moments, beside it: from the sweep that cut it out of its parent.
  std::vector<RegionMoments> moments{table.moments(table.wholeGrid())};
  if (table.litCells() == 0) {
    p.notes.push_back({NoteKind::Warning, "the probe is black: no lights"});
    return p;
  }

  // Splits region i in place (first part) and appends the second; false if the rule cannot cut it. A region
  // is cut only where both parts keep a lit cell (CutRule contract), so every split adds exactly one lit
  // region.
  struct Split {
    Cut cut;
    RegionMoments first, second;
  };
  // Where region i would be cut (it is not changed), or nothing.
  auto chooseSplit = [&](std::size_t i) -> std::optional<Split> {
    if (moments[i].litCells < 2) return std::nullopt;
    const RegionSweep sweep(table, p.regions[i], moments[i]);
    auto cut = rule.chooseCut(sweep);
    if (!cut) return std::nullopt;
    return Split{*cut, sweep.before(cut->axis, cut->position), sweep.after(cut->axis, cut->position)};
  };
  auto apply = [&](std::size_t i, const Split& s) {
    auto parts = splitRect(p.regions[i], s.cut.axis, s.cut.position);
    p.cuts.push_back(s.cut);
    p.regions[i] = parts[0], moments[i] = s.first;
    p.regions.push_back(parts[1]), moments.push_back(s.second);
  };
  auto split = [&](std::size_t i) {
    const auto s = chooseSplit(i);
    if (s) apply(i, *s);
    return s.has_value();
  };

  // A horizon cut first, where it leaves light on both sides; then only splits by priority.
  bool horizon = false;
  if (count >= 2 && horizonRow > 0 && horizonRow < table.height()) {
    auto parts = splitRect(p.regions[0], Axis::Y, horizonRow);
    const RegionSweep whole(table, p.regions[0], moments[0]);
    const RegionMoments above = whole.before(Axis::Y, horizonRow), below = whole.after(Axis::Y, horizonRow);
    if (above.litCells > 0 && below.litCells > 0) {
      p.cuts.push_back(Cut{p.regions[0], Axis::Y, horizonRow});
      p.regions = {parts[0], parts[1]};
      moments = {above, below};
      horizon = p.horizonCut = true;
    }
  }

  // N = 2^n: n rounds that split every region (the papers' algorithm exactly, when nothing stops a split).
  if (!horizon && std::has_single_bit(static_cast<unsigned>(count))) {
    // A round's regions are cut independently, so they are chosen side by side on the threads and applied in
    // order: the same partition as one after the other.
    for (int round = 0; round < std::countr_zero(static_cast<unsigned>(count)); ++round) {
      const std::size_t n = p.regions.size();
      std::vector<std::optional<Split>> splits(n);
      parallelFor(static_cast<std::int64_t>(n), [&](std::int64_t i) { splits[i] = chooseSplit(i); });
      for (std::size_t i = 0; i < n; ++i)
        if (splits[i]) apply(i, *splits[i]);
    }
  }

  // Otherwise (or to make up for regions that could not be split): split the region of largest priority.
  using Entry = std::tuple<double, long long, std::size_t>;  // priority, -creation order, index
  std::priority_queue<Entry> queue;
  long long order = 0;
  auto push = [&](std::size_t i) {
    if (moments[i].litCells >= 2) queue.emplace(rule.priority(moments[i]), -order++, i);
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
    p.notes.push_back({NoteKind::Warning, "made " + std::to_string(p.regions.size()) + " lights, not " +
                                              std::to_string(count) + ": the probe has only " +
                                              std::to_string(table.litCells()) + " lit " + cells});
  }
  return p;
}

std::optional<Partition> replayPartition(const MomentTable& table, const CutRule& rule,
                                         const Partition& previous) {
  if (table.litCells() == 0) return std::nullopt;
  Partition p;
  p.regions.push_back(table.wholeGrid());
  p.horizonCut = previous.horizonCut;
  std::vector<RegionMoments> moments{table.moments(table.wholeGrid())};
  // The previous tree's regions as its cuts made them, to know which region each cut split.
  std::vector<Rect> before{table.wholeGrid()};
  for (std::size_t k = 0; k < previous.cuts.size(); ++k) {
    const Cut& old = previous.cuts[k];
    std::size_t i = 0;
    while (i < before.size() && !(before[i] == old.region)) ++i;
    if (i == before.size()) throw Error("a partition's cuts do not make its regions (replayPartition)");
    auto oldParts = splitRect(before[i], old.axis, old.position);
    before[i] = oldParts[0], before.push_back(oldParts[1]);

    if (moments[i].litCells < 2) return std::nullopt;
    const RegionSweep sweep(table, p.regions[i], moments[i]);
    const auto range = litCutRange(sweep, old.axis);
    if (!range) return std::nullopt;
    int position = old.position;  // a horizon cut
    if (!(k == 0 && previous.horizonCut)) {
      const auto chosen = rule.positionAlong(sweep, old.axis);
      if (!chosen) return std::nullopt;
      position = *chosen;
    }
    position = std::clamp(position, (*range)[0], (*range)[1]);
    const Cut cut{p.regions[i], old.axis, position};
    auto parts = splitRect(p.regions[i], old.axis, position);
    p.cuts.push_back(cut);
    const RegionMoments first = sweep.before(old.axis, position), second = sweep.after(old.axis, position);
    p.regions[i] = parts[0], moments[i] = first;
    p.regions.push_back(parts[1]), moments.push_back(second);
  }
  return p;
}

double partitionSpread(const MomentTable& table, const Partition& partition) {
  double sum = 0;
  for (const Rect& r : partition.regions) sum += table.moments(r).variance();
  return sum;
}

}  // namespace probelights
