#include "probelights/evaluate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/pixel_sums.h"

namespace probelights {

unsigned parseEffects(const std::string& list) {
  unsigned effects = 0;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item == "diffuse")
      effects |= kDiffuse;
    else if (item == "shadow" || item == "shadows")
      effects |= kShadow;
    else if (item == "glossy")
      effects |= kGlossy;
    else
      throw Error("unknown effect '" + item + "': use diffuse, shadow and glossy, separated by commas");
  }
  if (!effects) throw Error("no effects given: use diffuse, shadow and/or glossy");
  return effects;
}

std::string effectsToString(unsigned e) {
  std::string s;
  for (auto [bit, name] :
       {std::pair{kDiffuse, "diffuse"}, std::pair{kShadow, "shadow"}, std::pair{kGlossy, "glossy"}}) {
    if (!(e & bit)) continue;
    if (!s.empty()) s.push_back(',');
    s.append(name);
  }
  return s;
}

double EffectErrors::worst(unsigned effects) const {
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

double lobe(double c, int exponent) {  // max(0, c)^exponent for exponent a power of two, by squaring
  if (c <= 0) return 0;
  double v = c;
  for (int e = 1; e < exponent; e *= 2) v *= v;
  return v;
}

double relativeRms(const std::vector<Rgb>& got, const std::vector<Rgb>& truth) {
  double d = 0, t = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    double a = luminance(got[i]), b = luminance(truth[i]);
    d += (a - b) * (a - b);
    t += b * b;
  }
  return t > 0 ? std::sqrt(d / t) : (d > 0 ? 1.0 : 0.0);
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

Evaluator::Evaluator(const Probe& probe, unsigned effects, EvaluatorOptions options) : effects_(effects) {
  // Probe samples: pixels, or cells of whole pixels for probes wider than options.maxWidth.
  const int maxWidth = std::max(1, options.maxWidth);
  const int cell = std::max(1, (probe.width() + maxWidth - 1) / maxWidth);
  const int cw = (probe.width() + cell - 1) / cell, ch = (probe.height() + cell - 1) / cell;
  std::vector<std::vector<PixelSums>> rows(ch);
  parallelFor(ch, [&](std::int64_t y) {
    rows[y].assign(cw, PixelSums{});
    accumulateRows(probe, static_cast<int>(y) * cell,
                   std::min(probe.height(), static_cast<int>(y + 1) * cell), 0, probe.width(), cell, rows[y]);
  });
  for (const auto& row : rows)
    for (const PixelSums& s : row) {
      if (s.rgb[0] <= 0 && s.rgb[1] <= 0 && s.rgb[2] <= 0) continue;
      const double len = s.moment.length();
      directions_.push_back(len > 0 ? (1.0 / len) * s.moment : Vec3{0, 0, 1});
      radiance_.push_back(s.rgb);
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
    for (int i = 0; i < 16; ++i)
      for (int j = 0; j < 16; ++j)
        points_.push_back({-2.5 + 5.0 * (i + 0.5) / 16, -2.5 + 5.0 * (j + 0.5) / 16, 0.0});
    shadow_ = truthAt(directions_, radiance_, points_.size(), [&](std::size_t i, const Vec3& d) {
      return d.z > 0 && visible(points_[i], d) ? d.z : 0.0;
    });
  }
  if (effects & kGlossy)
    for (int e = 0; e < 2; ++e)
      glossy_[e] = truthAt(directions_, radiance_, normals_.size(), [&](std::size_t i, const Vec3& d) {
        return (kGlossyExponents[e] + 1) / (2 * kPi) * lobe(dot(normals_[i], d), kGlossyExponents[e]);
      });
}

Rgb Evaluator::lightsDiffuse(const std::vector<Light>& lights, const Vec3& n) {
  Rgb s{};
  for (const Light& l : lights) {
    double w = std::max(0.0, dot(n, l.direction));
    for (int c = 0; c < 3; ++c) s[c] += l.rgb[c] * w;
  }
  return s;
}

Rgb Evaluator::lightsShadow(const std::vector<Light>& lights, const Vec3& p) {
  Rgb s{};
  for (const Light& l : lights) {
    if (l.direction.z <= 0 || !visible(p, l.direction)) continue;
    for (int c = 0; c < 3; ++c) s[c] += l.rgb[c] * l.direction.z;
  }
  return s;
}

Rgb Evaluator::lightsGlossy(const std::vector<Light>& lights, const Vec3& r, int exponent) {
  Rgb s{};
  for (const Light& l : lights) {
    double w = (exponent + 1) / (2 * kPi) * lobe(dot(r, l.direction), exponent);
    for (int c = 0; c < 3; ++c) s[c] += l.rgb[c] * w;
  }
  return s;
}

EffectErrors Evaluator::evaluate(const std::vector<Light>& lights) const {
  EffectErrors e;
  auto answer = [&](const std::vector<Vec3>& points, auto&& f) {
    std::vector<Rgb> out(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = f(points[i]);
    return out;
  };
  if (effects_ & kDiffuse)
    e.diffuse =
        relativeRms(answer(normals_, [&](const Vec3& n) { return lightsDiffuse(lights, n); }), diffuse_);
  if (effects_ & kShadow)
    e.shadow = relativeRms(answer(points_, [&](const Vec3& p) { return lightsShadow(lights, p); }), shadow_);
  if (effects_ & kGlossy) {
    // The two lobes' errors combined as one RMS over both sets of points.
    double d = 0, t = 0;
    for (int k = 0; k < 2; ++k) {
      auto got =
          answer(normals_, [&](const Vec3& r) { return lightsGlossy(lights, r, kGlossyExponents[k]); });
      double rel = relativeRms(got, glossy_[k]);
      double tt = 0;
      for (const Rgb& v : glossy_[k]) tt += luminance(v) * luminance(v);
      d += rel * rel * tt;
      t += tt;
    }
    e.glossy = t > 0 ? std::sqrt(d / t) : 0.0;
  }
  return e;
}

std::vector<double> nonNegativeLeastSquares(const std::vector<double>& A, int m, int n,
                                            const std::vector<double>& b) {
  // Lawson & Hanson (1974), chapter 23: an active-set method; P is the set of free (positive) variables. It
  // works on the normal equations G = A^T A, c = A^T b, built once: a step costs O(n^2) and a solve on P
  // O(|P|^3).
  std::vector<double> G(static_cast<std::size_t>(n) * n, 0.0), c(n, 0.0);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      const double aij = A[static_cast<std::size_t>(i) * n + j];
      if (aij == 0) continue;
      c[j] += aij * b[i];
      for (int k = 0; k <= j; ++k)
        G[static_cast<std::size_t>(j) * n + k] += aij * A[static_cast<std::size_t>(i) * n + k];
    }
  double trace = 0;
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < j; ++k)
      G[static_cast<std::size_t>(k) * n + j] = G[static_cast<std::size_t>(j) * n + k];
    trace += G[static_cast<std::size_t>(j) * n + j];
  }
  const double ridge = 1e-12 * trace / std::max(1, n);  // keeps rank-deficient sub-problems solvable
  std::vector<double> x(n, 0.0), w(n), z;
  std::vector<bool> inP(n, false);
  auto gradient = [&]() {  // w = A^T (b - A x) = c - G x
    for (int j = 0; j < n; ++j) {
      double s = c[j];
      for (int k = 0; k < n; ++k) s -= G[static_cast<std::size_t>(j) * n + k] * x[k];
      w[j] = s;
    }
  };
  auto solveP = [&]() {  // least squares on the columns in P: Cholesky of G restricted to P
    std::vector<int> cols;
    for (int j = 0; j < n; ++j)
      if (inP[j]) cols.push_back(j);
    const int k = static_cast<int>(cols.size());
    std::vector<double> L(static_cast<std::size_t>(k) * k), y(k);
    for (int a = 0; a < k; ++a) {
      for (int d = 0; d <= a; ++d) {
        double s = G[static_cast<std::size_t>(cols[a]) * n + cols[d]] + (a == d ? ridge : 0.0);
        for (int e = 0; e < d; ++e) s -= L[a * k + e] * L[d * k + e];
        L[a * k + d] = a == d ? std::sqrt(std::max(s, 1e-300)) : s / L[d * k + d];
      }
    }
    for (int a = 0; a < k; ++a) {
      double s = c[cols[a]];
      for (int e = 0; e < a; ++e) s -= L[a * k + e] * y[e];
      y[a] = s / L[a * k + a];
    }
    for (int a = k - 1; a >= 0; --a) {
      double s = y[a];
      for (int e = a + 1; e < k; ++e) s -= L[e * k + a] * y[e];
      y[a] = s / L[a * k + a];
    }
    z.assign(n, 0.0);
    for (int a = 0; a < k; ++a) z[cols[a]] = y[a];
  };
  double cmax = 0;
  for (double v : c) cmax = std::max(cmax, std::abs(v));
  const double tol = 1e-12 * std::max(cmax, 1e-300);
  for (int outer = 0; outer < 3 * n + 10; ++outer) {
    gradient();
    int best = -1;
    for (int j = 0; j < n; ++j)
      if (!inP[j] && w[j] > tol && (best < 0 || w[j] > w[best])) best = j;
    if (best < 0) break;
    inP[best] = true;
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      solveP();
      bool feasible = true;
      for (int j = 0; j < n; ++j)
        if (inP[j] && z[j] <= 0) feasible = false;
      if (feasible) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (int j = 0; j < n; ++j)
        if (inP[j] && z[j] <= 0) alpha = std::min(alpha, x[j] / (x[j] - z[j]));
      for (int j = 0; j < n; ++j) {
        x[j] += alpha * (z[j] - x[j]);
        if (inP[j] && x[j] <= 0) inP[j] = false, x[j] = 0;
      }
    }
  }
  return x;
}

namespace {

Vec3 rotateAbout(const Vec3& d, const Vec3& axis, double angle) {  // Rodrigues' rotation
  const Vec3 k = (1.0 / axis.length()) * axis;
  const Vec3 kxd{k.y * d.z - k.z * d.y, k.z * d.x - k.x * d.z, k.x * d.y - k.y * d.x};
  return std::cos(angle) * d + std::sin(angle) * kxd + (dot(k, d) * (1 - std::cos(angle))) * k;
}

// Coordinate descent on the lights' directions against the luminance irradiance on the fit normals, colours
// fixed. The sum of the lights' irradiance per normal is kept, so a trial move of one light costs one pass
// over the normals.
void moveDirections(const std::vector<Vec3>& normals, const std::vector<Rgb>& truth,
                    std::vector<Light>& lights) {
  const std::size_t m = normals.size();
  std::vector<double> target(m), sum(m, 0.0), term(m), trial(m);
  for (std::size_t i = 0; i < m; ++i) target[i] = luminance(truth[i]);
  auto contribution = [&](const Light& l, std::vector<double>& out) {
    const double y = luminance(l.rgb);
    for (std::size_t i = 0; i < m; ++i) out[i] = y * std::max(0.0, dot(normals[i], l.direction));
  };
  for (const Light& l : lights) {
    contribution(l, term);
    for (std::size_t i = 0; i < m; ++i) sum[i] += term[i];
  }
  auto error = [&](const std::vector<double>& s) {
    double e = 0;
    for (std::size_t i = 0; i < m; ++i) e += (s[i] - target[i]) * (s[i] - target[i]);
    return e;
  };
  double current = error(sum);
  for (double step : {4.0, 2.0, 1.0, 0.5})
    for (Light& l : lights) {
      const Vec3 d = l.direction;
      const Vec3 t1 = std::abs(d.z) < 0.9 ? Vec3{-d.y, d.x, 0} : Vec3{0, -d.z, d.y};
      const Vec3 t2{d.y * t1.z - d.z * t1.y, d.z * t1.x - d.x * t1.z, d.x * t1.y - d.y * t1.x};
      for (const Vec3& axis : {t1, t2})
        for (double sign : {1.0, -1.0}) {
          contribution(l, term);
          Light moved = l;
          moved.direction = rotateAbout(l.direction, axis, sign * step * kPi / 180);
          contribution(moved, trial);
          for (std::size_t i = 0; i < m; ++i) trial[i] = sum[i] - term[i] + trial[i];
          const double e = error(trial);
          if (e < current) current = e, sum.swap(trial), l.direction = moved.direction;
        }
    }
}

}  // namespace

std::vector<Light> refitIrradiance(const Evaluator& evaluator, const std::vector<Light>& lights,
                                   double* energyShift, bool moveDirs) {
  // Fitted on 1024 normals, not the 256 the error is measured on, so the error of a refit is not flattered.
  const auto& normals = evaluator.fitNormals();
  const auto& truth = evaluator.fitTruth();
  if (truth.empty()) throw Error("the irradiance refit needs an evaluator made for it (diffuse, forRefit)");
  if (lights.size() > kMaxRefitLights)
    throw Error("the irradiance refit takes at most " + std::to_string(kMaxRefitLights) + " lights, got " +
                std::to_string(lights.size()));
  const int m = static_cast<int>(normals.size()), n = static_cast<int>(lights.size());
  std::vector<Light> out = lights;
  if (n == 0) return out;
  auto solveColours = [&](std::vector<Light>& ls) {
    std::vector<double> A(static_cast<std::size_t>(m) * n);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < n; ++j) A[i * n + j] = std::max(0.0, dot(normals[i], ls[j].direction));
    for (int c = 0; c < 3; ++c) {
      std::vector<double> b(m);
      for (int i = 0; i < m; ++i) b[i] = truth[i][c];
      std::vector<double> x = nonNegativeLeastSquares(A, m, n, b);
      for (int j = 0; j < n; ++j) ls[j].rgb[c] = x[j];
    }
  };
  solveColours(out);
  for (int round = 0; moveDirs && round < 3; ++round) {
    moveDirections(normals, truth, out);
    solveColours(out);
  }
  double before = 0, after = 0;
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) before += lights[j].rgb[c], after += out[j].rgb[c];
  double total = 0;
  for (const Light& l : out) total += luminance(l.rgb);
  for (Light& l : out) l.energyShare = total > 0 ? luminance(l.rgb) / total : 0.0;
  if (energyShift) *energyShift = before > 0 ? after / before - 1.0 : 0.0;
  return out;
}

}  // namespace probelights
