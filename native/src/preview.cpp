#include "probelights/preview.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

#include "parallel.h"
#include "probelights/error.h"

namespace probelights {

namespace {

double srgbEncode(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

}  // namespace

void writePreview(const Probe& probe, const BakeResult& result, const std::string& path, int maxWidth) {
  probe.requirePixels("a preview");
  const int W = probe.width(), H = probe.height();
  const int pw = std::min(W, std::max(1, maxWidth));
  const int ph = std::max(1, static_cast<int>(std::lround(static_cast<double>(H) * pw / W)));

  // Box-filter the probe down to the preview size.
  std::vector<Rgb> small(static_cast<std::size_t>(pw) * ph);
  parallelFor(ph, [&](std::int64_t j) {
    int y0 = static_cast<int>(j * H / ph), y1 = std::max(y0 + 1, static_cast<int>((j + 1) * H / ph));
    for (int i = 0; i < pw; ++i) {
      int x0 = static_cast<int>(static_cast<int64_t>(i) * W / pw);
      int x1 = std::max(x0 + 1, static_cast<int>(static_cast<int64_t>(i + 1) * W / pw));
      Rgb s{};
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          Rgb L = probe.radiance(x, y);
          for (int k = 0; k < 3; ++k) s[k] += L[k];
        }
      double n = static_cast<double>(x1 - x0) * (y1 - y0);
      small[j * pw + i] = {s[0] / n, s[1] / n, s[2] / n};
    }
  });

  // Exposure from the log-average luminance (Reinhard et al. 2002, key 0.18), then Reinhard's L / (1 + L) on
  // luminance so hues survive, then sRGB.
  double logSum = 0;
  long long n = 0;
  for (const Rgb& c : small)
    if (double Y = luminance(c); Y > 0) logSum += std::log(Y), ++n;
  const double key = n > 0 ? 0.18 / std::exp(logSum / n) : 1.0;

  OIIO::ImageSpec spec(pw, ph, 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("Software", kPreviewSoftware);  // how a later library bake knows its own preview
  OIIO::ImageBuf buf(spec);
  for (int j = 0; j < ph; ++j)
    for (int i = 0; i < pw; ++i) {
      const Rgb& c = small[static_cast<std::size_t>(j) * pw + i];
      double Y = luminance(c) * key, scale = key / (1.0 + Y);
      float px[3];
      for (int k = 0; k < 3; ++k) px[k] = static_cast<float>(srgbEncode(c[k] * scale));
      buf.setpixel(i, j, px, 3);
    }

  // Region borders, then the lights: a red square at each light's direction, larger for a larger energy
  // share.
  const float border[3] = {0.15f, 0.9f, 0.25f}, lightColour[3] = {1.0f, 0.1f, 0.1f};
  auto sx = [&](int x) { return static_cast<int>(static_cast<int64_t>(x) * pw / W); };
  auto sy = [&](int y) { return static_cast<int>(static_cast<int64_t>(y) * ph / H); };
  auto box = [&](int x0, int x1, const Rect& r) {
    OIIO::ImageBufAlgo::render_box(buf, sx(x0), sy(r.y0), std::max(sx(x0), sx(x1) - 1),
                                   std::max(sy(r.y0), sy(r.y1) - 1), border, false);
  };
  for (const Rect& r : result.regionsAreRects ? result.regions : std::vector<Rect>{}) {
    box(r.x0, std::min(r.x1, W), r);
    if (r.x1 > W) box(0, r.x1 - W, r);  // a region of the sources that wraps round the seam (request.cpp)
  }
  for (const Light& light : result.lights) {
    auto uv = probe.projection().imagePosition(light.direction);
    int cx = static_cast<int>(uv[0] * pw), cy = static_cast<int>(uv[1] * ph);
    int half = 1 + static_cast<int>(std::lround(4.0 * std::sqrt(light.energyShare)));
    OIIO::ImageBufAlgo::render_box(buf, cx - half, cy - half, cx + half, cy + half, lightColour, true);
  }

  if (!buf.write(path, OIIO::TypeDesc::UINT8)) {
    std::string why = buf.geterror();
    std::replace(why.begin(), why.end(), '\n', ' ');
    throw Error("cannot write preview '" + path + "': " + why);
  }
}

}  // namespace probelights
