#include "probelights/sh_lights.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/pixel_sums.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {}  // namespace

int stratumOf(std::array<double, 2> u, int count) {
  const int rows = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(count))));
  const int base = count / rows, extra = count % rows;
  // Row i holds n_i = base + (i < extra) cells and has height n_i / count.
  double top = 0;
  int first = 0;
  for (int i = 0; i < rows; ++i) {
    const int n = base + (i < extra ? 1 : 0);
    const double bottom = i == rows - 1 ? 1.0 : top + static_cast<double>(n) / count;
    if (u[0] < bottom || i == rows - 1) return first + std::min(n - 1, static_cast<int>(u[1] * n));
    top = bottom;
    first += n;
  }
  return count - 1;
}

ShLightResult shLights(const Probe& probe, const ShLightOptions& o) {
  checkLightCount(o.lights);
  ShLightResult result;
  Stopwatch t;
  const ShSampler sampler(o.bands, projectProbe(probe, o.bands).luminance(), o.epsilon, o.depth);
  result.projectMs = t.ms();

  // Every pixel goes to the stratum its direction warps back to; blocks of rows in parallel, merged in order.
  t.restart();
  const int W = probe.width(), H = probe.height(), blocks = std::min(H, 64);
  struct Block {
    std::vector<PixelSums> sums;
    std::vector<Rect> bounds;
  };
  Block merged{std::vector<PixelSums>(o.lights), std::vector<Rect>(o.lights, Rect{W, H, 0, 0})};
  merged = parallelReduce(
      blocks, std::move(merged),
      [&](std::int64_t b) {
        Block block;
        block.sums.assign(o.lights, PixelSums{});
        block.bounds.assign(o.lights, Rect{W, H, 0, 0});
        std::vector<Vec3> dirs(W);
        std::vector<double> omega(W);
        for (int y = static_cast<int>(b * H / blocks); y < static_cast<int>((b + 1) * H / blocks); ++y) {
          probe.projection().rowGeometry(y, 0, W, dirs, omega);
          for (int x = 0; x < W; ++x) {
            if (omega[x] <= 0) continue;
            const int k = stratumOf(sampler.invert(dirs[x]), o.lights);
            accumulateRows(probe, y, y + 1, x, x + 1, 1, std::span<PixelSums>(&block.sums[k], 1));
            Rect& r = block.bounds[k];
            r = {std::min(r.x0, x), std::min(r.y0, y), std::max(r.x1, x + 1), std::max(r.y1, y + 1)};
          }
        }
        return block;
      },
      [&](Block& total, const Block& block, std::int64_t) {
        for (int k = 0; k < o.lights; ++k) {
          total.sums[k] += block.sums[k];
          const Rect& r = block.bounds[k];
          Rect& t = total.bounds[k];
          t = {std::min(t.x0, r.x0), std::min(t.y0, r.y0), std::max(t.x1, r.x1), std::max(t.y1, r.y1)};
        }
      });
  std::vector<PixelSums>& sums = merged.sums;
  std::vector<Rect>& bounds = merged.bounds;
  result.assignMs = t.ms();

  t.restart();
  for (Rect& r : bounds)
    if (r.empty()) r = {0, 0, 0, 0};
  result.lights = lightsFromSums(probe, bounds, sums);
  result.lightsMs = t.ms();
  if (static_cast<int>(result.lights.size()) < o.lights)
    result.notes.push_back({NoteKind::Warning, "made " + std::to_string(result.lights.size()) +
                                                   " lights, not " + std::to_string(o.lights) + ": " +
                                                   std::to_string(o.lights - result.lights.size()) +
                                                   " cells of the SH partition hold no lit pixel"});
  return result;
}

}  // namespace probelights
