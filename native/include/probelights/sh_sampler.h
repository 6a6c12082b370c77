// Importance sampling of a function given by SH coefficients: the generic hierarchical warp
// (hierarchical_warp.h: Jarosz, Carr & Jensen 2009, with Berger 2011's epsilon clamping) over the exact
// integrals of the SH reconstruction on a grid of the unit square.
//
// Domain: the unit square (s, t) mapped to the sphere by z = cos(theta) = 1 - 2s, phi = -pi + 2 pi t, which
// is area-preserving (dOmega = 4 pi ds dt), so the warp's density against the measure 4 pi is the pdf per
// steradian. The leaves are the exact integrals of the reconstruction over the 2^depth x 2^depth cells
// (ShRectIntegrator), negative where the reconstruction rings below zero: Berger's clamping keeps every part
// of the sphere sampled, pdf >= (4 epsilon^2)^depth / (4 pi). pbrt's shape: sample(u) -> (direction, pdf),
// pdf(direction).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/hierarchical_warp.h"
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
  double integral() const { return warp_.integral(); }  // of the reconstruction over the sphere
  double epsilon() const { return warp_.epsilon(); }
  int depth() const { return warp_.depth(); }

  static std::array<double, 2> toSquare(const Vec3& d);  // (s, t) of a direction
  static Vec3 toSphere(double s, double t);

 private:
  HierarchicalWarp warp_;
};

}  // namespace probelights
