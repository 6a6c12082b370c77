// The evaluator's truths (evaluate.cpp): the probe as samples, the brightest split into their pixels for the
// shadow truth, and the sums over the samples that give the irradiance and ground-point truths.
#pragma once

#include <array>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/probe.h"

namespace probelights::truth {

// The probe as samples: each a direction and its L dOmega (signed: Probe::light).
struct Samples {
  std::vector<Vec3> directions;
  std::vector<Rgb> radiance;

  // A sample from its luminance-weighted mean direction, or from the middle of its pixels (u, v in [0, 1])
  // when it has no positive luminance (only negative samples); none for no light.
  // Returns whether it added one.
  bool add(const Projection& projection, const Rgb& rgb, const Vec3& moment, double u, double v) {
    if (rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0) return false;
    const double len = moment.length();
    if (len > 0) {
      directions.push_back((1.0 / len) * moment);
    } else {
      const auto d = projection.direction(u, v);
      if (!d) return false;
      directions.push_back(*d);
    }
    radiance.push_back(rgb);
    return true;
  }
};

// `samples` with the brightest split into their pixels and those into points (none if none is that bright);
// at[i] is sample i's cell (x, y) of cell x cell pixels.
Samples splitBrightest(const Probe& probe, int cell, const Samples& samples,
                       const std::vector<std::array<int, 2>>& at);

// The irradiance truth E(n) = sum of L max(0, n . w) over the samples, at each normal.
std::vector<Rgb> irradianceTruthAt(const std::vector<Vec3>& directions, const std::vector<Rgb>& radiance,
                                   const std::vector<Vec3>& normals);

// Each ground point's truth (under the unit sphere at the origin): the upper hemisphere's irradiance less
// what the sphere hides.
std::vector<Rgb> shadowTruthAt(const std::vector<Vec3>& directions, const std::vector<Rgb>& radiance,
                               const std::vector<Vec3>& points);

}  // namespace probelights::truth
