// The evaluator: its ground truth against brute force and closed forms, and the effect names.
#include "probelights/evaluate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "probelights/error.h"
#include "probelights/moment_table.h"
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
  // Diffuse: the sum over the pixels' centres. Shadow: the renderer's world, each pixel a square of constant
  // radiance (here every pixel carries more than 1e-4 of the light, so the evaluator splits them all),
  // integrated by brute force on 64 x 64 points a pixel.
  const int W = 32, H = 16, S = 64;
  auto t = testing::makeProbe(W, H, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{0.1 + x % 5, 0.2 + y % 3, 1.0 + (x * y) % 7};
  });
  Evaluator ev(t.probe, kDiffuse | kShadow | kGlossy);
  const Projection& pr = t.probe.projection();
  double worstSplit = 0, worstCentres = 0;
  for (std::size_t i = 0; i < ev.normals().size(); i += 17) {
    Rgb diffuse{}, shadow{}, centres{};
    const Vec3 p = ev.groundPoints()[i];
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const Rgb L = t.probe.radiance(x, y);
        const double omega = pr.pixelSolidAngle(x, y);
        const Vec3 d = *pr.direction((x + 0.5) / W, (y + 0.5) / H);
        const double cn = std::max(0.0, dot(ev.normals()[i], d));
        const bool centreSeen = d.z > 0 && Evaluator::visible(p, d);
        double seen = 0;  // the pixel's visible fraction of its projected solid angle, by its points
        for (int sy = 0; sy < S; ++sy)
          for (int sx = 0; sx < S; ++sx) {
            const Vec3 e = *pr.direction((x + (sx + 0.5) / S) / W, (y + (sy + 0.5) / S) / H);
            if (e.z > 0 && Evaluator::visible(p, e)) seen += e.z;
          }
        for (int k = 0; k < 3; ++k) {
          diffuse[k] += L[k] * cn * omega;
          shadow[k] += L[k] * omega * seen / (S * S);
          if (centreSeen) centres[k] += L[k] * d.z * omega;
        }
      }
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(ev.diffuseTruth()[i][k], diffuse[k], 1e-12 * (1 + diffuse[k]));
      worstSplit = std::max(worstSplit, std::abs(ev.shadowTruth()[i][k] - shadow[k]) / shadow[k]);
      worstCentres = std::max(worstCentres, std::abs(centres[k] - shadow[k]) / shadow[k]);
    }
  }
  std::printf("worst relative shadow truth error: split pixels %.2e, pixel centres %.2e\n", worstSplit,
              worstCentres);
  EXPECT_LT(worstSplit, 0.02);              // measured 1.4e-2 (5 x 5 points a pixel here)
  EXPECT_GT(worstCentres, 5 * worstSplit);  // 1.4e-1
}

// The irradiance truth visits only the sample bins a normal's horizon crosses (the others by their moments):
// it must equal the sum over every pixel on the 256 normals and the refit's 1024, to rounding.
TEST(Evaluator, IrradianceTruthEqualsTheSumOverEveryPixel) {
  const int W = 256, H = 128;
  auto t = testing::makeProbe(W, H, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{0.1 + (x * 7 + y) % 13, (x / 9 + y / 5) % 2 == 0 ? 4.0 : 0.0, 1.0 + (x * y) % 7};
  });
  Evaluator ev(t.probe, kDiffuse, {2048, true});
  const Projection& pr = t.probe.projection();
  auto brute = [&](const Vec3& n) {
    Rgb e{};
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const double w = std::max(0.0, dot(n, *pr.direction((x + 0.5) / W, (y + 0.5) / H)));
        for (int k = 0; k < 3; ++k) e[k] += t.probe.radiance(x, y)[k] * pr.pixelSolidAngle(x, y) * w;
      }
    return e;
  };
  for (auto [normals, truth] :
       {std::pair{&ev.normals(), &ev.diffuseTruth()}, {&ev.fitNormals(), &ev.fitTruth()}})
    for (std::size_t i = 0; i < normals->size(); i += 7) {
      const Rgb e = brute((*normals)[i]);
      for (int k = 0; k < 3; ++k) EXPECT_NEAR((*truth)[i][k], e[k], 1e-11 * (1 + e[k])) << i;
    }
}

TEST(Evaluator, OneLightPerPixelIsExactAndFewLightsAreNot) {  // exact where the truth is the pixels' centres
  auto t = testing::makeProbe(16, 8, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{1.0 + x, 0.5 + y, 2.0};
  });
  Evaluator ev(t.probe, kDiffuse | kShadow | kGlossy);
  BakeOptions o;
  o.lights = 16 * 8;
  auto all = bake(t.probe, o);
  auto e = ev.evaluate(all.lights);
  EXPECT_LT(e.diffuse, 1e-12);
  // The shadow truth takes the pixels as squares (every pixel here is bright enough to be split), which a
  // light at each pixel's centre is not: 1.9 % apart on this probe.
  EXPECT_LT(e.shadow, 0.03);
  EXPECT_LT(e.glossy, 1e-12);
  o.lights = 2;
  auto few = ev.evaluate(bake(t.probe, o).lights);
  EXPECT_GT(few.diffuse, 1e-3);
  EXPECT_TRUE(std::isnan(Evaluator(t.probe, kDiffuse).evaluate(all.lights).shadow));  // only what was asked
}

TEST(Evaluator, SamplesFromTheWorkingGridEqualSamplesFromThePixels) {
  // A grid of 4 px cells serves samples of 16 px (a 512-wide estimate of a 2048-wide probe); a grid that does
  // not tile them (cells of 3 px) or has no cell sums (full resolution) leaves the evaluator on the pixels.
  const int W = 2048, H = 1024;
  auto t = testing::makeProbe(W, H, ProjectionKind::LatLong, [](int x, int y) {
    const bool sun = std::abs(x - 700) < 3 && std::abs(y - 200) < 3;
    return sun ? Rgb{4e4, 3.8e4, 3.5e4} : Rgb{0.2 + 0.1 * (x % 13), 0.3 + 0.01 * (y % 29), 0.5};
  });
  const Effects all = kDiffuse | kShadow | kGlossy;
  const EvaluatorOptions options{512, true};
  const Evaluator pixels(t.probe, all, options);
  BakeOptions o;
  o.lights = 24;
  const auto lights = bake(t.probe, o).lights;
  for (int cellSize : {4, 3, 1}) {
    const MomentTable grid(t.probe, cellSize);
    const Evaluator cells(t.probe, grid, all, options);
    // Equal up to rounding of the set's largest value (a ground point's truth is the sky less the hidden
    // part).
    auto near = [](const std::vector<Rgb>& a, const std::vector<Rgb>& b) {
      ASSERT_EQ(a.size(), b.size());
      double scale = 0;
      for (const Rgb& v : b) scale = std::max({scale, v[0], v[1], v[2]});
      for (std::size_t i = 0; i < a.size(); ++i)
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[i][k], b[i][k], 1e-12 * scale);
    };
    near(cells.diffuseTruth(), pixels.diffuseTruth());
    near(cells.shadowTruth(), pixels.shadowTruth());
    near(cells.fitTruth(), pixels.fitTruth());
    near(cells.fitShadowTruth(), pixels.fitShadowTruth());
    const EffectErrors a = cells.evaluate(lights), b = pixels.evaluate(lights);
    EXPECT_NEAR(a.diffuse, b.diffuse, 1e-12);
    EXPECT_NEAR(a.shadow, b.shadow, 1e-12);
    EXPECT_NEAR(a.glossy, b.glossy, 1e-12);
  }
}

TEST(Effects, ParseAndPrint) {
  EXPECT_EQ(parseEffects("diffuse,shadow"), kDiffuse | kShadow);
  EXPECT_EQ(effectsToString(kDiffuse | kGlossy), "diffuse,glossy");
  EXPECT_THROW(parseEffects("caustics"), Error);
}

}  // namespace
}  // namespace probelights
