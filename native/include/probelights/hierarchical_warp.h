// Hierarchical sample warping over the unit square (Jarosz, Carr & Jensen 2009), made robust to leaves whose
// integrals are negative (Berger 2011, "Approximate importance sampling of functions reconstructed from
// spherical harmonics", section 3). Generic over a 2^depth x 2^depth grid of leaf integrals, as pbrt's and
// Mitsuba's warps are over theirs: the SH sampler (sh_sampler.h) is a thin front end that supplies the
// leaves.
//
// A quadtree of `depth` levels: each node's integral is the sum of its quadrants; a sample is warped along
// s by the node's two halves, then along t inside the chosen half. Berger's rules:
//   - each warp probability is clamped to [epsilon, 1 - epsilon], so every quadrant keeps at least
//     epsilon^2 of its parent and no part of the square is left unsampled;
//   - in a node whose integral is not positive the recursion stops and the sample stays uniform there
//     (likewise a half whose integral is not positive is split evenly);
//   - the density is accumulated through the levels, each multiplying it by 4 p_s p_t (equation 7), so
//     density >= (4 epsilon^2)^depth / measure everywhere.
// epsilon = 0 on positive leaves gives Jarosz's distribution (density proportional to the leaf integrals);
// epsilon = 1/2 gives the uniform distribution. pbrt's shape: sample(u) -> (point, density), density(point),
// and invert(point) -> u.
#pragma once

#include <array>
#include <vector>

namespace probelights {

class HierarchicalWarp {
 public:
  struct Sample {
    std::array<double, 2> point;  // in [0, 1]^2
    double density = 0;           // with respect to the measure (its total: `measure`, e.g. 4 pi sr)
  };

  // leaves: the 2^depth x 2^depth leaf integrals, row-major in (s, t). measure: the total measure of the
  // square the density is taken against (1 for area; 4 pi for an area-preserving map onto the sphere).
  HierarchicalWarp(std::vector<double> leaves, int depth, double epsilon, double measure = 1.0);

  Sample sample(std::array<double, 2> u) const;
  double density(std::array<double, 2> point) const;
  std::array<double, 2> invert(std::array<double, 2> point) const;  // the u that sample() maps to point
  double integral() const { return levels_[0][0]; }                 // the sum of the leaves
  double epsilon() const { return epsilon_; }
  int depth() const { return depth_; }

 private:
  struct Split {
    bool positive;  // the node's integral > 0: it is warped, else uniform below
    double pS;      // probability of the first half along s (clamped)
    double pT[2];   // probability of the first half along t, in each s half (clamped)
  };
  // Walks from the root to the node holding `point`, calling visit(split, a, b) for each warped level (a, b:
  // the halves taken along s and t); returns the local (s, t) in the last node.
  template <class Visit>
  std::array<double, 2> descend(std::array<double, 2> point, Visit&& visit) const;
  const Split& split(int level, int is, int it) const {
    return splits_[level][static_cast<std::size_t>(is) << level | it];
  }

  double epsilon_;
  int depth_;
  double measure_;
  std::vector<std::vector<double>> levels_;  // integrals of the nodes at each level, 2^k x 2^k, row-major
  std::vector<std::vector<Split>> splits_;   // per level < depth
};

}  // namespace probelights
