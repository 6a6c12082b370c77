// The irradiance refit on real probes.
#include "probelights/refit.h"

#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace probelights
