// Importance sampling of a function given by SH coefficients: hierarchical sample warping (Jarosz, Carr &
// Jensen 2009) made robust to a reconstruction that goes negative (Berger 2011, "Approximate importance
// sampling of functions reconstructed from spherical harmonics").
//
// Domain: the unit square (s, t) mapped to the sphere by z = cos(theta) = 1 - 2s, phi = -pi + 2 pi t, which
// is area-preserving (dOmega = 4 pi ds dt). A quadtree of `depth` levels splits every node into quadrants;
// the exact integrals of the reconstruction over them (ShRectIntegrator) drive a warp along s, then along t
// inside the chosen half. Berger's rules (section 3):
//   - each warp probability is clamped to [epsilon, 1 - epsilon], so every quadrant keeps at least
//     epsilon^2 of its parent and no part of the sphere is left unsampled;
//   - in a node whose total integral is not positive the recursion stops and the sample stays uniform there
//     (likewise a half whose integral is not positive is split evenly);
//   - the pdf is accumulated through the levels, each multiplying it by 4 p_s p_t (equation 7), so
//     pdf >= (4 epsilon^2)^depth / (4 pi) everywhere.
// epsilon = 0 on a positive function gives Jarosz's distribution (pdf = f / integral of f on the leaves);
// epsilon = 1/2 gives the uniform distribution. pbrt's shape: sample(u) -> (direction, pdf), pdf(direction).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/spherical_harmonics.h"

namespace probelights {

class ShSampler {
 public:
  struct Sample {
    Vec3 direction;
    double pdf = 0;  // per steradian
  };

  ShSampler(int bands, std::vector<double> coefficients, double epsilon, int depth = 8);

  Sample sample(std::array<double, 2> u) const;
  // `count` samples of uniform points from a 64-bit Mersenne twister seeded with `seed` (reproducible).
  std::vector<Sample> sampleSeeded(int count, std::uint64_t seed) const;
  double pdf(const Vec3& direction) const;
  // The point of the unit square that sample() maps to `direction` (the inverse warp).
  std::array<double, 2> invert(const Vec3& direction) const;
  double integral() const { return levels_[0][0]; }  // of the reconstruction over the sphere
  double epsilon() const { return epsilon_; }
  int depth() const { return depth_; }

  static std::array<double, 2> toSquare(const Vec3& d);  // (s, t) of a direction
  static Vec3 toSphere(double s, double t);

 private:
  struct Split {
    bool positive;  // the node's integral > 0: it is warped, else uniform below
    double pS;      // probability of the first half along s (clamped)
    double pT[2];   // probability of the first half along t, in each s half (clamped)
  };
  // Walks from the root to the node holding `direction`, calling visit(split, a, b) for each warped level (a,
  // b: the halves taken along s and t); returns the local (s, t) in the last node.
  template <class Visit>
  std::array<double, 2> descend(const Vec3& direction, Visit&& visit) const;
  const Split& split(int level, int is, int it) const {
    return splits_[level][static_cast<std::size_t>(is) << level | it];
  }

  double epsilon_;
  int depth_;
  std::vector<std::vector<double>>
      levels_;  // integrals of the nodes at each level, 2^k x 2^k, row-major (s, t)
  std::vector<std::vector<Split>> splits_;  // per level < depth
};

// The Rec. 709 luminance SH of a probe, offset until the reconstruction is nowhere negative (Jarosz et al.'s
// remedy, which Berger argues against: it flattens the distribution). For comparisons in tests and
// benchmarks.
std::vector<double> offsetUntilPositive(int bands, std::vector<double> coefficients);

}  // namespace probelights
