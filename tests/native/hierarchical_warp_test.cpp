// The generic hierarchical warp on its own (no SH): chi-square fit of sample() against density(), the
// inverse, normalization, Berger's limits, and leaves that go negative.
#include "probelights/hierarchical_warp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "chi2.h"
#include "probelights/error.h"

namespace probelights {
namespace {

// A 2^depth x 2^depth grid of leaf integrals: a smooth bump plus a bright corner, optionally with a negative
// band (as a ringing reconstruction has).
std::vector<double> leaves(int depth, bool negative) {
  const int n = 1 << depth;
  std::vector<double> v(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double s = (i + 0.5) / n, t = (j + 0.5) / n;
      double f =
          std::exp(-20 * ((s - 0.3) * (s - 0.3) + (t - 0.6) * (t - 0.6))) + (s > 0.8 && t < 0.1 ? 5 : 0);
      if (negative && s > 0.5 && s < 0.6) f = -0.3;
      v[static_cast<std::size_t>(i) * n + j] = f / (n * n);
    }
  return v;
}

double pValue(const HierarchicalWarp& warp, int samples, std::uint64_t seed) {
  const int bins = 32, leaf = 1 << warp.depth();
  std::vector<double> expected(bins * bins, 0.0), observed(bins * bins, 0.0);
  for (int i = 0; i < leaf; ++i)
    for (int j = 0; j < leaf; ++j)
      expected[(i * bins / leaf) * bins + j * bins / leaf] +=
          warp.density({(i + 0.5) / leaf, (j + 0.5) / leaf}) / (static_cast<double>(leaf) * leaf) * samples;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < samples; ++k) {
    const double a = u(rng);
    auto p = warp.sample({a, u(rng)}).point;
    observed[std::min(bins - 1, static_cast<int>(p[0] * bins)) * bins +
             std::min(bins - 1, static_cast<int>(p[1] * bins))] += 1;
  }
  return testing::chiSquarePValue(observed, expected);
}

TEST(HierarchicalWarp, SamplesFollowTheirDensityAndInvertBack) {
  for (bool negative : {false, true}) {
    HierarchicalWarp warp(leaves(6, negative), 6, 0.05);
    EXPECT_GT(pValue(warp, 200000, 7), 0.01) << "negative leaves: " << negative;
    double total = 0;
    for (int i = 0; i < 256; ++i)
      for (int j = 0; j < 256; ++j)
        total += warp.density({(i + 0.5) / 256, (j + 0.5) / 256}) / (256.0 * 256.0);
    EXPECT_NEAR(total, 1.0, 1e-9);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int k = 0; k < 1000; ++k) {
      const std::array<double, 2> v{u(rng), u(rng)};
      const auto s = warp.sample(v);
      const auto back = warp.invert(s.point);
      EXPECT_NEAR(back[0], v[0], 1e-9);
      EXPECT_NEAR(back[1], v[1], 1e-9);
      EXPECT_NEAR(s.density, warp.density(s.point), 1e-9 * s.density);
      EXPECT_GE(s.density, std::pow(4 * 0.05 * 0.05, 6) * (1 - 1e-12));  // Berger's lower bound
    }
  }
}

TEST(HierarchicalWarp, EpsilonOneHalfIsUniformAndZeroFollowsTheLeaves) {
  HierarchicalWarp uniform(leaves(5, true), 5, 0.5);
  EXPECT_DOUBLE_EQ(uniform.density({0.9, 0.05}), 1.0);
  EXPECT_DOUBLE_EQ(uniform.density({0.2, 0.7}), 1.0);
  const auto v = leaves(5, false);
  HierarchicalWarp exact(v, 5, 0.0, 2.0);
  double sum = 0;
  for (double x : v) sum += x;
  const int n = 32, i = 28, j = 1;  // a leaf in the bright corner
  EXPECT_NEAR(exact.density({(i + 0.5) / n, (j + 0.5) / n}), v[i * n + j] * n * n / sum / 2.0, 1e-9);
}

TEST(HierarchicalWarp, RejectsBadParameters) {
  EXPECT_THROW(HierarchicalWarp(leaves(4, false), 4, 0.6), Error);
  EXPECT_THROW(HierarchicalWarp(leaves(4, false), 5, 0.1), Error);
  EXPECT_THROW(HierarchicalWarp(leaves(4, false), 0, 0.1), Error);
}

}  // namespace
}  // namespace probelights
