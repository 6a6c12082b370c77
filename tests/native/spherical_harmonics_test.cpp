// Spherical harmonics: white furnace, orthonormality to 20 bands, projection, exact rectangle integrals,
// irradiance.
#include "probelights/spherical_harmonics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "test_probes.h"

namespace probelights {
namespace {

// Gauss-Legendre nodes and weights on [-1, 1] by Newton's method on P_n (a test-only reference).
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.resize(n);
  w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1, p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[i] = z;
    w[i] = 2.0 / ((1 - z * z) * dp * dp);
  }
}

TEST(ShBasis, SloanConventionForTheFirstBands) {
  std::vector<double> y(9);
  Vec3 d{0.36, -0.48, 0.8};
  shBasis(3, d, y);
  const double k1 = std::sqrt(3.0 / (4 * kPi));
  EXPECT_NEAR(y[0], 0.5 / std::sqrt(kPi), 1e-15);
  EXPECT_NEAR(y[1], -k1 * d.y, 1e-15);
  EXPECT_NEAR(y[2], k1 * d.z, 1e-15);
  EXPECT_NEAR(y[3], -k1 * d.x, 1e-15);
  EXPECT_NEAR(y[4], 0.5 * std::sqrt(15 / kPi) * d.x * d.y, 1e-14);
  EXPECT_NEAR(y[6], 0.25 * std::sqrt(5 / kPi) * (3 * d.z * d.z - 1), 1e-14);
}

TEST(ShBasis, OrthonormalTo20BandsByQuadrature) {
  const int bands = 20, n = shCount(bands), nz = 24, nphi = 48;  // exact for products of degree <= 40
  std::vector<double> zs, ws, y(n);
  gaussLegendre(nz, zs, ws);
  std::vector<double> gram(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < nz; ++i)
    for (int j = 0; j < nphi; ++j) {
      double phi = 2 * kPi * j / nphi, r = std::sqrt(1 - zs[i] * zs[i]);
      shBasis(bands, {r * std::cos(phi), r * std::sin(phi), zs[i]}, y);
      double w = ws[i] * 2 * kPi / nphi;
      for (int a = 0; a < n; ++a)
        for (int b = a; b < n; ++b) gram[a * n + b] += w * y[a] * y[b];
    }
  double worst = 0;
  for (int a = 0; a < n; ++a)
    for (int b = a; b < n; ++b) worst = std::max(worst, std::abs(gram[a * n + b] - (a == b ? 1.0 : 0.0)));
  EXPECT_LT(worst, 1e-12);
}

TEST(ShBasis, StableAtHighBands) {
  // Band 200 values stay finite and of the size the normalization predicts (|N_l^m| <= sqrt((2l+1)/4pi)).
  std::vector<double> y(shCount(200));
  shBasis(200, {0.6, 0.0, 0.8}, y);
  for (double v : y) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_LE(std::abs(v), std::sqrt(2 * 401 / (4 * kPi)));
  }
}

TEST(ProjectProbe, WhiteFurnace) {
  const double L = 1.5;  // exact in float, as the probe stores it
  auto t = testing::uniformProbe(256, 128, ProjectionKind::LatLong, {L, L, L});
  ShCoefficients sh = projectProbe(t.probe, 8);
  EXPECT_NEAR(sh.c[0][1], 2 * std::sqrt(kPi) * L, 1e-12 * L);
  for (int i = 1; i < shCount(8); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_LT(std::abs(sh.c[i][k]), 1e-9 * L) << i;
  // And its irradiance is pi L on every normal.
  ShCoefficients e = irradianceCoefficients(sh);
  for (Vec3 n : {Vec3{0, 0, 1}, Vec3{1, 0, 0}, Vec3{0.6, -0.8, 0}})
    EXPECT_NEAR(e.evaluate(n)[0], kPi * L, 1e-9);
}

TEST(ProjectProbe, RecoversABandLimitedFunction) {
  const int bands = 5;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coef(-0.1, 0.1);
  ShCoefficients truth{bands, std::vector<Rgb>(shCount(bands))};
  for (auto& c : truth.c) c = {coef(rng), coef(rng), coef(rng)};
  truth.c[0] = {3, 3, 3};  // keeps the function positive (probes clamp negatives)
  const int W = 1024, H = 512;
  const Projection pr(ProjectionKind::LatLong, W, H);
  auto t = testing::makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) {
    return truth.evaluate(*pr.direction((x + 0.5) / W, (y + 0.5) / H));
  });
  ShCoefficients got = projectProbe(t.probe, bands);
  for (int i = 0; i < shCount(bands); ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got.c[i][k], truth.c[i][k], 2e-5) << i;
}

TEST(ProjectProbe, MirrorBallAgreesWithLatLong) {
  // The same smooth sky in both projections gives the same low-band coefficients.
  auto sky = [](const Vec3& d) { return Rgb{1 + d.z, 1 + 0.5 * d.x, 1 - 0.3 * d.y}; };
  const Projection llProjection(ProjectionKind::LatLong, 512, 256);
  auto ll = testing::makeProbe(512, 256, ProjectionKind::LatLong, [&](int x, int y) {
    return sky(*llProjection.direction((x + 0.5) / 512, (y + 0.5) / 256));
  });
  Projection ballProjection(ProjectionKind::MirrorBall, 512, 512);
  auto ball = testing::makeProbe(512, 512, ProjectionKind::MirrorBall, [&](int x, int y) {
    auto d = ballProjection.direction((x + 0.5) / 512, (y + 0.5) / 512);
    return d ? sky(*d) : Rgb{0, 0, 0};
  });
  ShCoefficients a = projectProbe(ll.probe, 3), b = projectProbe(ball.probe, 3);
  for (int i = 0; i < 9; ++i)
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.c[i][k], b.c[i][k], 0.02) << i;
}

TEST(ShRectIntegrator, AgreeWithBruteForce) {
  const int bands = 7;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coef(-1, 1);
  std::vector<double> c(shCount(bands));
  for (double& v : c) v = coef(rng);
  ShRectIntegrator integrator(bands, c);
  std::vector<double> y(c.size());
  for (auto [z0, z1, p0, p1] : {std::array{-1.0, 1.0, -kPi, kPi}, std::array{0.2, 0.9, -1.0, 2.0},
                                std::array{-0.95, -0.3, 2.5, 3.1}, std::array{0.99, 1.0, -3.0, -2.9}}) {
    const int n = 600;
    double brute = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        double z = z0 + (i + 0.5) * (z1 - z0) / n, phi = p0 + (j + 0.5) * (p1 - p0) / n,
               r = std::sqrt(1 - z * z);
        shBasis(bands, {r * std::cos(phi), r * std::sin(phi), z}, y);
        double f = 0;
        for (std::size_t k = 0; k < c.size(); ++k) f += c[k] * y[k];
        brute += f * (z1 - z0) * (p1 - p0) / n / n;
      }
    EXPECT_NEAR(integrator.integral(z0, z1, p0, p1), brute, 2e-5 * (z1 - z0) * (p1 - p0) * 10)
        << z0 << " " << p0;
  }
  // Over the whole sphere only the constant term survives: c_0 * sqrt(4 pi).
  EXPECT_NEAR(integrator.integral(-1, 1, -kPi, kPi), c[0] * std::sqrt(4 * kPi), 1e-12);
}

TEST(IrradianceCoefficients, MatchesADirectSumOnAProbe) {
  // A smooth sky: 9 bands of irradiance are within 0.5 % of the exact sum of L max(0, n.d) dOmega.
  auto sky = [](const Vec3& d) { return Rgb{0.2 + std::max(0.0, d.z), 0.3, 0.1 + 0.05 * (d.x + 1)}; };
  Projection pr(ProjectionKind::LatLong, 512, 256);
  auto t = testing::makeProbe(512, 256, ProjectionKind::LatLong, [&](int x, int y) {
    return sky(*pr.direction((x + 0.5) / 512, (y + 0.5) / 256));
  });
  ShCoefficients e = irradianceCoefficients(projectProbe(t.probe, 9));
  for (Vec3 n : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, Vec3{0.8, 0, 0.6}}) {
    double exact = 0;
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 512; ++x) {
        Vec3 d = *pr.direction((x + 0.5) / 512, (y + 0.5) / 256);
        exact += t.probe.radiance(x, y)[0] * std::max(0.0, dot(n, d)) * pr.pixelSolidAngle(x, y);
      }
    EXPECT_NEAR(e.evaluate(n)[0], exact, 5e-3 * exact);
  }
  EXPECT_NEAR(irradianceFactor(2), kPi / 4, 1e-15);
  EXPECT_NEAR(irradianceFactor(4), -kPi / 24, 1e-15);
  EXPECT_EQ(irradianceFactor(3), 0.0);
}

TEST(ApplyWindow, DampHighBandsOnly) {
  ShCoefficients sh{4, std::vector<Rgb>(16, Rgb{1, 1, 1})};
  applyWindow(sh, ShWindow::Lanczos);
  EXPECT_EQ(sh.c[0][0], 1.0);
  EXPECT_LT(sh.c[15][0], sh.c[5][0]);
  EXPECT_GT(sh.c[15][0], 0.0);
}

}  // namespace
}  // namespace probelights
