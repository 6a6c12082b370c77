#include "probelights/moment_table.h"

#include <algorithm>
#include <charconv>
#include <span>

#include "parallel.h"
#include "probelights/error.h"

namespace probelights {

int WorkingResolution::cellSize(int probeWidth) const {
  constexpr int kAutoWidth = 2048;
  switch (mode) {
    case Mode::Full:
      return 1;
    case Mode::Auto: {
      int size = 1;
      while (probeWidth / size > kAutoWidth) size *= 2;
      return size;
    }
    case Mode::Width:
      return std::max(1, (probeWidth + width - 1) / std::max(1, width));
  }
  return 1;
}

WorkingResolution WorkingResolution::parse(const std::string& text) {
  if (text == "full") return WorkingResolution{Mode::Full, 0};
  if (text == "auto") return WorkingResolution{Mode::Auto, 0};
  int w = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), w);
  if (ec != std::errc() || end != text.data() + text.size() || w < 1)
    throw Error("unknown resolution '" + text + "': use full, auto or a width in pixels");
  return WorkingResolution{Mode::Width, w};
}

std::string WorkingResolution::toString() const {
  switch (mode) {
    case Mode::Full:
      return "full";
    case Mode::Auto:
      return "auto";
    case Mode::Width:
      return std::to_string(width);
  }
  return "?";
}

MomentTable::MomentTable(const Probe& probe, int cellSize)
    : cellSize_(cellSize), pixelWidth_(probe.width()), pixelHeight_(probe.height()) {
  if (cellSize < 1) throw Error("working-grid cell size must be at least 1 pixel");
  const int W = probe.width(), H = probe.height();
  const int cellsX = (W + cellSize - 1) / cellSize, cellsY = (H + cellSize - 1) / cellSize;
  using Values = SummedAreaTable<5>::Values;
  // A coarse grid keeps every cell's full sums, so lights are summed from cells without reading the image
  // again; at full resolution that would be 100 bytes a pixel, and lights re-read the pixels of their regions
  // instead.
  if (cellSize > 1) cells_.reset(new CellLight[static_cast<std::size_t>(cellsX) * cellsY]);

  std::vector<PixelSums> rowTotals(cellsY);
  std::vector<long long> rowLitCells(cellsY);
  // Each cell row is summed by one thread in a fixed order (the table is bit-identical whatever the thread
  // count).
  sat_ = SummedAreaTable<5>(cellsX, cellsY, [&](int cy, std::span<Values> out) {
    thread_local std::vector<PixelSums> sums;
    sums.assign(cellsX, PixelSums{});
    accumulateRows(probe, cy * cellSize, std::min(H, (cy + 1) * cellSize), 0, W, cellSize, sums);
    PixelSums total;
    long long litCells = 0;
    for (int cx = 0; cx < cellsX; ++cx) {
      const PixelSums& c = sums[cx];
      out[cx] = {c.energy, c.moment.x, c.moment.y, c.moment.z, c.litPixels > 0 ? 1.0 : 0.0};
      total += c;
      litCells += c.litPixels > 0;
      if (cells_) {
        cells_[static_cast<std::size_t>(cy) * cellsX + cx] = {
            {c.rgb[0], c.rgb[1], c.rgb[2]}, c.solidAngle, c.energy2, {c.moment2.x, c.moment2.y, c.moment2.z}};
      }
    }
    rowTotals[cy] = total;
    rowLitCells[cy] = litCells;
  });

  PixelSums total;
  for (const PixelSums& r : rowTotals) total += r;
  integral_ = total.rgb;
  totalEnergy_ = total.energy;
  for (long long n : rowLitCells) litCells_ += n;
}

PixelSums MomentTable::cellSums(const Rect& c) const {
  PixelSums s;
  RegionMoments m = moments(c);
  s.energy = m.energy;
  s.moment = m.moment;
  s.litPixels = m.litCells;  // lit cells: all a light needs to know is that there is light
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x) {
      const CellLight& cell = cells_[static_cast<std::size_t>(y) * sat_.width() + x];
      for (int k = 0; k < 3; ++k) s.rgb[k] += cell.rgb[k];
      s.solidAngle += cell.solidAngle;
      s.energy2 += cell.energy2;
      s.moment2 += Vec3{cell.moment2[0], cell.moment2[1], cell.moment2[2]};
    }
  return s;
}

Rect MomentTable::toPixels(const Rect& c) const {
  return {c.x0 * cellSize_, c.y0 * cellSize_, std::min(pixelWidth_, c.x1 * cellSize_),
          std::min(pixelHeight_, c.y1 * cellSize_)};
}

}  // namespace probelights
