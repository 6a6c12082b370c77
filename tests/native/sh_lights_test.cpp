// The "sh" light method: strata of equal area, cells of nearly equal reconstructed energy, exact light sums.
#include "probelights/sh_lights.h"

#include <gtest/gtest.h>

#include "probelights/placement.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(ShLights, StrataHaveEqualArea) {
  for (int n : {1, 2, 3, 7, 16, 33, 64}) {
    std::vector<int> counts(n, 0);
    const int g = 600;
    for (int i = 0; i < g; ++i)
      for (int j = 0; j < g; ++j) ++counts[stratumOf({(i + 0.5) / g, (j + 0.5) / g}, n)];
    for (int c : counts) EXPECT_NEAR(static_cast<double>(c) / (g * g), 1.0 / n, 2.0 / g) << n;
  }
}

TEST(ShLights, CellsHoldNearlyEqualReconstructedEnergy) {
  // A smooth positive sky: with epsilon 0 (Jarosz's warping) each cell holds 1/N of the reconstructed energy.
  const int W = 512, H = 256, bands = 4, n = 16;
  Projection pr(ProjectionKind::LatLong, W, H);
  auto t = testing::makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) {
    Vec3 d = *pr.direction((x + 0.5) / W, (y + 0.5) / H);
    return Rgb{1.5 + d.z + 0.3 * d.x, 1.5 + d.z + 0.3 * d.x, 1.5 + d.z + 0.3 * d.x};
  });
  ShCoefficients sh = projectProbe(t.probe, bands);
  ShSampler sampler(bands, sh.luminance(), 0.0, 8);
  std::vector<double> energy(n, 0.0);
  double total = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      Vec3 d = *pr.direction((x + 0.5) / W, (y + 0.5) / H);
      double f = luminance(sh.evaluate(d)) * pr.pixelSolidAngle(x, y);
      energy[stratumOf(sampler.invert(d), n)] += f;
      total += f;
    }
  double worst = 0;
  for (double e : energy) worst = std::max(worst, std::abs(e / total * n - 1.0));
  // Relative to 1/N (measured 1.4 % at 512 x 256); what is left is the pixels' discretization of the cell
  // borders.
  EXPECT_LT(worst, 0.02);
}

TEST(ShLights, BakeGivesNLightsThatCarryTheProbesEnergy) {
  auto t = testing::makeProbe(256, 128, ProjectionKind::LatLong, [](int x, int y) {
    if (x == 80 && y == 30) return Rgb{1e4, 9e3, 8e3};
    return Rgb{0.2 + 0.001 * x, 0.3, 0.5 - 0.002 * y};
  });
  for (int n : {1, 5, 16, 64}) {
    BakeOptions o;
    o.method = Method::SphericalHarmonics;
    o.lights = n;
    auto r = bake(t.probe, o);
    EXPECT_EQ(static_cast<int>(r.lights.size()), n);
    EXPECT_LE(testing::maxRelativeDifference(testing::sumRgb(r.lights), t.probe.integral()), 1e-12);
    EXPECT_FALSE(r.regionsAreRects);
    for (const Light& l : r.lights) EXPECT_NEAR(l.direction.length(), 1.0, 1e-12);
  }
}

TEST(ShLights, SaysSoWhenCellsAreDark) {
  auto t = testing::makeProbe(64, 32, ProjectionKind::LatLong, [](int x, int y) {
    return x == 10 && y == 5 ? Rgb{1, 1, 1} : Rgb{0, 0, 0};
  });
  BakeOptions o;
  o.method = Method::SphericalHarmonics;
  o.lights = 8;
  auto r = bake(t.probe, o);
  EXPECT_EQ(r.lights.size(), 1u);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes[0].text.find("made 1 lights, not 8"), std::string::npos) << r.notes[0].text;
}

}  // namespace
}  // namespace probelights
