// Both cuts (AccuracyOptions::cuts, CutChoice): variance minimization and median cut each made ready, and the
// lights that fit the probe better kept; auto: above kBothFinishedUpTo lights both started and the better
// finished alone.
#include <gtest/gtest.h>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/image_file.h"
#include "probelights/refit.h"
#include "probelights/sun_angles.h"
#include "test_probes.h"

namespace probelights {
namespace {

// The lights are those of one cut alone, bit for bit, and the cut is `expected`; from either start.
void expectKept(const Probe& probe, BakeOptions o, const AccuracyOptions& a, Method expected,
                const std::string& note) {
  o.method = expected;
  AccuracyOptions alone = a;
  alone.cuts = CutChoice::One;
  const EvaluatedBake better = bakeEvaluated(probe, o, alone);
  for (Method start : {Method::Variance, Method::MedianCut}) {
    o.method = start;
    const EvaluatedBake kept = bakeEvaluated(probe, o, a);
    EXPECT_EQ(kept.cut, expected);
    ASSERT_EQ(kept.bake.lights.size(), better.bake.lights.size());
    for (std::size_t i = 0; i < kept.bake.lights.size(); ++i) {
      EXPECT_EQ(kept.bake.lights[i].rgb, better.bake.lights[i].rgb);
      EXPECT_EQ(kept.bake.lights[i].direction.x, better.bake.lights[i].direction.x);
      EXPECT_EQ(kept.bake.lights[i].angle, better.bake.lights[i].angle);
    }
    EXPECT_EQ(kept.errors.shadow, better.errors.shadow);
    EXPECT_EQ(kept.energyShift, better.energyShift);
    ASSERT_FALSE(kept.bake.notes.empty());
    EXPECT_EQ(kept.bake.notes.back().text, note + toString(expected) + " kept");
    EXPECT_EQ(kept.bake.notes.back().kind, NoteKind::Chosen);
  }
}

TEST(BothCuts, KeepsTheCutWhoseLightsFitBetterAsThatCutAloneMakesThem) {
  const Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  AccuracyOptions a;
  a.effects = kDiffuse | kShadow, a.refit = a.moveDirections = true, a.evaluatorWidth = 128;
  const Evaluator evaluator(probe, a.effects, {a.evaluatorWidth, true, a.sunProfile});
  const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
  for (int lights : {4, 16}) {
    SCOPED_TRACE(lights);
    BakeOptions o;
    o.lights = lights, o.centroid = CentroidWeight::Energy2;
    o.method = Method::Variance;
    const double fitVariance = evaluator.fitError(receivers, bakeEvaluated(probe, o, a).bake.lights);
    o.method = Method::MedianCut;
    const double fitMedian = evaluator.fitError(receivers, bakeEvaluated(probe, o, a).bake.lights);
    ASSERT_NE(fitVariance, fitMedian);
    AccuracyOptions both = a;
    both.cuts = CutChoice::Both;
    expectKept(probe, o, both, fitMedian < fitVariance ? Method::MedianCut : Method::Variance,
               "both cuts fitted: ");
  }
}

TEST(BothCuts, AutoFinishesBothUpTo16LightsAndAboveTheBetterStartedCutAlone) {
  const Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  AccuracyOptions a;
  a.effects = kDiffuse | kShadow, a.refit = a.moveDirections = true, a.evaluatorWidth = 128;
  a.cuts = CutChoice::Auto;
  const Evaluator evaluator(probe, a.effects, {a.evaluatorWidth, true, a.sunProfile});
  const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
  BakeOptions o;
  o.centroid = CentroidWeight::Energy2;
  // Up to 16 lights auto is both.
  o.lights = static_cast<int>(kBothFinishedUpTo);
  AccuracyOptions both = a;
  both.cuts = CutChoice::Both;
  const EvaluatedBake viaBoth = bakeEvaluated(probe, o, both), viaAuto = bakeEvaluated(probe, o, a);
  EXPECT_EQ(viaAuto.cut, viaBoth.cut);
  EXPECT_EQ(viaAuto.errors.shadow, viaBoth.errors.shadow);
  EXPECT_EQ(viaAuto.bake.notes.back(), viaBoth.bake.notes.back());
  // Above: the cut whose angled lights fit better with their colours solved, finished alone.
  for (int lights : {24, 40}) {
    SCOPED_TRACE(lights);
    o.lights = lights;
    double started[2];
    for (Method m : {Method::Variance, Method::MedianCut}) {
      o.method = m;
      std::vector<Light> ls = bake(probe, o).lights;
      applySunAngles(a.sunAngles, &evaluator, ls, true);
      solveColours(evaluator, receivers, ls);
      started[m == Method::MedianCut] = evaluator.fitError(receivers, ls);
    }
    ASSERT_NE(started[0], started[1]);
    expectKept(probe, o, a, started[1] < started[0] ? Method::MedianCut : Method::Variance,
               "both cuts started: ");
  }
}

TEST(BothCuts, RefusesWhatItCannotCompare) {
  const Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  AccuracyOptions a;
  a.cuts = CutChoice::Both;
  BakeOptions o;
  for (CutChoice cuts : {CutChoice::Both, CutChoice::Auto}) {
    a.cuts = cuts, a.maxError = 0;
    o.method = Method::SphericalHarmonics;
    EXPECT_THROW(bakeEvaluated(probe, o, a), Error);
    o.method = Method::Variance;
    a.maxError = 0.02;
    EXPECT_THROW(bakeEvaluated(probe, o, a), Error);
  }
  EXPECT_EQ(parseCutChoice("auto"), CutChoice::Auto);
  EXPECT_THROW(parseCutChoice("all"), Error);
}

}  // namespace
}  // namespace probelights
