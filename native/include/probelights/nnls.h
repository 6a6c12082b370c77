// Non-negative least squares (Lawson & Hanson 1974, chapter 23): the solver behind the refit (refit.h).
#pragma once

#include <vector>

namespace probelights {

// x >= 0 minimizing |A x - b| (A is m x n, row-major).
std::vector<double> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                            const std::vector<double>& b);
// The same for several right-hand sides (A^T A formed once).
std::vector<std::vector<double>> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                                         const std::vector<std::vector<double>>& bs);

}  // namespace probelights
