#include "probelights/hierarchical_warp.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "probelights/error.h"

namespace probelights {

HierarchicalWarp::HierarchicalWarp(std::vector<double> leaves, int depth, double epsilon, double measure)
    : epsilon_(epsilon), depth_(depth), measure_(measure) {
  if (!(epsilon >= 0.0 && epsilon <= 0.5)) {
    char text[64];
    std::snprintf(text, sizeof text, "%g", epsilon);
    throw Error(std::string("epsilon must be in [0, 0.5], got ") + text);
  }
  if (depth < 1 || depth > 12) throw Error("sampler depth must be 1 to 12, got " + std::to_string(depth));
  const std::size_t n = std::size_t{1} << depth;
  if (leaves.size() != n * n) throw Error("the warp needs 2^depth x 2^depth leaf integrals");
  levels_.resize(depth + 1);
  levels_[depth] = std::move(leaves);
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

HierarchicalWarp::Sample HierarchicalWarp::sample(std::array<double, 2> u) const {
  double s0 = 0, t0 = 0, size = 1, density = 1.0 / measure_;
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
    density *= 4.0 * ps * pt;  // equation 7
    s0 += a * size;
    t0 += b * size;
    is = 2 * is + a;
    it = 2 * it + b;
  }
  u[0] = std::clamp(u[0], 0.0, 1.0);
  u[1] = std::clamp(u[1], 0.0, 1.0);
  return {{s0 + u[0] * size, t0 + u[1] * size}, density};
}

template <class Visit>
std::array<double, 2> HierarchicalWarp::descend(std::array<double, 2> point, Visit&& visit) const {
  auto [s, t] = point;
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

double HierarchicalWarp::density(std::array<double, 2> point) const {
  double density = 1.0 / measure_;
  descend(point, [&](const Split& sp, int a, int b) {
    density *= 4.0 * (a == 0 ? sp.pS : 1.0 - sp.pS) * (b == 0 ? sp.pT[a] : 1.0 - sp.pT[a]);
  });
  return density;
}

std::array<double, 2> HierarchicalWarp::invert(std::array<double, 2> point) const {
  struct Step {
    int a, b;
    const Split* sp;
  };
  Step path[16];
  int n = 0;
  auto [s, t] = descend(point, [&](const Split& sp, int a, int b) { path[n++] = {a, b, &sp}; });
  // (s, t) are the local coordinates in the last node; unwind the warps from the bottom up.
  for (int k = n - 1; k >= 0; --k) {
    const Split& sp = *path[k].sp;
    const int a = path[k].a, b = path[k].b;
    t = b == 0 ? t * sp.pT[a] : sp.pT[a] + t * (1.0 - sp.pT[a]);
    s = a == 0 ? s * sp.pS : sp.pS + s * (1.0 - sp.pS);
  }
  return {s, t};
}

}  // namespace probelights
