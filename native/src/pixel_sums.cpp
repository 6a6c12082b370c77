#include "probelights/pixel_sums.h"

#include <algorithm>
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
                    std::span<PixelSums> cells, bool squares) {
  const Projection& projection = probe.projection();
  if (projection.kind() == ProjectionKind::LatLong) {
    const ImageView& view = probe.view();
    const std::ptrdiff_t step = view.pixelStep();
    auto cellsOfRow = [&]<bool Grey, bool Squares>(int y) {
      const auto row = projection.latLongRow(y);
      const double dw = row.solidAngle;
      const float* p = view.pixel(x0, y);
      for (int x = x0, c = 0; x < x1; ++c) {
        const int start = x, end = std::min(x1, x + cellSize);
        double r = 0, g = 0, b = 0, sY = 0, sYc = 0, sYs = 0, sY2 = 0, sY2c = 0, sY2s = 0;
        long long lit = 0;
        for (; x < end; ++x, p += step) {
          // Colours keep a negative sample's sign (Probe::light); the weights read it as 0.
          double Rs = Probe::finite(p[0]), Gs = Rs, Bs = Rs;
          if constexpr (!Grey) Gs = Probe::finite(p[1]), Bs = Probe::finite(p[2]);
          const double R = Rs > 0 ? Rs : 0.0, G = Gs > 0 ? Gs : 0.0, B = Bs > 0 ? Bs : 0.0;
          const double Y = luminance(R, G, B), Y2 = Y * Y;
          r += Rs, g += Gs, b += Bs;
          sY += Y, sYc += Y * row.cosPhi[x], sYs += Y * row.sinPhi[x];
          if constexpr (Squares) sY2 += Y2, sY2c += Y2 * row.cosPhi[x], sY2s += Y2 * row.sinPhi[x];
          lit += Y > 0;
        }
        PixelSums& s = cells[c];
        s.rgb[0] += r * dw, s.rgb[1] += g * dw, s.rgb[2] += b * dw;
        s.solidAngle += dw * (end - start);
        s.energy += sY * dw;
        s.moment += Vec3{dw * row.cosEl * sYc, dw * row.cosEl * sYs, dw * row.sinEl * sY};
        s.energy2 += sY2 * dw;
        s.moment2 += Vec3{dw * row.cosEl * sY2c, dw * row.cosEl * sY2s, dw * row.sinEl * sY2};
        s.litPixels += lit;
      }
    };
    // Without the squares (only the energy2 centroid reads them) the loop has three fewer chains of sums.
    const auto segmentBytes = static_cast<std::ptrdiff_t>(x1 - x0) * step * 4;
    for (int y = y0; y < y1; ++y) {
      // A region's rows are short pieces of long image rows, which the hardware prefetcher picks up late:
      // ask for the next row's piece now.
      if (y + 1 < y1 && x1 - x0 < view.width) {
        const char* next = reinterpret_cast<const char*>(view.pixel(x0, y + 1));
        for (std::ptrdiff_t b = 0; b < segmentBytes; b += 64) __builtin_prefetch(next + b);
      }
      if (view.channels < 3)
        squares ? cellsOfRow.template operator()<true, true>(y)
                : cellsOfRow.template operator()<true, false>(y);
      else
        squares ? cellsOfRow.template operator()<false, true>(y)
                : cellsOfRow.template operator()<false, false>(y);
    }
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
