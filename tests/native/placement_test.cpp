// Placement (placement.h): every registered method named, parsed and baking; bake(): energy conservation,
// any N, hard small probes (numerically stable: the whole float range, a hot pixel, all black, the seam), the
// horizon split, working resolutions, determinism.
#include "probelights/placement.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "probelights/error.h"
#include "probelights/median_cut.h"
#include "probelights/request.h"
#include "probelights/variance_minimization.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::bakeWith;
using testing::makeProbe;
using testing::maxRelativeDifference;
using testing::sumRgb;
using testing::uniformProbe;

// The registered methods that cut the working grid (the tests below are about cuts and regions).
std::vector<Method> gridMethods() {
  std::vector<Method> out;
  for (const PlacementMethod& m : placementMethods())
    if (m.rule) out.push_back(m.method());
  return out;
}
const std::vector<Method> kMethods = gridMethods();
const WorkingResolution kFull{WorkingResolution::Mode::Full, 0};

void expectFiniteAndConserving(const Probe& probe, const BakeResult& r, double tolerance = 1e-9) {
  for (const Light& l : r.lights) {
    EXPECT_TRUE(std::isfinite(l.direction.x) && std::isfinite(l.direction.y) && std::isfinite(l.direction.z));
    EXPECT_NEAR(l.direction.length(), 1.0, 1e-9);
    for (double c : l.rgb) EXPECT_TRUE(std::isfinite(c) && c >= 0);
    EXPECT_TRUE(std::isfinite(l.angularRadius) && l.angularRadius >= 0 && l.angularRadius <= kPi);
    EXPECT_TRUE(std::isfinite(l.energyShare));
  }
  Rgb integral = probe.integral();
  EXPECT_LE(maxRelativeDifference(sumRgb(r.lights), integral), tolerance);
  EXPECT_LE(maxRelativeDifference(r.totalRgb, integral), tolerance);
}

TEST(Bake, UniformProbeTotalIsFourPiL) {
  const Rgb L{0.5, 1.0, 2.0};
  for (auto kind : {ProjectionKind::LatLong, ProjectionKind::MirrorBall, ProjectionKind::Angular}) {
    auto t = uniformProbe(256, kind == ProjectionKind::LatLong ? 128 : 256, kind, L);
    for (Method m : kMethods) {
      auto r = bakeWith(t.probe, m, 16);
      Rgb sum = sumRgb(r.lights);
      double tol = kind == ProjectionKind::Angular ? 1e-6 : 1e-10;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(sum[k] / (4 * kPi * L[k]), 1.0, tol) << toString(kind);
      EXPECT_EQ(r.lights.size(), 16u);
    }
  }
}

// A sky gradient with a small sun: a probe shaped like the real ones.
testing::TestProbe sunnySky(int W, int H) {
  return makeProbe(W, H, ProjectionKind::LatLong, [=](int x, int y) {
    double v = (y + 0.5) / H;
    if (std::abs(x - W / 3) <= 1 && std::abs(y - H / 5) <= 1) return Rgb{5e4, 4.5e4, 4e4};
    if (v > 0.5) return Rgb{0.1 + 0.05 * (x % 13) / 13.0, 0.12, 0.08};
    return Rgb{0.3 * (1 - v), 0.5 * (1 - v), 1.0};
  });
}

// What a new method gets by its registration alone: its names in the options and their usage text, and bakes
// of finite lights that carry the probe's energy.
TEST(PlacementMethods, EveryRegisteredMethodIsNamedParsedAndBakes) {
  const RequestOption& option = requestOption("method");
  auto t = sunnySky(128, 64);
  ASSERT_EQ(everyMethod().size(), placementMethods().size());
  for (const PlacementMethod& m : placementMethods()) {
    SCOPED_TRACE(m.name);
    EXPECT_NE(m.rule == nullptr, m.place == nullptr);  // cuts the working grid, or places from the pixels
    EXPECT_EQ(usesWorkingGrid(m.method()), m.rule != nullptr);
    EXPECT_EQ(toString(m.method()), m.name);
    EXPECT_EQ(parseMethod(m.name), m.method());
    for (const std::string& alias : m.aliases) EXPECT_EQ(parseMethod(alias), m.method());
    EXPECT_NE(option.values.find(m.name), std::string::npos);
    EXPECT_NE(option.help.find(m.label), std::string::npos);
    for (int n : {1, 8, 33}) {
      auto r = bakeWith(t.probe, m.method(), n);
      EXPECT_GE(r.lights.size(), 1u);
      EXPECT_LE(static_cast<int>(r.lights.size()), n);
      expectFiniteAndConserving(t.probe, r, 1e-6);
    }
  }
  EXPECT_THROW(parseMethod("no-such-method"), Error);
  // The core's own, by the constants its code names them with, are registered under those names.
  for (Method m : {Method::MedianCut, Method::Variance, Method::SphericalHarmonics})
    EXPECT_EQ(parseMethod(std::string(m.name())), m);
  EXPECT_THROW(toString(Method("no-such-method")), Error);
}

TEST(Bake, AnyNGivesExactlyNLightsAndConservesEnergy) {
  auto t = sunnySky(256, 128);
  for (Method m : kMethods)
    for (int n : {1, 2, 3, 5, 7, 16, 33, 100, 256}) {
      auto r = bakeWith(t.probe, m, n);
      EXPECT_EQ(static_cast<int>(r.lights.size()), n) << toString(m);
      EXPECT_TRUE(r.notes.empty());
      expectFiniteAndConserving(t.probe, r);
      // The regions tile the image exactly once.
      long long area = 0;
      for (const Rect& reg : r.regions) area += reg.area();
      EXPECT_EQ(area, 256LL * 128);
    }
}

TEST(Bake, AnyNMoreLightsThanLitPixelsGivesFewerAndSaysSo) {
  auto t = makeProbe(32, 16, ProjectionKind::LatLong, [](int x, int y) {
    return (x == 3 && y == 4) || (x == 20 && y == 10) || (x == 31 && y == 0) ? Rgb{1, 2, 3} : Rgb{0, 0, 0};
  });
  for (Method m : kMethods) {
    auto r = bakeWith(t.probe, m, 8);
    EXPECT_EQ(r.lights.size(), 3u);
    ASSERT_EQ(r.notes.size(), 1u);
    EXPECT_NE(r.notes[0].text.find("made 3 lights, not 8"), std::string::npos) << r.notes[0].text;
    EXPECT_EQ(r.notes[0].kind, NoteKind::Warning);
    expectFiniteAndConserving(t.probe, r);
  }
}

TEST(Bake, HardProbeSingleHotPixelGivesOneExactLight) {
  const int W = 128, H = 64, px = 77, py = 20;
  auto t = makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) {
    return x == px && y == py ? Rgb{1e7, 2e7, 3e7} : Rgb{0, 0, 0};
  });
  for (Method m : kMethods)
    for (int n : {1, 4, 5}) {
      auto r = bakeWith(t.probe, m, n);
      ASSERT_EQ(r.lights.size(), 1u);
      const Light& l = r.lights[0];
      double omega = t.probe.projection().pixelSolidAngle(px, py);
      EXPECT_NEAR(l.rgb[1], 2e7 * omega, 1e-9 * 2e7 * omega);
      EXPECT_NEAR(dot(l.direction, *t.probe.projection().direction((px + 0.5) / W, (py + 0.5) / H)), 1.0,
                  1e-12);
      EXPECT_NEAR(l.angularRadius, 0.0, 1e-6);
      EXPECT_EQ(l.energyShare, 1.0);
    }
}

TEST(Bake, HardProbeTinyAndDegenerateShapes) {
  for (auto [w, h] : {std::pair{1, 1}, std::pair{2, 1}, std::pair{1, 7}, std::pair{9, 1}, std::pair{3, 2}}) {
    auto t = makeProbe(w, h, ProjectionKind::LatLong, [](int x, int y) {
      return Rgb{1.0 + x, 2.0 + y, 0.5};
    });
    for (Method m : kMethods)
      for (int n : {1, 2, 3, 16}) {
        auto r = bakeWith(t.probe, m, n);
        EXPECT_EQ(static_cast<int>(r.lights.size()), std::min(n, w * h)) << w << "x" << h;
        expectFiniteAndConserving(t.probe, r);
      }
  }
}

TEST(Bake, HardProbeAllBlackGivesNoLightsAndSaysSo) {
  auto t = uniformProbe(64, 32, ProjectionKind::LatLong, {0, 0, 0});
  for (Method m : kMethods) {
    auto r = bakeWith(t.probe, m, 16);
    EXPECT_TRUE(r.lights.empty());
    ASSERT_FALSE(r.notes.empty());
    EXPECT_NE(r.notes[0].text.find("black"), std::string::npos);
    EXPECT_EQ(r.totalRgb, (Rgb{0, 0, 0}));
  }
}

TEST(Bake, HardProbeASourceStraddlingTheSeamPointsBehind) {
  // Columns W-2, W-1, 0, 1 at the equator: the lat-long seam is at phi = +-pi, direction -X.
  const int W = 256, H = 128;
  auto t = makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) {
    bool spot = (x <= 1 || x >= W - 2) && (y == H / 2 - 1 || y == H / 2);
    return spot ? Rgb{100, 100, 100} : Rgb{0.001, 0.001, 0.001};
  });
  for (Method m : kMethods) {
    auto one = bakeWith(t.probe, m, 1);
    ASSERT_EQ(one.lights.size(), 1u);
    EXPECT_LT(one.lights[0].direction.x, -0.99) << toString(m);
    auto many = bakeWith(t.probe, m, 16);
    expectFiniteAndConserving(t.probe, many);
    for (const Light& l : many.lights) {
      if (l.energyShare > 0.1) {
        EXPECT_LT(l.direction.x, -0.99) << toString(m);
      }
    }
  }
}

TEST(Bake, HardProbeBrightSunBesideDimSky) {
  // 1e7 : 1e-2, as in the issue, at a size a test can afford.
  auto t = makeProbe(1024, 512, ProjectionKind::LatLong, [](int x, int y) {
    return x == 700 && y == 100 ? Rgb{1e7, 1e7, 1e7} : Rgb{1e-2, 1e-2, 1e-2};
  });
  for (Method m : kMethods)
    for (int n : {16, 256}) {
      auto r = bakeWith(t.probe, m, n);
      EXPECT_EQ(static_cast<int>(r.lights.size()), n);
      expectFiniteAndConserving(t.probe, r, 1e-10);
      // The sun is one light of its own (plus, for median cut, nothing else shares its region's energy).
      double maxShare = 0;
      for (const Light& l : r.lights) maxShare = std::max(maxShare, l.energyShare);
      EXPECT_GT(maxShare, 0.9);
    }
}

TEST(Bake, HorizonFirstCutSeparatesSkyFromGroundAndNoLightMixesThem) {
  auto t = sunnySky(256, 128);
  for (Method m : kMethods)
    for (int n : {2, 16, 64}) {
      auto r = bakeWith(t.probe, m, n, kFull, /*horizon=*/true);
      EXPECT_TRUE(r.horizonSplit);
      ASSERT_FALSE(r.cuts.empty());
      EXPECT_EQ(r.cuts[0].axis, Axis::Y);
      EXPECT_EQ(r.cuts[0].position, 64);
      for (const Rect& reg : r.regions) EXPECT_TRUE(reg.y1 <= 64 || reg.y0 >= 64);
      EXPECT_EQ(static_cast<int>(r.lights.size()), n);
      expectFiniteAndConserving(t.probe, r);
    }
  // One light cannot be split; a probe lit on one side only has nothing to separate.
  EXPECT_FALSE(bakeWith(t.probe, Method::Variance, 1, kFull, true).horizonSplit);
  auto skyOnly = makeProbe(64, 32, ProjectionKind::LatLong, [](int, int y) {
    return y < 16 ? Rgb{1, 1, 1} : Rgb{0, 0, 0};
  });
  auto r = bakeWith(skyOnly.probe, Method::Variance, 8, kFull, true);
  EXPECT_FALSE(r.horizonSplit);
  EXPECT_EQ(r.lights.size(), 8u);
}

TEST(WorkingResolution, CoarseCutsFallOnCellBordersAndStillConserve) {
  auto t = sunnySky(512, 256);
  for (Method m : kMethods) {
    auto r = bakeWith(t.probe, m, 32, WorkingResolution{WorkingResolution::Mode::Width, 128});
    EXPECT_EQ(r.cellSize, 4);
    EXPECT_EQ(r.lights.size(), 32u);
    for (const Rect& reg : r.regions) {
      EXPECT_EQ(reg.x0 % 4, 0);
      EXPECT_EQ(reg.y0 % 4, 0);
    }
    expectFiniteAndConserving(t.probe, r);
  }
  EXPECT_EQ((WorkingResolution{WorkingResolution::Mode::Auto, 0}.cellSize(8192)), 4);
  EXPECT_EQ((WorkingResolution{WorkingResolution::Mode::Auto, 0}.cellSize(2048)), 1);
  EXPECT_EQ((WorkingResolution{WorkingResolution::Mode::Width, 1000}.cellSize(8192)), 9);
}

TEST(Bake, BitIdenticalWhateverTheThreadCount) {
  auto t = sunnySky(512, 256);
  int threads = 0;
  OIIO::getattribute("threads", threads);
  OIIO::attribute("threads", 1);
  auto one = bakeWith(t.probe, Method::Variance, 37);
  OIIO::attribute("threads", 4);
  auto four = bakeWith(t.probe, Method::Variance, 37);
  OIIO::attribute("threads", threads);
  ASSERT_EQ(one.lights.size(), four.lights.size());
  for (std::size_t i = 0; i < one.lights.size(); ++i) {
    EXPECT_EQ(one.lights[i].rgb, four.lights[i].rgb);
    EXPECT_EQ(one.lights[i].direction.x, four.lights[i].direction.x);
    EXPECT_EQ(one.lights[i].rect, four.lights[i].rect);
  }
}

TEST(Bake, OnePrebuiltGridGivesEveryCountTheLightsOfItsOwnBake) {
  // autoCount and the tradeoff grid build the working grid once and bake every count on it.
  auto t = sunnySky(512, 256);
  for (Method m : {Method::MedianCut, Method::Variance})
    for (int cellSize : {1, 4}) {
      const MomentTable table(t.probe, cellSize);
      for (int n : {1, 7, 64}) {
        BakeOptions o;
        o.method = m;
        o.lights = n;
        o.resolution = cellSize == 1 ? WorkingResolution{WorkingResolution::Mode::Full, 0}
                                     : WorkingResolution{WorkingResolution::Mode::Width, 128};
        BakeResult own = bake(t.probe, o), shared = bake(t.probe, table, o);
        ASSERT_EQ(own.lights.size(), shared.lights.size());
        EXPECT_EQ(own.cellSize, shared.cellSize);
        EXPECT_EQ(shared.timings.tablesMs, 0.0);
        for (std::size_t i = 0; i < own.lights.size(); ++i) {
          EXPECT_EQ(own.lights[i].rgb, shared.lights[i].rgb);
          EXPECT_EQ(own.lights[i].direction.x, shared.lights[i].direction.x);
          EXPECT_EQ(own.lights[i].rect, shared.lights[i].rect);
        }
      }
    }
  BakeOptions sh;
  sh.method = Method::SphericalHarmonics;
  EXPECT_THROW(bake(t.probe, MomentTable(t.probe, 1), sh), Error);  // SH has no grid
}

TEST(Bake, RejectsZeroAndAbsurdLightCounts) {
  auto t = uniformProbe(8, 4, ProjectionKind::LatLong, {1, 1, 1});
  BakeOptions o;
  o.lights = 0;
  EXPECT_THROW(bake(t.probe, o), Error);
  o.lights = kMaxLights + 1;
  EXPECT_THROW(bake(t.probe, o), Error);
}

// Pixels across the whole float range at once: zeros, denormals, 1e-30, 1e30 and values near FLT_MAX. Every
// method must stay finite and conserve energy (sums are in double: 1e38 x 4pi x 1e5 pixels is far from
// overflow).
TEST(Bake, HardProbeTheWholeFloatRangeInOneProbe) {
  const float values[] = {0.0f, 1e-42f, 1e-30f, 1.0f, 1e30f, 3.0e38f};
  std::mt19937 rng(99);
  std::uniform_int_distribution<int> pick(0, 5);
  auto t = testing::makeProbe(128, 64, ProjectionKind::LatLong, [&](int, int) {
    return Rgb{values[pick(rng)], values[pick(rng)], values[pick(rng)]};
  });
  for (Method m : {Method::MedianCut, Method::Variance, Method::SphericalHarmonics})
    for (int n : {1, 7, 64}) {
      BakeOptions o;
      o.method = m;
      o.lights = n;
      auto r = bake(t.probe, o);
      EXPECT_EQ(static_cast<int>(r.lights.size()), n) << toString(m);
      expectFiniteAndConserving(t.probe, r, 1e-9);
    }
}

}  // namespace
}  // namespace probelights
