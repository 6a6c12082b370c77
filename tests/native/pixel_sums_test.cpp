// accumulateRows, the one loop that sums pixels into cells (the working grid, lights at full resolution, the
// evaluator's samples), against the same sums taken pixel by pixel in plain double arithmetic.
#include "probelights/pixel_sums.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../../native/src/lanes.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::randomProbe;

// The sums of pixels [x0, x1) x [y0, y1) of a lat-long probe, one pixel at a time (PixelSums' definitions).
PixelSums reference(const Probe& probe, int x0, int x1, int y0, int y1) {
  const ImageView& v = probe.view();
  PixelSums s;
  for (int y = y0; y < y1; ++y) {
    const auto row = probe.projection().latLongRow(y);
    for (int x = x0; x < x1; ++x) {
      const float* p = v.pixel(x, y);
      Rgb L;
      for (int k = 0; k < 3; ++k) L[k] = Probe::finite(p[v.channels < 3 ? 0 : k]);
      const double dw = row.solidAngle;
      const double Y =
          0.2126 * std::max(0.0, L[0]) + 0.7152 * std::max(0.0, L[1]) + 0.0722 * std::max(0.0, L[2]);
      const Vec3 d{row.cosEl * row.cosPhi[x], row.cosEl * row.sinPhi[x], row.sinEl};
      for (int k = 0; k < 3; ++k) s.rgb[k] += L[k] * dw;
      s.solidAngle += dw;
      s.energy += Y * dw;
      s.moment += (Y * dw) * d;
      s.energy2 += Y * Y * dw;
      s.moment2 += (Y * Y * dw) * d;
      s.litPixels += Y > 0;
    }
  }
  return s;
}

void expectClose(const PixelSums& a, const PixelSums& b, const std::string& what) {
  auto near = [&](double x, double y, const char* name) {
    EXPECT_NEAR(x, y, 1e-12 * (1 + std::abs(y))) << what << " " << name;
  };
  for (int k = 0; k < 3; ++k) near(a.rgb[k], b.rgb[k], "rgb");
  near(a.solidAngle, b.solidAngle, "solid angle");
  near(a.energy, b.energy, "energy");
  near(a.moment.x, b.moment.x, "moment x"), near(a.moment.y, b.moment.y, "moment y");
  near(a.moment.z, b.moment.z, "moment z");
  near(a.energy2, b.energy2, "energy2");
  near(a.moment2.x, b.moment2.x, "moment2 x"), near(a.moment2.y, b.moment2.y, "moment2 y");
  near(a.moment2.z, b.moment2.z, "moment2 z");
  EXPECT_EQ(a.litPixels, b.litPixels) << what;
}

TEST(PixelSums, LatLongCellsEqualTheirPixelsSummedOneByOne) {
  const int W = 37, H = 19;
  for (int channels : {1, 4}) {
    const testing::TestProbe t = randomProbe(W, H, channels, 7u + channels);
    const Probe& probe = t.probe;
    // Row counts that fill four lanes, leave some empty, or one; cells of 1 to 9 pixels, a ragged last cell.
    for (auto [y0, y1] : {std::pair{0, 19}, {3, 4}, {4, 10}, {5, 8}, {0, 2}})
      for (int cellSize : {1, 2, 3, 4, 9})
        for (auto [x0, x1] : {std::pair{0, 37}, {5, 6}, {2, 30}}) {
          const int cells = (x1 - x0 + cellSize - 1) / cellSize;
          std::vector<PixelSums> got(cells);
          bool odd = false;
          accumulateRows(probe, y0, y1, x0, x1, cellSize, got, true, &odd);
          const std::string what = "channels " + std::to_string(channels) + ", rows " + std::to_string(y0) +
                                   "-" + std::to_string(y1) + ", cells of " + std::to_string(cellSize) +
                                   " from " + std::to_string(x0);
          for (int c = 0; c < cells; ++c)
            expectClose(got[c],
                        reference(probe, x0 + c * cellSize, std::min(x1, x0 + (c + 1) * cellSize), y0, y1),
                        what + ", cell " + std::to_string(c));
          bool expected = false;  // any sample read negative, NaN or Inf
          for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
              for (int k = 0; k < std::min(channels, 3); ++k) {
                const float f = probe.view().pixel(x, y)[k];
                expected |= !(f >= 0.0f && f <= std::numeric_limits<float>::max());
              }
          EXPECT_EQ(odd, expected) << what;
        }
  }
}

TEST(PixelSums, PortableAndAvx2PathsGiveTheSameBits) {
  // accumulateRows takes the AVX2 clone on this processor where it has AVX2, the portable build when the
  // tests say so (lanes::portableOnly); without AVX2 both calls are the portable build.
  const int W = 61, H = 23;
  for (int channels : {1, 4}) {
    const testing::TestProbe t = randomProbe(W, H, channels, 11u + channels);
    const Probe& probe = t.probe;
    for (auto [y0, y1] : {std::pair{0, 23}, {2, 5}, {7, 8}})
      for (int cellSize : {1, 3, 4, 16})
        for (bool squares : {false, true}) {
          const int cells = (W + cellSize - 1) / cellSize;
          std::vector<PixelSums> fast(cells), portable(cells);
          bool oddFast = false, oddPortable = false;
          accumulateRows(probe, y0, y1, 0, W, cellSize, fast, squares, &oddFast);
          lanes::portableOnly() = true;
          accumulateRows(probe, y0, y1, 0, W, cellSize, portable, squares, &oddPortable);
          lanes::portableOnly() = false;
          EXPECT_EQ(oddFast, oddPortable);
          for (int c = 0; c < cells; ++c) {
            const PixelSums &f = fast[c], &p = portable[c];
            const std::string what = "channels " + std::to_string(channels) + ", rows " + std::to_string(y0) +
                                     "-" + std::to_string(y1) + ", cells of " + std::to_string(cellSize) +
                                     ", cell " + std::to_string(c);
            EXPECT_EQ(f.rgb, p.rgb) << what;
            EXPECT_EQ(f.solidAngle, p.solidAngle) << what;
            EXPECT_EQ(f.energy, p.energy) << what;
            EXPECT_EQ(f.moment.x, p.moment.x) << what;
            EXPECT_EQ(f.moment.y, p.moment.y) << what;
            EXPECT_EQ(f.moment.z, p.moment.z) << what;
            EXPECT_EQ(f.energy2, p.energy2) << what;
            EXPECT_EQ(f.moment2.x, p.moment2.x) << what;
            EXPECT_EQ(f.moment2.y, p.moment2.y) << what;
            EXPECT_EQ(f.moment2.z, p.moment2.z) << what;
            EXPECT_EQ(f.litPixels, p.litPixels) << what;
          }
        }
  }
}

TEST(PixelSums, OddSamplesSaysWhetherAnySampleReadWasNegativeNaNOrInf) {
  const int W = 16, H = 9;
  std::vector<float> pixels(static_cast<std::size_t>(W) * H * 3, 1.0f);
  const ImageView view{pixels.data(), W, H, 3};
  auto odd = [&](int y0, int y1) {
    const Probe probe = Probe::unchecked(view, ProjectionKind::LatLong);
    std::vector<PixelSums> cells(4);
    bool seen = true;
    accumulateRows(probe, y0, y1, 0, W, 4, cells, false, &seen);
    return seen;
  };
  EXPECT_FALSE(odd(0, H));
  // One sample in each lane position of a group of four rows, and in a group of one: each is seen alone.
  for (int y : {0, 1, 2, 3, 8})
    for (float bad :
         {-1.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
      pixels[(static_cast<std::size_t>(y) * W + 13) * 3 + 2] = bad;
      EXPECT_TRUE(odd(0, H)) << "row " << y << " sample " << bad;
      EXPECT_EQ(odd(y, y + 1), true) << "row " << y;
      EXPECT_FALSE(odd(y == 0 ? 1 : 0, y == 0 ? 2 : 1)) << "a row without it, beside row " << y;
      pixels[(static_cast<std::size_t>(y) * W + 13) * 3 + 2] = 1.0f;
    }
}

}  // namespace
}  // namespace probelights
