// Non-negative least squares against a known solution.
#include "probelights/nnls.h"

#include <gtest/gtest.h>

#include <cmath>

#include "probelights/error.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(Nnls, SolvesAKnownNonNegativeProblem) {
  // A x = b with x* = (1, 0, 2): NNLS finds it; with b pushing x2 negative it clamps to 0.
  const std::vector<double> A = {1, 0, 1, 0, 1, 0, 1, 1, 0, 0, 0, 1};
  auto x = nonNegativeLeastSquares(A, 4, 3, {3, 0, 1, 2});
  EXPECT_NEAR(x[0], 1, 1e-9);  // the tiny ridge that keeps rank-deficient solves stable
  EXPECT_NEAR(x[1], 0, 1e-12);
  EXPECT_NEAR(x[2], 2, 1e-9);
  auto y = nonNegativeLeastSquares(A, 4, 3, {1, -5, 1, 0});
  for (double v : y) EXPECT_GE(v, 0.0);
  EXPECT_NEAR(y[1], 0, 1e-12);
}

}  // namespace
}  // namespace probelights
