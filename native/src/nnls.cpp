#include "probelights/nnls.h"

#include <algorithm>
#include <cmath>

#include "probelights/error.h"

namespace probelights {

std::vector<double> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                            const std::vector<double>& b) {
  // Lawson & Hanson (1974), chapter 23: an active-set method; P is the set of free (positive) variables. It
  // works on the normal equations G = A^T A, c = A^T b, built once: a step costs O(n^2) and a solve on P
  // O(|P|^3).
  std::vector<double> G(static_cast<std::size_t>(n) * n, 0.0), c(n, 0.0);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      const double aij = A[static_cast<std::size_t>(i) * n + j];
      if (aij == 0) continue;
      c[j] += aij * b[i];
      for (int k = 0; k <= j; ++k)
        G[static_cast<std::size_t>(j) * n + k] += aij * A[static_cast<std::size_t>(i) * n + k];
    }
  double trace = 0;
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < j; ++k)
      G[static_cast<std::size_t>(k) * n + j] = G[static_cast<std::size_t>(j) * n + k];
    trace += G[static_cast<std::size_t>(j) * n + j];
  }
  const double ridge = 1e-12 * trace / std::max(1, n);  // keeps rank-deficient sub-problems solvable
  std::vector<double> x(n, 0.0), w(n), z;
  std::vector<bool> inP(n, false);
  auto gradient = [&]() {  // w = A^T (b - A x) = c - G x
    for (int j = 0; j < n; ++j) {
      double s = c[j];
      for (int k = 0; k < n; ++k) s -= G[static_cast<std::size_t>(j) * n + k] * x[k];
      w[j] = s;
    }
  };
  auto solveP = [&]() {  // least squares on the columns in P: Cholesky of G restricted to P
    std::vector<int> cols;
    for (int j = 0; j < n; ++j)
      if (inP[j]) cols.push_back(j);
    const int k = static_cast<int>(cols.size());
    std::vector<double> L(static_cast<std::size_t>(k) * k), y(k);
    for (int a = 0; a < k; ++a) {
      for (int d = 0; d <= a; ++d) {
        double s = G[static_cast<std::size_t>(cols[a]) * n + cols[d]] + (a == d ? ridge : 0.0);
        for (int e = 0; e < d; ++e) s -= L[a * k + e] * L[d * k + e];
        L[a * k + d] = a == d ? std::sqrt(std::max(s, 1e-300)) : s / L[d * k + d];
      }
    }
    for (int a = 0; a < k; ++a) {
      double s = c[cols[a]];
      for (int e = 0; e < a; ++e) s -= L[a * k + e] * y[e];
      y[a] = s / L[a * k + a];
    }
    for (int a = k - 1; a >= 0; --a) {
      double s = y[a];
      for (int e = a + 1; e < k; ++e) s -= L[e * k + a] * y[e];
      y[a] = s / L[a * k + a];
    }
    z.assign(n, 0.0);
    for (int a = 0; a < k; ++a) z[cols[a]] = y[a];
  };
  double cmax = 0;
  for (double v : c) cmax = std::max(cmax, std::abs(v));
  const double tol = 1e-12 * std::max(cmax, 1e-300);
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    gradient();
    int best = -1;
    for (int j = 0; j < n; ++j)
      if (!inP[j] && w[j] > tol && (best < 0 || w[j] > w[best])) best = j;
    if (best < 0) break;
    inP[best] = true;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      solveP();
      bool feasible = true;
      for (int j = 0; j < n; ++j)
        if (inP[j] && z[j] <= 0) feasible = false;
      if (feasible) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (int j = 0; j < n; ++j)
        if (inP[j] && z[j] <= 0) alpha = std::min(alpha, x[j] / (x[j] - z[j]));
      for (int j = 0; j < n; ++j) {
        x[j] += alpha * (z[j] - x[j]);
        if (inP[j] && x[j] <= 0) inP[j] = false, x[j] = 0;
      }
    }
  }
  return x;
}

}  // namespace probelights
