// The evaluator: its ground truth against brute force and closed forms, and the effect names.
#include "probelights/evaluate.h"

#include <gtest/gtest.h>

#include <cmath>

#include "probelights/error.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(Evaluator, UniformProbeClosedForms) {
  const double L = 2.0;
  auto t = testing::uniformProbe(1024, 512, ProjectionKind::LatLong, {L, L, L});
  Evaluator ev(t.probe, kDiffuse | kShadow);
  // Irradiance pi L on every normal, to the pixel discretization of the cosine (measured 1.7e-6 at 1024 x
  // 512).
  for (const Rgb& e : ev.diffuseTruth()) EXPECT_NEAR(e[0], kPi * L, 5e-6 * kPi * L);
  // A ground point sees the upper hemisphere (pi L) less the cap of the unit sphere resting on the plane:
  // half-angle a = asin(1 / D), axis at angle b from the zenith; the cap touches the horizon, so its
  // projected solid angle is pi sin^2(a) cos(b).
  for (std::size_t i = 0; i < ev.groundPoints().size(); ++i) {
    const Vec3 p = ev.groundPoints()[i], toCentre = Vec3{0, 0, 1} - p;
    const double D = toCentre.length(), sina = 1 / D, cosb = toCentre.z / D;
    const double expected = kPi * L * (1 - sina * sina * cosb);
    EXPECT_NEAR(ev.shadowTruth()[i][0], expected, 4e-3 * expected) << p.x << "," << p.y;
  }
}

TEST(Evaluator, GroundTruthMatchesABruteForceSum) {
  const int W = 32, H = 16;
  auto t = testing::makeProbe(W, H, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{0.1 + x % 5, 0.2 + y % 3, 1.0 + (x * y) % 7};
  });
  Evaluator ev(t.probe, kDiffuse | kShadow | kGlossy);
  const Projection& pr = t.probe.projection();
  for (std::size_t i = 0; i < ev.normals().size(); i += 17) {
    Rgb diffuse{}, shadow{};
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        Vec3 d = *pr.direction((x + 0.5) / W, (y + 0.5) / H);
        Rgb L = t.probe.radiance(x, y);
        double omega = pr.pixelSolidAngle(x, y);
        double cn = std::max(0.0, dot(ev.normals()[i], d));
        const Vec3 p = ev.groundPoints()[i], o = p - Vec3{0, 0, 1};
        double b = dot(d, o), disc = b * b - (dot(o, o) - 1);
        bool blocked = b < 0 && disc > 0;
        for (int k = 0; k < 3; ++k) {
          diffuse[k] += L[k] * cn * omega;
          if (d.z > 0 && !blocked) shadow[k] += L[k] * d.z * omega;
        }
      }
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(ev.diffuseTruth()[i][k], diffuse[k], 1e-12 * (1 + diffuse[k]));
      EXPECT_NEAR(ev.shadowTruth()[i][k], shadow[k], 1e-12 * (1 + shadow[k]));
    }
  }
}

TEST(Evaluator, OneLightPerPixelIsExactAndFewLightsAreNot) {
  auto t = testing::makeProbe(16, 8, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{1.0 + x, 0.5 + y, 2.0};
  });
  Evaluator ev(t.probe, kDiffuse | kShadow | kGlossy);
  BakeOptions o;
  o.lights = 16 * 8;
  auto all = bake(t.probe, o);
  auto e = ev.evaluate(all.lights);
  EXPECT_LT(e.diffuse, 1e-12);
  EXPECT_LT(e.shadow, 1e-12);
  EXPECT_LT(e.glossy, 1e-12);
  o.lights = 2;
  auto few = ev.evaluate(bake(t.probe, o).lights);
  EXPECT_GT(few.diffuse, 1e-3);
  EXPECT_TRUE(std::isnan(Evaluator(t.probe, kDiffuse).evaluate(all.lights).shadow));  // only what was asked
}

TEST(Effects, ParseAndPrint) {
  EXPECT_EQ(parseEffects("diffuse,shadow"), kDiffuse | kShadow);
  EXPECT_EQ(effectsToString(kDiffuse | kGlossy), "diffuse,glossy");
  EXPECT_THROW(parseEffects("caustics"), Error);
}

}  // namespace
}  // namespace probelights
