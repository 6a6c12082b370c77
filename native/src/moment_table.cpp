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

MomentTable::MomentTable(const Probe& probe, int cellSize, CentroidWeight centroid, PixelReport* counts)
    : MomentTable(probe.width(), probe.height(), cellSize, centroid) {
  probe.requirePixels("building the working grid");
  if (counts) rowCounts_.assign(height(), PixelReport{});
  addBand(probe, 0, probe.height());
  finish();
  if (counts) {
    *counts = PixelReport{};
    for (const PixelReport& r : rowCounts_) counts->add(r);
    rowCounts_ = {};
  }
}

MomentTable::MomentTable(int pixelWidth, int pixelHeight, int cellSize, CentroidWeight centroid)
    : cellSize_(cellSize), pixelWidth_(pixelWidth), pixelHeight_(pixelHeight) {
  if (cellSize < 1) throw Error("working-grid cell size must be at least 1 pixel");
  const int cellsX = (pixelWidth + cellSize - 1) / cellSize, cellsY = (pixelHeight + cellSize - 1) / cellSize;
  // A coarse grid keeps every cell's sums, so lights are summed from cells without reading the image again;
  // at full resolution that would be 32 (or 64) bytes a pixel, and lights re-read their regions' pixels
  // instead.
  if (cellSize > 1) {
    const auto n = static_cast<std::size_t>(cellsX) * cellsY;
    cells_ = keptArray<CellLight>(n);
    if (centroid == CentroidWeight::Energy2) second_ = keptArray<CellSecond>(n);
  }
  sat_ = SummedAreaTable<5>(cellsX, cellsY);
  rowTotals_.assign(cellsY, PixelSums{});
  rowLitCells_.assign(cellsY, 0);
}

void MomentTable::addBand(const Probe& band, int y0, int y1) {
  const int W = pixelWidth_, H = pixelHeight_, cellSize = cellSize_, cellsX = sat_.width();
  if (y0 % cellSize != 0 || (y1 % cellSize != 0 && y1 != H) || y0 >= y1)
    throw Error("a band of the working grid must cover whole cell rows");
  using Values = SummedAreaTable<5>::Values;
  if (cellSize == 1 && band.projection().kind() == ProjectionKind::LatLong) {
    addLatLongPixels(band, y0, y1);
    return;
  }
  // Each cell row is summed by one thread in a fixed order (the table is bit-identical whatever the thread
  // count).
  sat_.fillRows(y0 / cellSize, (y1 + cellSize - 1) / cellSize, [&](int cy, std::span<Values> out) {
    thread_local std::vector<PixelSums> sums;
    sums.assign(cellsX, PixelSums{});
    const int rows0 = cy * cellSize, rows1 = std::min(H, (cy + 1) * cellSize);
    bool odd = true;
    accumulateRows(band, rows0, rows1, 0, W, cellSize, sums, true, rowCounts_.empty() ? nullptr : &odd);
    PixelSums total;
    long long litCells = 0;
    for (int cx = 0; cx < cellsX; ++cx) {
      const PixelSums& c = sums[cx];
      out[cx] = {c.energy, c.moment.x, c.moment.y, c.moment.z, c.litPixels > 0 ? 1.0 : 0.0};
      total += c;
      litCells += c.litPixels > 0;
      const auto i = static_cast<std::size_t>(cy) * cellsX + cx;
      if (cells_) cells_[i] = {{c.rgb[0], c.rgb[1], c.rgb[2]}, c.solidAngle};
      if (second_) second_[i] = {c.energy2, {c.moment2.x, c.moment2.y, c.moment2.z}};
    }
    rowTotals_[cy] = total;
    rowLitCells_[cy] = litCells;
    // The pixels' check, when asked: rows where the sums met a negative, NaN or Inf sample are counted
    // (still in cache); in the others there is nothing to count, and their light is the energy just summed.
    checkRows(band, cy, odd, rows0, rows1, total.energy);
  });
}

void MomentTable::addLatLongPixels(const Probe& band, int y0, int y1) {
  // Full resolution, lat-long: each cell is one pixel, so its five table values are written straight from the
  // pixel with the same operations, in the same order, as accumulateRows would sum them into a cell of one
  // (bit-identical), without its per-cell sums of everything a light needs (lights re-read their pixels).
  const ImageView& view = band.view();
  const std::ptrdiff_t step = view.pixelStep();
  const bool grey = view.channels < 3;
  using Values = SummedAreaTable<5>::Values;
  sat_.fillRows(y0, y1, [&](int y, std::span<Values> out) {
    const auto row = band.projection().latLongRow(y);
    const double dw = row.solidAngle, dwCos = dw * row.cosEl, dwSin = dw * row.sinEl;
    const float* p = view.pixel(0, y);
    double r = 0, g = 0, b = 0, energy = 0;
    long long lit = 0;
    bool odd = false;  // a negative, NaN or Inf sample in the row (for the pixels' check)
    for (int x = 0; x < pixelWidth_; ++x, p += step) {
      for (int k = 0; k < (grey ? 1 : 3); ++k) odd |= !(p[k] >= 0.0f && p[k] <= 3.4028234e38f);
      const double Rs = Probe::finite(p[0]), Gs = grey ? Rs : Probe::finite(p[1]),
                   Bs = grey ? Rs : Probe::finite(p[2]);
      const double R = Rs > 0 ? Rs : 0.0, G = Gs > 0 ? Gs : 0.0, B = Bs > 0 ? Bs : 0.0;
      const double Y = luminance(R, G, B);
      double sY = 0, sYc = 0, sYs = 0;
      sY += Y, sYc += Y * row.cosPhi[x], sYs += Y * row.sinPhi[x];
      double e = 0, mx = 0, my = 0, mz = 0;
      e += sY * dw, mx += dwCos * sYc, my += dwCos * sYs, mz += dwSin * sY;
      out[x] = {e, mx, my, mz, Y > 0 ? 1.0 : 0.0};
      double cr = 0, cg = 0, cb = 0, sr = 0, sg = 0, sb = 0;
      sr += Rs, sg += Gs, sb += Bs;
      cr += sr * dw, cg += sg * dw, cb += sb * dw;
      r += cr, g += cg, b += cb, energy += e;
      lit += Y > 0;
    }
    PixelSums total;
    total.rgb = {r, g, b};
    total.energy = energy;
    rowTotals_[y] = total;
    rowLitCells_[y] = lit;
    checkRows(band, y, odd, y, y + 1, energy);
  });
}

void MomentTable::checkRows(const Probe& band, int cellRow, bool odd, int y0, int y1, double energy) {
  if (rowCounts_.empty()) return;
  if (odd)
    rowCounts_[cellRow] = band.countRows(y0, y1);
  else
    rowCounts_[cellRow].positiveLight = energy;
}

void MomentTable::finish() {
  sat_.finish();
  PixelSums total;
  for (const PixelSums& r : rowTotals_) total += r;
  integral_ = total.rgb;
  totalEnergy_ = total.energy;
  litCells_ = 0;
  for (long long n : rowLitCells_) litCells_ += n;
  rowTotals_ = {};
  rowLitCells_ = {};
}

PixelSums MomentTable::cellSums(const Rect& c) const {
  PixelSums s;
  RegionMoments m = moments(c);
  s.energy = m.energy;
  s.moment = m.moment;
  s.litPixels = m.litCells;  // lit cells: all a light needs to know is that there is light
  for (int y = c.y0; y < c.y1; ++y)
    for (int x = c.x0; x < c.x1; ++x) {
      const auto i = static_cast<std::size_t>(y) * sat_.width() + x;
      const CellLight& cell = cells_[i];
      for (int k = 0; k < 3; ++k) s.rgb[k] += cell.rgb[k];
      s.solidAngle += cell.solidAngle;
      if (second_) {
        s.energy2 += second_[i].energy2;
        s.moment2 += Vec3{second_[i].moment2[0], second_[i].moment2[1], second_[i].moment2[2]};
      }
    }
  return s;
}

Rect MomentTable::toPixels(const Rect& c) const {
  return {c.x0 * cellSize_, c.y0 * cellSize_, std::min(pixelWidth_, c.x1 * cellSize_),
          std::min(pixelHeight_, c.y1 * cellSize_)};
}

}  // namespace probelights
