#include "probelights/tradeoff.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>

#include "probelights/error.h"

namespace probelights {

namespace {
using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}
double bakeMs(const BakeResult& r) { return r.timings.tablesMs + r.timings.partitionMs + r.timings.lightsMs; }
}  // namespace

std::vector<TradeoffRow> tradeoff(const Probe& probe, const Evaluator& evaluator, const TradeoffOptions& o) {
  std::vector<TradeoffRow> rows;
  for (Method method : o.methods)
    for (const WorkingResolution& res : o.resolutions) {
      // The SH method does not use the working grid: one resolution is enough.
      if (method == Method::SphericalHarmonics && &res != &o.resolutions.front()) continue;
      for (int n : o.counts) {
        BakeOptions b;
        b.method = method;
        b.lights = n;
        b.resolution = res;
        BakeResult r = bake(probe, b);
        const std::string resName = method == Method::SphericalHarmonics ? "-" : res.toString();
        rows.push_back({method, n, static_cast<int>(r.lights.size()), resName, false, bakeMs(r),
                        evaluator.evaluate(r.lights)});
        if (o.refit && (evaluator.effects() & kDiffuse) && r.lights.size() <= kMaxRefitLights) {
          auto t = Clock::now();
          auto refit = refitIrradiance(evaluator, r.lights, nullptr, /*moveDirections=*/true);
          rows.push_back({method, n, static_cast<int>(refit.size()), resName, true, bakeMs(r) + msSince(t),
                          evaluator.evaluate(refit)});
        }
      }
    }
  return rows;
}

namespace {

const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

}  // namespace

void writeTradeoffPlot(const std::vector<TradeoffRow>& rows, unsigned effects, const std::string& title,
                       const std::string& path) {
  const int W = 960, H = 640, left = 90, right = 250, top = 50, bottom = 70;
  OIIO::ImageBuf img(OIIO::ImageSpec(W, H, 3, OIIO::TypeDesc::FLOAT));
  const float white[3] = {1, 1, 1}, grey[3] = {0.85f, 0.85f, 0.85f}, black[3] = {0, 0, 0};
  OIIO::ImageBufAlgo::fill(img, white);
  std::vector<TradeoffRow> pts;
  for (const TradeoffRow& r : rows)
    if (r.errors.worst(effects) > 0 && r.bakeMs > 0 && (r.resolution == "full" || r.resolution == "-"))
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
    OIIO::ImageBufAlgo::render_text(img, x, y, s, size, std::filesystem::exists(kFont) ? kFont : "",
                                    OIIO::cspan<float>(colour, 3));
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
  const std::map<Method, std::array<float, 3>> colours{{Method::MedianCut, {0.85f, 0.2f, 0.1f}},
                                                       {Method::Variance, {0.1f, 0.35f, 0.85f}},
                                                       {Method::SphericalHarmonics, {0.1f, 0.6f, 0.2f}}};
  int legend = top + 10;
  for (auto [method, colour] : colours)
    for (bool refit : {false, true}) {
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

AutoCountResult autoCount(const Probe& probe, const Evaluator& evaluator, BakeOptions options,
                          double tolerance, bool refit, int maxLights, bool moveDirections) {
  if (!(tolerance > 0)) throw Error("the error tolerance must be positive");
  AutoCountResult best;
  auto attempt = [&](int n) {
    options.lights = n;
    BakeResult r = bake(probe, options);
    if (refit && r.lights.size() <= kMaxRefitLights)
      r.lights = refitIrradiance(evaluator, r.lights, nullptr, moveDirections);
    EffectErrors e = evaluator.evaluate(r.lights);
    best.tried.push_back({n, e.worst(evaluator.effects())});
    return std::pair{std::move(r), e};
  };
  // Doubling until the tolerance is met, then bisection between the last miss and the first hit.
  int lo = 0, hi = 0;
  for (int n = 1; n <= maxLights; n *= 2) {
    auto [r, e] = attempt(n);
    if (e.worst(evaluator.effects()) <= tolerance) {
      hi = n;
      best.bake = std::move(r), best.errors = e, best.lights = n, best.met = true;
      break;
    }
    lo = n;
    best.bake = std::move(r), best.errors = e, best.lights = n;
    if (static_cast<int>(best.bake.lights.size()) < n)
      break;  // fewer lit pixels than lights: more cannot help
  }
  if (!best.met) return best;
  while (hi - lo > 1) {
    int mid = lo + (hi - lo) / 2;
    auto [r, e] = attempt(mid);
    if (e.worst(evaluator.effects()) <= tolerance) {
      hi = mid;
      best.bake = std::move(r), best.errors = e, best.lights = mid;
    } else {
      lo = mid;
    }
  }
  return best;
}

EvaluatedBake bakeEvaluated(const Probe& probe, BakeOptions options, AccuracyOptions a) {
  EvaluatedBake out;
  const bool evaluating = a.evaluate || a.refit || a.maxError > 0;
  if (a.refit) a.effects |= kDiffuse;
  if (!evaluating) {
    out.bake = bake(probe, options);
    out.lights = options.lights;
    return out;
  }
  const Evaluator evaluator(probe, a.effects, EvaluatorOptions{a.evaluatorWidth, a.refit});
  if (a.maxError > 0) {
    AutoCountResult chosen =
        autoCount(probe, evaluator, options, a.maxError, a.refit, 1024, a.moveDirections);
    out.bake = std::move(chosen.bake);
    out.autoCount = true, out.met = chosen.met, out.tried = std::move(chosen.tried),
    out.lights = chosen.lights;
    char line[200];
    std::snprintf(line, sizeof line, "%s: %d lights, worst error %.2f%% (asked at most %.2f%%)",
                  chosen.met ? "auto count" : "auto count missed the tolerance", chosen.lights,
                  100 * chosen.errors.worst(a.effects), 100 * a.maxError);
    out.bake.notes.push_back(line);
  } else {
    out.bake = bake(probe, options);
    out.lights = options.lights;
    if (a.refit) {
      if (out.bake.lights.size() > kMaxRefitLights)
        throw Error("the refit takes at most " + std::to_string(kMaxRefitLights) + " lights");
      out.bake.lights = refitIrradiance(evaluator, out.bake.lights, &out.energyShift, a.moveDirections);
    }
  }
  out.evaluated = true;
  out.effects = a.effects;
  out.errors = evaluator.evaluate(out.bake.lights);
  return out;
}

}  // namespace probelights
