// Sums over a set of pixels of everything a light needs, and the one loop that accumulates them from a probe.
#pragma once

#include <span>

#include "probelights/geometry.h"
#include "probelights/probe.h"

namespace probelights {

// With w = Y dOmega (Y = Rec. 709 luminance of the pixel's radiance L, dOmega its exact solid angle, d its
// unit direction), over a set of pixels:
struct PixelSums {
  Rgb rgb{};                // sum of L dOmega, L signed (Probe::light); the rest weigh L clamped at 0
  double solidAngle = 0;    // sum of dOmega
  double energy = 0;        // sum of w
  Vec3 moment;              // sum of w d
  double energy2 = 0;       // sum of w Y   (Yang 2015's "Centroid Formula 2": L^2 weighting)
  Vec3 moment2;             // sum of w Y d
  long long litPixels = 0;  // pixels with w > 0

  PixelSums& operator+=(const PixelSums& o);
};

// Adds pixels [x0, x1) of rows [y0, y1) to cells: pixel x goes to cells[(x - x0) / cellSize]. Row by row,
// each row's pixels summed per cell with the row's weights (dOmega, cos el, sin el) applied once per cell; a
// lat-long pixel's cos phi and sin phi come from the row's tables. squares = false leaves energy2 and moment2
// at 0 (only the energy2 centroid needs them). `oddSamples` (if given): false when the loop saw that every
// sample it read is finite and not negative (it looks in lat-long probes; otherwise true), so a pixel check
// (Probe::countRows) has nothing to find there but their light.
void accumulateRows(const Probe& probe, int y0, int y1, int x0, int x1, int cellSize,
                    std::span<PixelSums> cells, bool squares = true, bool* oddSamples = nullptr);

// The sums over a rectangle of pixels.
PixelSums sumPixels(const Probe& probe, const Rect& pixels, bool squares = true);

}  // namespace probelights
