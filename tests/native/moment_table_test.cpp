// The moment tables the cuts are decided on: the variance about the centroid, and the 8K sun-and-sky stress
// probe (double prefix sums keep a dim sky's sums next to a bright sun).
#include "probelights/moment_table.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "test_probes.h"

namespace probelights {
namespace {

TEST(MomentTable, VarianceIsTheSpreadAboutTheCentroidOnTheSphere) {
  auto t = testing::makeProbe(64, 32, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{0.1 + x % 7, 0.2 + y % 5, 1.0 + (x * y) % 3};
  });
  MomentTable table(t.probe, 1);
  const Projection& p = t.probe.projection();
  for (Rect r : {Rect{0, 0, 64, 32}, Rect{5, 3, 20, 30}, Rect{40, 0, 64, 5}}) {
    // Brute force: sum of w |d - c|^2 with c the w-weighted mean direction.
    double w = 0;
    Vec3 m;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        double wi = luminance(t.probe.radiance(x, y)) * p.pixelSolidAngle(x, y);
        w += wi;
        m += wi * *p.direction((x + 0.5) / 64, (y + 0.5) / 32);
      }
    Vec3 c = (1.0 / w) * m;
    double spread = 0;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) {
        Vec3 d = *p.direction((x + 0.5) / 64, (y + 0.5) / 32) - c;
        spread += luminance(t.probe.radiance(x, y)) * p.pixelSolidAngle(x, y) * dot(d, d);
      }
    EXPECT_NEAR(table.moments(r).energy, w, 1e-12 * w);
    EXPECT_NEAR(table.moments(r).variance(), spread, 1e-10 * w);
  }
}

// An 8192x4096 probe holding a 1-pixel sun of 1e7 next to a sky of 1e-2: region sums from the tables must
// agree with brute-force sums, where plain float prefix sums lose the sky entirely.
TEST(MomentTable, EightKSunAndSkyStress) {
  const int W = 8192, H = 4096, sunX = 3000, sunY = 1000;
  std::vector<float> grey(static_cast<std::size_t>(W) * H, 1e-2f);
  grey[static_cast<std::size_t>(sunY) * W + sunX] = 1e7f;
  Probe probe(ImageView{grey.data(), W, H, 1}, ProjectionKind::LatLong);
  const Projection& p = probe.projection();
  auto weight = [&](int x, int y) {
    return static_cast<double>(grey[static_cast<std::size_t>(y) * W + x]) * p.pixelSolidAngle(x, y);
  };
  auto brute = [&](const Rect& r) {
    long double s = 0;
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x) s += weight(x, y);
    return static_cast<double>(s);
  };

  // Regions of sky after, below and beside the sun (whose prefix sums contain it), one holding it, and tiny
  // ones.
  const std::vector<Rect> rects = {{sunX + 1, sunY, sunX + 2, sunY + 1},
                                   {sunX + 1, sunY + 1, sunX + 11, sunY + 11},
                                   {5000, 3000, 5010, 3010},
                                   {sunX + 1, sunY, W, sunY + 1},
                                   {4000, 2000, 8192, 4096},
                                   {0, sunY + 1, W, H},
                                   {sunX - 5, sunY - 5, sunX + 5, sunY + 5},
                                   {0, 0, W, H},
                                   {8191, 4095, 8192, 4096}};

  {
    MomentTable table(probe, 1);
    const double total = table.totalEnergy();
    for (const Rect& r : rects) {
      // The bound of summed_area_table.h: eps * (largest prefix) * (rows + columns), and 1e-7 relative.
      double expected = brute(r), got = table.moments(r).energy;
      double bound = std::max(1e-7 * expected,
                              4 * std::numeric_limits<double>::epsilon() * total * (r.width() + r.height()));
      EXPECT_NEAR(got, expected, bound) << r.x0 << "," << r.y0 << " " << r.width() << "x" << r.height();
      if (r.area() >= 100 && r.y0 > 0 && r.y1 < H) {
        EXPECT_NEAR(got, expected, 2e-7 * expected);
      }
    }
  }

  // The same queries on a plain float summed-area table (what the precision argument rules out).
  std::vector<float> floatTable(static_cast<std::size_t>(W + 1) * (H + 1), 0.0f);
  for (int y = 0; y < H; ++y) {
    float running = 0;
    for (int x = 0; x < W; ++x) {
      running += static_cast<float>(weight(x, y));
      floatTable[(y + 1) * std::size_t(W + 1) + x + 1] = floatTable[y * std::size_t(W + 1) + x + 1] + running;
    }
  }
  auto at = [&](int x, int y) { return static_cast<double>(floatTable[y * std::size_t(W + 1) + x]); };
  double worstFloat = 0;
  for (const Rect& r : rects) {
    double f = at(r.x1, r.y1) - at(r.x0, r.y1) - at(r.x1, r.y0) + at(r.x0, r.y0), expected = brute(r);
    worstFloat = std::max(worstFloat, std::abs(f - expected) / expected);
  }
  EXPECT_GT(worstFloat, 0.5) << "float prefix sums were expected to fail on this probe";
}

}  // namespace
}  // namespace probelights
