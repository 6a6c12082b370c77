#include "probelights/sh_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "probelights/error.h"

namespace probelights {

std::array<double, 2> ShSampler::toSquare(const Vec3& d) {
  double len = d.length();
  double z = len > 0 ? std::clamp(d.z / len, -1.0, 1.0) : 1.0;
  double phi = std::atan2(d.y, d.x);
  double s = std::clamp(0.5 * (1.0 - z), 0.0, std::nextafter(1.0, 0.0));
  double t = std::clamp((phi + kPi) / (2.0 * kPi), 0.0, std::nextafter(1.0, 0.0));
  return {s, t};
}

Vec3 ShSampler::toSphere(double s, double t) {
  double z = 1.0 - 2.0 * s, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = -kPi + 2.0 * kPi * t;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

namespace {

// The exact integrals of the SH reconstruction over the 2^depth x 2^depth cells of the unit square
// (separable: z integrals per row, phi integrals per column), row-major in (s, t).
std::vector<double> leafIntegrals(int bands, std::vector<double> coefficients, int depth) {
  if (depth < 1 || depth > 12) throw Error("sampler depth must be 1 to 12, got " + std::to_string(depth));
  ShRectIntegrator integrator(bands, std::move(coefficients));
  const int n = 1 << depth;
  std::vector<std::vector<double>> zInt(
      n, std::vector<double>(static_cast<std::size_t>(bands) * (bands + 1) / 2));
  std::vector<std::vector<double>> phiInt(n, std::vector<double>(2 * bands - 1));
  for (int i = 0; i < n; ++i) {
    integrator.zIntegrals(1.0 - 2.0 * (i + 1) / n, 1.0 - 2.0 * i / n, zInt[i]);
    integrator.phiIntegrals(-kPi + 2.0 * kPi * i / n, -kPi + 2.0 * kPi * (i + 1) / n, phiInt[i]);
  }
  std::vector<double> leaves(static_cast<std::size_t>(n) * n);
  for (int is = 0; is < n; ++is)
    for (int it = 0; it < n; ++it)
      leaves[static_cast<std::size_t>(is) * n + it] = integrator.combine(zInt[is], phiInt[it]);
  return leaves;
}

}  // namespace

ShSampler::ShSampler(int bands, std::vector<double> coefficients, double epsilon, int depth)
    : warp_(leafIntegrals(bands, std::move(coefficients), depth), depth, epsilon, 4.0 * kPi) {}

ShSampler::Sample ShSampler::sample(std::array<double, 2> u) const {
  const HierarchicalWarp::Sample w = warp_.sample(u);
  return {toSphere(w.point[0], w.point[1]), w.density};
}

double ShSampler::pdf(const Vec3& direction) const { return warp_.density(toSquare(direction)); }

std::array<double, 2> ShSampler::invert(const Vec3& direction) const {
  return warp_.invert(toSquare(direction));
}

std::vector<ShSampler::Sample> ShSampler::sampleSeeded(int count, std::uint64_t seed) const {
  if (count < 1) throw Error("asked for " + std::to_string(count) + " samples: ask for at least 1");
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Sample> out(static_cast<std::size_t>(count));
  for (Sample& s : out) {
    const double a = u(rng);
    s = sample({a, u(rng)});
  }
  return out;
}

}  // namespace probelights
