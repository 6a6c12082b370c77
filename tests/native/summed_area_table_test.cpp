// Summed-area tables against brute-force sums.
#include "probelights/summed_area_table.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "probelights/one_thread.h"
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

TEST(SummedAreaTable, BuiltOnOneThreadInBandsIsBitIdentical) {
  // OnOneThread builds rows in order in one pass; rows given out of order, and the rest, fall back to the two
  // passes. Every way gives the same bits.
  const int W = 300, H = 97;
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> value(-1, 1000);
  std::vector<std::array<double, 3>> cells(W * H);
  for (auto& c : cells) c = {value(rng), value(rng) * 1e-9, value(rng) * 1e9};
  auto rows = [&](int y, std::span<std::array<double, 3>> row) {
    for (int x = 0; x < W; ++x) row[x] = cells[y * W + x];
  };
  const SummedAreaTable<3> reference(W, H, rows);
  auto same = [&](const SummedAreaTable<3>& t) {
    for (int y = 0; y <= H; y += 3)
      for (int x = 0; x <= W; x += 7) {
        const Rect r{0, 0, x, y};
        EXPECT_EQ(t.sum(r), reference.sum(r)) << x << "," << y;
      }
  };
  {
    const OnOneThread one;
    same(SummedAreaTable<3>(W, H, rows));
    SummedAreaTable<3> bands(W, H);  // in order, in bands of 40 rows
    for (int y = 0; y < H; y += 40) bands.fillRows(y, std::min(H, y + 40), rows);
    bands.finish();
    same(bands);
    SummedAreaTable<3> mixed(W, H);  // the first band in order, then the last before the middle
    mixed.fillRows(0, 30, rows);
    mixed.fillRows(60, H, rows);
    mixed.fillRows(30, 60, rows);
    mixed.finish();
    same(mixed);
  }
  SummedAreaTable<3> parallelBands(W, H);
  parallelBands.fillRows(50, H, rows);
  parallelBands.fillRows(0, 50, rows);
  parallelBands.finish();
  same(parallelBands);
}

}  // namespace
}  // namespace probelights
