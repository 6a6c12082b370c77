// The lights' angles: points, the regions' spread, and angles fitted to the probe's shadows (sun_angles.h).
#include "probelights/sun_angles.h"

#include <gtest/gtest.h>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/image_file.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(SunAngles, FittedAnglesCastCloserShadowsThanPointsOrSpread) {
  // The bundled probe (a sun near the zenith) at 16 lights, measured: shadow error 2.09 % as points, 4.55 %
  // with the spread's angles, 1.61 % fitted.
  Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  const Evaluator ev(probe, kDiffuse | kShadow, {512});
  BakeOptions o;
  o.lights = 16;
  const std::vector<Light> made = bake(probe, o).lights;
  auto with = [&](SunAngles choice) {
    std::vector<Light> lights = made;
    applySunAngles(choice, &ev, lights);
    return lights;
  };
  const auto points = with(SunAngles::Points), spread = with(SunAngles::Spread), fit = with(SunAngles::Fit);
  for (std::size_t i = 0; i < made.size(); ++i) {
    EXPECT_EQ(points[i].angle, 0.0);
    EXPECT_EQ(spread[i].angle, made[i].angularRadius);
    EXPECT_GE(fit[i].angle, 0.0);
    EXPECT_LE(fit[i].angle, kPi);
    EXPECT_EQ(fit[i].rgb, made[i].rgb);  // the fit moves angles only
  }
  const double p = ev.evaluate(points).shadow, s = ev.evaluate(spread).shadow, f = ev.evaluate(fit).shadow;
  EXPECT_LT(f, 0.85 * p);
  EXPECT_LT(f, 0.85 * s);
  EXPECT_LT(ev.evaluate(fit).diffuse, ev.evaluate(spread).diffuse + 1e-3);  // and no worse shading
}

TEST(SunAngles, BlenderThreesDiscStaysFinite) {
  Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  EvaluatorOptions options{256};
  options.sunProfile = SunProfile::TangentDisc;
  const Evaluator ev(probe, kDiffuse | kShadow, options);
  BakeOptions o;
  o.lights = 8;
  std::vector<Light> lights = bake(probe, o).lights;
  fitSunAngles(ev, lights);
  for (const Light& l : lights) EXPECT_LE(l.angle, 178 * kPi / 180 + 1e-12);
}

TEST(SunAngles, NamesAndWhatTheyNeed) {
  EXPECT_EQ(parseSunAngles("fit"), SunAngles::Fit);
  EXPECT_EQ(toString(SunAngles::Points), "points");
  EXPECT_THROW(parseSunAngles("soft"), Error);
  EXPECT_EQ(parseSunProfile("disc"), SunProfile::TangentDisc);
  Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  const Evaluator diffuseOnly(probe, kDiffuse, {128});
  std::vector<Light> lights(2);
  EXPECT_THROW(fitSunAngles(diffuseOnly, lights), Error);
  EXPECT_FALSE(applySunAngles(SunAngles::Fit, &diffuseOnly, lights));  // nothing to fit to: left as made
}

TEST(SunAngles, TheBakeReportsWhatItDid) {
  Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  BakeOptions o;
  o.lights = 8;
  AccuracyOptions a;
  a.evaluate = true;
  a.effects = kDiffuse | kShadow;
  a.evaluatorWidth = 256;
  EXPECT_EQ(bakeEvaluated(probe, o, a).sunAngles, SunAngles::Fit);
  a.effects = kDiffuse;
  EXPECT_EQ(bakeEvaluated(probe, o, a).sunAngles, SunAngles::Spread);
  a.sunAngles = SunAngles::Points;
  for (const Light& l : bakeEvaluated(probe, o, a).bake.lights) EXPECT_EQ(l.angle, 0.0);
  a.evaluate = false;
  for (const Light& l : bakeEvaluated(probe, o, a).bake.lights) EXPECT_EQ(l.angle, 0.0);
}

TEST(SunAngles, AboveHorizonNoConeCrossesTheHorizon) {
  // EEVEE darkens a sun by the part of its cone below a floor's horizon (cone.h): with SunCones::AboveHorizon
  // no light's cone crosses it, fitted (within the fit, not cut after it), from the spread, or without an
  // evaluator; the lights' rgb stay as made.
  EXPECT_NEAR(horizonAngle({1, 0, 1}), kPi / 2, 1e-12);
  EXPECT_NEAR(horizonAngle({0, 3, -3}), kPi / 2, 1e-12);
  EXPECT_EQ(horizonAngle({2, 1, 0}), 0.0);
  EXPECT_EQ(parseSunCones("above-horizon"), SunCones::AboveHorizon);
  EXPECT_EQ(toString(SunCones::Free), "free");
  EXPECT_THROW(parseSunCones("above"), Error);

  // A dim sky and ground with a broad bright band low over the horizon (elevations 3-30 degrees, a quarter
  // of the way round): its lights' fitted cones cross the horizon when free.
  const testing::TestProbe band = testing::makeProbe(128, 64, ProjectionKind::LatLong, [](int x, int y) {
    const double elevation = 90 - 180 * (y + 0.5) / 64;
    if (elevation > 3 && elevation < 30 && x >= 48 && x < 80) return Rgb{30, 28, 25};
    return elevation > 0 ? Rgb{0.5, 0.6, 0.8} : Rgb{0.2, 0.2, 0.2};
  });
  const Probe& probe = band.probe;
  BakeOptions o;
  o.lights = 4;
  AccuracyOptions a;
  a.evaluate = true;
  a.effects = kDiffuse | kShadow;
  a.evaluatorWidth = 128;
  auto crossing = [](const std::vector<Light>& lights) {
    int n = 0;
    for (const Light& l : lights) n += l.angle > horizonAngle(l.direction) + 1e-12;
    return n;
  };
  const EvaluatedBake free = bakeEvaluated(probe, o, a);
  EXPECT_GT(crossing(free.bake.lights), 0) << "the test needs a fit whose cones cross the horizon";
  a.sunCones = SunCones::AboveHorizon;
  const EvaluatedBake above = bakeEvaluated(probe, o, a);
  EXPECT_EQ(above.sunCones, SunCones::AboveHorizon);
  EXPECT_EQ(crossing(above.bake.lights), 0);
  ASSERT_EQ(above.bake.lights.size(), free.bake.lights.size());
  int narrowed = 0;
  for (std::size_t i = 0; i < free.bake.lights.size(); ++i) {
    EXPECT_EQ(above.bake.lights[i].rgb, free.bake.lights[i].rgb);
    narrowed += above.bake.lights[i].angle < free.bake.lights[i].angle;
  }
  EXPECT_GT(narrowed, 0);
  // Fitted within the horizon: no farther than the free fit's cones cut to it (here the same: each wide cone
  // fits best at its widest).
  std::vector<Light> cut = free.bake.lights;
  keepSunCones(SunCones::AboveHorizon, cut);
  EXPECT_LE(above.errors.shadow,
            Evaluator(probe, a.effects, {a.evaluatorWidth}).evaluate(cut).shadow + 1e-12);
  for (SunAngles angles : {SunAngles::Spread, SunAngles::Fit})
    for (bool evaluate : {true, false})
      for (bool refit : {false, true}) {  // the refit moving the directions, as the add-on bakes
        a.sunAngles = angles;
        a.evaluate = evaluate;
        a.refit = a.moveDirections = refit;
        a.effects = angles == SunAngles::Fit ? kDiffuse : kDiffuse | kShadow;  // fit without shadows: spread
        EXPECT_EQ(crossing(bakeEvaluated(probe, o, a).bake.lights), 0)
            << toString(angles) << evaluate << refit;
      }
  a.sunAngles = SunAngles::Fit;
  a.effects = kDiffuse | kShadow;
  EXPECT_EQ(crossing(bakeEvaluated(probe, o, a).bake.lights), 0) << "fitted and refit";
}

}  // namespace
}  // namespace probelights
