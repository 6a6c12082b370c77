// Keep the world, take its sources (issue 30): a probe split into the bright sources the lamps take and the
// residual the world keeps, so that a renderer lighting with both (EEVEE's world lighting, a game engine's
// image-based light, Cycles' world) counts nothing twice.
//
// A pixel whose luminance Y (Rec. 709, of its positive channels) is above the level T is scaled down to T,
// its colour kept: R = L+ T / Y; the rest of it, X = L - R, is the sources'. Below the level, R = L+
// (negative channels are 0) and X = L - R holds only the negative part. So per pixel and channel R >= 0,
// Y(R) <= T (to float rounding of the scaling), and R + X = L exactly: X is computed in float as L - R and R
// then as L - X, which is exact (Sterbenz's lemma: whichever of R and X is the larger is at least half of
// L), so the lamps made from X (their rgb the sums of X over their regions) plus the residual's sums give
// back the probe's light per region and channel.
#pragma once

#include <memory>
#include <vector>

#include "probelights/image.h"
#include "probelights/probe.h"

namespace probelights {

// The level a residual is asked for without one (the CLI's --residual alone; the add-on's default).
inline constexpr double kDefaultSourceLevel = 10;

// The knob: where the sources end. Exactly one of the two is set (> 0).
struct SourceLevel {
  // A multiple of the probe's mean luminance (its luminous energy over 4 pi): what the world keeps at most
  // of any pixel. 10 keeps a clear sky's blue and gives the sun to the lamps.
  double level = 0;
  // Or: the share of the probe's luminous energy (of its positive luminance) the lamps take, from the
  // brightest pixels down (the level that gives it, found exactly).
  double share = 0;
  bool operator==(const SourceLevel&) const = default;
};

struct SourceSplit {
  std::shared_ptr<const Image> residual;  // R, RGB float, the probe's size and projection
  std::shared_ptr<Image> sources;         // X = L - R, RGB float (the lamps' bake rolls it: rollColumns)
  double level = 0;                       // T, in the probe's units (luminance)
  double meanLuminance = 0;               // the probe's luminous energy over 4 pi
  double share = 0;                       // the sources' share of the probe's luminous energy
  Rgb residualRgb{}, sourcesRgb{};        // their integrals, sum of value x solid angle per channel
};

// Throws Error for a knob that is not exactly one value > 0 (a share below 1).
SourceSplit splitSources(const Probe& probe, const SourceLevel& how);

// The cuts that share the sources among lamps are rectangles of the image, and on a lat-long image they do
// not wrap round its left and right edges: a sun on the seam (straight behind, phi = pi) would be cut in
// two, a lamp each side, each with half a disc's fitted angle. So the lamps are cut on the sources rolled
// round the vertical axis, the seam moved to where they are darkest: the boundary b (between columns b - 1
// and b, mod the width) whose two columns carry the least of the sources' light, |Y| dw summed down each
// column. 0 (the image's own edge) when it is as dark as any, so a probe whose sources keep off the edge is
// cut as it was, and 0 for the projections that are discs (mirror ball, angular).
int darkestSeam(const Probe& probe, const Image& sources);

// In place: column x of the image becomes column (x + b) mod width, a turn of the lat-long sphere by
// -2 pi b / width about Z (a direction's phi = 2 pi (0.5 - u) falls by that much).
void rollColumns(Image& image, int b);

}  // namespace probelights
