#include "probelights/nnls.h"

#include <algorithm>
#include <cmath>

#include "probelights/error.h"

namespace probelights {

namespace {

// Lawson & Hanson (1974), chapter 23: an active-set method; P is the set of free (positive) variables. It
// works on the normal equations G = A^T A, c = A^T b: a step costs O(n^2) and a solve on P O(|P|^3).
std::vector<double> solveNormal(const std::vector<double>& G, const std::vector<double>& c, int n,
                                double ridge, NnlsStats* stats) {
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
    if (stats) ++stats->factorizations;
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
  // Warm start: solve on every variable, drop those that come out non-positive, solve again, until the
  // solution on P is positive (P only shrinks: a few rounds). That is a feasible point of the method (x_P the
  // least squares on P, the rest 0), so the loop below only adds what the gradient still asks for, instead of
  // adding the n variables one by one from x = 0 with a factorization each (O(n^4)).
  std::fill(inP.begin(), inP.end(), true);
  for (bool shrunk = true; shrunk;) {
    solveP();
    shrunk = false;
    for (int j = 0; j < n; ++j)
      if (inP[j] && !(z[j] > 0)) inP[j] = false, shrunk = true;
  }
  x = z;
  // A variable whose own solve gives it no positive value (rounding: in exact arithmetic it cannot happen) is
  // not offered again until another one has entered, so the method cannot cycle on it.
  std::vector<bool> refused(n, false);
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    gradient();
    int best = -1;
    for (int j = 0; j < n; ++j)
      if (!inP[j] && !refused[j] && w[j] > tol && (best < 0 || w[j] > w[best])) best = j;
    if (best < 0) break;
    inP[best] = true;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      solveP();
      if (inner == 0 && !(z[best] > 0)) {
        inP[best] = false, refused[best] = true;
        break;
      }
      if (inner == 0) std::fill(refused.begin(), refused.end(), false);
      bool feasible = true;
      for (int j = 0; j < n; ++j)
        if (inP[j] && z[j] <= 0) feasible = false;
      if (feasible) {
        x = z;
        break;
      }
      // Step from x towards z until the first variable of P reaches 0; that one leaves P exactly (in floating
      // point x + alpha (z - x) may land a rounding above 0, and the loop would then step by 0 for ever).
      double alpha = 1.0;
      int blocking = -1;
      for (int j = 0; j < n; ++j) {
        if (!inP[j] || z[j] > 0) continue;
        const double a = x[j] > 0 ? x[j] / (x[j] - z[j]) : 0.0;
        if (blocking < 0 || a < alpha) alpha = a, blocking = j;
      }
      for (int j = 0; j < n; ++j) {
        x[j] += alpha * (z[j] - x[j]);
        if (inP[j] && (x[j] <= 0 || j == blocking)) inP[j] = false, x[j] = 0;
      }
    }
  }
  return x;
}

}  // namespace

std::vector<std::vector<double>> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                                         const std::vector<std::vector<double>>& bs,
                                                         NnlsStats* stats) {
  // G = A^T A once for every right-hand side (the costly part for tall A: m n^2 / 2).
  std::vector<double> G(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      const double aij = A[static_cast<std::size_t>(i) * n + j];
      if (aij == 0) continue;
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
  std::vector<std::vector<double>> out;
  for (const std::vector<double>& b : bs) {
    std::vector<double> c(n, 0.0);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < n; ++j) c[j] += A[static_cast<std::size_t>(i) * n + j] * b[i];
    out.push_back(solveNormal(G, c, n, ridge, stats));
  }
  return out;
}

std::vector<double> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                            const std::vector<double>& b, NnlsStats* stats) {
  return nonNegativeLeastSquares(A, m, n, std::vector<std::vector<double>>{b}, stats).front();
}

}  // namespace probelights
