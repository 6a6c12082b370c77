// The lights' side of the evaluator: each light's kernels as the renderer draws it (cone.h), the lights'
// answers on the evaluator's points, and their errors against the probe's truths (evaluate.cpp builds those).
#include <algorithm>
#include <cmath>

#include "probelights/evaluate.h"

namespace probelights {

namespace {

double relativeRms(const std::vector<Rgb>& got, const std::vector<Rgb>& truth) {
  double d = 0, t = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    double a = luminance(got[i]), b = luminance(truth[i]);
    d += (a - b) * (a - b);
    t += b * b;
  }
  return t > 0 ? std::sqrt(d / t) : (d > 0 ? 1.0 : 0.0);
}

}  // namespace

double Evaluator::maxSunAngle() const { return profile_ == SunProfile::Cone ? kPi : 178 * kPi / 180; }
double Evaluator::widestSunAngle(const Vec3& direction) const {
  const double widest = maxSunAngle();
  return cones_ == SunCones::AboveHorizon ? std::min(widest, horizonAngle(direction)) : widest;
}

double Evaluator::diffuseKernel(const Light& l, const Vec3& n) const {
  return l.angle > 0 ? coneIrradiance(l.direction, l.angle, n, nullptr, profile_)
                     : std::max(0.0, dot(n, l.direction));
}

double Evaluator::shadowKernel(const Light& l, const Vec3& p) const {
  if (l.angle > 0) {
    const Cap sphere = sphereCap(p, {0, 0, 1}, 1.0);
    return coneIrradiance(l.direction, l.angle, {0, 0, 1}, &sphere, profile_);
  }
  return l.direction.z > 0 && visible(p, l.direction) ? l.direction.z : 0.0;
}

double Evaluator::kernel(const Light& l, const Receiver& r) const {
  if (!(l.angle > 0)) return r.ground ? shadowKernel(l, r.at) : diffuseKernel(l, r.at);
  return coneIrradiance(makeCone(l.direction, l.angle, profile_), r.ground ? Vec3{0, 0, 1} : r.at,
                        r.ground ? &r.sphere : nullptr);
}

namespace {
// out[i] = scale * the light's kernel at receivers[at(i)], i < out.size(), its cone prepared once.
template <class At>
void kernelsAt(const Evaluator& evaluator, const Light& l, const std::vector<Receiver>& receivers, At&& at,
               double scale, std::span<double> out) {
  if (!(l.angle > 0)) {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = scale * evaluator.kernel(l, receivers[at(i)]);
    return;
  }
  const Cone cone = makeCone(l.direction, l.angle, evaluator.sunProfile());
  const Vec3 up{0, 0, 1};
  const double open = coneIrradiance(cone, up);  // a ground point the sphere hides none of the cone from
  for (std::size_t i = 0; i < out.size(); ++i) {
    const Receiver& r = receivers[at(i)];
    out[i] = scale * (!r.ground                  ? coneIrradiance(cone, r.at)
                      : overlaps(cone, r.sphere) ? coneIrradiance(cone, up, &r.sphere)
                                                 : open);
  }
}
}  // namespace

void Evaluator::kernels(const Light& l, const std::vector<Receiver>& receivers, double scale,
                        std::vector<double>& out) const {
  out.resize(receivers.size());
  kernelsAt(
      *this, l, receivers, [](std::size_t i) { return i; }, scale, out);
}

void Evaluator::kernels(const Light& l, const std::vector<Receiver>& receivers, std::span<const int> which,
                        double scale, std::span<double> out) const {
  kernelsAt(
      *this, l, receivers, [&](std::size_t i) { return static_cast<std::size_t>(which[i]); }, scale, out);
}

double Evaluator::fitError(const std::vector<Receiver>& receivers, const std::vector<Light>& lights) const {
  std::vector<double> y(receivers.size(), 0.0), term;
  for (const Light& l : lights) {
    kernels(l, receivers, luminance(l.rgb), term);
    for (std::size_t k = 0; k < y.size(); ++k) y[k] += term[k];
  }
  double e = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    const double d = y[k] - luminance(receivers[k].truth);
    e += receivers[k].weight * d * d;
  }
  return e;
}

double Evaluator::glossyKernel(const Light& l, const Vec3& r, int exponent) const {
  return coneGlossy(l.direction, l.angle, r, exponent, profile_);  // angle 0: the point light's lobe
}

namespace {
template <class Kernel>
Rgb sumOver(const std::vector<Light>& lights, Kernel&& kernel) {
  Rgb s{};
  for (const Light& l : lights) {
    const double w = kernel(l);
    if (w > 0)
      for (int c = 0; c < 3; ++c) s[c] += l.rgb[c] * w;
  }
  return s;
}
}  // namespace

Rgb Evaluator::lightsDiffuse(const std::vector<Light>& lights, const Vec3& n) const {
  return sumOver(lights, [&](const Light& l) { return diffuseKernel(l, n); });
}

Rgb Evaluator::lightsShadow(const std::vector<Light>& lights, const Vec3& p) const {
  return sumOver(lights, [&](const Light& l) { return shadowKernel(l, p); });
}

Rgb Evaluator::lightsGlossy(const std::vector<Light>& lights, const Vec3& r, int exponent) const {
  return sumOver(lights, [&](const Light& l) { return glossyKernel(l, r, exponent); });
}

EffectErrors Evaluator::truthNorms() const {
  auto norm = [](std::initializer_list<const std::vector<Rgb>*> sets) {
    double t = 0;
    for (const auto* set : sets)
      for (const Rgb& v : *set) t += luminance(v) * luminance(v);
    return std::sqrt(t);
  };
  EffectErrors n;
  if (effects_ & kDiffuse) n.diffuse = norm({&diffuse_});
  if (effects_ & kShadow) n.shadow = norm({&shadow_});
  if (effects_ & kGlossy) n.glossy = norm({&glossy_[0], &glossy_[1]});
  return n;
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
  if (effects_ & kShadow) {
    // Each light's cone prepared once, each point's cap once.
    std::vector<Rgb> got(points_.size(), Rgb{});
    for (const Light& l : lights) {
      const bool cone = l.angle > 0;
      const Cone c = cone ? makeCone(l.direction, l.angle, profile_) : Cone{};
      for (std::size_t i = 0; i < points_.size(); ++i) {
        const double w = cone ? coneIrradiance(c, {0, 0, 1}, &pointCaps_[i]) : shadowKernel(l, points_[i]);
        if (w > 0)
          for (int k = 0; k < 3; ++k) got[i][k] += l.rgb[k] * w;
      }
    }
    e.shadow = relativeRms(got, shadow_);
  }
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

}  // namespace probelights
