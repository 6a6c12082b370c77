// lightsFromRegions: a region's angular radius, the centroid weights, and negative light.
#include <gtest/gtest.h>

#include <cmath>

#include "probelights/placement.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::bakeWith;
using testing::makeProbe;

const WorkingResolution kFull{WorkingResolution::Mode::Full, 0};

TEST(LightsFromRegions, AngularRadiusOfAUniformCap) {
  // A uniform cap of 15 degrees around +Z on a black sphere: one light, radius ~15 degrees.
  const double cap = 15 * kPi / 180;
  auto t = makeProbe(2048, 1024, ProjectionKind::LatLong, [&](int, int y) {
    double el = kPi / 2 - kPi * (y + 0.5) / 1024;
    return kPi / 2 - el <= cap ? Rgb{1, 1, 1} : Rgb{0, 0, 0};
  });
  auto r = bakeWith(t.probe, Method::Variance, 1);
  ASSERT_EQ(r.lights.size(), 1u);
  EXPECT_NEAR(r.lights[0].angularRadius, cap, 0.01);
  EXPECT_NEAR(r.lights[0].direction.z, 1.0, 1e-12);
}

TEST(LightsFromRegions, NegativeLightGoesToTheNearestLightThatCanTakeIt) {
  // Three regions of an 8 x 4 probe: A bright (+x), B with net negative red (a lossy EXR's ringing cut off
  // beside its sun), C with no positive light at all. No light may be negative, and the lights' sums stay the
  // regions' sums: B's and C's negative red go to A, the only light with that much red.
  auto t = makeProbe(8, 4, ProjectionKind::LatLong, [](int, int) { return Rgb{1, 1, 1}; });
  const std::vector<Rect> regions{{0, 0, 4, 4}, {4, 0, 6, 4}, {6, 0, 8, 4}};
  std::vector<PixelSums> sums(3);
  sums[0].rgb = {5, 5, 5}, sums[0].energy = 5, sums[0].moment = {5, 0, 0}, sums[0].solidAngle = 2;
  sums[1].rgb = {-1, 2, 2}, sums[1].energy = 1, sums[1].moment = {0, 1, 0}, sums[1].solidAngle = 1;
  sums[2].rgb = {-0.5, -0.5, 0}, sums[2].energy = 0, sums[2].solidAngle = 1;
  const std::vector<Light> lights = lightsFromSums(t.probe, regions, sums, CentroidWeight::Energy);
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_EQ(lights[0].rgb, (Rgb{3.5, 4.5, 5}));
  EXPECT_EQ(lights[1].rgb, (Rgb{0, 2, 2}));
}

TEST(LightsFromRegions, ADeficitNoOneLightCanTakeIsTakenFromTheNearestInTurn) {
  // C's red deficit (-4) is more than either light has (3 and 2): the light nearer C gives all its red, the
  // other the rest. The red still sums to the regions' 1, and no light is negative.
  auto t = makeProbe(8, 4, ProjectionKind::LatLong, [](int, int) { return Rgb{1, 1, 1}; });
  const std::vector<Rect> regions{{0, 0, 4, 4}, {4, 0, 6, 4}, {6, 0, 8, 4}};
  std::vector<PixelSums> sums(3);
  sums[0].rgb = {3, 1, 1}, sums[0].energy = 1, sums[0].moment = {1, 0, 0}, sums[0].solidAngle = 2;
  sums[1].rgb = {2, 1, 1}, sums[1].energy = 1, sums[1].moment = {0, 1, 0}, sums[1].solidAngle = 1;
  sums[2].rgb = {-4, 0, 0}, sums[2].energy = 0, sums[2].solidAngle = 1;
  const std::vector<Light> lights = lightsFromSums(t.probe, regions, sums, CentroidWeight::Energy);
  ASSERT_EQ(lights.size(), 2u);
  const Vec3 c = *t.probe.projection().direction(7.0 / 8, 0.5);
  const bool firstNearer = dot(lights[0].direction, c) > dot(lights[1].direction, c);
  const Light &nearer = lights[firstNearer ? 0 : 1], &farther = lights[firstNearer ? 1 : 0];
  EXPECT_EQ(nearer.rgb[0], 0.0);
  EXPECT_DOUBLE_EQ(farther.rgb[0], 1.0);
  EXPECT_DOUBLE_EQ(nearer.rgb[1] + farther.rgb[1], 2.0);
}

TEST(LightsFromRegions, MuchNegativeLightKeepsTheIntegralInEveryMethod) {
  // Ringing everywhere (as an unsharp mask makes it): every other pixel column negative, -0.4 of the light in
  // red, -0.9 in blue. Every method's lights are non-negative and sum to the probe's integral per channel.
  auto t = makeProbe(256, 128, ProjectionKind::LatLong, [](int x, int y) {
    const double bright = (x > 100 && x < 110 && y > 30 && y < 36) ? 40.0 : 1.0 + 0.3 * std::sin(0.1 * x);
    return (x + y) % 2 ? Rgb{bright, bright, bright} : Rgb{-0.7 * bright, 0.2 * bright, -0.95 * bright};
  });
  const Rgb total = t.probe.integral();
  ASSERT_GT(total[0], 0);
  for (Method m : {Method::MedianCut, Method::Variance, Method::SphericalHarmonics})
    for (int n : {1, 7, 64, 1024}) {
      const BakeResult r = bakeWith(t.probe, m, n);
      Rgb sum{};
      for (const Light& l : r.lights)
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(l.rgb[k], 0.0);
          sum[k] += l.rgb[k];
        }
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k], total[k], 1e-9 * total[k]) << toString(m) << " " << n;
    }
}

TEST(LightsFromRegions, AChannelWithNoLightIsSaid) {
  auto t = makeProbe(64, 32, ProjectionKind::LatLong, [](int x, int) {
    return x % 2 ? Rgb{1, 1, 1} : Rgb{2, 1, -1.5};
  });
  const BakeResult r = bakeWith(t.probe, Method::Variance, 4);
  double blue = 0;
  for (const Light& l : r.lights) blue += l.rgb[2];
  EXPECT_EQ(blue, 0.0);
  bool said = false;
  for (const auto& n : r.notes) said |= n.text.find("blue light sums to") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(LightsFromRegions, Energy2CentroidLeansTowardsTheBrightestPixels) {
  auto t = makeProbe(256, 128, ProjectionKind::LatLong, [](int x, int y) {
    if (x == 100 && y == 64) return Rgb{50, 50, 50};
    return x >= 90 && x < 130 && y >= 60 && y < 68 ? Rgb{1, 1, 1} : Rgb{0, 0, 0};
  });
  BakeOptions o;
  o.lights = 1;
  o.resolution = kFull;
  auto energy = bake(t.probe, o);
  o.centroid = CentroidWeight::Energy2;
  auto energy2 = bake(t.probe, o);
  Vec3 hot = *t.probe.projection().direction(100.5 / 256, 64.5 / 128);
  EXPECT_GT(dot(energy2.lights[0].direction, hot), dot(energy.lights[0].direction, hot));
}

}  // namespace
}  // namespace probelights
