// What the shells ask of spherical harmonics, one option table each (request.h's pattern): the CLI's sh and
// sample, the module's sh_project and sh_sample take the same names, values and defaults.
#pragma once

#include <cstdint>
#include <vector>

#include "probelights/request.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"

namespace probelights {

// The probe's SH coefficients (spherical_harmonics.h): of the radiance, windowed, or of the irradiance.
struct ShRequest {
  ProbeOptions probe;  // its nonfinite policy (a file's projection too)
  int bands = 0;       // required: at least 1
  ShWindow window = ShWindow::None;
  bool irradiance = false;
};
using ShOption = TableOption<ShRequest>;
const std::vector<ShOption>& shOptions();
ShCoefficients shProject(const Probe& probe, const ShRequest& request);

// Samples of the SH importance sampler of the probe's luminance (sh_sampler.h: Jarosz et al. 2009 warping,
// Berger 2011's epsilon clamp), seeded; epsilon's default the sh method's (placement.h).
struct SampleRequest {
  ProbeOptions probe;
  int bands = 0;  // required: at least 1
  double epsilon = BakeOptions{}.shEpsilon;
  int samples = 1024;
  int depth = 8;
  std::uint64_t seed = 1;
};
using SampleOption = TableOption<SampleRequest>;
const std::vector<SampleOption>& sampleOptions();
std::vector<ShSampler::Sample> shSamples(const Probe& probe, const SampleRequest& request);

// An Error, "no SH bands given", with its remedy (each shell's spelling of bands), when bands < 1: a shell
// checks it before the probe is read; shProject and shSamples check it too.
void requireBands(int bands);

}  // namespace probelights
