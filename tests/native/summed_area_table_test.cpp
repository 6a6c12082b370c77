// Summed-area tables against brute-force sums.
#include "probelights/summed_area_table.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "test_probes.h"

namespace probelights {
namespace {

TEST(SummedAreaTable, MatchesBruteForceOnRandomRectangles) {
  const int W = 37, H = 23;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> value(0, 10);
  std::vector<std::array<double, 2>> cells(W * H);
  for (auto& c : cells) c = {value(rng), -value(rng)};
  SummedAreaTable<2> sat(W, H, [&](int y, std::span<std::array<double, 2>> row) {
    for (int x = 0; x < W; ++x) row[x] = cells[y * W + x];
  });
  std::uniform_int_distribution<int> xs(0, W), ys(0, H);
  for (int i = 0; i < 500; ++i) {
    int x0 = xs(rng), x1 = xs(rng), y0 = ys(rng), y1 = ys(rng);
    Rect r{std::min(x0, x1), std::min(y0, y1), std::max(x0, x1), std::max(y0, y1)};
    std::array<double, 2> brute{};
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x)
        for (int k = 0; k < 2; ++k) brute[k] += cells[y * W + x][k];
    auto s = sat.sum(r);
    for (int k = 0; k < 2; ++k) EXPECT_NEAR(s[k], brute[k], 1e-10);
  }
}

}  // namespace
}  // namespace probelights
