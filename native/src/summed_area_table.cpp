#include "probelights/summed_area_table.h"

#include <vector>

#include "parallel.h"

namespace probelights {

template <int K>
SummedAreaTable<K>::SummedAreaTable(int width, int height, const RowValues& rowValues)
    : SummedAreaTable(width, height) {
  fillRows(0, height, rowValues);
  finish();
}

template <int K>
SummedAreaTable<K>::SummedAreaTable(int width, int height)
    : width_(width),
      height_(height),
      table_(keptArray<double>(static_cast<std::size_t>(width + 1) * (height + 1) *
                               K)) {  // not zero-filled: written once
  std::fill_n(entry(0, 0), (width + 1) * K, 0.0);
}

template <int K>
void SummedAreaTable<K>::fillRows(int y0, int y1, const RowValues& rowValues) {
  fillRowSums(y0, y1, [&](int y, double* out, const double* above) {
    thread_local std::vector<Values> row;
    row.assign(static_cast<std::size_t>(width_), Values{});
    rowValues(y, std::span<Values>(row));
    Values running{};
    for (int x = 0; x < width_; ++x)
      for (int k = 0; k < K; ++k) {
        running[k] += row[x][k];
        const std::size_t c = static_cast<std::size_t>(x + 1) * K + k;
        out[c] = above ? above[c] + running[k] : running[k];
      }
  });
}

template <int K>
void SummedAreaTable<K>::fillRowSums(int y0, int y1, const RowSums& rowSums) {
  // Table row y + 1 gets the prefix sums along row y, added to the row above when `above` is given.
  auto writeRow = [&](int y, const double* above) {
    double* out = entry(0, y + 1);
    std::fill_n(out, K, 0.0);
    rowSums(y, out, above);
  };
  if (oneThread && y0 == finalRows_) {
    // Rows in order on one thread (one_thread.h): each row's prefix sums go straight onto the running sums of
    // the row above, still in cache, so the table is written once; the same additions in the same order as
    // the two passes (bit-identical).
    for (int y = y0; y < y1; ++y) writeRow(y, y == 0 ? nullptr : entry(0, y));
    finalRows_ = y1;
    return;
  }
  // Pass 1 of two: the prefix sums along each row, rows spread over the threads.
  parallelFor(y1 - y0, [&](std::int64_t i) { writeRow(y0 + static_cast<int>(i), nullptr); });
}

template <int K>
void SummedAreaTable<K>::finish() {
  // Pass 2: running sums down the columns, in blocks of columns, below the rows already final.
  const int first = std::max(1, finalRows_);
  const int columns = (width_ + 1) * K, blocks = std::max(1, std::min(64, columns / 512));
  parallelFor(blocks, [&](std::int64_t b) {
    const int c0 = static_cast<int>(b * columns / blocks), c1 = static_cast<int>((b + 1) * columns / blocks);
    for (int y = first; y < height_; ++y) {
      const double* above = entry(0, y);
      double* out = entry(0, y + 1);
      for (int c = c0; c < c1; ++c) out[c] = above[c] + out[c];
    }
  });
  finalRows_ = height_;
}

template class SummedAreaTable<1>;
template class SummedAreaTable<2>;
template class SummedAreaTable<3>;
template class SummedAreaTable<4>;
template class SummedAreaTable<5>;

}  // namespace probelights
