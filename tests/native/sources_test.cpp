// Lamps for the sources, a residual for the world (sources.h): the split is exact per pixel, the lamps plus
// the residual give back the probe's light per region and channel, two suns stay two lamps, the knobs mean
// what they say, and a request that would break the residual's exactness is refused.
#include "probelights/sources.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "probelights/error.h"
#include "probelights/image_file.h"
#include "probelights/preview.h"
#include "probelights/request.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::makeProbe;

// A sky of 0.1 (bluish) with two suns on the horizon, opposite each other at +`axis` and -`axis` (X or Y),
// each a disc of a few pixels: the two sources of issue 30's "two opposite suns stay two lamps" (EEVEE's sun
// extraction averages them into one between them).
testing::TestProbe twoSuns(int axis = 0) {
  const int W = 256, H = 128;
  return makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) -> Rgb {
    // Pixel centres: phi = 2 pi (0.5 - u), elevation = pi / 2 - pi v.
    const double phi = 2 * kPi * (0.5 - (x + 0.5) / W), el = kPi / 2 - kPi * (y + 0.5) / H;
    const Vec3 d{std::cos(el) * std::cos(phi), std::cos(el) * std::sin(phi), std::sin(el)};
    const double a = axis == 0 ? d.x : d.y;
    if (std::abs(a) > std::cos(3 * kPi / 180)) return a > 0 ? Rgb{800, 700, 600} : Rgb{300, 400, 500};
    return {0.08, 0.1, 0.14};
  });
}

// Sum of value x solid angle over pixels [x0, x1) x [y0, y1) of an RGB image of the probe's size (columns
// mod the width: a region of the sources may wrap round the seam).
Rgb regionSum(const Probe& probe, const float* pixels, const Rect& r) {
  Rgb s{};
  for (int y = r.y0; y < r.y1; ++y)
    for (int xx = r.x0; xx < r.x1; ++xx) {
      const int x = xx % probe.width();
      const double w = probe.projection().pixelSolidAngle(x, y);
      for (int c = 0; c < 3; ++c)
        s[c] += pixels[(static_cast<std::size_t>(y) * probe.width() + x) * 3 + c] * w;
    }
  return s;
}

TEST(Sources, SplitIsExactPerPixelAndKeepsTheResidualUnderTheLevel) {
  const auto p = twoSuns();
  const SourceSplit s = splitSources(p.probe, {10, 0});
  EXPECT_DOUBLE_EQ(s.level, 10 * s.meanLuminance);
  const float* R = s.residual->pixels.get();
  const float* X = s.sources->pixels.get();
  int clipped = 0;
  for (int y = 0; y < p.probe.height(); ++y)
    for (int x = 0; x < p.probe.width(); ++x) {
      const std::size_t i = (static_cast<std::size_t>(y) * p.probe.width() + x) * 3;
      const Rgb l = p.probe.light(x, y);
      for (int c = 0; c < 3; ++c) {
        ASSERT_GE(R[i + c], 0.0f);
        ASSERT_EQ(static_cast<double>(R[i + c]) + static_cast<double>(X[i + c]), l[c]) << x << "," << y;
      }
      const double Y = luminance(R[i], R[i + 1], R[i + 2]);
      ASSERT_LE(Y, s.level * (1 + 1e-6));
      clipped += X[i] > 0;
    }
  EXPECT_GT(clipped, 20);  // the two suns' pixels
  const Rgb total = p.probe.integral();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.residualRgb[c] + s.sourcesRgb[c], total[c], 1e-12 * total[c]);
  EXPECT_GT(s.share, 0.5);
}

TEST(Sources, TwoOppositeSunsStayTwoLampsAndEachRegionGivesBackTheProbe) {
  // At +Y and -Y (a quarter of the way in from each edge of the lat-long image), two lamps, one each.
  const auto p = twoSuns(1);
  BakeRequest request;
  request.bake.lights = 2;
  request.sources = {10, 0};
  const EvaluatedBake ev = bakeLoaded(p.probe, request);
  ASSERT_TRUE(ev.sources);
  ASSERT_EQ(ev.bake.lights.size(), 2u);
  bool north = false, south = false;
  for (const Light& l : ev.bake.lights) {
    north |= l.direction.y > 0.99;
    south |= l.direction.y < -0.99;
  }
  EXPECT_TRUE(north && south) << ev.bake.lights[0].direction.y << " " << ev.bake.lights[1].direction.y;
  // Per region and channel: the residual's sum plus the lamp is the probe's sum.
  const float* R = ev.sources->residual->pixels.get();
  for (const Light& l : ev.bake.lights) {
    const Rgb r = regionSum(p.probe, R, l.rect);
    const Rgb whole = regionSum(p.probe, p.pixels->data(), l.rect);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c] + l.rgb[c], whole[c], 1e-9 * whole[c]) << c;
  }
}

// A sun on the lat-long image's seam (-X: phi = pi) would be cut in two by the image's edges (a region of the
// rectangles the cuts make cannot wrap round), a lamp each side with half the disc's angle. The lamps are
// cut on the sources rolled to their darkest column (sources.h: darkestSeam), so the seam's sun gets one
// lamp, the same lamp as the same sun a quarter turn away (twoSuns(1)'s -Y sun: the same pixels, 64 columns
// over), its fitted angle included, and its region, which wraps round, gives back the probe's light with
// the residual.
TEST(Sources, ASunOnTheSeamTakesOneLampAsItWouldAnywhereElse) {
  const auto seam = twoSuns(0), away = twoSuns(1);
  BakeRequest request;
  request.bake.lights = 2;
  request.sources = {10, 0};
  request.accuracy.evaluate = true;
  request.accuracy.effects = kDiffuse | kShadow;
  EXPECT_EQ(darkestSeam(away.probe, *splitSources(away.probe, {10, 0}).sources), 0);  // cut as before
  EXPECT_NE(darkestSeam(seam.probe, *splitSources(seam.probe, {10, 0}).sources), 0);
  const EvaluatedBake a = bakeLoaded(seam.probe, request), b = bakeLoaded(away.probe, request);
  ASSERT_EQ(a.bake.lights.size(), 2u);
  ASSERT_EQ(b.bake.lights.size(), 2u);
  const int W = seam.probe.width();
  for (const Light& l : a.bake.lights) {
    EXPECT_GT(std::abs(l.direction.x), 0.99) << l.direction.x;
    const bool behind = l.direction.x < 0;
    const Light& twin = *std::find_if(b.bake.lights.begin(), b.bake.lights.end(), [&](const Light& m) {
      return (m.direction.y < 0) == behind;  // -X here is -Y there, +X is +Y
    });
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(l.rgb[c], twin.rgb[c], 1e-9 * twin.rgb[c]) << c;
    EXPECT_NEAR(l.angle, twin.angle, 1e-6) << l.angle << " " << twin.angle;
    EXPECT_TRUE(l.rect.x0 >= 0 && l.rect.x0 < W && l.rect.x1 > l.rect.x0 && l.rect.x1 <= l.rect.x0 + W);
    if (behind) {
      EXPECT_GT(l.rect.x1, W) << "the seam's sun's region wraps round";
    }
    const Rgb r = regionSum(seam.probe, a.sources->residual->pixels.get(), l.rect);
    const Rgb whole = regionSum(seam.probe, seam.pixels->data(), l.rect);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(r[c] + l.rgb[c], whole[c], 1e-9 * whole[c]) << c;
  }
  // Cut on the image's own edges the two lamps came out both at +X, the seam's sun split between them
  // (shadow error 73 %); now 3.05 % against 2.85 % a quarter turn away (the evaluator's directions are fixed
  // in the world, so a turned probe is judged on other samples).
  EXPECT_NEAR(a.errors.shadow, b.errors.shadow, 0.1 * b.errors.shadow);
}

// The preview draws a region that wraps round the seam on both edges: its right border is where its columns
// end past the width, wrapped to the left edge (cut on the image's own edges, no region drew a line there).
TEST(Sources, ThePreviewDrawsAWrappedRegionOnBothEdges) {
  const auto p = twoSuns(0);
  BakeRequest request;
  request.bake.lights = 2;
  request.sources = {10, 0};
  const EvaluatedBake ev = bakeLoaded(p.probe, request);
  const int W = p.probe.width(), H = p.probe.height();
  const auto wrapped =
      std::find_if(ev.bake.regions.begin(), ev.bake.regions.end(), [&](const Rect& r) { return r.x1 > W; });
  ASSERT_NE(wrapped, ev.bake.regions.end());
  const std::string path = ::testing::TempDir() + "wrapped_preview.png";
  writePreview(p.probe, ev.bake, path);
  const Image png = readImage(path);
  std::remove(path.c_str());
  ASSERT_EQ(png.width * H, png.height * W);
  const int column = static_cast<int>(static_cast<std::int64_t>(wrapped->x1 - W) * png.width / W) - 1;
  ASSERT_GE(column, 0);
  int green = 0, rows = 0;
  for (int y = wrapped->y0 * png.height / H + 1; y < wrapped->y1 * png.height / H - 1; ++y) {
    if (std::abs(y - png.height / 2) < 12)
      continue;  // the suns' red squares on the horizon are drawn over it
    const float* px = png.pixels.get() + (static_cast<std::size_t>(y) * png.width + column) * png.channels;
    green += px[1] > 0.5f && px[0] < 0.5f && px[2] < 0.5f;
    ++rows;
  }
  EXPECT_GT(rows, 10);
  EXPECT_EQ(green, rows) << "column " << column;
}

TEST(Sources, AShareFindsItsLevel) {
  const auto p = twoSuns();
  for (double share : {0.05, 0.3, 0.9}) {
    const SourceSplit s = splitSources(p.probe, {0, share});
    EXPECT_NEAR(s.share, share, 1e-9) << share;
  }
}

TEST(Sources, NegativeChannelsGoToTheLamps) {
  const auto p = makeProbe(16, 8, ProjectionKind::LatLong, [](int x, int y) -> Rgb {
    return x == 3 && y == 2 ? Rgb{-0.5, 0.2, 0.1} : Rgb{0.1, 0.1, 0.1};
  });
  const SourceSplit s = splitSources(p.probe, {10, 0});
  const std::size_t i = (2 * 16 + 3) * 3;
  EXPECT_EQ(s.residual->pixels.get()[i], 0.0f);
  EXPECT_EQ(s.sources->pixels.get()[i], -0.5f);
}

TEST(Sources, BadKnobsAndRequestsThatWouldBreakTheResidualAreRefused) {
  const auto p = twoSuns();
  EXPECT_THROW(splitSources(p.probe, {0, 0}), Error);
  EXPECT_THROW(splitSources(p.probe, {10, 0.5}), Error);
  EXPECT_THROW(splitSources(p.probe, {0, 1}), Error);
  BakeRequest request;
  request.sources = {10, 0};
  request.accuracy.refit = true;
  EXPECT_THROW(bakeLoaded(p.probe, request), Error);
  request.accuracy.refit = false;
  request.accuracy.maxError = 0.01;
  EXPECT_THROW(bakeLoaded(p.probe, request), Error);
  EXPECT_THROW(requestOption("source_level").set(request, "source_level", "-1"), Error);
  EXPECT_THROW(requestOption("source_share").set(request, "source_share", "100%"), Error);
}

// The bundled probe: its evaluation is of lamps plus residual, far below the lamps' error against the
// sources alone, and the residual written and read back is the residual.
TEST(Sources, BundledProbeEvaluatesLampsPlusResidualAndWritesTheResidual) {
  const Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  BakeRequest request;
  request.bake.lights = 4;
  request.sources = {10, 0};
  request.accuracy.evaluate = true;
  request.accuracy.effects = kDiffuse | kShadow;
  const EvaluatedBake ev = bakeLoaded(probe, request);
  ASSERT_TRUE(ev.evaluated && ev.sources);
  EXPECT_LT(ev.errors.diffuse, 0.01);
  EXPECT_LT(ev.errors.shadow, 0.02);
  Rgb sum = ev.sources->residualRgb;
  for (const Light& l : ev.bake.lights)
    for (int c = 0; c < 3; ++c) sum[c] += l.rgb[c];
  const Rgb total = probe.integral();
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], total[c], 1e-9 * total[c]);
  const std::string path = ::testing::TempDir() + "residual.exr";
  writeImage(ev.sources->residual->view(), path);
  const Image back = readImage(path);
  ASSERT_EQ(back.width, probe.width());
  const std::size_t n = static_cast<std::size_t>(back.width) * back.height * 3;
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(back.pixels.get()[i], ev.sources->residual->pixels.get()[i]);
}

}  // namespace
}  // namespace probelights
