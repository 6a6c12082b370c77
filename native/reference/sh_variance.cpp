#include "probelights_reference/sh_variance.h"

#include <algorithm>
#include <vector>

namespace probelights::reference {

EstimatorVariance irradianceEstimatorVariance(const Probe& probe, const Vec3& normal,
                                              const std::function<double(const Vec3&)>& pdf) {
  const int W = probe.width(), H = probe.height();
  std::vector<Vec3> dirs(W);
  std::vector<double> omega(W);
  double e = 0, e2 = 0;
  for (int y = 0; y < H; ++y) {
    probe.projection().rowGeometry(y, 0, W, dirs, omega);
    for (int x = 0; x < W; ++x) {
      if (omega[x] <= 0) continue;
      const double f = luminance(probe.radiance(x, y)) * std::max(0.0, dot(normal, dirs[x]));
      if (f == 0) continue;
      e += f * omega[x];
      e2 += f * f / pdf(dirs[x]) * omega[x];
    }
  }
  return {e, e2 - e * e};
}

}  // namespace probelights::reference
