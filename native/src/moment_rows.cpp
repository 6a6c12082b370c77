// The working grid's row kernels (moment_rows.h).
#include "moment_rows.h"

#include <algorithm>

#include "lanes.h"

namespace probelights::rowsum {

using namespace lanes;

namespace {

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

}  // namespace

void sumMarginalRow(const MarginalRow& a, bool grey, MomentTable::Sums& row) {
#if defined(__x86_64__)
  if (hasAvx2()) return marginalRowAvx2(a, grey, row);
#endif
  marginalRowPortable(a, grey, row);
}

namespace {

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

}  // namespace

void sumTableRow(const TableRow& a, bool grey, RowTotals& t) {
#if defined(__x86_64__)
  if (hasAvx2()) return tableRowAvx2(a, grey, t);
#endif
  tableRowPortable(a, grey, t);
}

}  // namespace probelights::rowsum
