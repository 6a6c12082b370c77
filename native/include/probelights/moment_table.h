// The working grid every partition decides its cuts on, with summed-area tables of the moments the cut rules
// need.
//
// Working resolution is the accuracy-for-time knob: the grid's cells are blocks of cellSize x cellSize pixels
// (cellSize 1 = full resolution, the papers' exact algorithm). Each cell holds exact double sums over its
// pixels of
//   w = Y * dOmega   (Rec. 709 luminance times the pixel's exact solid angle: the energy median cut balances)
//   w * d            (d = the pixel's unit direction: the first moment, for variance and centroids)
//   lit              (1 if w > 0: the partition never cuts off a part without light)
// so a region's energy and spread are exact whatever the cell size; only where cuts may fall gets coarser.
// Lights are always summed from the full-resolution pixels of their regions (lights.h).
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/lights.h"
#include "probelights/pixel_sums.h"
#include "probelights/probe.h"
#include "probelights/summed_area_table.h"

namespace probelights {

struct RegionMoments {
  double energy = 0;       // sum of w
  Vec3 moment;             // sum of w * d
  long long litCells = 0;  // cells with w > 0 (an exact integer count, so "is anything here" has no rounding)

  // Spread about the centroid on the unit sphere: sum of w |d - c|^2 with c = moment / energy, which expands
  // to energy - |moment|^2 / energy because |d| = 1. The chord distance on the sphere plays the role of the
  // image-plane distance d_p in Viriyothai & Debevec 2009, and stays right across the lat-long seam and at
  // the poles.
  double variance() const {
    if (energy <= 0) return 0;
    double v = energy - dot(moment, moment) / energy;
    return v > 0 ? v : 0;
  }
};

// How fine the working grid is: "full", "auto" (full up to 2048 pixels wide, then the power-of-two cell size
// that brings the width to at most 2048), or a target working width in pixels.
struct WorkingResolution {
  enum class Mode { Full, Auto, Width } mode = Mode::Auto;
  int width = 0;

  int cellSize(int probeWidth) const;
  static WorkingResolution parse(const std::string& text);  // throws Error naming the choices
  std::string toString() const;
};

class MomentTable {
 public:
  // Whether a full-resolution lat-long table keeps summed-area tables: Auto = up to kTablesUpToWidth pixels
  // wide (see hasTables); Tables or Pixels to choose (the tests compare both).
  enum class Storage { Auto, Tables, Pixels };

  // `centroid`: the lights' centroid weighting the cells' sums serve (CentroidWeight::Energy2 also keeps each
  // cell's Y^2-weighted sums: 32 more bytes a cell).
  // `counts`: the pixels' check (Probe::countRows) done in the same pass, row by row just before the rows are
  // summed (Probe::unchecked: one read of the image instead of two), written there.
  // `storage`: Pixels only for cell size 1 and a lat-long probe (else it has tables whatever is asked).
  MomentTable(const Probe& probe, int cellSize, CentroidWeight centroid = CentroidWeight::Energy,
              PixelReport* counts = nullptr, Storage storage = Storage::Auto);

  // The same table built band by band (grid_load.h reads a probe this way, never holding it whole): a table
  // for a pixelWidth x pixelHeight probe; addBand() with every band of pixel rows [y0, y1) once (y0 and y1 on
  // cell borders, or y1 the last row; `band` holds those rows: Probe::band), then finish(). Bit-identical to
  // the one-call build.
  MomentTable(int pixelWidth, int pixelHeight, int cellSize,
              CentroidWeight centroid = CentroidWeight::Energy);
  void addBand(const Probe& band, int y0, int y1);
  void finish();

  int cellSize() const { return cellSize_; }
  int width() const { return (pixelWidth_ + cellSize_ - 1) / cellSize_; }    // in cells
  int height() const { return (pixelHeight_ + cellSize_ - 1) / cellSize_; }  // in cells
  Rect wholeGrid() const { return {0, 0, width(), height()}; }

  RegionMoments moments(const Rect& cells) const {
    if (!hasTables()) return summedMoments(cells);
    auto s = sat_.sum(cells);
    return {s[0], {s[1], s[2], s[3]}, std::llround(s[4])};
  }

  // Whether the table keeps summed-area tables. A full-resolution table of a lat-long probe wider than
  // kTablesUpToWidth keeps none (they would be 40 bytes a pixel: 1.3 GB at 8K): it keeps a
  // view of the probe's pixels (which must outlive it) and sums a region's columns and rows from them when a
  // cut rule sweeps it (RegionSweep, partition.h): a pass over the pixels per round of cuts instead of one
  // to build the tables, the same regions. Up to 4K the tables are faster (docs/decisions.md).
  static constexpr int kTablesUpToWidth = 4096;
  bool hasTables() const { return !pixels_; }
  // w, w dx, w dy, w dz and lit pixels, summed.
  using Sums = std::array<double, 5>;
  // For a table without summed-area tables: the sums of each column and of each row of the pixel rectangle
  // `cells` (cells are pixels there), in order.
  void marginals(const Rect& cells, std::vector<Sums>& columns, std::vector<Sums>& rows) const;
  // The pixels a rectangle of cells covers (the last row and column of cells may be partial).
  Rect toPixels(const Rect& cells) const;

  // Full sums over a rectangle of cells of a coarse grid (cellSize > 1; see hasCellSums()): energy and moment
  // from the tables, the other light channels from the cells it kept.
  bool hasCellSums() const { return cells_ != nullptr; }
  // Whether the cell sums hold energy2 and moment2 (built for CentroidWeight::Energy2; else they are 0).
  bool hasSecondMoments() const { return second_ != nullptr; }
  PixelSums cellSums(const Rect& cells) const;

  // Exact probe integral per channel and total energy, accumulated while the table was built.
  const Rgb& integral() const { return integral_; }
  double totalEnergy() const { return totalEnergy_; }
  long long litCells() const { return litCells_; }

 private:
  void addLatLongPixels(const Probe& band, int y0, int y1);
  // The pixels' check of cell row `cellRow` (pixel rows [y0, y1)), when the build checks them: counted when
  // its sums met a negative, NaN or Inf sample (`odd`), else nothing to count and its light is `energy`.
  void checkRows(const Probe& band, int cellRow, bool odd, int y0, int y1, double energy);

  void allocate(CentroidWeight centroid);
  void buildWithoutTables(const Probe& probe, PixelReport* counts);
  RegionMoments summedMoments(const Rect& cells) const;  // without tables: from the pixels

  int cellSize_, pixelWidth_, pixelHeight_;
  std::optional<Probe> pixels_;  // without tables: a view of the probe's pixels (not a copy)
  RegionMoments whole_;          // without tables: the whole probe's moments
  SummedAreaTable<5> sat_;
  Rgb integral_{};
  double totalEnergy_ = 0;
  long long litCells_ = 0;
  // What a light needs beyond the tables' channels, per cell of a coarse grid (uninitialized until built),
  // and the second moments when asked for.
  struct CellLight {
    double rgb[3], solidAngle;
  };
  struct CellSecond {
    double energy2, moment2[3];
  };
  KeptArray<CellLight> cells_;  // reused across tables in a process (memory.h)
  KeptArray<CellSecond> second_;
  std::vector<PixelSums> rowTotals_;  // per cell row, while the table is built
  std::vector<long long> rowLitCells_;
  std::vector<PixelReport> rowCounts_;  // per cell row, when the build also checks the pixels
};

}  // namespace probelights
