// A sequence baked into lights that keep their identities (sequence.h): every frame carries its probe's light
// exactly in N lights, the sun stays one light from frame to frame, held cuts move the lights less than cuts
// made afresh every frame, a still world bakes as a single bake does, and the hard frames (black, another
// size) are met with dark lights or a clear error.
#include "probelights/sequence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>
#include <random>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/sequence_request.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::makeProbe;
using testing::sumRgb;

constexpr double kPi = 3.14159265358979323846;

Vec3 latLongDirection(double u, double v) {
  const double phi = 2 * kPi * (0.5 - u), el = kPi / 2 - kPi * v;
  return {std::cos(el) * std::cos(phi), std::cos(el) * std::sin(phi), std::sin(el)};
}

Vec3 sunAt(int frame, int frames) {
  // Sunrise in the east to sunset in the west over the south: azimuth -90 to 90 degrees, elevation up to 60.
  const double s = (frame + 0.5) / frames, azimuth = kPi * (s - 0.5), elevation = kPi / 3 * std::sin(kPi * s);
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

// Frame `frame` of a day: a sky brighter towards the zenith, a ground of 0.05, a window of 2 fixed in the
// north, and a sun disc of 3 degrees whose strength and the exposure change with its elevation.
testing::TestProbe dayFrame(int frame, int frames, int W = 256, int H = 128) {
  const Vec3 sun = sunAt(frame, frames);
  const double exposure = 0.5 + sun.z;
  return makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) -> Rgb {
    const Vec3 d = latLongDirection((x + 0.5) / W, (y + 0.5) / H);
    double r = 0.05, g = 0.05, b = 0.05;
    if (d.z > 0) r = 0.2 + 0.3 * d.z, g = 0.3 + 0.3 * d.z, b = 0.5 + 0.4 * d.z;
    if (dot(d, Vec3{-0.9, 0.0, 0.436}) > std::cos(0.15)) r += 2, g += 2, b += 2;
    if (dot(d, sun) > std::cos(1.5 * kPi / 180)) r += 4000, g += 3600, b += 3000;
    return {exposure * r, exposure * g, exposure * b};
  });
}

BakeOptions options(int lights, Method method = Method::Variance) {
  BakeOptions o;
  o.lights = lights;
  o.method = method;
  return o;
}

int brightest(const std::vector<Light>& lights) {
  return static_cast<int>(
      std::max_element(lights.begin(), lights.end(),
                       [](const Light& a, const Light& b) { return luminance(a.rgb) < luminance(b.rgb); }) -
      lights.begin());
}

TEST(SequenceBaker, EveryFrameHasNLightsThatSumToItsProbe) {
  for (Method method : {Method::Variance, Method::MedianCut}) {
    SequenceBaker baker(options(16, method), {});
    for (int f = 0; f < 12; ++f) {
      auto p = dayFrame(f, 12);
      const SequenceFrame frame = baker.add(p.probe);
      ASSERT_EQ(frame.lights.size(), 16u);
      const Rgb total = p.probe.integral();
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(frame.totalRgb[k], total[k], 1e-9 * total[k]);
        EXPECT_NEAR(sumRgb(frame.lights)[k], total[k], 1e-9 * total[k]) << toString(method) << " frame " << f;
      }
      for (const Light& l : frame.lights) EXPECT_GT(luminance(l.rgb), 0) << "every light lit";
    }
  }
}

// The ids of the lights that carry the sun: within 5 degrees of it, with a tenth of the frame's light or more
// (a bake of 2^n lights splits every region n times, so the sun is sometimes two lights side by side).
std::vector<int> sunIds(const SequenceFrame& frame, const Vec3& sun) {
  std::vector<int> ids;
  for (int id = 0; id < static_cast<int>(frame.lights.size()); ++id) {
    const Light& l = frame.lights[id];
    if (std::acos(std::min(1.0, dot(l.direction, sun))) < 5 * kPi / 180 &&
        luminance(l.rgb) > 0.1 * luminance(frame.totalRgb))
      ids.push_back(id);
  }
  return ids;
}

TEST(SequenceBaker, TheSunKeepsItsLightsFromFrameToFrame) {
  for (int lights : {16, 12}) {
    SequenceBaker baker(options(lights), {});
    std::vector<int> last;
    int changes = 0, lastBrightest = -1;
    for (int f = 0; f < 24; ++f) {
      auto p = dayFrame(f, 24);
      const SequenceFrame frame = baker.add(p.probe);
      const std::vector<int> ids = sunIds(frame, sunAt(f, 24));
      ASSERT_FALSE(ids.empty()) << "frame " << f << ": no light on the sun";
      changes += f > 0 && brightest(frame.lights) != lastBrightest;
      lastBrightest = brightest(frame.lights);
      double share = 0;
      for (int id : ids) share += luminance(frame.lights[id].rgb) / luminance(frame.totalRgb);
      EXPECT_GT(share, 0.6) << "frame " << f;
      if (f > 0) {
        std::vector<int> both;
        std::set_intersection(ids.begin(), ids.end(), last.begin(), last.end(), std::back_inserter(both));
        EXPECT_FALSE(both.empty()) << lights << " lights, frame " << f << ": the sun went to another light";
      }
      last = ids;
    }
    // Measured: the brightest light is one id all day at 16 lights; at 12 the sun is two lights in a frame
    // and the other half stays the brighter after it.
    EXPECT_LE(changes, 1) << lights << " lights";
  }
}

// A day baked as a sequence (smoothness >= 0) or as independent single bakes (< 0): the mean per-frame
// errors, the lamp-lit response's change from frame to frame over the world-lit response's own (flicker),
// and how many frames were cut afresh.
struct DayJudgement {
  double diffuse = 0, shadow = 0, flicker = 0;
  int recuts = 0;
};

DayJudgement judgeDay(double smoothness, int frames) {
  std::optional<SequenceBaker> baker;
  if (smoothness >= 0) baker.emplace(options(16), SequenceOptions{smoothness});
  DayJudgement j;
  FrameResponse last;
  double lampChange = 0, truthChange = 0;
  for (int f = 0; f < frames; ++f) {
    auto p = dayFrame(f, frames);
    std::vector<Light> lights;
    if (baker) {
      SequenceFrame frame = baker->add(p.probe);
      lights = frame.lights;
      j.recuts += frame.recut;
    } else {
      lights = bake(p.probe, options(16)).lights;
    }
    FrameResponse r = judgeFrame(p.probe, lights);
    j.diffuse += r.errors.diffuse / frames, j.shadow += r.errors.shadow / frames;
    if (f > 0) lampChange += rmsChange(r.lamps, last.lamps), truthChange += rmsChange(r.truth, last.truth);
    last = std::move(r);
  }
  j.flicker = lampChange / truthChange;
  return j;
}

TEST(SequenceBaker, ADayFlickersAsTheWorldDoesAndEachFrameIsAsGoodAsASingleBake) {
  // Issue 53's targets: flicker within 1.5x of the world's own change, per-frame error within 1.2x of single
  // bakes. Measured here: flicker 0.99 (single bakes 0.99), errors within 3 % of the single bakes'.
  const DayJudgement held = judgeDay(SequenceOptions{}.smoothness, 24), single = judgeDay(-1, 24);
  std::printf(
      "day of 24 frames: diffuse %.4f (single bakes %.4f), shadow %.4f (%.4f), flicker %.3f (%.3f), "
      "%d frames cut afresh\n",
      held.diffuse, single.diffuse, held.shadow, single.shadow, held.flicker, single.flicker, held.recuts);
  EXPECT_LT(held.flicker, 1.5);
  EXPECT_LT(held.diffuse, 1.2 * single.diffuse);
  EXPECT_LT(held.shadow, 1.2 * single.shadow);
}

TEST(SequenceBaker, FinishedAsTheAddonsBakeEachFrameIsAsGoodAsItsSingleBakeAndTheSunKeepsItsLight) {
  // Angles fitted to each frame's shadows and the refit of colours and directions (the add-on's recipe):
  // with the energy free to move, against single bakes finished the same way (bakeEvaluated); with every
  // frame's energy exact (the default), against each frame baked alone with it exact too.
  AccuracyOptions a;
  a.sunAngles = SunAngles::Fit, a.refit = true, a.moveDirections = true, a.evaluatorWidth = 512;
  a.effects = kDiffuse | kShadow;
  const SequenceFinish finish{SunAngles::Fit, SunCones::Free, true, true};  // at its sequence price
  SequenceOptions free, exactAlone;
  free.exactEnergy = false, exactAlone.independent = true;
  SequenceBaker baker(options(16), free, finish), exact(options(16), {}, finish),
      alone(options(16), exactAlone, finish);
  double held[2] = {0, 0}, single[2] = {0, 0}, plain[2] = {0, 0}, kept[2] = {0, 0}, keptAlone[2] = {0, 0};
  SequenceBaker unfinished(options(16), {});
  int lastBrightest = -1, changes = 0;
  double shift = 0;
  const int frames = 8;
  for (int f = 0; f < frames; ++f) {
    auto p = dayFrame(f, frames);
    const SequenceFrame frame = baker.add(p.probe);
    ASSERT_EQ(frame.lights.size(), 16u);
    EXPECT_TRUE(std::isfinite(frame.energyShift));
    EXPECT_LT(std::abs(frame.energyShift), 0.2) << f;
    shift = std::max(shift, std::abs(frame.energyShift));
    const EffectErrors mine = judgeFrame(p.probe, frame.lights).errors;
    const EffectErrors single1 =
        judgeFrame(p.probe, bakeEvaluated(p.probe, options(16), a).bake.lights).errors;
    const EffectErrors asCut = judgeFrame(p.probe, unfinished.add(p.probe).lights).errors;
    held[0] += mine.diffuse, held[1] += mine.shadow, single[0] += single1.diffuse,
        single[1] += single1.shadow;
    plain[0] += asCut.diffuse, plain[1] += asCut.shadow;
    changes += f > 0 && brightest(frame.lights) != lastBrightest;
    lastBrightest = brightest(frame.lights);
    for (const Light& l : frame.lights) EXPECT_GE(l.angle, 0);
    // Energy exact: the lights sum to the frame's probe, channel by channel.
    const SequenceFrame e = exact.add(p.probe), e1 = alone.add(p.probe);
    EXPECT_LT(std::abs(e.energyShift), 1e-12) << f;
    for (int c = 0; c < 3; ++c) {
      double sum = 0;
      for (const Light& l : e.lights) sum += l.rgb[c];
      EXPECT_NEAR(sum, e.totalRgb[c], 1e-9 * e.totalRgb[c]) << f << " " << c;
    }
    const EffectErrors k = judgeFrame(p.probe, e.lights).errors, k1 = judgeFrame(p.probe, e1.lights).errors;
    kept[0] += k.diffuse, kept[1] += k.shadow, keptAlone[0] += k1.diffuse, keptAlone[1] += k1.shadow;
  }
  std::printf(
      "finished day of %d frames: diffuse %.4f (single bakes %.4f, unfinished %.4f), shadow %.4f "
      "(%.4f, %.4f), energy shift up to %.4f; energy exact: diffuse %.4f (alone %.4f), shadow %.4f (%.4f)\n",
      frames, held[0] / frames, single[0] / frames, plain[0] / frames, held[1] / frames, single[1] / frames,
      plain[1] / frames, shift, kept[0] / frames, keptAlone[0] / frames, kept[1] / frames,
      keptAlone[1] / frames);
  EXPECT_LT(held[0], 1.2 * single[0]);
  EXPECT_LT(held[1], 1.2 * single[1]);
  EXPECT_LT(held[0] + held[1], plain[0] + plain[1]);  // finishing pays
  EXPECT_LT(kept[0], 1.2 * keptAlone[0]);
  EXPECT_LT(kept[1], 1.2 * keptAlone[1]);
  EXPECT_LT(kept[0] + kept[1], plain[0] + plain[1]);  // with the energy held too
  EXPECT_LE(changes, 1);
}

TEST(SequenceBaker, MoreSmoothnessKeepsTheCutsLonger) {
  const int loose = judgeDay(0, 24).recuts, usual = judgeDay(0.5, 24).recuts, held = judgeDay(5, 24).recuts;
  std::printf("frames cut afresh of 24: smoothness 0: %d, 0.5: %d, 5: %d\n", loose, usual, held);
  EXPECT_GT(loose, usual);
  EXPECT_GT(usual, held);
  EXPECT_GE(held, 1);  // the first frame
}

TEST(SequenceBaker, AStillWorldBakesAsOneBakeAndNeverMoves) {
  auto p = dayFrame(5, 12);
  const std::vector<Light> single = bake(p.probe, options(16)).lights;
  SequenceBaker baker(options(16), {0.5});
  for (int f = 0; f < 4; ++f) {
    const SequenceFrame frame = baker.add(p.probe);
    EXPECT_EQ(frame.motion, 0);
    EXPECT_EQ(frame.recut, f == 0);
    ASSERT_EQ(frame.lights.size(), single.size());
    for (std::size_t i = 0; i < single.size(); ++i) {
      EXPECT_EQ(frame.lights[i].rect, single[i].rect);
      EXPECT_EQ(frame.lights[i].rgb, single[i].rgb);
    }
  }
}

TEST(SequenceBaker, ABlackFrameDarkensEveryLightWhereItWasAndTheLightComesBack) {
  SequenceBaker baker(options(8), {});
  auto first = dayFrame(3, 12);
  const SequenceFrame a = baker.add(first.probe);
  auto black = testing::uniformProbe(256, 128, ProjectionKind::LatLong, {0, 0, 0});
  const SequenceFrame b = baker.add(black.probe);
  ASSERT_EQ(b.lights.size(), 8u);
  for (int id = 0; id < 8; ++id) {
    EXPECT_EQ(b.lights[id].rgb, (Rgb{0, 0, 0}));
    EXPECT_EQ(b.lights[id].direction.x, a.lights[id].direction.x);
    EXPECT_FALSE(std::isnan(b.lights[id].direction.z));
  }
  auto again = dayFrame(3, 12);
  const SequenceFrame c = baker.add(again.probe);
  EXPECT_TRUE(c.recut);
  const int sun = brightest(a.lights);
  EXPECT_EQ(brightest(c.lights), sun) << "the sun comes back as the light it was";
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(sumRgb(c.lights)[k], c.totalRgb[k], 1e-9 * c.totalRgb[k]);
}

TEST(SequenceBaker, FewerLitCellsThanLightsLeavesTheRestDark) {
  // Three lit pixels, then the day: the first frame makes three lights and five dark ones.
  SequenceBaker baker(options(8), {});
  auto sparse = makeProbe(64, 32, ProjectionKind::LatLong, [](int x, int y) -> Rgb {
    return (y == 10 && (x == 5 || x == 20 || x == 40)) ? Rgb{1, 1, 1} : Rgb{0, 0, 0};
  });
  const SequenceFrame a = baker.add(sparse.probe);
  EXPECT_EQ(std::count_if(a.lights.begin(), a.lights.end(), [](const Light& l) { return l.rgb[1] > 0; }), 3);
  auto lit = makeProbe(64, 32, ProjectionKind::LatLong, [](int x, int y) -> Rgb {
    return {1.0 + x, 1.0 + y, 1.0};
  });
  const SequenceFrame b = baker.add(lit.probe);
  EXPECT_EQ(std::count_if(b.lights.begin(), b.lights.end(), [](const Light& l) { return l.rgb[1] > 0; }), 8);
}

TEST(SequenceBaker, AFrameOfAnotherSizeOrABadRequestIsRefused) {
  SequenceBaker baker(options(8), {});
  auto a = dayFrame(0, 4);
  baker.add(a.probe);
  auto small = dayFrame(1, 4, 128, 64);
  try {
    baker.add(small.probe);
    FAIL() << "another size was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame 2 is 128x64 latlong, the sequence's first frame 256x128"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(SequenceBaker(options(8, Method::SphericalHarmonics), {}), Error);
  EXPECT_THROW(SequenceBaker(options(kMaxSequenceLights + 1), {}), Error);
  EXPECT_THROW(SequenceBaker(options(8), {kMaxSmoothness + 1}), Error);
  EXPECT_THROW(SequenceBaker(options(8), {-0.1}), Error);
  EXPECT_THROW(SequenceBaker(options(8), {std::numeric_limits<double>::infinity()}), Error);
  EXPECT_THROW(SequenceBaker(options(8), {std::nan("")}), Error);
  EXPECT_THROW(SequenceBaker(options(8), {}, SequenceFinish{SunAngles::Fit, SunCones::Free, true, false, -1}),
               Error);
}

TEST(SequenceFiles, FramesAreFoundAsBlenderNumbersThem) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("probelights_seq_" + std::to_string(std::random_device{}()));
  fs::create_directories(dir / "sky_0003.exr");  // a folder is not a frame
  for (const char* name : {"sky_0001.exr", "sky_0002.exr", "sky_12345.exr", "sky_01.exr", "sky_00004.exr",
                           "sky_0005.exr.bak", "other_0001.exr", "sky_00a1.exr"})
    std::ofstream(dir / name) << "x";
  const auto files = sequenceFiles((dir / "sky_####.exr").string());
  std::vector<int> frames;
  for (const auto& f : files) frames.push_back(f.frame);
  EXPECT_EQ(frames, (std::vector<int>{1, 2, 12345}));
  EXPECT_EQ(fs::path(files[1].path).filename(), "sky_0002.exr");
  EXPECT_EQ(sequenceFiles((dir / "sky_####.exr").string(), std::array<int, 2>{2, 2}).size(), 1u);
  EXPECT_THROW(sequenceFiles((dir / "sky_####.exr").string(), std::array<int, 2>{1, 3}), Error);
  EXPECT_THROW(sequenceFiles((dir / "sky_##_##.exr").string()), Error);
  EXPECT_THROW(sequenceFiles((dir / "sky_0001.exr").string()), Error);
  EXPECT_THROW(sequenceFiles((dir / "none" / "sky_####.exr").string()), Error);
  fs::remove_all(dir);
}

TEST(MinimumCostAssignment, IsTheBestOfEveryPermutation) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0, 10);
  for (int n = 1; n <= 6; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> cost(n * n);
      for (double& c : cost) c = trial % 3 == 0 ? std::floor(uniform(rng) / 4) : uniform(rng);  // ties too
      std::vector<int> perm(n);
      std::iota(perm.begin(), perm.end(), 0);
      double best = 1e300;
      do {
        double s = 0;
        for (int i = 0; i < n; ++i) s += cost[i * n + perm[i]];
        best = std::min(best, s);
      } while (std::next_permutation(perm.begin(), perm.end()));
      const auto column = minimumCostAssignment(cost, n);
      std::vector<int> sorted = column;
      std::sort(sorted.begin(), sorted.end());
      for (int i = 0; i < n; ++i) ASSERT_EQ(sorted[i], i) << "a permutation";
      double s = 0;
      for (int i = 0; i < n; ++i) s += cost[i * n + column[i]];
      EXPECT_NEAR(s, best, 1e-9);
    }
  EXPECT_THROW(minimumCostAssignment({0, 1, std::nan(""), 2}, 2), Error);
  EXPECT_THROW(minimumCostAssignment({0, 1, std::numeric_limits<double>::infinity(), 2}, 2), Error);
}

}  // namespace
}  // namespace probelights
