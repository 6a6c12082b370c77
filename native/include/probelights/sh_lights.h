// Lights from the SH sampler (the "sh" method): N stratified cells of the unit square, warped through the
// sampler, partition the sphere into N cells of nearly equal reconstructed energy; each light's rgb and
// direction are then summed over the real probe's pixels in its cell, exactly as for median cut and variance
// minimization.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "probelights/lights.h"
#include "probelights/note.h"
#include "probelights/probe.h"
#include "probelights/sh_sampler.h"

namespace probelights {

struct ShLightOptions {
  int lights = 16;
  int bands = 8;
  double epsilon = 0.01;  // Berger's value
  int depth = 8;
};

struct ShLightResult {
  std::vector<Light> lights;
  std::vector<Note> notes;
  double projectMs = 0, assignMs = 0, lightsMs = 0;
};

// The stratum of point u among `count` equal-area cells of the unit square: rows along u[0] of heights n_i /
// count, row i cut into n_i equal cells (n_i = count / rows, one more in the first count % rows rows).
int stratumOf(std::array<double, 2> u, int count);

ShLightResult shLights(const Probe& probe, const ShLightOptions& options);

}  // namespace probelights
