// How well a pdf serves as an importance function for irradiance: the exact per-sample variance of the Monte
// Carlo estimator X = Y(w) max(0, n.w) / pdf(w) of E(n) = integral of Y max(0, n.w) dw, for a probe of
// piecewise-constant pixels: Var = sum over pixels of (Y cos+)^2 / pdf * dOmega - E^2 (pdf at pixel centres).
// No random numbers, so the comparison of samplers is exact and repeatable (tests/native/sh_sampler_test.cpp,
// native/bench/sh_benchmark.cpp). Not in the core library: a reference the tests and benchmarks measure by.
#pragma once

#include <functional>

#include "probelights/probe.h"

namespace probelights::reference {

struct EstimatorVariance {
  double irradiance = 0;  // E(n), luminance
  double variance = 0;    // per sample; with N samples the estimator's variance is this / N
};

EstimatorVariance irradianceEstimatorVariance(const Probe& probe, const Vec3& normal,
                                              const std::function<double(const Vec3&)>& pdf);

}  // namespace probelights::reference
