// Synthetic probes for the tests: small float buffers the test owns, viewed by a Probe without copying.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "probelights/placement.h"
#include "probelights/probe.h"

namespace probelights::testing {

// A probe together with the pixels it views.
struct TestProbe {
  std::shared_ptr<std::vector<float>> pixels;
  Probe probe;
};

// An RGB probe whose pixel (x, y) has radiance fill(x, y).
inline TestProbe makeProbe(int width, int height, ProjectionKind kind,
                           const std::function<Rgb(int, int)>& fill) {
  auto pixels = std::make_shared<std::vector<float>>(static_cast<std::size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Rgb c = fill(x, y);
      for (int k = 0; k < 3; ++k)
        (*pixels)[(static_cast<std::size_t>(y) * width + x) * 3 + k] = static_cast<float>(c[k]);
    }
  Probe probe(ImageView{pixels->data(), width, height, 3}, kind);
  return {pixels, std::move(probe)};
}

// A lat-long probe of random RGBA pixels (or one grey channel) in [-0.2, 3), one NaN and one Inf, rows stored
// bottom first and read through a flipped view (Blender's layout), unchecked (Probe::unchecked): the loops'
// hard cases in a few pixels.
inline TestProbe randomProbe(int W, int H, int channels, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.2f, 3.0f);
  auto data = std::make_shared<std::vector<float>>(static_cast<std::size_t>(W) * H * channels);
  for (float& f : *data) f = u(rng);
  (*data)[5 * channels] = std::numeric_limits<float>::quiet_NaN();
  (*data)[(static_cast<std::size_t>(W) * 3 + 7) * channels] = std::numeric_limits<float>::infinity();
  ImageView view{data->data() + static_cast<std::size_t>(H - 1) * W * channels, W, H, channels};
  view.rowStride = -static_cast<std::ptrdiff_t>(W) * channels;
  return {data, Probe::unchecked(view, ProjectionKind::LatLong)};
}

inline TestProbe uniformProbe(int width, int height, ProjectionKind kind, Rgb L) {
  return makeProbe(width, height, kind, [L](int, int) { return L; });
}

inline Rgb sumRgb(const std::vector<Light>& lights) {
  Rgb s{};
  for (const Light& l : lights)
    for (int k = 0; k < 3; ++k) s[k] += l.rgb[k];
  return s;
}

inline double maxRelativeDifference(const Rgb& a, const Rgb& b) {
  double worst = 0;
  for (int k = 0; k < 3; ++k) {
    double scale = std::max(std::abs(a[k]), std::abs(b[k]));
    if (scale > 0) worst = std::max(worst, std::abs(a[k] - b[k]) / scale);
  }
  return worst;
}

inline BakeResult bakeWith(const Probe& probe, Method method, int lights,
                           WorkingResolution resolution = {WorkingResolution::Mode::Full, 0},
                           bool horizon = false) {
  BakeOptions o;
  o.splitAtHorizon = horizon;
  o.method = method;
  o.lights = lights;
  o.resolution = resolution;
  return bake(probe, o);
}

}  // namespace probelights::testing
