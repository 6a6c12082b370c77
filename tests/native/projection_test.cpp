// Projections: the lat-long convention (a test that catches a flipped axis), mirror ball and angular maps,
// and exact pixel solid angles.
#include "probelights/projection.h"

#include <gtest/gtest.h>

#include <random>

#include "test_probes.h"

namespace probelights {
namespace {

using testing::bakeWith;
using testing::makeProbe;

// The convention in DEVELOPERS.md, measured with a Cycles render of a single bright pixel.
Vec3 conventionDirection(double u, double v) {
  double phi = 2 * kPi * (0.5 - u), el = kPi / 2 - kPi * v;
  return {std::cos(el) * std::cos(phi), std::cos(el) * std::sin(phi), std::sin(el)};
}

// One bright pixel in a black lat-long probe; the single light must point where the convention says.
Vec3 brightPixelLight(int width, int height, int px, int py) {
  auto t = makeProbe(width, height, ProjectionKind::LatLong, [&](int x, int y) {
    return x == px && y == py ? Rgb{100, 100, 100} : Rgb{0, 0, 0};
  });
  auto r = bakeWith(t.probe, Method::Variance, 1);
  EXPECT_EQ(r.lights.size(), 1u);
  return r.lights.at(0).direction;
}

TEST(Projection, LatLongBrightPixelLightFollowsTheBlenderConvention) {
  const int W = 64, H = 32;
  // Column 16 of 64 is a quarter of the way from the left edge: phi ~ +pi/2, so the light is towards +Y.
  Vec3 d = brightPixelLight(W, H, 16, 15);
  EXPECT_GT(d.y, 0.99);
  // The centre column looks along +X; column 0 (the left edge) along -X.
  EXPECT_GT(brightPixelLight(W, H, 32, 15).x, 0.99);
  EXPECT_LT(brightPixelLight(W, H, 0, 15).x, -0.99);
  // The top row is up (+Z), the bottom row down.
  EXPECT_GT(brightPixelLight(W, H, 40, 0).z, 0.99);
  EXPECT_LT(brightPixelLight(W, H, 40, H - 1).z, -0.99);
  // And exactly the formula, pixel centre by pixel centre.
  for (int px : {3, 21, 50})
    for (int py : {2, 16, 29}) {
      Vec3 e = conventionDirection((px + 0.5) / W, (py + 0.5) / H), got = brightPixelLight(W, H, px, py);
      EXPECT_NEAR(got.x, e.x, 1e-12);
      EXPECT_NEAR(got.y, e.y, 1e-12);
      EXPECT_NEAR(got.z, e.z, 1e-12);
    }
}

TEST(Projection, LatLongRightHandedZUp) {
  Projection p(ProjectionKind::LatLong, 256, 128);
  // Walking right in the image turns clockwise seen from above (phi decreases): +X then -Y.
  Vec3 a = *p.direction(0.5, 0.5), b = *p.direction(0.75, 0.5);
  EXPECT_NEAR(a.x, 1, 1e-12);
  EXPECT_NEAR(b.y, -1, 1e-12);
}

TEST(Projection, SolidAnglesSumToTheSphere) {
  struct Case {
    ProjectionKind kind;
    int w, h;
    double tolerance;
  };
  for (Case c :
       {Case{ProjectionKind::LatLong, 1024, 512, 1e-12}, Case{ProjectionKind::LatLong, 1000, 500, 1e-12},
        Case{ProjectionKind::LatLong, 3, 1, 1e-12}, Case{ProjectionKind::MirrorBall, 256, 256, 1e-10},
        Case{ProjectionKind::MirrorBall, 101, 77, 1e-10}, Case{ProjectionKind::Angular, 256, 256, 1e-6},
        Case{ProjectionKind::Angular, 99, 99, 1e-6}}) {
    Projection p(c.kind, c.w, c.h);
    double total = 0;
    for (int y = 0; y < c.h; ++y)
      for (int x = 0; x < c.w; ++x) total += p.pixelSolidAngle(x, y);
    EXPECT_NEAR(total / (4 * kPi), 1.0, c.tolerance) << toString(c.kind) << " " << c.w << "x" << c.h;
  }
}

TEST(Projection, DirectionRoundTrip) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n;
  for (auto kind : {ProjectionKind::LatLong, ProjectionKind::MirrorBall, ProjectionKind::Angular}) {
    Projection p(kind, 512, kind == ProjectionKind::LatLong ? 256 : 512);
    for (int i = 0; i < 1000; ++i) {
      Vec3 d{n(rng), n(rng), n(rng)};
      d = (1.0 / d.length()) * d;
      if (d.y > 0.999) continue;  // the ball's rim is a single direction
      auto uv = p.imagePosition(d);
      auto back = p.direction(uv[0], uv[1]);
      ASSERT_TRUE(back) << toString(kind);
      EXPECT_NEAR(dot(*back, d), 1.0, 1e-9) << toString(kind);
    }
  }
}

TEST(Projection, MirrorBallMatchesBlendersOrientation) {
  Projection p(ProjectionKind::MirrorBall, 256, 256);
  auto centre = *p.direction(0.5, 0.5);
  EXPECT_NEAR(centre.y, -1, 1e-12);  // the ball's centre reflects the camera, which looks along +Y
  // Half-way to the right edge: the normal is tilted 30 degrees, the reflection 60 degrees from -Y towards
  // +X.
  auto right = *p.direction(0.75, 0.5);
  EXPECT_NEAR(right.x, std::sin(kPi / 3), 1e-12);
  EXPECT_NEAR(right.y, -std::cos(kPi / 3), 1e-12);
  auto up = *p.direction(0.5, 0.25);  // v from the top: up in the image is +Z
  EXPECT_NEAR(up.z, std::sin(kPi / 3), 1e-12);
  // Half-way to the rim in radius is the equal-area half: the cap around -Y of solid angle pi (a quarter
  // sphere).
  auto rim = *p.direction(0.5 + 0.5 * 0.999999, 0.5);
  EXPECT_GT(rim.y, 0.999);
  EXPECT_FALSE(p.direction(0.95, 0.95));  // a corner outside the ball
}

TEST(Projection, AngularAngleGrowsLinearlyWithRadius) {
  Projection p(ProjectionKind::Angular, 200, 200);
  EXPECT_NEAR(p.direction(0.5, 0.5)->y, -1, 1e-12);
  // Radius 0.5 (half-way to the rim) is 90 degrees from the centre: straight right is +X.
  auto d = *p.direction(0.75, 0.5);
  EXPECT_NEAR(d.x, 1, 1e-12);
  auto up = *p.direction(0.5, 0.25);
  EXPECT_NEAR(up.z, 1, 1e-12);
}

TEST(Projection, AngularPixelSolidAngleMatchesFineQuadrature) {
  Projection p(ProjectionKind::Angular, 64, 64);
  for (auto [x, y] :
       {std::pair{32, 32}, std::pair{10, 30}, std::pair{3, 25}, std::pair{0, 31}, std::pair{60, 60}}) {
    // Brute force: midpoint rule on 400 x 400 sub-pixels of the density pi sin(pi r) / r.
    double sum = 0, h = 2.0 / 64 / 400;
    for (int i = 0; i < 400; ++i)
      for (int j = 0; j < 400; ++j) {
        double a = 2.0 * x / 64 - 1 + (i + 0.5) * h, b = 1 - 2.0 * (y + 1) / 64 + (j + 0.5) * h;
        double r = std::sqrt(a * a + b * b);
        if (r < 1) sum += kPi * std::sin(kPi * r) / r * h * h;
      }
    EXPECT_NEAR(p.pixelSolidAngle(x, y), sum, 1e-6 * 4 * kPi / (64 * 64)) << x << "," << y;
  }
}

TEST(RectangleAreaInUnitDisc, RectangleAreaInClosedForm) {
  EXPECT_NEAR(rectangleAreaInUnitDisc(-1, 1, -1, 1), kPi, 1e-14);
  EXPECT_NEAR(rectangleAreaInUnitDisc(0, 1, 0, 1), kPi / 4, 1e-14);
  EXPECT_NEAR(rectangleAreaInUnitDisc(-0.1, 0.2, 0.3, 0.5), 0.3 * 0.2, 1e-14);
  EXPECT_EQ(rectangleAreaInUnitDisc(0.9, 1, 0.9, 1), 0.0);
  // A rectangle the circle cuts, against a fine midpoint rule.
  double a0 = 0.55, a1 = 0.95, b0 = -0.4, b1 = 0.7, sum = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double a = a0 + (i + 0.5) * (a1 - a0) / n, b = b0 + (j + 0.5) * (b1 - b0) / n;
      if (a * a + b * b < 1) sum += (a1 - a0) * (b1 - b0) / n / n;
    }
  EXPECT_NEAR(rectangleAreaInUnitDisc(a0, a1, b0, b1), sum, 1e-5);
}

}  // namespace
}  // namespace probelights
