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

ShSampler::ShSampler(int bands, std::vector<double> coefficients, double epsilon, int depth)
    : epsilon_(epsilon), depth_(depth) {
  if (!(epsilon >= 0.0 && epsilon <= 0.5)) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", epsilon);
    throw Error(std::string("epsilon must be in [0, 0.5], got ") + text);
  }
  if (depth < 1 || depth > 12) throw Error("sampler depth must be 1 to 12, got " + std::to_string(depth));
  ShRectIntegrator integrator(bands, std::move(coefficients));
  // Integrals of the finest cells (separable: z integrals per row, phi integrals per column), then sums
  // upwards.
  const int n = 1 << depth;
  std::vector<std::vector<double>> zInt(
      n, std::vector<double>(static_cast<std::size_t>(bands) * (bands + 1) / 2));
  std::vector<std::vector<double>> phiInt(n, std::vector<double>(2 * bands - 1));
  for (int i = 0; i < n; ++i) {
    integrator.zIntegrals(1.0 - 2.0 * (i + 1) / n, 1.0 - 2.0 * i / n, zInt[i]);
    integrator.phiIntegrals(-kPi + 2.0 * kPi * i / n, -kPi + 2.0 * kPi * (i + 1) / n, phiInt[i]);
  }
  levels_.resize(depth + 1);
  levels_[depth].resize(static_cast<std::size_t>(n) * n);
  for (int is = 0; is < n; ++is)
    for (int it = 0; it < n; ++it)
      levels_[depth][static_cast<std::size_t>(is) * n + it] = integrator.combine(zInt[is], phiInt[it]);
  // Each coarser level: its nodes' integrals (sums of their quadrants) and warp probabilities, clamped
  // (Berger 3.1).
  auto clamp = [&](double p) { return std::clamp(p, epsilon_, 1.0 - epsilon_); };
  splits_.resize(depth);
  for (int k = depth - 1; k >= 0; --k) {
    const int m = 1 << k;
    levels_[k].resize(static_cast<std::size_t>(m) * m);
    splits_[k].resize(static_cast<std::size_t>(m) * m);
    const auto& fine = levels_[k + 1];
    for (int is = 0; is < m; ++is)
      for (int it = 0; it < m; ++it) {
        auto f = [&](int a, int b) {
          return fine[static_cast<std::size_t>(2 * is + a) * 2 * m + 2 * it + b];
        };
        const double total = f(0, 0) + f(0, 1) + f(1, 0) + f(1, 1);
        levels_[k][static_cast<std::size_t>(is) * m + it] = total;
        Split& sp = splits_[k][static_cast<std::size_t>(is) * m + it];
        sp.positive = total > 0;
        sp.pS = sp.positive ? clamp((f(0, 0) + f(0, 1)) / total) : 0.5;
        for (int a = 0; a < 2; ++a) {
          const double half = f(a, 0) + f(a, 1);
          sp.pT[a] = half > 0 ? clamp(f(a, 0) / half) : 0.5;
        }
      }
  }
}

ShSampler::Sample ShSampler::sample(std::array<double, 2> u) const {
  double s0 = 0, t0 = 0, size = 1, pdf = 1.0 / (4.0 * kPi);
  int is = 0, it = 0;
  for (int k = 0; k < depth_; ++k) {
    const Split& sp = split(k, is, it);
    if (!sp.positive) break;  // uniform in this node
    size *= 0.5;
    int a = u[0] < sp.pS ? 0 : 1;
    double ps = a == 0 ? sp.pS : 1.0 - sp.pS;
    u[0] = a == 0 ? u[0] / sp.pS : (u[0] - sp.pS) / (1.0 - sp.pS);
    int b = u[1] < sp.pT[a] ? 0 : 1;
    double pt = b == 0 ? sp.pT[a] : 1.0 - sp.pT[a];
    u[1] = b == 0 ? u[1] / sp.pT[a] : (u[1] - sp.pT[a]) / (1.0 - sp.pT[a]);
    pdf *= 4.0 * ps * pt;  // equation 7
    s0 += a * size;
    t0 += b * size;
    is = 2 * is + a;
    it = 2 * it + b;
  }
  u[0] = std::clamp(u[0], 0.0, 1.0);
  u[1] = std::clamp(u[1], 0.0, 1.0);
  return {toSphere(s0 + u[0] * size, t0 + u[1] * size), pdf};
}

template <class Visit>
std::array<double, 2> ShSampler::descend(const Vec3& direction, Visit&& visit) const {
  auto [s, t] = toSquare(direction);
  int is = 0, it = 0;
  for (int k = 0; k < depth_; ++k) {
    const Split& sp = split(k, is, it);
    if (!sp.positive) break;  // uniform below: nothing more to visit
    const int a = s < 0.5 ? 0 : 1, b = t < 0.5 ? 0 : 1;
    s = 2.0 * s - a;
    t = 2.0 * t - b;
    visit(sp, a, b);
    is = 2 * is + a;
    it = 2 * it + b;
  }
  return {s, t};
}

double ShSampler::pdf(const Vec3& direction) const {
  double pdf = 1.0 / (4.0 * kPi);
  descend(direction, [&](const Split& sp, int a, int b) {
    pdf *= 4.0 * (a == 0 ? sp.pS : 1.0 - sp.pS) * (b == 0 ? sp.pT[a] : 1.0 - sp.pT[a]);
  });
  return pdf;
}

std::array<double, 2> ShSampler::invert(const Vec3& direction) const {
  struct Step {
    int a, b;
    const Split* sp;
  };
  Step path[16];
  int n = 0;
  auto [s, t] = descend(direction, [&](const Split& sp, int a, int b) { path[n++] = {a, b, &sp}; });
  // (s, t) are the local coordinates in the last node; unwind the warps from the bottom up.
  for (int k = n - 1; k >= 0; --k) {
    const Split& sp = *path[k].sp;
    const int a = path[k].a, b = path[k].b;
    t = b == 0 ? t * sp.pT[a] : sp.pT[a] + t * (1.0 - sp.pT[a]);
    s = a == 0 ? s * sp.pS : sp.pS + s * (1.0 - sp.pS);
  }
  return {s, t};
}

std::vector<double> offsetUntilPositive(int bands, std::vector<double> c) {
  // The minimum of the reconstruction over a fine grid of directions; adding -min to the constant term
  // (Y_0^0 = 1 / sqrt(4 pi)) lifts it to >= 0 there.
  double minimum = 0;
  std::vector<double> y(shCount(bands));
  for (int i = 0; i < 256; ++i)
    for (int j = 0; j < 512; ++j) {
      shBasis(bands, ShSampler::toSphere((i + 0.5) / 256, (j + 0.5) / 512), y);
      double f = 0;
      for (int k = 0; k < shCount(bands); ++k) f += c[k] * y[k];
      minimum = std::min(minimum, f);
    }
  c[0] += -minimum * std::sqrt(4.0 * kPi) * 1.001;
  return c;
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
