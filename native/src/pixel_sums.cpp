#include "probelights/pixel_sums.h"

#include <algorithm>
#include <type_traits>
#include <vector>

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
// sin phi), so rows are taken four at a time, one row per lane of a vector of four doubles: each lane sums
// its row's pixels of a cell, the lanes are scaled by their rows' weights and added once per cell,
// ((l0 + l1) + (l2 + l3)). A group of fewer rows fills its empty lanes with its first row at weight 0 (0
// exactly). The same operations in the same order whoever calls and on any processor (the AVX2 build below
// has no FMA: no contraction), so band and whole builds stay bit-identical; a cell of one pixel gets exactly
// the products the full-resolution table writes (MomentTable::addLatLongPixels).
using D4 = double __attribute__((vector_size(32)));
using F4 = float __attribute__((vector_size(16)));
using I4 = long long __attribute__((vector_size(32)));
constexpr double kMax = 3.4028234663852886e38;  // FLT_MAX: Probe::finite's bounds

struct LatLongRows {
  const ImageView& view;
  const Projection& projection;
  int y0, y1, x0, x1, cellSize;
  PixelSums* cells;
};

[[gnu::always_inline]] inline double hsum(const D4& v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// The four rows' samples of one channel at column offset `at`, as doubles; NaN, Inf and values beyond FLT_MAX
// read as 0 (Probe::finite); `odd` collects, when checking, whether any was negative, NaN or Inf. (Vectors go
// in and out by reference: by value they would change the ABI between the portable and the AVX2 build.)
template <bool Check>
[[gnu::always_inline]] inline void samples4(const float* const* p, std::ptrdiff_t at, I4& odd, D4& out) {
  const F4 f = {p[0][at], p[1][at], p[2][at], p[3][at]};
  const D4 v = __builtin_convertvector(f, D4), zero = {0, 0, 0, 0};
  const D4 lo = {-kMax, -kMax, -kMax, -kMax}, hi = {kMax, kMax, kMax, kMax};
  if constexpr (Check) odd |= ~((v >= zero) & (v <= hi));
  out = ((v >= lo) & (v <= hi)) ? v : zero;
}

template <bool Grey, bool Squares, bool Check>
[[gnu::always_inline]] inline bool latLongGroups(const LatLongRows& a) {
  const std::ptrdiff_t step = a.view.pixelStep();
  const D4 zero = {0, 0, 0, 0};
  const D4 wR = {0.2126, 0.2126, 0.2126, 0.2126}, wG = {0.7152, 0.7152, 0.7152, 0.7152},
           wB = {0.0722, 0.0722, 0.0722, 0.0722};
  const double* cosPhi = a.projection.latLongRow(a.y0).cosPhi;
  const double* sinPhi = a.projection.latLongRow(a.y0).sinPhi;
  const auto pieceBytes = static_cast<std::ptrdiff_t>(a.x1 - a.x0) * step * 4;
  I4 odd = {0, 0, 0, 0};
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
    D4 dw = zero, dwCos = zero, dwSin = zero;
    for (int k = 0; k < 4; ++k) {
      const int y = k < rows ? g + k : g;
      p[k] = a.view.pixel(a.x0, y);
      if (k >= rows) continue;
      const auto row = a.projection.latLongRow(y);
      dw[k] = row.solidAngle, dwCos[k] = row.solidAngle * row.cosEl, dwSin[k] = row.solidAngle * row.sinEl;
    }
    for (int x = a.x0, c = 0; x < a.x1; ++c) {
      const int end = std::min(a.x1, x + a.cellSize), count = end - x;
      D4 r = zero, gr = zero, b = zero, sY = zero, sYc = zero, sYs = zero, sY2 = zero, sY2c = zero,
         sY2s = zero;
      I4 lit = {0, 0, 0, 0};
      for (; x < end; ++x) {
        const std::ptrdiff_t at = static_cast<std::ptrdiff_t>(x - a.x0) * step;
        D4 Rs, Gs, Bs;
        samples4<Check>(p, at, odd, Rs);
        if constexpr (Grey) {
          Gs = Rs, Bs = Rs;
        } else {
          samples4<Check>(p, at + 1, odd, Gs), samples4<Check>(p, at + 2, odd, Bs);
        }
        // Colours keep a negative sample's sign (Probe::light); the weights read it as 0.
        const D4 R = Rs > zero ? Rs : zero, G = Gs > zero ? Gs : zero, B = Bs > zero ? Bs : zero;
        const D4 Y = wR * R + wG * G + wB * B;
        const double cp = cosPhi[x], sp = sinPhi[x];
        r += Rs, gr += Gs, b += Bs;
        sY += Y, sYc += Y * cp, sYs += Y * sp;
        if constexpr (Squares) {
          const D4 Y2 = Y * Y;
          sY2 += Y2, sY2c += Y2 * cp, sY2s += Y2 * sp;
        }
        lit -= Y > zero;
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
      for (int k = 0; k < rows; ++k) s.litPixels += lit[k];
    }
  }
  return (odd[0] | odd[1] | odd[2] | odd[3]) != 0;
}

// The three choices (grey, squares, check) become the loop's template arguments here, once (a switch, not
// lambdas: a lambda would be compiled for the default target inside the AVX2 clone too).
[[gnu::always_inline]] inline bool latLongChoices(const LatLongRows& a, bool grey, bool squares, bool check) {
  switch ((grey ? 4 : 0) | (squares ? 2 : 0) | (check ? 1 : 0)) {
    case 0:
      return latLongGroups<false, false, false>(a);
    case 1:
      return latLongGroups<false, false, true>(a);
    case 2:
      return latLongGroups<false, true, false>(a);
    case 3:
      return latLongGroups<false, true, true>(a);
    case 4:
      return latLongGroups<true, false, false>(a);
    case 5:
      return latLongGroups<true, false, true>(a);
    case 6:
      return latLongGroups<true, true, false>(a);
    default:
      return latLongGroups<true, true, true>(a);
  }
}

bool latLongPortable(const LatLongRows& a, bool grey, bool squares, bool check) {
  return latLongChoices(a, grey, squares, check);
}

#if defined(__x86_64__)
// The same loop with four-double AVX2 vectors (the portable build splits each into two SSE2 pairs).
__attribute__((target("avx2"))) bool latLongAvx2(const LatLongRows& a, bool grey, bool squares, bool check) {
  return latLongChoices(a, grey, squares, check);
}
#endif

bool latLongRows(const LatLongRows& a, bool grey, bool squares, bool check) {
#if defined(__x86_64__)
  static const bool avx2 = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  if (avx2) return latLongAvx2(a, grey, squares, check);
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
