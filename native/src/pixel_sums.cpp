#include "probelights/pixel_sums.h"

#include <algorithm>
#include <type_traits>
#include <vector>

#include "lanes.h"

namespace probelights {

PixelSums& PixelSums::operator+=(const PixelSums& o) {
  for (int k = 0; k < 3; ++k) rgb[k] += o.rgb[k];
  solidAngle += o.solidAngle;
  energy += o.energy;
  moment += o.moment;
  energy2 += o.energy2;
  moment2 += o.moment2;
  litPixels += o.litPixels;
  return *this;
}

namespace {

// The lat-long loop. A pixel's weights are its row's (dOmega, cos el, sin el) and its column's (cos phi,
// sin phi), so rows are taken four at a time, one row per lane: each lane sums its row's pixels of a cell,
// the lanes are scaled by their rows' weights and added once per cell, ((l0 + l1) + (l2 + l3)). A group of
// fewer rows fills its empty lanes with its first row at weight 0 (0 exactly). The lanes are lanes.h's: a
// vector of four doubles in the AVX2 clone, two SSE2 pairs (rows 0-1, rows 2-3) in the portable build, the
// same bits either way. Band and whole builds stay bit-identical; a cell of one pixel gets exactly the
// products the full-resolution table writes (MomentTable's lat-long rows).
using namespace lanes;

struct LatLongRows {
  const ImageView& view;
  const Projection& projection;
  int y0, y1, x0, x1, cellSize;
  PixelSums* cells;
};

// The four rows' samples of one channel at column offset `at`, as doubles; NaN, Inf and values beyond FLT_MAX
// read as 0 (Probe::finite); `odd` collects, when checking, whether any was negative, NaN or Inf. (Vectors go
// in and out by reference: by value a four-double vector would change the ABI between the two builds.)
template <class V, bool Check>
[[gnu::always_inline]] inline void samples4(const float* const* p, std::ptrdiff_t at,
                                            typename Lanes<V>::Mask& odd, V& out) {
  using L = Lanes<V>;
  V v, zero, lo, hi;
  L::load(p[0][at], p[1][at], p[2][at], p[3][at], v);
  L::splat(0, zero), L::splat(-kMax, lo), L::splat(kMax, hi);
  if constexpr (Check) odd = odd | ~((v >= zero) & (v <= hi));
  L::keep(v, (v >= lo) & (v <= hi), out);
}

template <class V, bool Grey, bool Squares, bool Check>
[[gnu::always_inline]] inline bool latLongGroups(const LatLongRows& a) {
  using L = Lanes<V>;
  using M = typename L::Mask;
  const std::ptrdiff_t step = a.view.pixelStep();
  V zero, wR, wG, wB;
  L::splat(0, zero), L::splat(0.2126, wR), L::splat(0.7152, wG), L::splat(0.0722, wB);
  const M none = zero > zero;
  const double* cosPhi = a.projection.latLongRow(a.y0).cosPhi;
  const double* sinPhi = a.projection.latLongRow(a.y0).sinPhi;
  const auto pieceBytes = static_cast<std::ptrdiff_t>(a.x1 - a.x0) * step * 4;
  M odd = none;
  for (int g = a.y0; g < a.y1; g += 4) {
    const int rows = std::min(4, a.y1 - g);
    // A region's rows are short pieces of long image rows, which the hardware prefetcher picks up late:
    // ask for the next group's pieces now.
    if (a.x1 - a.x0 < a.view.width)
      for (int y = g + 4; y < std::min(a.y1, g + 8); ++y) {
        const char* next = reinterpret_cast<const char*>(a.view.pixel(a.x0, y));
        for (std::ptrdiff_t b = 0; b < pieceBytes; b += 64) __builtin_prefetch(next + b);
      }
    const float* p[4];
    V dw = zero, dwCos = zero, dwSin = zero;
    for (int k = 0; k < 4; ++k) {
      const int y = k < rows ? g + k : g;
      p[k] = a.view.pixel(a.x0, y);
      if (k >= rows) continue;
      const auto row = a.projection.latLongRow(y);
      L::set(dw, k, row.solidAngle), L::set(dwCos, k, row.solidAngle * row.cosEl);
      L::set(dwSin, k, row.solidAngle * row.sinEl);
    }
    for (int x = a.x0, c = 0; x < a.x1; ++c) {
      const int end = std::min(a.x1, x + a.cellSize), count = end - x;
      V r = zero, gr = zero, b = zero, sY = zero, sYc = zero, sYs = zero, sY2 = zero, sY2c = zero,
        sY2s = zero;
      M lit = none;
      for (; x < end; ++x) {
        const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(x - a.x0) * step;
        V Rs = zero, Gs = zero, Bs = zero;
        samples4<V, Check>(p, at, odd, Rs);
        if constexpr (Grey) {
          Gs = Rs, Bs = Rs;
        } else {
          samples4<V, Check>(p, at + 1, odd, Gs), samples4<V, Check>(p, at + 2, odd, Bs);
        }
        // Colours keep a negative sample's sign (Probe::light); the weights read it as 0.
        V R, G, B;
        L::keep(Rs, Rs > zero, R), L::keep(Gs, Gs > zero, G), L::keep(Bs, Bs > zero, B);
        const V Y = wR * R + wG * G + wB * B;
        const double cp = cosPhi[x], sp = sinPhi[x];
        r = r + Rs, gr = gr + Gs, b = b + Bs;
        sY = sY + Y, sYc = sYc + Y * cp, sYs = sYs + Y * sp;
        if constexpr (Squares) {
          const V Y2 = Y * Y;
          sY2 = sY2 + Y2, sY2c = sY2c + Y2 * cp, sY2s = sY2s + Y2 * sp;
        }
        lit = lit - (Y > zero);
      }
      PixelSums& s = a.cells[c];
      s.rgb[0] += hsum(r * dw), s.rgb[1] += hsum(gr * dw), s.rgb[2] += hsum(b * dw);
      s.solidAngle += hsum(dw * static_cast<double>(count));
      s.energy += hsum(sY * dw);
      s.moment += Vec3{hsum(sYc * dwCos), hsum(sYs * dwCos), hsum(sY * dwSin)};
      if constexpr (Squares) {
        s.energy2 += hsum(sY2 * dw);
        s.moment2 += Vec3{hsum(sY2c * dwCos), hsum(sY2s * dwCos), hsum(sY2 * dwSin)};
      }
      for (int k = 0; k < rows; ++k) s.litPixels += L::get(lit, k);
    }
  }
  return (L::get(odd, 0) | L::get(odd, 1) | L::get(odd, 2) | L::get(odd, 3)) != 0;
}

// The three choices (grey, squares, check) become the loop's template arguments here, once (a switch, not
// lambdas: a lambda would be compiled for the default target inside the AVX2 clone too).
template <class V>
[[gnu::always_inline]] inline bool latLongChoices(const LatLongRows& a, bool grey, bool squares, bool check) {
  switch ((grey ? 4 : 0) | (squares ? 2 : 0) | (check ? 1 : 0)) {
    case 0:
      return latLongGroups<V, false, false, false>(a);
    case 1:
      return latLongGroups<V, false, false, true>(a);
    case 2:
      return latLongGroups<V, false, true, false>(a);
    case 3:
      return latLongGroups<V, false, true, true>(a);
    case 4:
      return latLongGroups<V, true, false, false>(a);
    case 5:
      return latLongGroups<V, true, false, true>(a);
    case 6:
      return latLongGroups<V, true, true, false>(a);
    default:
      return latLongGroups<V, true, true, true>(a);
  }
}

bool latLongPortable(const LatLongRows& a, bool grey, bool squares, bool check) {
  return latLongChoices<Pairs>(a, grey, squares, check);
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) bool latLongAvx2(const LatLongRows& a, bool grey, bool squares, bool check) {
  return latLongChoices<D4>(a, grey, squares, check);
}
#endif

bool latLongRows(const LatLongRows& a, bool grey, bool squares, bool check) {
#if defined(__x86_64__)
  if (hasAvx2()) return latLongAvx2(a, grey, squares, check);
#endif
  return latLongPortable(a, grey, squares, check);
}

}  // namespace

void accumulateRows(const Probe& probe, int y0, int y1, int x0, int x1, int cellSize,
                    std::span<PixelSums> cells, bool squares, bool* oddSamples) {
  const Projection& projection = probe.projection();
  if (oddSamples) *oddSamples = true;  // unless the lat-long loop below looked
  if (projection.kind() == ProjectionKind::LatLong) {
    if (y0 >= y1 || x0 >= x1) {
      if (oddSamples) *oddSamples = false;
      return;
    }
    const bool odd = latLongRows({probe.view(), projection, y0, y1, x0, x1, cellSize, cells.data()},
                                 probe.view().channels < 3, squares, oddSamples != nullptr);
    if (oddSamples) *oddSamples = odd;
    return;
  }
  // Ball and angular maps: per-pixel directions and solid angles.
  thread_local std::vector<Vec3> dirs;
  thread_local std::vector<double> omega;
  dirs.resize(x1 - x0);
  omega.resize(x1 - x0);
  for (int y = y0; y < y1; ++y) {
    projection.rowGeometry(y, x0, x1, dirs, omega);
    for (int x = x0; x < x1; ++x) {
      PixelSums& s = cells[(x - x0) / cellSize];
      const Rgb light = probe.light(x, y), L = probe.radiance(x, y);
      const double dw = omega[x - x0], Y = luminance(L), w = Y * dw;
      const Vec3& d = dirs[x - x0];
      for (int k = 0; k < 3; ++k) s.rgb[k] += light[k] * dw;
      s.solidAngle += dw;
      s.energy += w;
      s.moment += w * d;
      s.energy2 += w * Y;
      s.moment2 += (w * Y) * d;
      s.litPixels += w > 0;
    }
  }
}

PixelSums sumPixels(const Probe& probe, const Rect& r, bool squares) {
  PixelSums s;
  accumulateRows(probe, r.y0, r.y1, r.x0, r.x1, r.width(), std::span<PixelSums>(&s, 1), squares);
  return s;
}

}  // namespace probelights
