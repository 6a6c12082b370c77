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

void accumulateRows(const Probe& probe, int y0, int y1, int x0, int x1, int cellSize,
                    std::span<PixelSums> cells, bool squares, bool* oddSamples) {
  const Projection& projection = probe.projection();
  if (oddSamples) *oddSamples = true;  // unless the lat-long loop below looked
  if (projection.kind() == ProjectionKind::LatLong) {
    const ImageView& view = probe.view();
    const std::ptrdiff_t step = view.pixelStep();
    // Pixels are summed two at a time, even and odd pixels of a cell in the two lanes of a pair of doubles
    // (SSE2, which every x86-64 has; elsewhere the compiler splits the pairs), the lanes added at the cell's
    // end: the same operations in the same order whoever calls, so band and whole builds stay bit-identical.
    using D2 = double __attribute__((vector_size(16)));
    using I2 = long long __attribute__((vector_size(16)));
    constexpr double kMax = 3.4028234663852886e38;  // FLT_MAX: Probe::finite's bounds
    const D2 zero = {0, 0}, lo = {-kMax, -kMax}, hi = {kMax, kMax};
    const D2 wR = {0.2126, 0.2126}, wG = {0.7152, 0.7152}, wB = {0.0722, 0.0722};
    // `odd` collects, when asked, whether any sample read was negative, NaN or Inf.
    I2 odd = {0, 0};
    auto finite2 = [&]<bool Check>(float a, float b) {
      const D2 v = {a, b};
      if constexpr (Check) odd |= ~((v >= zero) & (v <= hi));
      return ((v >= lo) & (v <= hi)) ? v : zero;
    };
    auto load2 = [](const double* v) {
      D2 d;
      __builtin_memcpy(&d, v, sizeof d);
      return d;
    };
    auto cellsOfRow = [&]<bool Grey, bool Squares, bool Check>(int y) {
      const auto row = projection.latLongRow(y);
      const double dw = row.solidAngle;
      const float* p = view.pixel(x0, y);
      for (int x = x0, c = 0; x < x1; ++c) {
        const int start = x, end = std::min(x1, x + cellSize);
        D2 r = zero, g = zero, b = zero, sY = zero, sYc = zero, sYs = zero, sY2 = zero, sY2c = zero,
           sY2s = zero;
        I2 lit = {0, 0};
        auto add = [&](D2 Rs, D2 Gs, D2 Bs, D2 cosPhi, D2 sinPhi) {
          // Colours keep a negative sample's sign (Probe::light); the weights read it as 0.
          const D2 R = Rs > zero ? Rs : zero, G = Gs > zero ? Gs : zero, B = Bs > zero ? Bs : zero;
          const D2 Y = wR * R + wG * G + wB * B, Y2 = Y * Y;
          r += Rs, g += Gs, b += Bs;
          sY += Y, sYc += Y * cosPhi, sYs += Y * sinPhi;
          if constexpr (Squares) sY2 += Y2, sY2c += Y2 * cosPhi, sY2s += Y2 * sinPhi;
          lit -= Y > zero;
        };
        for (; x + 1 < end; x += 2, p += 2 * step) {
          const D2 Rs = finite2.template operator()<Check>(p[0], p[step]);
          const D2 Gs = Grey ? Rs : finite2.template operator()<Check>(p[1], p[step + 1]),
                   Bs = Grey ? Rs : finite2.template operator()<Check>(p[2], p[step + 2]);
          add(Rs, Gs, Bs, load2(row.cosPhi + x), load2(row.sinPhi + x));
        }
        if (x < end) {  // an odd pixel left: the even lane takes it
          const double Rs = Probe::finite(p[0]), Gs = Grey ? Rs : Probe::finite(p[1]),
                       Bs = Grey ? Rs : Probe::finite(p[2]);
          if constexpr (Check)
            for (int k = 0; k < (Grey ? 1 : 3); ++k) odd[0] |= !(p[k] >= 0.0f && p[k] <= 3.4028234e38f);
          add(D2{Rs, 0}, D2{Gs, 0}, D2{Bs, 0}, D2{row.cosPhi[x], 0}, D2{row.sinPhi[x], 0});
          ++x, p += step;
        }
        auto sum = [](D2 v) { return v[0] + v[1]; };
        PixelSums& s = cells[c];
        s.rgb[0] += sum(r) * dw, s.rgb[1] += sum(g) * dw, s.rgb[2] += sum(b) * dw;
        s.solidAngle += dw * (end - start);
        s.energy += sum(sY) * dw;
        s.moment += Vec3{dw * row.cosEl * sum(sYc), dw * row.cosEl * sum(sYs), dw * row.sinEl * sum(sY)};
        s.energy2 += sum(sY2) * dw;
        s.moment2 += Vec3{dw * row.cosEl * sum(sY2c), dw * row.cosEl * sum(sY2s), dw * row.sinEl * sum(sY2)};
        s.litPixels += lit[0] + lit[1];
      }
    };
    // Without the squares (only the energy2 centroid reads them) the loop has three fewer chains of sums.
    // The three choices (grey, squares, check) become the loop's template arguments here, once.
    auto withFlag = [](bool flag, auto&& f) { flag ? f(std::true_type{}) : f(std::false_type{}); };
    auto rowOf = [&](int y) {
      withFlag(view.channels < 3, [&](auto grey) {
        withFlag(squares, [&](auto sq) {
          withFlag(oddSamples != nullptr, [&](auto check) {
            cellsOfRow
                .template operator()<decltype(grey)::value, decltype(sq)::value, decltype(check)::value>(y);
          });
        });
      });
    };
    const auto segmentBytes = static_cast<std::ptrdiff_t>(x1 - x0) * step * 4;
    for (int y = y0; y < y1; ++y) {
      // A region's rows are short pieces of long image rows, which the hardware prefetcher picks up late:
      // ask for the next row's piece now.
      if (y + 1 < y1 && x1 - x0 < view.width) {
        const char* next = reinterpret_cast<const char*>(view.pixel(x0, y + 1));
        for (std::ptrdiff_t b = 0; b < segmentBytes; b += 64) __builtin_prefetch(next + b);
      }
      rowOf(y);
    }
    if (oddSamples) *oddSamples = (odd[0] | odd[1]) != 0;
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
