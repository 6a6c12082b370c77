#include "probelights/evaluate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

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

void Evaluator::addSample(const Projection& projection, const Rgb& rgb, const Vec3& moment, double u,
                          double v) {
  if (rgb[0] == 0 && rgb[1] == 0 && rgb[2] == 0) return;
  const double len = moment.length();
  if (len > 0) {
    directions_.push_back((1.0 / len) * moment);
  } else {
    const auto d = projection.direction(u, v);
    if (!d) return;
    directions_.push_back(*d);
  }
  radiance_.push_back(rgb);
}

Evaluator::Evaluator(const Probe& probe, const MomentTable* grid, Effects effects, EvaluatorOptions options)
    : effects_(effects), profile_(options.sunProfile) {
  // Probe samples: pixels, or cells of whole pixels for probes wider than options.maxWidth.
  const int maxWidth = std::max(1, options.maxWidth);
  const int cell = std::max(1, (probe.width() + maxWidth - 1) / maxWidth);
  const int cw = (probe.width() + cell - 1) / cell, ch = (probe.height() + cell - 1) / cell;
  // The middle of sample i's pixels along an axis of n pixels, in [0, 1].
  auto middle = [&](int i, int n) { return 0.5 * (i * cell + std::min(n, (i + 1) * cell)) / n; };
  if (grid && grid->hasCellSums() && cell % grid->cellSize() == 0) {
    // Each sample is a block of k x k cells of the grid: rgb from the cells' sums, the moment from its table.
    const int k = cell / grid->cellSize();
    parallelReduce(
        ch, 0,
        [&](std::int64_t y) {
          std::vector<std::pair<Rgb, Vec3>> row(cw);
          for (int x = 0; x < cw; ++x) {
            const Rect cells{x * k, static_cast<int>(y) * k, std::min(grid->width(), (x + 1) * k),
                             std::min(grid->height(), static_cast<int>(y + 1) * k)};
            row[x] = {grid->cellSums(cells).rgb, grid->moments(cells).moment};
          }
          return row;
        },
        [&](int&, const std::vector<std::pair<Rgb, Vec3>>& row, std::int64_t y) {
          for (int x = 0; x < cw; ++x)
            addSample(probe.projection(), row[x].first, row[x].second, middle(x, probe.width()),
                      middle(static_cast<int>(y), probe.height()));
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
          for (int x = 0; x < cw; ++x)
            addSample(probe.projection(), row[x].rgb, row[x].moment, middle(x, probe.width()),
                      middle(static_cast<int>(y), probe.height()));
        });
  }
  normals_ = fibonacciSphere(256);
  if (effects & kDiffuse) {
    diffuse_ = truthAt(directions_, radiance_, normals_.size(),
                       [&](std::size_t i, const Vec3& d) { return std::max(0.0, dot(normals_[i], d)); });
    if (options.forRefit) {
      fitNormals_ = fibonacciSphere(1024);
      fitTruth_ = truthAt(directions_, radiance_, fitNormals_.size(), [&](std::size_t i, const Vec3& d) {
        return std::max(0.0, dot(fitNormals_[i], d));
      });
    }
  }
  if (effects & kShadow) {
    points_ = groundGrid(16);
    for (const Vec3& p : points_) pointCaps_.push_back(sphereCap(p, {0, 0, 1}, 1.0));
    shadow_ = shadowTruthAt(points_);
    fitPoints_ = groundGrid(20);
    fitShadow_ = shadowTruthAt(fitPoints_);
    if (options.forRefit) {
      refitPoints_ = groundGrid(32);
      refitShadow_ = shadowTruthAt(refitPoints_);
    }
  }
  if (effects & kGlossy)
    for (int e = 0; e < 2; ++e)
      glossy_[e] = truthAt(directions_, radiance_, normals_.size(), [&](std::size_t i, const Vec3& d) {
        return (kGlossyExponents[e] + 1) / (2 * kPi) * lobe(dot(normals_[i], d), kGlossyExponents[e]);
      });
}

// A ground point's truth is the upper hemisphere's irradiance less what the sphere hides: the samples inside
// the sphere's cap seen from the point. The samples above the horizon are binned by (z, azimuth), so each
// point visits only the bins the cap's bounding box touches (a few percent of the samples) and tests those
// exactly.
std::vector<Rgb> Evaluator::shadowTruthAt(const std::vector<Vec3>& points) const {
  constexpr int kBandsZ = 128, kBinsPhi = 256;
  auto binOf = [&](const Vec3& d) {
    const int z = std::min(kBandsZ - 1, static_cast<int>(d.z * kBandsZ));
    const double u = (std::atan2(d.y, d.x) + kPi) / (2 * kPi);
    return z * kBinsPhi + std::min(kBinsPhi - 1, static_cast<int>(u * kBinsPhi));
  };
  std::vector<int> start(kBandsZ * kBinsPhi + 1, 0);
  Rgb upper{};
  for (std::size_t k = 0; k < directions_.size(); ++k)
    if (directions_[k].z > 0) {
      ++start[binOf(directions_[k]) + 1];
      for (int c = 0; c < 3; ++c) upper[c] += radiance_[k][c] * directions_[k].z;
    }
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<Vec3> dir(start.back());
  std::vector<Rgb> rad(start.back());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < directions_.size(); ++k)
      if (directions_[k].z > 0) {
        const int at = fill[binOf(directions_[k])]++;
        dir[at] = directions_[k], rad[at] = radiance_[k];
      }
  }
  std::vector<Rgb> out(points.size());
  parallelFor(static_cast<std::int64_t>(points.size()), [&](std::int64_t i) {
    const Cap cap = sphereCap(points[i], {0, 0, 1}, 1.0);
    const double cosG = std::cos(cap.radius), theta = std::acos(std::clamp(cap.axis.z, -1.0, 1.0));
    const double zLo = std::cos(std::min(0.5 * kPi, theta + cap.radius));
    const bool pole = theta <= cap.radius;  // the cap holds the zenith: every azimuth
    const double zHi = pole ? 1.0 : std::cos(theta - cap.radius);
    int phiFirst = 0, phiCount = kBinsPhi;
    if (!pole) {
      const double half = std::asin(std::min(1.0, std::sin(cap.radius) / std::sin(theta)));
      const double u0 = (std::atan2(cap.axis.y, cap.axis.x) - half + kPi) / (2 * kPi);
      phiFirst = static_cast<int>(std::floor(u0 * kBinsPhi));
      phiCount = std::min(kBinsPhi, static_cast<int>(std::ceil(2 * half / (2 * kPi) * kBinsPhi)) + 2);
    }
    Rgb hidden{};
    const int z0 = std::max(0, static_cast<int>(zLo * kBandsZ)),
              z1 = std::min(kBandsZ - 1, int(zHi * kBandsZ));
    for (int z = z0; z <= z1; ++z)
      for (int j = 0; j < phiCount; ++j) {
        const int b = z * kBinsPhi + ((phiFirst + j) % kBinsPhi + kBinsPhi) % kBinsPhi;
        for (int k = start[b]; k < start[b + 1]; ++k)
          if (dot(dir[k], cap.axis) > cosG)
            for (int c = 0; c < 3; ++c) hidden[c] += rad[k][c] * dir[k].z;
      }
    for (int c = 0; c < 3; ++c) out[i][c] = upper[c] - hidden[c];
  });
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
