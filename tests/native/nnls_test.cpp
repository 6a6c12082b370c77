// Non-negative least squares against a known solution.
#include "probelights/nnls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

TEST(Nnls, MeetsTheOptimalityConditionsWhereTheUnconstrainedSolutionIsNegative) {
  // Random tall problems whose unconstrained solutions have negative parts (the warm start then drops
  // variables): the answer satisfies the KKT conditions, x >= 0, w = A^T (b - A x) <= 0 where x = 0 and ~0
  // where x > 0; several right-hand sides at once give the same answers as one at a time.
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  int pinned = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const int m = 40, n = 12;
    std::vector<double> A(m * n);
    for (double& a : A) a = g(rng);
    std::vector<std::vector<double>> bs(3, std::vector<double>(m));
    for (auto& b : bs)
      for (double& v : b) v = g(rng);
    const auto xs = nonNegativeLeastSquares(A, m, n, bs);
    for (int r = 0; r < 3; ++r) {
      const std::vector<double>& x = xs[r];
      EXPECT_EQ(x, nonNegativeLeastSquares(A, m, n, bs[r]));
      std::vector<double> residual(bs[r]);
      for (int i = 0; i < m; ++i)
        for (int j = 0; j < n; ++j) residual[i] -= A[i * n + j] * x[j];
      for (int j = 0; j < n; ++j) {
        double w = 0;
        for (int i = 0; i < m; ++i) w += A[i * n + j] * residual[i];
        EXPECT_GE(x[j], 0.0);
        if (x[j] > 0) {
          EXPECT_NEAR(w, 0.0, 1e-8) << "trial " << trial << " variable " << j;
        } else {
          EXPECT_LE(w, 1e-8) << "trial " << trial << " variable " << j;
          ++pinned;
        }
      }
    }
  }
  EXPECT_GE(pinned, 100);  // the cases do pin variables at 0
}

}  // namespace
}  // namespace probelights
