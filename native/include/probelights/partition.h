// Partitioning the sphere into regions, one light each: the shared driver of median cut and variance
// minimization.
//
// Both algorithms (Debevec 2005; Viriyothai & Debevec 2009) grow a kd-tree of axis-aligned rectangles of the
// working grid; they differ only in where a region is cut (a CutRule). The driver:
//  - N = 2^n: n rounds, each splitting every region, as both papers do;
//  - any other N, and after the rounds if a region could not be split: split the region with the largest
//    CutRule::priority until N regions carry energy (ties broken by creation order: deterministic).
// A region is only cut where both parts keep at least one lit cell (a cell with energy), so every region of
// the partition carries light and every split adds one light. When the probe has fewer lit cells than N, the
// partition ends with fewer regions and says so in its notes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/moment_table.h"

namespace probelights {

enum class Axis { X, Y };

// A cut of a region of cells into [start, position) and [position, end) along an axis.
struct Cut {  // in cells of the working grid (BakeResult reports them in pixels: PixelCut)
  Rect region;
  Axis axis = Axis::X;
  int position = 0;
};

// The two parts of region r on either side of a cut at `position` along `axis`.
std::array<Rect, 2> splitRect(const Rect& r, Axis axis, int position);

// The cut positions along `axis` that leave at least one lit cell on both sides of region `cells`: [first,
// last], or nullopt if there is none. Both rules choose only among these.
std::optional<std::array<int, 2>> litCutRange(const MomentTable& table, const Rect& cells, Axis axis);

// The smallest p in [lo, hi] with pred(p) true, for a pred that is false then true; hi + 1 if none.
template <class Pred>
int firstTrue(int lo, int hi, Pred&& pred) {
  int end = hi + 1;
  while (lo < end) {
    int mid = lo + (end - lo) / 2;
    if (pred(mid))
      end = mid;
    else
      lo = mid + 1;
  }
  return lo;
}

class CutRule {
 public:
  virtual ~CutRule() = default;
  virtual std::string name() const = 0;
  // Where to cut a region that holds at least two lit cells, at a position within litCutRange; nullopt if
  // none.
  virtual std::optional<Cut> chooseCut(const MomentTable& table, const Rect& cells) const = 0;
  // Which region to split next when not every region is split in a round: the largest value first.
  virtual double priority(const MomentTable& table, const Rect& cells) const = 0;
};

struct Partition {
  std::vector<Rect> regions;  // in cells; together they tile the working grid exactly once
  std::vector<Cut> cuts;      // in the order they were made
  bool horizonCut = false;    // the first cut is at horizonRow
  std::vector<std::string> notes;
};

// horizonRow: for a lat-long probe, the working-grid row where the horizon is (-1: none). When set and N >=
// 2, the first cut is there, so no light mixes sky and ground: a region across the horizon would put its
// light at the mean of both, and a ground plane then blocks sky light it should pass. (Measured in Cycles
// renders of a sphere over a plane it did not lower the error at 64 lights and raised it at 16, so it is off
// by default.) After it, every split is by priority.
Partition partitionSphere(const MomentTable& table, const CutRule& rule, int count, int horizonRow = -1);

}  // namespace probelights
