// Non-negative least squares (Lawson & Hanson 1974, chapter 23): the solver behind the refit (refit.h).
#pragma once

#include <vector>

namespace probelights {

// What a solve took (tests): the factorizations of the normal equations on the free set, one per step.
struct NnlsStats {
  long factorizations = 0;
};

// x >= 0 minimizing |A x - b| (A is m x n, row-major).
std::vector<double> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                            const std::vector<double>& b, NnlsStats* stats = nullptr);
// The same for several right-hand sides (A^T A formed once).
std::vector<std::vector<double>> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                                         const std::vector<std::vector<double>>& bs,
                                                         NnlsStats* stats = nullptr);

}  // namespace probelights
