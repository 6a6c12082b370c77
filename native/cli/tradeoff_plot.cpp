// The tradeoff plot of `probelights tradeoff --plot`, drawn with OpenImageIO: a CLI concern, not the
// library's.
#include "tradeoff_plot.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "probelights/error.h"

namespace probelights::cli {

namespace {

// The labels' font, found at run time: DejaVu Sans where installed (Debian: fonts-dejavu-core), else
// OpenImageIO's own default font.
std::string labelFont() {
  for (const char* path : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
                           "/usr/share/fonts/TTF/DejaVuSans.ttf", "/usr/share/fonts/dejavu/DejaVuSans.ttf"})
    if (std::filesystem::exists(path)) return path;
  return "";
}

}  // namespace

void writeTradeoffPlot(const std::vector<TradeoffRow>& rows, Effects effects, const std::string& title,
                       const std::string& path) {
  const int W = 960, H = 640, left = 90, right = 250, top = 50, bottom = 70;
  const std::string font = labelFont();
  OIIO::ImageBuf img(OIIO::ImageSpec(W, H, 3, OIIO::TypeDesc::FLOAT));
  const float white[3] = {1, 1, 1}, grey[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0, 0, 0};
  OIIO::ImageBufAlgo::fill(img, white);
  std::vector<TradeoffRow> pts;
  for (const TradeoffRow& r : rows)
    if (r.errors.worst(effects) > 0 && r.bakeMs > 0 &&
        (!r.resolution || r.resolution->mode == WorkingResolution::Mode::Full))
      pts.push_back(r);
  if (pts.empty()) throw Error("nothing to plot");
  double tmin = 1e300, tmax = 0, emin = 1e300, emax = 0;
  for (const auto& r : pts) {
    tmin = std::min(tmin, r.bakeMs), tmax = std::max(tmax, r.bakeMs);
    double e = 100 * r.errors.worst(effects);
    emin = std::min(emin, e), emax = std::max(emax, e);
  }
  const double lt0 = std::floor(std::log10(tmin)), lt1 = std::ceil(std::log10(tmax));
  const double le0 = std::floor(std::log10(emin)), le1 = std::ceil(std::log10(emax));
  auto X = [&](double ms) {
    return left + (std::log10(ms) - lt0) / std::max(1e-9, lt1 - lt0) * (W - left - right);
  };
  auto Y = [&](double pct) {
    return H - bottom - (std::log10(pct) - le0) / std::max(1e-9, le1 - le0) * (H - top - bottom);
  };
  auto text = [&](int x, int y, const std::string& s, int size, const float* colour) {
    OIIO::ImageBufAlgo::render_text(img, x, y, s, size, font, OIIO::cspan<float>(colour, 3));
  };
  for (double d = lt0; d <= lt1; ++d) {  // decades
    int x = static_cast<int>(X(std::pow(10, d)));
    OIIO::ImageBufAlgo::render_line(img, x, top, x, H - bottom, grey);
    text(x - 12, H - bottom + 22, d >= 0 ? std::to_string(static_cast<long long>(std::pow(10, d))) : "0.1",
         16, black);
  }
  for (double d = le0; d <= le1; ++d) {
    int y = static_cast<int>(Y(std::pow(10, d)));
    OIIO::ImageBufAlgo::render_line(img, left, y, W - right, y, grey);
    char label[32];
    std::snprintf(label, sizeof label, "%g %%", std::pow(10, d));
    text(10, y + 5, label, 16, black);
  }
  OIIO::ImageBufAlgo::render_box(img, left, top, W - right, H - bottom, black);
  text(left, 32, title, 20, black);
  text(left + (W - left - right) / 2 - 80, H - 20, "bake time (ms, log)", 16, black);
  // One colour per registered method, in their order (placement.h).
  const std::array<std::array<float, 3>, 6> palette{{{0.85f, 0.2f, 0.1f},
                                                     {0.1f, 0.35f, 0.85f},
                                                     {0.1f, 0.6f, 0.2f},
                                                     {0.6f, 0.2f, 0.7f},
                                                     {0.9f, 0.6f, 0.1f},
                                                     {0.3f, 0.3f, 0.3f}}};
  int legend = top + 10;
  for (std::size_t m = 0; m < placementMethods().size(); ++m)
    for (bool refit : {false, true}) {
      const Method method = placementMethods()[m].method();
      const std::array<float, 3>& colour = palette[m % palette.size()];
      std::vector<const TradeoffRow*> curve;
      for (const auto& r : pts)
        if (r.method == method && r.refit == refit) curve.push_back(&r);
      if (curve.empty()) continue;
      std::sort(curve.begin(), curve.end(), [](auto* a, auto* b) { return a->lights < b->lights; });
      float c[3] = {colour[0], colour[1], colour[2]};
      if (refit)
        for (float& v : c) v = 0.45f + 0.55f * v;  // lighter: the same bakes, refit
      for (std::size_t i = 0; i < curve.size(); ++i) {
        int x = static_cast<int>(X(curve[i]->bakeMs)),
            y = static_cast<int>(Y(100 * curve[i]->errors.worst(effects)));
        OIIO::ImageBufAlgo::render_box(img, x - 3, y - 3, x + 3, y + 3, c, true);
        if (!refit) text(x + 5, y - 5, std::to_string(curve[i]->lights), 12, c);
        if (i > 0)
          OIIO::ImageBufAlgo::render_line(img, static_cast<int>(X(curve[i - 1]->bakeMs)),
                                          static_cast<int>(Y(100 * curve[i - 1]->errors.worst(effects))), x,
                                          y, c);
      }
      OIIO::ImageBufAlgo::render_box(img, W - right + 15, legend - 8, W - right + 35, legend + 2, c, true);
      text(W - right + 42, legend + 2, toString(method) + (refit ? " + refit" : ""), 16, black);
      legend += 26;
    }
  text(W - right + 15, legend + 20, "error: " + effectsToString(effects), 14, black);
  text(W - right + 15, legend + 40, "(worst of them, rms %)", 14, black);
  text(W - right + 15, legend + 60, "labels: lights", 14, black);
  if (!img.write(path, OIIO::TypeDesc::UINT8))
    throw Error("cannot write plot '" + path + "': " + img.geterror());
}

}  // namespace probelights::cli
