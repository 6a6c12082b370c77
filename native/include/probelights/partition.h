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
#include "probelights/note.h"

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

// A region and what the cut rules read of it: its moments, and those of its two parts on either side of a
// cut at any position along either axis. From the summed-area tables (each asked for in O(1) when read), or,
// for a table without them (MomentTable::hasTables), from the region's column and row sums taken from its
// pixels in one pass when the sweep is made.
class RegionSweep {
 public:
  RegionSweep(const MomentTable& table, const Rect& cells, const RegionMoments& total);
  const Rect& cells() const { return cells_; }
  const Rect& pixels() const { return pixels_; }  // the pixels the cells cover
  const RegionMoments& total() const { return total_; }
  // The moments of splitRect(cells(), axis, p)[0] and [1], for a position p inside the region along axis.
  RegionMoments before(Axis axis, int p) const;
  RegionMoments after(Axis axis, int p) const;

 private:
  const MomentTable& table_;
  Rect cells_, pixels_;
  RegionMoments total_;
  std::vector<RegionMoments> before_[2], after_[2];  // without tables: index p - start, per axis
};

// The cut positions along `axis` that leave at least one lit cell on both sides of the region: [first,
// last], or nullopt if there is none. Both rules choose only among these.
std::optional<std::array<int, 2>> litCutRange(const RegionSweep& region, Axis axis);

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
  virtual std::optional<Cut> chooseCut(const RegionSweep& region) const = 0;
  // Where the rule would cut the region along `axis` alone, within litCutRange; nullopt if it cannot be cut
  // along it. A sequence's frame keeps the previous frame's axes and moves only the positions (sequence.h).
  virtual std::optional<int> positionAlong(const RegionSweep& region, Axis axis) const = 0;
  // Which region (of these moments) to split next when not every region is split in a round: the largest
  // value first.
  virtual double priority(const RegionMoments& region) const = 0;
};

struct Partition {
  std::vector<Rect> regions;  // in cells; together they tile the working grid exactly once
  std::vector<Cut> cuts;      // in the order they were made
  bool horizonCut = false;    // the first cut is at horizonRow
  std::vector<Note> notes;
};

// horizonRow: for a lat-long probe, the working-grid row where the horizon is (-1: none). When set and N >=
// 2, the first cut is there, so no light mixes sky and ground: a region across the horizon would put its
// light at the mean of both, and a ground plane then blocks sky light it should pass. (Measured in Cycles
// renders of a sphere over a plane it did not lower the error at 64 lights and raised it at 16, so it is off
// by default.) After it, every split is by priority.
Partition partitionSphere(const MomentTable& table, const CutRule& rule, int count, int horizonRow = -1);

// `previous`'s tree of cuts made again on another probe's table of the same size (the next frame of a
// sequence, sequence.h): each cut splits the same region, along the same axis, in the same order, at the
// position the rule picks along that axis in this probe. A horizon cut stays where it was. The regions come
// in previous's order, so region i is the same light as before. nullopt when a cut can no longer be made (a
// region lost its light).
std::optional<Partition> replayPartition(const MomentTable& table, const CutRule& rule,
                                         const Partition& previous);

// The partition's spread: the sum over its regions of sum w |d - c|^2 (RegionMoments::variance), what
// variance minimization makes small; how far a light's region is from being one direction.
double partitionSpread(const MomentTable& table, const Partition& partition);

}  // namespace probelights
