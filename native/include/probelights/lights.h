// Lights from regions: what a renderer needs to stand in for the probe over each region.
#pragma once

#include <string>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/pixel_sums.h"
#include "probelights/probe.h"

namespace probelights {

// Which pixels' weight places a light inside its region: energy = Y dOmega (the centroid of the region's
// light), energy2 = Y^2 dOmega (S.-Y. Yang, "Environment Lights", CSIE5098 homework 3, National Taiwan
// University, 2015: "Centroid Formula 2", pulled towards the brightest pixels).
enum class CentroidWeight { Energy, Energy2 };
inline constexpr int kMaxLights = 65536;
// The one check of a requested light count (1 to kMaxLights), shared by every entry point; throws Error.
void checkLightCount(int lights);

std::string toString(CentroidWeight weight);            // "energy", "energy2"
CentroidWeight parseCentroid(const std::string& name);  // throws Error naming the choices

struct Light {
  Vec3 direction;         // unit vector towards the light (normalized weighted mean of pixel directions)
  Rgb rgb{};              // sum over the region of L * dOmega: the irradiance on a surface facing it, W/m^2
                          // for a Blender sun lamp's strength
  double solidAngle = 0;  // of the region
  double angularRadius = 0;  // radians: the cap with the same spread as the region's light (see lights.cpp)
  // The full cone angle the renderer draws it with (a Blender sun's Angle), radians in [0, pi]; 0 is a point
  // direction. Made from the spread (angularRadius; see lights.cpp), fitted to the probe's shadows when they
  // are evaluated (sun_angles.h). The evaluator models the light as this cone (cone.h).
  double angle = 0;
  Rect rect;  // the region, in pixels; a lamp of a lat-long probe's sources may wrap round: x1 > width
  double energyShare = 0;  // the region's luminance energy / the probe's
};

// One light per region that carries energy, from the exact sums over the region's full-resolution pixels.
std::vector<Light> lightsFromSums(const Probe& probe, const std::vector<Rect>& pixelRegions,
                                  const std::vector<PixelSums>& sums,
                                  CentroidWeight centroid = CentroidWeight::Energy);

// The same, summing each region's pixels. Regions are visited in parallel; each is summed by one thread in a
// fixed order, so the result is bit-identical whatever the thread count.
std::vector<Light> lightsFromRegions(const Probe& probe, const std::vector<Rect>& pixelRegions,
                                     CentroidWeight centroid = CentroidWeight::Energy);

}  // namespace probelights
