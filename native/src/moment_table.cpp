// The working grid's moments (moment_table.h): summed-area tables built from the pixels, cell row by cell row
// for a coarse grid or four pixels at a time at full resolution; or, for a probe too wide for tables at full
// resolution, no tables: the column and row sums of each region a cut rule sweeps, from its pixels.
#include "probelights/moment_table.h"

#include <algorithm>
#include <charconv>
#include <span>

#include "moment_rows.h"
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

MomentTable::MomentTable(const Probe& probe, int cellSize, CentroidWeight centroid, PixelReport* counts,
                         Storage storage)
    : cellSize_(cellSize), pixelWidth_(probe.width()), pixelHeight_(probe.height()) {
  probe.requirePixels("building the working grid");
  if (cellSize == 1 && probe.projection().kind() == ProjectionKind::LatLong &&
      (storage == Storage::Pixels || (storage == Storage::Auto && probe.width() > kTablesUpToWidth))) {
    buildWithoutTables(probe, counts);
    return;
  }
  allocate(centroid);
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
  allocate(centroid);
}

void MomentTable::allocate(CentroidWeight centroid) {
  if (cellSize_ < 1) throw Error("working-grid cell size must be at least 1 pixel");
  const int cellsX = (pixelWidth_ + cellSize_ - 1) / cellSize_,
            cellsY = (pixelHeight_ + cellSize_ - 1) / cellSize_;
  // A coarse grid keeps every cell's sums, so lights are summed from cells without reading the image again;
  // at full resolution that would be 32 (or 64) bytes a pixel, and lights re-read their regions' pixels
  // instead.
  if (cellSize_ > 1) {
    const auto n = static_cast<std::size_t>(cellsX) * cellsY;
    cells_ = keptArray<CellLight>(n);
    if (centroid == CentroidWeight::Energy2) second_ = keptArray<CellSecond>(n);
  }
  sat_ = SummedAreaTable<5>(cellsX, cellsY);
  rowTotals_.assign(cellsY, PixelSums{});
  rowLitCells_.assign(cellsY, 0);
}

void MomentTable::buildWithoutTables(const Probe& probe, PixelReport* counts) {
  // One pass for the probe's totals (and the pixels' check), four rows at a time; the regions' sums come
  // later, from the pixels, when the cuts sweep them.
  pixels_.emplace(Probe::unchecked(probe.view(), ProjectionKind::LatLong));
  const int groups = (pixelHeight_ + 3) / 4;
  std::vector<PixelSums> sums(groups);
  std::vector<char> odd(groups, 0);
  parallelFor(groups, [&](std::int64_t g) {
    const int y0 = static_cast<int>(g) * 4, y1 = std::min(pixelHeight_, y0 + 4);
    bool o = true;
    accumulateRows(*pixels_, y0, y1, 0, pixelWidth_, pixelWidth_, std::span<PixelSums>(&sums[g], 1), false,
                   &o);
    odd[g] = o;
  });
  PixelSums total;
  if (counts) *counts = PixelReport{};
  for (int g = 0; g < groups; ++g) {
    total += sums[g];
    if (!counts) continue;
    const int y0 = g * 4, y1 = std::min(pixelHeight_, y0 + 4);
    if (odd[g]) {
      counts->add(probe.countRows(y0, y1));
    } else {
      PixelReport r;
      r.positiveLight = sums[g].energy;
      counts->add(r);
    }
  }
  integral_ = total.rgb;
  totalEnergy_ = total.energy;
  litCells_ = total.litPixels;
  whole_ = {total.energy, total.moment, total.litPixels};
}

void MomentTable::marginals(const Rect& cells, std::vector<Sums>& columns, std::vector<Sums>& rows) const {
  if (hasTables()) throw Error("MomentTable::marginals: the table has summed-area tables (use moments)");
  const Probe& probe = *pixels_;
  const ImageView& view = probe.view();
  const int width = cells.width(), height = cells.height(), padded = (width + 3) / 4 * 4;
  const auto first = probe.projection().latLongRow(cells.y0);
  rows.assign(height, Sums{});
  // Rows in blocks of a fixed height (not of the thread count): each block sums its columns on its own, the
  // blocks are then added in order, so the sums are the same bits however many threads ran.
  constexpr int kBlockRows = 256;
  const int blocks = (height + kBlockRows - 1) / kBlockRows;
  std::vector<std::vector<double>> blockColumns(blocks);
  parallelFor(blocks, [&](std::int64_t b) {
    std::vector<double>& c = blockColumns[b];
    c.assign(5 * static_cast<std::size_t>(padded), 0.0);
    const int y0 = cells.y0 + static_cast<int>(b) * kBlockRows, y1 = std::min(cells.y1, y0 + kBlockRows);
    for (int y = y0; y < y1; ++y) {
      const auto row = probe.projection().latLongRow(y);
      const double dw = row.solidAngle;
      rowsum::MarginalRow a{view.pixel(cells.x0, y), view.pixelStep(),        width,
                            first.cosPhi + cells.x0, first.sinPhi + cells.x0, dw,
                            dw * row.cosEl,          dw * row.sinEl,          {}};
      for (int k = 0; k < 5; ++k) a.columns[k] = c.data() + static_cast<std::size_t>(k) * padded;
      rowsum::sumMarginalRow(a, view.channels < 3, rows[y - cells.y0]);
    }
  });
  columns.assign(width, Sums{});
  for (const std::vector<double>& c : blockColumns)
    for (int x = 0; x < width; ++x)
      for (int k = 0; k < 5; ++k) columns[x][k] += c[static_cast<std::size_t>(k) * padded + x];
}

RegionMoments MomentTable::summedMoments(const Rect& cells) const {
  if (cells.x0 == 0 && cells.y0 == 0 && cells.x1 == width() && cells.y1 == height()) return whole_;
  std::vector<Sums> columns, rows;
  marginals(cells, columns, rows);
  Sums s{};
  for (const Sums& c : columns)
    for (int k = 0; k < 5; ++k) s[k] += c[k];
  return {s[0], {s[1], s[2], s[3]}, std::llround(s[4])};
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
  // Full resolution, lat-long: each cell is one pixel, so its table values are made straight from the
  // pixel with the products accumulateRows makes for a cell of one pixel (tableRow) and summed along the row
  // in the same loop, without its per-cell sums of everything a light needs (lights re-read their pixels).
  const ImageView& view = band.view();
  const bool grey = view.channels < 3;
  const auto first = band.projection().latLongRow(y0);
  sat_.fillRowSums(y0, y1, [&](int y, double* out, const double* above) {
    const auto row = band.projection().latLongRow(y);
    const double dw = row.solidAngle;
    rowsum::RowTotals t;
    rowsum::sumTableRow({view.pixel(0, y), view.pixelStep(), pixelWidth_, first.cosPhi, first.sinPhi, dw,
                         dw * row.cosEl, dw * row.sinEl, out, above},
                        grey, t);
    PixelSums total;
    total.rgb = {t.rgb[0], t.rgb[1], t.rgb[2]};
    total.energy = t.energy;
    rowTotals_[y] = total;
    rowLitCells_[y] = t.lit;
    checkRows(band, y, t.odd, y, y + 1, t.energy);
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
