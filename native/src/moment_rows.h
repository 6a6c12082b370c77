// The working grid's row kernels (moment_table.cpp): one row of pixels summed four at a time, one per SIMD
// lane (AVX2 where the processor has it, else pairs of doubles, lanes.h), for the full-resolution table and
// for a region's column and row sums.
#pragma once

#include <cstddef>

#include "probelights/moment_table.h"

namespace probelights::rowsum {

// One row of the full-resolution lat-long table (MomentTable::addLatLongPixels), and what it adds up.
struct TableRow {
  const float* pixels;
  std::ptrdiff_t step;
  int width;
  const double *cosPhi, *sinPhi;
  double dw, dwCos, dwSin;
  double* out;          // the table row's entries, pixel x at out[(x + 1) * 5]
  const double* above;  // the row above's final entries (Above), or none (pass 1 of two)
};
struct RowTotals {
  double rgb[3], energy;
  long long lit;
  bool odd;  // a negative, NaN or Inf sample in the row (for the pixels' check)
};

// One row of a region for its column and row sums (MomentTable::marginals): four pixels at a time, one per
// lane, with the table's products; each column's sums (five arrays, padded to whole groups of four) gain the
// row's values, the row's sums are four partial sums per channel added at the end.
struct MarginalRow {
  const float* pixels;  // the region's first pixel in the row
  std::ptrdiff_t step;
  int width;
  const double *cosPhi, *sinPhi;  // from the region's first column
  double dw, dwCos, dwSin;
  double* columns[5];  // per channel, width rounded up to four
};

// Sums one table row into a.out and t (the row's totals).
void sumTableRow(const TableRow& a, bool grey, RowTotals& t);
// Adds one region row to a.columns and returns the row's sums in `row`.
void sumMarginalRow(const MarginalRow& a, bool grey, MomentTable::Sums& row);

}  // namespace probelights::rowsum
