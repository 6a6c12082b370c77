#include "probelights_reference/offset_until_positive.h"

#include <algorithm>
#include <cmath>

#include "probelights/geometry.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"

namespace probelights::reference {

std::vector<double> offsetUntilPositive(int bands, std::vector<double> c) {
  // The minimum of the reconstruction over a fine grid of directions; adding -min to the constant term
  // (Y_0^0 = 1 / sqrt(4 pi)) lifts it to >= 0 there.
  double minimum = 0;
  std::vector<double> y(shCount(bands));
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 512; ++j) {
      shBasis(bands, ShSampler::toSphere((i + 0.5) / 256, (j + 0.5) / 512), y);
      double f = 0;
      for (int k = 0; k < shCount(bands); ++k) f += c[k] * y[k];
      minimum = std::min(minimum, f);
    }
  c[0] += -minimum * std::sqrt(4.0 * kPi) * 1.001;
  return c;
}

}  // namespace probelights::reference
