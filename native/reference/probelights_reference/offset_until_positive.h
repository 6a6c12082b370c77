// Jarosz et al.'s remedy for an SH reconstruction that goes negative, which Berger argues against and the SH
// sampler does not use (sh_sampler.h clamps with Berger's epsilon instead): kept for the tests and the
// benchmark that compare the two.
#pragma once

#include <vector>

namespace probelights::reference {

// The Rec. 709 luminance SH of a probe, offset until the reconstruction is nowhere negative (Jarosz et al.'s
// remedy, which Berger argues against: it flattens the distribution).
std::vector<double> offsetUntilPositive(int bands, std::vector<double> coefficients);

}  // namespace probelights::reference
