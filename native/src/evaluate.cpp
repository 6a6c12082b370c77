#include "probelights/evaluate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "evaluator_truth.h"
#include "parallel.h"
#include "probelights/error.h"
#include "probelights/names.h"
#include "probelights/pixel_sums.h"

namespace probelights {

namespace {
constexpr NameTable<Effect, 4> kEffects{
    {{kDiffuse, "diffuse"}, {kShadow, "shadow"}, {kShadow, "shadows"}, {kGlossy, "glossy"}}};
}  // namespace

Effects parseEffects(const std::string& list) {
  Effects effects;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) effects |= parseName(kEffects, "effect", item);
  if (effects.empty())
    throw Error("no effects given: use diffuse, shadow and/or glossy, separated by commas");
  return effects;
}

std::string effectsToString(Effects e) {
  std::string s;
  for (Effect bit : {kDiffuse, kShadow, kGlossy}) {
    if (!(e & bit)) continue;
    if (!s.empty()) s.push_back(',');
    s.append(nameOf(kEffects, bit));
  }
  return s;
}

double EffectErrors::worst(Effects effects) const {
  double w = 0;
  if (effects & kDiffuse) w = std::max(w, diffuse);
  if (effects & kShadow) w = std::max(w, shadow);
  if (effects & kGlossy) w = std::max(w, glossy);
  return w;
}

namespace {

// 256 normals spread evenly over the sphere (Fibonacci lattice): deterministic, no clustering at poles.
std::vector<Vec3> fibonacciSphere(int n) {
  std::vector<Vec3> v(n);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = golden * i;
    v[i] = {r * std::cos(phi), r * std::sin(phi), z};
  }
  return v;
}

// n x n ground points at the middles of the cells of [-2.5, 2.5]^2 (z = 0): the shadow scene's receivers.
std::vector<Vec3> groundGrid(int n) {
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      points.push_back({-2.5 + 5.0 * (i + 0.5) / n, -2.5 + 5.0 * (j + 0.5) / n, 0.0});
  return points;
}

double lobe(double c, int exponent) {  // max(0, c)^exponent for exponent a power of two, by squaring
  if (c <= 0) return 0;
  double v = c;
  for (int e = 1; e < exponent; e *= 2) v *= v;
  return v;
}

template <class Kernel>
std::vector<Rgb> truthAt(const std::vector<Vec3>& dirs, const std::vector<Rgb>& radiance, std::size_t count,
                         Kernel&& kernel) {
  std::vector<Rgb> out(count);
  parallelFor(static_cast<std::int64_t>(count), [&](std::int64_t i) {
    Rgb s{};
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      double w = kernel(static_cast<std::size_t>(i), dirs[k]);
      if (w > 0)
        for (int c = 0; c < 3; ++c) s[c] += radiance[k][c] * w;
    }
    out[i] = s;
  });
  return out;
}

}  // namespace

bool Evaluator::visible(const Vec3& p, const Vec3& d) {
  // Ray p + t d against the sphere |x - c| = 1, c = (0, 0, 1); p is outside it. Hit iff the ray's closest
  // approach is ahead (b < 0) and within the radius (discriminant > 0).
  const Vec3 o = p - Vec3{0, 0, 1};
  const double b = dot(d, o), cc = dot(o, o) - 1.0;
  return !(b < 0 && b * b - cc > 0);
}

Evaluator::Evaluator(const Probe& probe, Effects effects, EvaluatorOptions options)
    : Evaluator(probe, nullptr, effects, options) {}

Evaluator::Evaluator(const Probe& probe, const MomentTable& grid, Effects effects, EvaluatorOptions options)
    : Evaluator(probe, &grid, effects, options) {}

Evaluator::Evaluator(const Probe& probe, const MomentTable* grid, Effects effects, EvaluatorOptions options)
    : effects_(effects), profile_(options.sunProfile), cones_(options.sunCones) {
  // Probe samples: pixels, or cells of whole pixels for probes wider than options.maxWidth.
  const int maxWidth = std::max(1, options.maxWidth);
  const int cell = std::max(1, (probe.width() + maxWidth - 1) / maxWidth);
  const int cw = (probe.width() + cell - 1) / cell, ch = (probe.height() + cell - 1) / cell;
  // The middle of sample i's pixels along an axis of n pixels, in [0, 1], for samples of `size` pixels.
  auto middle = [&](int i, int n, int size) { return 0.5 * (i * size + std::min(n, (i + 1) * size)) / n; };
  truth::Samples samples;
  std::vector<std::array<int, 2>> sampleCells;  // each sample's (x, y)
  auto addRow = [&](int y, auto&& sampleAt) {
    for (int x = 0; x < cw; ++x) {
      const auto [rgb, moment] = sampleAt(x);
      if (samples.add(probe.projection(), rgb, moment, middle(x, probe.width(), cell),
                      middle(y, probe.height(), cell)))
        sampleCells.push_back({x, y});
    }
  };
  if (grid && grid->hasCellSums() && cell % grid->cellSize() == 0) {
    // Each sample is a block of g x g cells of the grid: rgb from the cells' sums, the moment from its table.
    const int g = cell / grid->cellSize();
    parallelReduce(
        ch, 0,
        [&](std::int64_t y) {
          std::vector<std::pair<Rgb, Vec3>> row(cw);
          for (int x = 0; x < cw; ++x) {
            const Rect cells{x * g, static_cast<int>(y) * g, std::min(grid->width(), (x + 1) * g),
                             std::min(grid->height(), static_cast<int>(y + 1) * g)};
            row[x] = {grid->cellSums(cells).rgb, grid->moments(cells).moment};
          }
          return row;
        },
        [&](int&, const std::vector<std::pair<Rgb, Vec3>>& row, std::int64_t y) {
          addRow(static_cast<int>(y), [&](int x) { return row[x]; });
        });
  } else {
    probe.requirePixels("evaluating lights");
    parallelReduce(
        ch, 0,
        [&](std::int64_t y) {
          std::vector<PixelSums> row(cw);
          accumulateRows(probe, static_cast<int>(y) * cell,
                         std::min(probe.height(), static_cast<int>(y + 1) * cell), 0, probe.width(), cell,
                         row);
          return row;
        },
        [&](int&, const std::vector<PixelSums>& row, std::int64_t y) {
          addRow(static_cast<int>(y), [&](int x) { return std::pair{row[x].rgb, row[x].moment}; });
        });
  }
  const truth::Samples fine = (effects & kShadow) && probe.hasPixels()
                                  ? truth::splitBrightest(probe, cell, samples, sampleCells)
                                  : truth::Samples{};
  directions_ = std::move(samples.directions), radiance_ = std::move(samples.radiance);
  normals_ = fibonacciSphere(256);
  if (effects & kDiffuse) {
    // Both sets' truth in one pass (the samples binned once).
    if (options.forRefit) fitNormals_ = fibonacciSphere(std::max(1, options.fitNormals));
    std::vector<Vec3> all = normals_;
    all.insert(all.end(), fitNormals_.begin(), fitNormals_.end());
    const std::vector<Rgb> truth = truth::irradianceTruthAt(directions_, radiance_, all);
    diffuse_.assign(truth.begin(), truth.begin() + static_cast<std::ptrdiff_t>(normals_.size()));
    fitTruth_.assign(truth.begin() + static_cast<std::ptrdiff_t>(normals_.size()), truth.end());
  }
  if (effects & kShadow) {
    points_ = groundGrid(16);
    for (const Vec3& p : points_) pointCaps_.push_back(sphereCap(p, {0, 0, 1}, 1.0));
    fitPoints_ = groundGrid(20);
    if (options.forRefit) refitPoints_ = groundGrid(32);
    // The three sets' truth in one pass (the samples binned once).
    std::vector<Vec3> all = points_;
    all.insert(all.end(), fitPoints_.begin(), fitPoints_.end());
    all.insert(all.end(), refitPoints_.begin(), refitPoints_.end());
    const std::vector<Rgb> truth = fine.directions.empty()
                                       ? truth::shadowTruthAt(directions_, radiance_, all)
                                       : truth::shadowTruthAt(fine.directions, fine.radiance, all);
    auto at = truth.begin();
    for (auto [set, size] : {std::pair{&shadow_, points_.size()},
                             {&fitShadow_, fitPoints_.size()},
                             {&refitShadow_, refitPoints_.size()}})
      set->assign(at, at + static_cast<std::ptrdiff_t>(size)), at += static_cast<std::ptrdiff_t>(size);
  }
  if (effects & kGlossy)
    for (int e = 0; e < 2; ++e)
      glossy_[e] = truthAt(directions_, radiance_, normals_.size(), [&](std::size_t i, const Vec3& d) {
        return (kGlossyExponents[e] + 1) / (2 * kPi) * lobe(dot(normals_[i], d), kGlossyExponents[e]);
      });
}

std::vector<Vec3> Evaluator::brightestDirections(std::size_t count) const {
  std::vector<std::size_t> order(radiance_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  count = std::min(count, order.size());
  auto brighter = [&](std::size_t a, std::size_t b) {
    const double la = luminance(radiance_[a]), lb = luminance(radiance_[b]);
    return la != lb ? la > lb : a < b;
  };
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count), order.end(), brighter);
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < count; ++i) out.push_back(directions_[order[i]]);
  return out;
}

std::vector<Receiver> Evaluator::fitReceivers(bool refit) const {
  std::vector<Receiver> out;
  auto add = [&](const std::vector<Vec3>& at, const std::vector<Rgb>& truth, bool ground) {
    double sum = 0;
    for (const Rgb& t : truth) sum += luminance(t) * luminance(t);
    if (!(sum > 0)) return;
    for (std::size_t k = 0; k < at.size(); ++k)
      out.push_back({at[k], ground, truth[k], 1 / sum, ground ? sphereCap(at[k], {0, 0, 1}, 1.0) : Cap{}});
  };
  if (!fitNormals_.empty())
    add(fitNormals_, fitTruth_, false);
  else if (!diffuse_.empty())
    add(normals_, diffuse_, false);
  if (refit && !refitPoints_.empty())
    add(refitPoints_, refitShadow_, true);
  else
    add(fitPoints_, fitShadow_, true);
  return out;
}

}  // namespace probelights
