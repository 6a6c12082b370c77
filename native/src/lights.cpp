#include "probelights/lights.h"

#include <OpenImageIO/parallel.h>

#include <algorithm>
#include <cmath>

namespace probelights {

namespace {

struct RegionSums {
  Rgb rgb{};             // sum of L dOmega
  double energy = 0;     // sum of Y dOmega
  Vec3 moment;           // sum of Y dOmega d
  double energy2 = 0;    // sum of Y^2 dOmega
  Vec3 moment2;          // sum of Y^2 dOmega d
  double solidAngle = 0;
};

RegionSums sumRegion(const Probe& probe, const Rect& r) {
  RegionSums s;
  std::vector<Vec3> dirs(r.width());
  std::vector<double> omega(r.width());
  for (int y = r.y0; y < r.y1; ++y) {
    probe.projection().rowGeometry(y, r.x0, r.x1, dirs, omega);
    for (int x = r.x0; x < r.x1; ++x) {
      const Rgb L = probe.radiance(x, y);
      const double dw = omega[x - r.x0], Y = luminance(L), w = Y * dw;
      const Vec3& d = dirs[x - r.x0];
      for (int k = 0; k < 3; ++k) s.rgb[k] += L[k] * dw;
      s.energy += w;
      s.moment += w * d;
      s.energy2 += w * Y;
      s.moment2 += (w * Y) * d;
      s.solidAngle += dw;
    }
  }
  return s;
}

}  // namespace

std::vector<Light> lightsFromRegions(const Probe& probe, const std::vector<Rect>& regions, CentroidWeight centroid) {
  std::vector<RegionSums> sums(regions.size());
  OIIO::parallel_for(std::int64_t{0}, static_cast<std::int64_t>(regions.size()),
                     [&](std::int64_t i) { sums[i] = sumRegion(probe, regions[i]); });
  double totalEnergy = 0;
  for (const RegionSums& s : sums) totalEnergy += s.energy;

  std::vector<Light> lights;
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const RegionSums& s = sums[i];
    if (!(s.energy > 0)) continue;
    Light light;
    const bool energy = centroid == CentroidWeight::Energy;
    const Vec3& m = energy ? s.moment : s.moment2;
    const double len = m.length();
    if (len > 1e-9 * (energy ? s.energy : s.energy2)) {
      light.direction = (1.0 / len) * m;
    } else {
      // Light from every side of the region cancels (e.g. one region for a uniform sphere): no mean direction, so
      // take the region's middle.
      const Rect& r = regions[i];
      auto d = probe.projection().direction((0.5 * (r.x0 + r.x1)) / probe.width(), (0.5 * (r.y0 + r.y1)) / probe.height());
      light.direction = d ? *d : Vec3{0, 0, 1};
    }
    light.rgb = s.rgb;
    light.solidAngle = s.solidAngle;
    // Angular radius of the cap whose light is as spread as the region's: for a uniform cap of radius a the mean
    // resultant length |sum w d| / sum w is (1 + cos a) / 2, so cos a = 2 R - 1. A one-pixel sun gives ~0 (sharp
    // shadows), a region of uniform sky gives its own size. A Blender sun lamp's angle is 2a.
    const double R = std::clamp(s.moment.length() / s.energy, 0.0, 1.0);
    light.angularRadius = std::acos(std::clamp(2.0 * R - 1.0, -1.0, 1.0));
    light.rect = regions[i];
    light.energyShare = s.energy / totalEnergy;
    lights.push_back(light);
  }
  return lights;
}

}  // namespace probelights
