// Summed-area tables (Crow 1984) of K channels: any rectangle's sums in O(1).
//
// Precision. A probe with a 1-pixel sun of 1e7 beside a sky of 1e-2 gives per-pixel weights 3.7 and 3.7e-9 at
// 8192x4096: a float prefix sum (24-bit mantissa) stops growing once it holds the sun, so a sky region's sum,
// taken as the difference of four prefix values of ~3.7, comes out as noise or 0. The table therefore stores
// double prefix sums. A rectangle sum S(x1,y1) - S(x0,y1) - S(x1,y0) + S(x0,y0) then carries an error of
// about eps * (largest prefix value) * (rows + columns of the rectangle), because the rounding done before
// the rectangle's first row and column is shared by the four terms and cancels: ~1e-15 absolute on that
// probe, 1e-8 relative to a 10x10 sky region. tests/native/summed_area_table_test.cpp checks this against
// brute force.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/memory.h"

namespace probelights {

// Explicitly instantiated for K = 1..5 (summed_area_table.cpp).
template <int K>
class SummedAreaTable {
 public:
  using Values = std::array<double, K>;

  SummedAreaTable() = default;

  // rowValues(y, std::span<Values>) fills the `width` values of row y. It is called for several rows at once
  // from worker threads, so it must be safe to call concurrently for different rows.
  //
  // Built in two parallel passes: (1) each row's prefix sums along x, rows spread over the threads (which
  // also spreads the first touch of the table's pages); (2) the running sums down each column, column blocks
  // spread over the threads. Every entry gets the same additions in the same order as a one-pass build, so
  // the table is bit-identical whatever the thread count.
  using RowValues = std::function<void(int, std::span<Values>)>;
  SummedAreaTable(int width, int height, const RowValues& rowValues);

  // The same table built in parts, for rows that arrive in bands (a probe read band by band): allocate, then
  // fillRows() every row once (pass 1, in any order), then finish() (pass 2). The result is bit-identical to
  // the one-call build. On a thread in an OnOneThread scope (parallel.h) rows given in order are summed down
  // the columns as they come (one pass), and finish() has only the rest to do.
  SummedAreaTable(int width, int height);
  void fillRows(int y0, int y1, const RowValues& rowValues);
  // fillRows for callers that sum a row themselves (a loop that makes each value and adds it in one go):
  // rowSums(y, out, above) writes out[(x + 1) * K + k] for x in [0, width), channel k: the running sum of row
  // y's values of channel k over [0, x], added last to above[(x + 1) * K + k] when `above` is given (the
  // row above's final sums), that is `above[c] + running` as fillRows adds them; out[0..K) is written here.
  using RowSums = std::function<void(int, double*, const double*)>;
  void fillRowSums(int y0, int y1, const RowSums& rowSums);
  void finish();

  int width() const { return width_; }
  int height() const { return height_; }

  // Sums over the half-open rectangle r (clipped by the caller to the table).
  Values sum(const Rect& r) const {
    const double* a = entry(r.x0, r.y0);
    const double* b = entry(r.x1, r.y0);
    const double* c = entry(r.x0, r.y1);
    const double* d = entry(r.x1, r.y1);
    Values s;
    for (int k = 0; k < K; ++k) s[k] = (d[k] - b[k]) - (c[k] - a[k]);
    return s;
  }

 private:
  // Entry (x, y) holds the sums over [0, x) x [0, y).
  const double* entry(int x, int y) const {
    return table_.get() + (static_cast<std::size_t>(y) * (width_ + 1) + x) * K;
  }
  double* entry(int x, int y) { return table_.get() + (static_cast<std::size_t>(y) * (width_ + 1) + x) * K; }

  int width_ = 0, height_ = 0;
  int finalRows_ =
      0;  // rows 0 .. finalRows_ - 1 already hold their column sums (built in order on one thread)
  KeptArray<double> table_;  // reused across tables in a process (memory.h)
};

}  // namespace probelights
