// The working grid's moments (moment_table.h): summed-area tables built from the pixels, cell row by cell row
// for a coarse grid or four pixels at a time at full resolution; or, for a probe too wide for tables at full
// resolution, no tables: the column and row sums of each region a cut rule sweeps, from its pixels.
#include "probelights/moment_table.h"

#include <algorithm>
#include <charconv>
#include <span>

#include "lanes.h"
#include "parallel.h"
#include "probelights/error.h"

namespace probelights {

namespace {

using namespace lanes;

// One row of the full-resolution lat-long table (MomentTable::addLatLongPixels), and what it adds up.
struct TableRow {
  const float* pixels;
  std::ptrdiff_t step;
  int width;
  const double *cosPhi, *sinPhi;
  double dw, dwCos, dwSin;
  double* out;          // the table row's entries, pixel x at out[(x + 1) * 5]
  const double* above;  // the row above's final entries (Above), or none (pass 1 of two)
};
struct RowTotals {
  double rgb[3], energy;
  long long lit;
  bool odd;  // a negative, NaN or Inf sample in the row (for the pixels' check)
};

// Samples p[0], p[step], ... of n <= 4 pixels (0 past them); NaN, Inf and beyond FLT_MAX read as 0
// (Probe::finite). `odd`, when given, collects the lanes that read a negative, NaN or Inf sample.
template <class V>
[[gnu::always_inline]] inline void finiteSamples(const float* p, std::ptrdiff_t step, int n, const V& lo,
                                                 const V& hi, V& out,
                                                 typename Lanes<V>::Mask* odd = nullptr) {
  using L = Lanes<V>;
  V raw, zero;
  if (n == 4)
    L::load(p[0], p[step], p[2 * step], p[3 * step], raw);
  else
    L::load(p[0], n > 1 ? p[step] : 0.0f, n > 2 ? p[2 * step] : 0.0f, 0.0f, raw);
  L::splat(0, zero);
  if (odd) *odd = *odd | ~((raw >= zero) & (raw <= hi));
  L::keep(raw, (raw >= lo) & (raw <= hi), out);
}

// Four pixels at a time, one per lane: their samples, luminance and four weighted moments (w, w dx, w dy,
// w dz: the products accumulateRows makes for a cell of one pixel) as vectors, then turned (transpose) into
// one vector per pixel, so the running sums along the row are one vector add per pixel, channel by channel
// in pixel order. The row's totals are four partial sums, one per lane, added at the end.
template <class V, bool Grey, bool Above>
struct TableRowLoop {
  using L = Lanes<V>;
  using M = typename L::Mask;
  const TableRow& a;
  // Locals, not a's fields: the stores to the table could alias `a` and have them re-read every pixel.
  const float* const pixels = a.pixels;
  const double* const cosPhiAt = a.cosPhi;
  const double* const sinPhiAt = a.sinPhi;
  const double* const above = a.above;
  double* __restrict const out = a.out;
  const std::ptrdiff_t step = a.step;
  V zero, one, lo, hi, wR, wG, wB, dw, dwCos, dwSin;
  V run, sumR, sumG, sumB, sumE;
  M odd, lit;
  double runLit = 0;

  explicit TableRowLoop(const TableRow& row) : a(row) {
    L::splat(0, zero), L::splat(1, one), L::splat(-kMax, lo), L::splat(kMax, hi);
    L::splat(0.2126, wR), L::splat(0.7152, wG), L::splat(0.0722, wB);
    L::splat(a.dw, dw), L::splat(a.dwCos, dwCos), L::splat(a.dwSin, dwSin);
    run = sumR = sumG = sumB = sumE = zero;
    odd = lit = zero > zero;
  }

  // Channel c of pixels x .. x + n - 1 (0 past them): NaN, Inf and beyond FLT_MAX read as 0 (Probe::finite);
  // `odd` collects negative, NaN or Inf.
  template <int N>
  [[gnu::always_inline]] void channel(int x, int n, int c, V& s) {
    finiteSamples(pixels + static_cast<std::ptrdiff_t>(x) * step + c, step, N == 4 ? 4 : n, lo, hi, s, &odd);
  }

  [[gnu::always_inline]] void write(int x, const V& value, double lit1) {
    run = run + value;
    runLit += lit1;
    const std::ptrdiff_t at = (static_cast<std::ptrdiff_t>(x) + 1) * 5;
    if constexpr (Above) {
      V up;
      L::loadu(above + at, up);
      L::storeu(out + at, up + run);
      out[at + 4] = above[at + 4] + runLit;
    } else {
      L::storeu(out + at, run);
      out[at + 4] = runLit;
    }
  }

  // Pixels x .. x + n - 1: all four lanes (N = 4), or the row's last n < 4 (N = 0).
  template <int N>
  [[gnu::always_inline]] void group(int x, int n) {
    V Rs, Gs, Bs, cosPhi, sinPhi;
    channel<N>(x, n, 0, Rs);
    if constexpr (Grey) {
      Gs = Rs, Bs = Rs;
    } else {
      channel<N>(x, n, 1, Gs), channel<N>(x, n, 2, Bs);
    }
    if constexpr (N == 4) {
      L::loadu(cosPhiAt + x, cosPhi), L::loadu(sinPhiAt + x, sinPhi);
    } else {
      cosPhi = sinPhi = zero;
      for (int k = 0; k < n; ++k) L::set(cosPhi, k, cosPhiAt[x + k]), L::set(sinPhi, k, sinPhiAt[x + k]);
    }
    V R, G, B, lit1;
    L::keep(Rs, Rs > zero, R), L::keep(Gs, Gs > zero, G), L::keep(Bs, Bs > zero, B);
    const V Y = wR * R + wG * G + wB * B;
    V e = Y * dw, mx = (Y * cosPhi) * dwCos, my = (Y * sinPhi) * dwCos, mz = Y * dwSin;
    const M isLit = Y > zero;
    L::keep(one, isLit, lit1);
    lit = lit - isLit;
    sumR = sumR + Rs * dw, sumG = sumG + Gs * dw, sumB = sumB + Bs * dw, sumE = sumE + e;
    L::transpose(e, mx, my, mz);  // now one vector per pixel: (w, w dx, w dy, w dz)
    write(x, e, L::get(lit1, 0));
    if (N == 4 || n > 1) write(x + 1, mx, L::get(lit1, 1));
    if (N == 4 || n > 2) write(x + 2, my, L::get(lit1, 2));
    if (N == 4) write(x + 3, mz, L::get(lit1, 3));
  }

  [[gnu::always_inline]] void operator()(RowTotals& t) {
    int x = 0;
    for (; x + 4 <= a.width; x += 4) group<4>(x, 4);
    if (x < a.width) group<0>(x, a.width - x);
    t = {{hsum(sumR), hsum(sumG), hsum(sumB)},
         hsum(sumE),
         L::get(lit, 0) + L::get(lit, 1) + L::get(lit, 2) + L::get(lit, 3),
         (L::get(odd, 0) | L::get(odd, 1) | L::get(odd, 2) | L::get(odd, 3)) != 0};
  }
};

// Four pixels at a time, one per lane: their samples, luminance and four weighted moments (w, w dx, w dy,
// w dz: the products accumulateRows makes for a cell of one pixel) as vectors, then turned (transpose) into
// one vector per pixel, so the running sums along the row are one vector add per pixel, channel by channel
// in pixel order. The row's totals are four partial sums, one per lane, added at the end.
template <class V, bool Grey, bool Above>
[[gnu::always_inline]] inline void tableRow(const TableRow& a, RowTotals& t) {
  TableRowLoop<V, Grey, Above> loop(a);
  loop(t);
}

// One row of a region for its column and row sums (MomentTable::marginals): four pixels at a time, one per
// lane, with the table's products; each column's sums (five arrays, padded to whole groups of four) gain the
// row's values, the row's sums are four partial sums per channel added at the end.
struct MarginalRow {
  const float* pixels;  // the region's first pixel in the row
  std::ptrdiff_t step;
  int width;
  const double *cosPhi, *sinPhi;  // from the region's first column
  double dw, dwCos, dwSin;
  double* columns[5];  // per channel, width rounded up to four
};

template <class V, bool Grey>
[[gnu::always_inline]] inline void marginalRow(const MarginalRow& a, MomentTable::Sums& row) {
  using L = Lanes<V>;
  using M = typename L::Mask;
  V zero, one, lo, hi, wR, wG, wB, dw, dwCos, dwSin;
  L::splat(0, zero), L::splat(1, one), L::splat(-kMax, lo), L::splat(kMax, hi);
  L::splat(0.2126, wR), L::splat(0.7152, wG), L::splat(0.0722, wB);
  L::splat(a.dw, dw), L::splat(a.dwCos, dwCos), L::splat(a.dwSin, dwSin);
  V sums[5] = {zero, zero, zero, zero, zero};
  const float* const pixels = a.pixels;
  const std::ptrdiff_t step = a.step;
  double* __restrict const c0 = a.columns[0];
  double* __restrict const c1 = a.columns[1];
  double* __restrict const c2 = a.columns[2];
  double* __restrict const c3 = a.columns[3];
  double* __restrict const c4 = a.columns[4];
  for (int x = 0; x < a.width; x += 4) {
    const int n = std::min(4, a.width - x);
    const float* p = pixels + static_cast<std::ptrdiff_t>(x) * step;
    V Rs, Gs, Bs, cosPhi, sinPhi;
    finiteSamples(p, step, n, lo, hi, Rs);
    if constexpr (Grey) {
      Gs = Rs, Bs = Rs;
    } else {
      finiteSamples(p + 1, step, n, lo, hi, Gs), finiteSamples(p + 2, step, n, lo, hi, Bs);
    }
    if (n == 4) {
      L::loadu(a.cosPhi + x, cosPhi), L::loadu(a.sinPhi + x, sinPhi);
    } else {
      cosPhi = sinPhi = zero;
      for (int k = 0; k < n; ++k) L::set(cosPhi, k, a.cosPhi[x + k]), L::set(sinPhi, k, a.sinPhi[x + k]);
    }
    V R, G, B, lit1;
    L::keep(Rs, Rs > zero, R), L::keep(Gs, Gs > zero, G), L::keep(Bs, Bs > zero, B);
    const V Y = wR * R + wG * G + wB * B;
    const M isLit = Y > zero;
    L::keep(one, isLit, lit1);
    const V values[5] = {Y * dw, (Y * cosPhi) * dwCos, (Y * sinPhi) * dwCos, Y * dwSin, lit1};
    double* const columns[5] = {c0, c1, c2, c3, c4};
    for (int k = 0; k < 5; ++k) {
      V column;
      L::loadu(columns[k] + x, column);
      L::storeu(columns[k] + x, column + values[k]);
      sums[k] = sums[k] + values[k];
    }
  }
  for (int k = 0; k < 5; ++k) row[k] = hsum(sums[k]);
}

void marginalRowPortable(const MarginalRow& a, bool grey, MomentTable::Sums& row) {
  grey ? marginalRow<Pairs, true>(a, row) : marginalRow<Pairs, false>(a, row);
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) void marginalRowAvx2(const MarginalRow& a, bool grey,
                                                     MomentTable::Sums& row) {
  grey ? marginalRow<D4, true>(a, row) : marginalRow<D4, false>(a, row);
}
#endif

void sumMarginalRow(const MarginalRow& a, bool grey, MomentTable::Sums& row) {
#if defined(__x86_64__)
  if (hasAvx2()) return marginalRowAvx2(a, grey, row);
#endif
  marginalRowPortable(a, grey, row);
}

template <class V>
[[gnu::always_inline]] inline void tableRowChoices(const TableRow& a, bool grey, RowTotals& t) {
  if (grey)
    a.above ? tableRow<V, true, true>(a, t) : tableRow<V, true, false>(a, t);
  else
    a.above ? tableRow<V, false, true>(a, t) : tableRow<V, false, false>(a, t);
}

void tableRowPortable(const TableRow& a, bool grey, RowTotals& t) { tableRowChoices<Pairs>(a, grey, t); }

#if defined(__x86_64__)
__attribute__((target("avx2"))) void tableRowAvx2(const TableRow& a, bool grey, RowTotals& t) {
  tableRowChoices<D4>(a, grey, t);
}
#endif

void sumTableRow(const TableRow& a, bool grey, RowTotals& t) {
#if defined(__x86_64__)
  if (hasAvx2()) return tableRowAvx2(a, grey, t);
#endif
  tableRowPortable(a, grey, t);
}

}  // namespace

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
      MarginalRow a{view.pixel(cells.x0, y), view.pixelStep(),        width,
                    first.cosPhi + cells.x0, first.sinPhi + cells.x0, dw,
                    dw * row.cosEl,          dw * row.sinEl,          {}};
      for (int k = 0; k < 5; ++k) a.columns[k] = c.data() + static_cast<std::size_t>(k) * padded;
      sumMarginalRow(a, view.channels < 3, rows[y - cells.y0]);
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
    RowTotals t;
    sumTableRow({view.pixel(0, y), view.pixelStep(), pixelWidth_, first.cosPhi, first.sinPhi, dw,
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
