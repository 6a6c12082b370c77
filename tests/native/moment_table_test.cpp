// The moment tables the cuts are decided on: the variance about the centroid, the full-resolution lat-long
// table against its pixels summed one by one (and the same bits on its AVX2 and portable paths, on one
// thread or two passes), and the 8K sun-and-sky stress probe (double prefix sums keep a dim sky's sums next
// to a bright sun).
#include "probelights/moment_table.h"

#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <random>

#include "../../native/src/lanes.h"
#include "probelights/one_thread.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::randomProbe;

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

// Every prefix rectangle [0, x) x [0, y): together they are the whole table.
std::vector<RegionMoments> prefixes(const MomentTable& t) {
  std::vector<RegionMoments> out;
  for (int y = 0; y <= t.height(); ++y)
    for (int x = 0; x <= t.width(); ++x) out.push_back(t.moments({0, 0, x, y}));
  return out;
}

TEST(MomentTable, FullResolutionLatLongTableEqualsItsPixelsSummedOneByOne) {
  // Widths that end on a whole group of four pixels, and on 1, 2 and 3 left over.
  for (int W : {36, 37, 38, 39})
    for (int channels : {1, 4}) {
      const int H = W / 2;
      const testing::TestProbe t = randomProbe(W, H, channels, 3u + W + channels);
      const Probe& probe = t.probe;
      PixelReport counts;
      const MomentTable table(probe, 1, CentroidWeight::Energy, &counts);
      const std::string what = std::to_string(W) + " wide, " + std::to_string(channels) + " channels";
      // Per pixel: w = Y dOmega, w d, lit; the probe's integral of the signed samples.
      std::vector<double> w(W * H);
      std::vector<Vec3> wd(W * H);
      Rgb integral{};
      for (int y = 0; y < H; ++y) {
        const auto row = probe.projection().latLongRow(y);
        for (int x = 0; x < W; ++x) {
          const float* p = probe.view().pixel(x, y);
          Rgb L;
          for (int k = 0; k < 3; ++k) L[k] = Probe::finite(p[channels < 3 ? 0 : k]);
          const double Y = luminance(std::max(0.0, L[0]), std::max(0.0, L[1]), std::max(0.0, L[2]));
          w[y * W + x] = Y * row.solidAngle;
          wd[y * W + x] =
              w[y * W + x] * Vec3{row.cosEl * row.cosPhi[x], row.cosEl * row.sinPhi[x], row.sinEl};
          for (int k = 0; k < 3; ++k) integral[k] += L[k] * row.solidAngle;
        }
      }
      double total = 0;
      long long litPixels = 0;
      for (double v : w) total += v, litPixels += v > 0;
      EXPECT_EQ(table.litCells(), litPixels) << what;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(table.integral()[k], integral[k], 1e-12 * 4 * kPi) << what;
      EXPECT_NEAR(table.totalEnergy(), total, 1e-12 * total) << what;
      for (const Rect& r : {Rect{0, 0, W, H}, Rect{1, 2, W - 1, H - 3}, Rect{W - 3, 0, W, H},
                            Rect{4, 5, 5, 6}, Rect{W - 1, H - 1, W, H}}) {
        double e = 0;
        Vec3 m;
        long long lit = 0;
        for (int y = r.y0; y < r.y1; ++y)
          for (int x = r.x0; x < r.x1; ++x) e += w[y * W + x], m += wd[y * W + x], lit += w[y * W + x] > 0;
        const RegionMoments got = table.moments(r);
        EXPECT_NEAR(got.energy, e, 1e-12 * total) << what;
        EXPECT_NEAR(got.moment.x, m.x, 1e-12 * total) << what;
        EXPECT_NEAR(got.moment.y, m.y, 1e-12 * total) << what;
        EXPECT_NEAR(got.moment.z, m.z, 1e-12 * total) << what;
        EXPECT_EQ(got.litCells, lit) << what;
      }
      // The pixels' check made in the same pass: the negative samples, the NaN and the Inf.
      const PixelReport expected = probe.countPixels();
      EXPECT_EQ(counts.negativeSamples, expected.negativeSamples) << what;
      EXPECT_EQ(counts.nonFiniteSamples, 2) << what;
      EXPECT_EQ(counts.nonFiniteSamples, expected.nonFiniteSamples) << what;
    }
}

TEST(MomentTable, FullResolutionLatLongTableIsTheSameBitsOnEveryPath) {
  // The AVX2 clone (where the processor has it) and the portable build; on one thread (each row summed onto
  // the row above as it comes) and in two passes on the threads.
  const int W = 39, H = 20;
  for (int channels : {1, 4}) {
    const testing::TestProbe t = randomProbe(W, H, channels, 5u + channels);
    const Probe& probe = t.probe;
    const std::vector<RegionMoments> reference = prefixes(MomentTable(probe, 1));
    const Rgb integral = MomentTable(probe, 1).integral();
    for (bool portable : {false, true})
      for (bool one : {false, true}) {
        lanes::portableOnly() = portable;
        std::optional<OnOneThread> scope;
        if (one) scope.emplace();
        const MomentTable table(probe, 1);
        lanes::portableOnly() = false;
        const std::vector<RegionMoments> got = prefixes(table);
        const std::string what = std::to_string(channels) + " channels" + (portable ? ", portable" : "") +
                                 (one ? ", one thread" : "");
        EXPECT_EQ(table.integral(), integral) << what;
        for (std::size_t i = 0; i < got.size(); ++i) {
          EXPECT_EQ(got[i].energy, reference[i].energy) << what << ", entry " << i;
          EXPECT_EQ(got[i].moment.x, reference[i].moment.x) << what << ", entry " << i;
          EXPECT_EQ(got[i].moment.y, reference[i].moment.y) << what << ", entry " << i;
          EXPECT_EQ(got[i].moment.z, reference[i].moment.z) << what << ", entry " << i;
          EXPECT_EQ(got[i].litCells, reference[i].litCells) << what << ", entry " << i;
        }
      }
  }
}

TEST(MomentTable, WithoutSummedAreaTablesTheSameSumsFromThePixels) {
  // A region's moments, its column and row sums, the totals and the pixels' check, from the pixels (the
  // storage of a full-resolution table wider than 4096) against the summed-area tables; the same bits
  // whatever the processor's path.
  for (int W : {37, 40})
    for (int channels : {1, 4}) {
      const int H = W / 2;
      const testing::TestProbe t = randomProbe(W, H, channels, 9u + W + channels);
      const Probe& probe = t.probe;
      PixelReport withTables, withPixels;
      const MomentTable tables(probe, 1, CentroidWeight::Energy, &withTables);
      const MomentTable pixels(probe, 1, CentroidWeight::Energy, &withPixels, MomentTable::Storage::Pixels);
      ASSERT_FALSE(pixels.hasTables());
      const std::string what = std::to_string(W) + " wide, " + std::to_string(channels) + " channels";
      const double total = tables.totalEnergy();
      EXPECT_NEAR(pixels.totalEnergy(), total, 1e-12 * total) << what;
      EXPECT_EQ(pixels.litCells(), tables.litCells()) << what;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(pixels.integral()[k], tables.integral()[k], 1e-12 * 4 * kPi);
      EXPECT_EQ(withPixels.negativeSamples, withTables.negativeSamples) << what;
      EXPECT_EQ(withPixels.nonFiniteSamples, 2) << what;
      EXPECT_NEAR(withPixels.positiveLight, withTables.positiveLight, 1e-12 * total) << what;
      auto near = [&](const RegionMoments& a, const RegionMoments& b, const std::string& where) {
        EXPECT_NEAR(a.energy, b.energy, 1e-12 * total) << where;
        EXPECT_NEAR(a.moment.x, b.moment.x, 1e-12 * total) << where;
        EXPECT_NEAR(a.moment.y, b.moment.y, 1e-12 * total) << where;
        EXPECT_NEAR(a.moment.z, b.moment.z, 1e-12 * total) << where;
        EXPECT_EQ(a.litCells, b.litCells) << where;
      };
      for (const Rect& r :
           {Rect{0, 0, W, H}, Rect{1, 2, W - 1, H - 3}, Rect{W - 3, 0, W, H}, Rect{4, 5, 5, 6}}) {
        const std::string where = what + ", rect from " + std::to_string(r.x0) + "," + std::to_string(r.y0);
        near(pixels.moments(r), tables.moments(r), where);
        std::vector<MomentTable::Sums> columns, rows, columnsPortable, rowsPortable;
        pixels.marginals(r, columns, rows);
        lanes::portableOnly() = true;
        pixels.marginals(r, columnsPortable, rowsPortable);
        lanes::portableOnly() = false;
        EXPECT_EQ(columns, columnsPortable) << where;
        EXPECT_EQ(rows, rowsPortable) << where;
        ASSERT_EQ(columns.size(), static_cast<std::size_t>(r.width()));
        ASSERT_EQ(rows.size(), static_cast<std::size_t>(r.height()));
        auto moments = [](const MomentTable::Sums& s) {
          return RegionMoments{s[0], {s[1], s[2], s[3]}, std::llround(s[4])};
        };
        for (int x = r.x0; x < r.x1; ++x)
          near(moments(columns[x - r.x0]), tables.moments({x, r.y0, x + 1, r.y1}), where + " column");
        for (int y = r.y0; y < r.y1; ++y)
          near(moments(rows[y - r.y0]), tables.moments({r.x0, y, r.x1, y + 1}), where + " row");
      }
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
