#include "probelights/lights.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/names.h"

namespace probelights {

namespace {
constexpr NameTable<CentroidWeight, 2> kCentroids{
    {{CentroidWeight::Energy, "energy"}, {CentroidWeight::Energy2, "energy2"}}};
}  // namespace

void checkLightCount(int lights) {
  if (lights < 1) throw Error("asked for " + std::to_string(lights) + " lights: ask for at least 1");
  if (lights > kMaxLights)
    throw Error("asked for " + std::to_string(lights) + " lights: at most " + std::to_string(kMaxLights));
}

std::string toString(CentroidWeight weight) { return nameOf(kCentroids, weight); }
CentroidWeight parseCentroid(const std::string& name) { return parseName(kCentroids, "centroid", name); }

std::vector<Light> lightsFromRegions(const Probe& probe, const std::vector<Rect>& regions,
                                     CentroidWeight centroid) {
  probe.requirePixels("summing lights from pixels");
  std::vector<PixelSums> sums(regions.size());
  const bool squares = centroid == CentroidWeight::Energy2;
  parallelFor(static_cast<std::int64_t>(regions.size()),
              [&](std::int64_t i) { sums[i] = sumPixels(probe, regions[i], squares); });
  return lightsFromSums(probe, regions, sums, centroid);
}

std::vector<Light> lightsFromSums(const Probe& probe, const std::vector<Rect>& regions,
                                  const std::vector<PixelSums>& sums, CentroidWeight centroid) {
  double totalEnergy = 0;
  for (const PixelSums& s : sums) totalEnergy += s.energy;

  // Negative samples are light too (Probe::light): Cycles renders them, so the lights' colours keep them. A
  // lamp cannot be negative, though: a region whose light sums below 0 in a channel (a lossy EXR's ringing
  // beside its sun, cut off on its own) or that has no positive light gives that light to the nearest light
  // that can take it, and the lights still sum to the probe's integral.
  struct Deficit {
    Vec3 direction;
    Rgb rgb;
  };
  std::vector<Deficit> deficits;
  auto middle = [&](const Rect& r) {
    auto d = probe.projection().direction((0.5 * (r.x0 + r.x1)) / probe.width(),
                                          (0.5 * (r.y0 + r.y1)) / probe.height());
    return d ? *d : Vec3{0, 0, 1};
  };

  std::vector<Light> lights;
  for (std::size_t i = 0; i < regions.size(); ++i) {
    const PixelSums& s = sums[i];
    if (!(s.energy > 0)) {
      if (s.rgb[0] < 0 || s.rgb[1] < 0 || s.rgb[2] < 0)
        deficits.push_back({middle(regions[i]),
                            {std::min(0.0, s.rgb[0]), std::min(0.0, s.rgb[1]), std::min(0.0, s.rgb[2])}});
      continue;
    }
    Light light;
    const bool energy = centroid == CentroidWeight::Energy;
    const Vec3& m = energy ? s.moment : s.moment2;
    const double len = m.length();
    if (len > 1e-9 * (energy ? s.energy : s.energy2)) {
      light.direction = (1.0 / len) * m;
    } else {
      // Light from every side of the region cancels (e.g. one region for a uniform sphere): no mean
      // direction, so take the region's middle.
      light.direction = middle(regions[i]);
    }
    light.rgb = s.rgb;
    if (s.rgb[0] < 0 || s.rgb[1] < 0 || s.rgb[2] < 0) {
      Deficit d{light.direction, {}};
      for (int k = 0; k < 3; ++k)
        if (s.rgb[k] < 0) d.rgb[k] = s.rgb[k], light.rgb[k] = 0;
      deficits.push_back(d);
    }
    light.solidAngle = s.solidAngle;
    // Angular radius of the cap whose light is as spread as the region's: for a uniform cap of radius a the
    // mean resultant length |sum w d| / sum w is (1 + cos a) / 2, so cos a = 2 R - 1. A one-pixel sun gives
    // ~0 (sharp shadows), a region of uniform sky gives its own size. A Blender sun lamp's angle is 2a.
    const double R = std::clamp(s.moment.length() / s.energy, 0.0, 1.0);
    light.angularRadius = std::acos(std::clamp(2.0 * R - 1.0, -1.0, 1.0));
    // A sun of angle 2a has the region's spread; half that, a full angle of the radius, rendered closer in
    // Cycles before angles were fitted (conversion.py in the add-on has the figures).
    light.angle = light.angularRadius;
    light.rect = regions[i];
    light.energyShare = s.energy / totalEnergy;
    lights.push_back(light);
  }
  // Each deficit is taken from the lights nearest it, as much from each as it has (a light ends at 0, never
  // below), so the lights carry the probe's integral exactly whenever that is positive; only the part of a
  // channel whose whole integral is not positive is left out (its light cannot be a lamp), and the bake says
  // so (placement.cpp, noteNonPositiveChannels). The nearest light that still has some is found by a scan
  // each time: a deficit usually ends at the first (a sort per deficit cost L log L, and up to 65536 lights).
  for (const Deficit& d : deficits)
    for (int k = 0; k < 3; ++k) {
      double owed = -d.rgb[k];
      while (owed > 0) {
        Light* nearest = nullptr;
        for (Light& l : lights)
          if (l.rgb[k] > 0 &&
              (!nearest || dot(l.direction, d.direction) > dot(nearest->direction, d.direction)))
            nearest = &l;
        if (!nearest) break;  // no light has any left: the channel's integral is not positive
        const double taken = std::min(nearest->rgb[k], owed);
        owed -= taken;
        nearest->rgb[k] = taken == nearest->rgb[k] ? 0.0 : nearest->rgb[k] - taken;
      }
    }
  return lights;
}

}  // namespace probelights
