// The irradiance refit on real probes.
#include "probelights/refit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "probelights/accuracy.h"
#include "probelights/error.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(Refit, LowersTheDiffuseErrorOnRealProbes) {
  Probe probe = Probe::load(PROBELIGHTS_BUNDLED_PROBE);
  Evaluator ev(probe, kDiffuse | kShadow, {2048, true});
  for (int n : {16, 64}) {
    BakeOptions o;
    o.lights = n;
    auto lights = bake(probe, o).lights;
    double shift = 0;
    auto refit = refitIrradiance(ev, lights, &shift);
    EXPECT_LT(ev.evaluate(refit).diffuse, ev.evaluate(lights).diffuse);
    EXPECT_LT(std::abs(shift), 0.02);
    for (const Light& l : refit)
      for (double c : l.rgb) EXPECT_GE(c, 0.0);
  }
  EXPECT_THROW(refitIrradiance(Evaluator(probe, kDiffuse), std::vector<Light>(3)),
               Error);  // not made for refit
}

TEST(Refit, MovingDirectionsLowersItFurther) {
  Probe probe = Probe::load(PROBELIGHTS_BUNDLED_PROBE);
  Evaluator ev(probe, kDiffuse | kShadow, {2048, true});
  BakeOptions o;
  o.lights = 16;
  auto lights = bake(probe, o).lights;
  auto colours = refitIrradiance(ev, lights);
  auto moved = refitIrradiance(ev, lights, nullptr, true);
  EXPECT_LT(ev.evaluate(moved).diffuse, ev.evaluate(colours).diffuse);
  for (const Light& l : moved) EXPECT_NEAR(l.direction.length(), 1.0, 1e-9);
}

// The refit solves three colours a light, so it fits on its own 32 x 32 ground points (none of them the
// 16 x 16 the error is measured on, nor the angle fit's 20 x 20).
TEST(Refit, FitsOnItsOwnDenserGroundPoints) {
  Probe probe = Probe::load(PROBELIGHTS_BUNDLED_PROBE);
  Evaluator ev(probe, kDiffuse | kShadow, {512, true});
  ASSERT_EQ(ev.refitGroundPoints().size(), 1024u);
  auto count = [](const std::vector<Receiver>& rs, bool ground) {
    return std::count_if(rs.begin(), rs.end(), [&](const Receiver& r) { return r.ground == ground; });
  };
  EXPECT_EQ(count(ev.fitReceivers(), true), 400);
  EXPECT_EQ(count(ev.fitReceivers(true), true), 1024);
  EXPECT_EQ(count(ev.fitReceivers(true), false), 1024);
  for (const Vec3& p : ev.refitGroundPoints()) {
    for (const Vec3& q : ev.groundPoints()) EXPECT_GT((p - q).length(), 1e-3);
    for (const Vec3& q : ev.fitGroundPoints()) EXPECT_GT((p - q).length(), 1e-3);
  }
  // An evaluator not made for the refit has none; its fits fall back to the 400.
  Evaluator plain(probe, kDiffuse | kShadow);
  EXPECT_TRUE(plain.refitGroundPoints().empty());
  EXPECT_EQ(count(plain.fitReceivers(true), true), 400);
}

// On 400 ground points the refit overfit them: Blender's interior at 16 suns (the add-on's Refit: energy^2
// centroids, colours and directions) was estimated 2.38 % shadow error; on 1024, 1.10 %.
TEST(Refit, DenserGroundPointsKeepTheRefitFromOverfitting) {
  const std::string path = std::string(PROBELIGHTS_STUDIOLIGHTS) + "/interior.exr";
  if (!std::filesystem::exists(path))
    GTEST_SKIP() << "skipped: Blender's studio lights not found (" << path << ")";
  Probe probe = Probe::load(path);
  Evaluator ev(probe, kDiffuse | kShadow, {2048, true});
  BakeOptions o;
  o.lights = 16;
  o.centroid = CentroidWeight::Energy2;
  auto lights = finishLights(ev, bake(probe, o).lights, true, true, SunAngles::Fit);
  EXPECT_LT(ev.evaluate(lights).shadow, 0.016);
}

}  // namespace
}  // namespace probelights
