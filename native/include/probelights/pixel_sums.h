// Sums over a set of pixels of everything a light needs, and the one loop that accumulates them from a probe.
#pragma once

#include <span>

#include "probelights/geometry.h"
#include "probelights/probe.h"

namespace probelights {

// With w = Y dOmega (Y = Rec. 709 luminance of the pixel's radiance L, dOmega its exact solid angle, d its
// unit direction), over a set of pixels:
struct PixelSums {
  Rgb rgb{};                // sum of L dOmega
  double solidAngle = 0;    // sum of dOmega
  double energy = 0;        // sum of w
  Vec3 moment;              // sum of w d
  double energy2 = 0;       // sum of w Y   (Yang 2015's "Centroid Formula 2": L^2 weighting)
  Vec3 moment2;             // sum of w Y d
  long long litPixels = 0;  // pixels with w > 0

  PixelSums& operator+=(const PixelSums& o);
};

// Adds pixels [x0, x1) of rows [y0, y1) to cells: pixel x goes to cells[(x - x0) / cellSize].
// For a lat-long probe the direction is separable, d = (cos el cos phi, cos el sin phi, sin el) with phi
// fixed on a column and el on a row. So the rows are first summed per column, sum_y Y dOmega_y (1, cos el_y,
// sin el_y) and likewise for L and Y^2 (a loop with no dependency from one pixel to the next, which the
// compiler vectorizes), and only then multiplied by cos phi and sin phi and gathered into cells: every pixel
// is read once, with a few multiply-adds.
void accumulateRows(const Probe& probe, int y0, int y1, int x0, int x1, int cellSize,
                    std::span<PixelSums> cells);

// The sums over a rectangle of pixels.
PixelSums sumPixels(const Probe& probe, const Rect& pixels);

}  // namespace probelights
