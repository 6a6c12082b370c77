// Both cuts (AccuracyOptions::bothCuts): variance minimization and median cut each made ready, and the lights
// that fit the probe better kept.
#include <gtest/gtest.h>

#include "probelights/accuracy.h"
#include "probelights/error.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(BothCuts, KeepsTheCutWhoseLightsFitBetterAsThatCutAloneMakesThem) {
  const Probe probe = Probe::load(PROBELIGHTS_BUNDLED_PROBE);
  AccuracyOptions a;
  a.effects = kDiffuse | kShadow, a.refit = a.moveDirections = true, a.evaluatorWidth = 128;
  const Evaluator evaluator(probe, a.effects, {a.evaluatorWidth, true, a.sunProfile});
  const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
  for (int lights : {4, 16}) {
    SCOPED_TRACE(lights);
    BakeOptions o;
    o.lights = lights, o.centroid = CentroidWeight::Energy2;
    o.method = Method::Variance;
    const EvaluatedBake variance = bakeEvaluated(probe, o, a);
    o.method = Method::MedianCut;
    const EvaluatedBake median = bakeEvaluated(probe, o, a);
    const double fitVariance = evaluator.fitError(receivers, variance.bake.lights),
                 fitMedian = evaluator.fitError(receivers, median.bake.lights);
    ASSERT_NE(fitVariance, fitMedian);
    const EvaluatedBake& better = fitMedian < fitVariance ? median : variance;
    AccuracyOptions both = a;
    both.bothCuts = true;
    for (Method start : {Method::Variance, Method::MedianCut}) {
      o.method = start;
      const EvaluatedBake kept = bakeEvaluated(probe, o, both);
      EXPECT_EQ(kept.cut, fitMedian < fitVariance ? Method::MedianCut : Method::Variance);
      ASSERT_EQ(kept.bake.lights.size(), better.bake.lights.size());
      for (std::size_t i = 0; i < kept.bake.lights.size(); ++i) {
        EXPECT_EQ(kept.bake.lights[i].rgb, better.bake.lights[i].rgb);
        EXPECT_EQ(kept.bake.lights[i].direction.x, better.bake.lights[i].direction.x);
        EXPECT_EQ(kept.bake.lights[i].angle, better.bake.lights[i].angle);
      }
      EXPECT_EQ(kept.errors.shadow, better.errors.shadow);
      EXPECT_EQ(kept.energyShift, better.energyShift);
      ASSERT_FALSE(kept.bake.notes.empty());
      EXPECT_NE(kept.bake.notes.back().find("both cuts fitted: " + toString(kept.cut) + " kept"),
                std::string::npos)
          << kept.bake.notes.back();
    }
  }
}

TEST(BothCuts, RefusesWhatItCannotCompare) {
  const Probe probe = Probe::load(PROBELIGHTS_BUNDLED_PROBE);
  AccuracyOptions a;
  a.bothCuts = true;
  BakeOptions o;
  o.method = Method::SphericalHarmonics;
  EXPECT_THROW(bakeEvaluated(probe, o, a), Error);
  o.method = Method::Variance;
  a.maxError = 0.02;
  EXPECT_THROW(bakeEvaluated(probe, o, a), Error);
}

}  // namespace
}  // namespace probelights
