// Pearson's chi-square goodness of fit, as Mitsuba's warp tests do it: for any sampler test that bins its
// samples against the counts its pdf expects.
#pragma once

#include <cmath>
#include <vector>

namespace probelights::testing {

// Regularized lower incomplete gamma P(a, x) (series / continued fraction), for chi-square p-values.
inline double gammaP(double a, double x) {
  if (x <= 0) return 0;
  const double lga = std::lgamma(a);
  if (x < a + 1) {
    double sum = 1 / a, term = sum;
    for (int n = 1; n < 1000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-15) break;
    }
    return sum * std::exp(-x + a * std::log(x) - lga);
  }
  double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::abs(c) < 1e-300) c = 1e-300;
    d = 1 / d;
    double del = d * c;
    h *= del;
    if (std::abs(del - 1) < 1e-15) break;
  }
  return 1 - std::exp(-x + a * std::log(x) - lga) * h;
}

// The p-value of observed against expected bin counts; bins expecting fewer than 5 are pooled into one.
inline double chiSquarePValue(const std::vector<double>& observed, const std::vector<double>& expected) {
  double chi2 = 0, poolE = 0, poolO = 0;
  int dof = -1;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] < 5) {
      poolE += expected[i], poolO += observed[i];
      continue;
    }
    chi2 += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++dof;
  }
  if (poolE > 0) {
    chi2 += (poolO - poolE) * (poolO - poolE) / poolE;
    ++dof;
  }
  return 1 - gammaP(0.5 * dof, 0.5 * chi2);
}

}  // namespace probelights::testing
