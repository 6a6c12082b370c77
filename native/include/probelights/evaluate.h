// Simulating only the effects a scene calls for: each effect's ground truth computed from the full probe, and
// the lights' answer in closed form, at a fixed set of sample points; no general renderer.
//   diffuse: irradiance E(n) = sum over the probe of L max(0, n.w) dw on 256 well-spread normals
//            (Fibonacci sphere);
//   shadow:  irradiance on a ground plane (z = 0, normal +Z) at 16 x 16 points of [-2.5, 2.5]^2 under a
//            sphere of radius 1 resting on it at the origin, visibility by analytic ray-sphere tests;
//   glossy:  a normalized Phong lobe (n + 1) / (2 pi) max(0, r.w)^n, n = 8 and 64, around 256 directions r.
// Error of an effect = relative RMS of luminance over its points: rms(lights - truth) / rms(truth).
// Lights are drawn as the renderer draws them (cone.h): a light of angle 0 is a point direction contributing
// rgb x kernel(direction); a sun of angle 2a is a cone of uniform radiance, its kernels integrated over the
// cone (shadow: the part of the cone the sphere hides, exactly). The probe is used pixel by pixel up to 2048
// pixels wide (EvaluatorOptions::maxWidth); wider probes are grouped into cells of whole pixels with exact
// rgb sums at their energy centroid (at 2048 a cell is at most 0.18 degrees across: nothing the smooth
// kernels resolve; the add-on's quick estimate uses 512).
#pragma once

#include <limits>
#include <span>
#include <string>
#include <vector>

#include "probelights/cone.h"
#include "probelights/lights.h"
#include "probelights/moment_table.h"
#include "probelights/probe.h"

namespace probelights {

enum Effect : unsigned { kDiffuse = 1, kShadow = 2, kGlossy = 4 };

// A set of effects: `effects & kShadow` asks whether it holds one; kDiffuse | kShadow makes one.
class Effects {
 public:
  constexpr Effects() = default;
  constexpr Effects(Effect e) : bits_(e) {}  // NOLINT: an effect is a set of one
  constexpr bool operator&(Effect e) const { return (bits_ & e) != 0; }
  constexpr Effects operator|(Effects o) const { return Effects(bits_ | o.bits_); }
  constexpr Effects& operator|=(Effects o) { return bits_ |= o.bits_, *this; }
  constexpr bool operator==(const Effects&) const = default;
  constexpr bool empty() const { return bits_ == 0; }

 private:
  constexpr explicit Effects(unsigned bits) : bits_(bits) {}
  unsigned bits_ = 0;
};
constexpr Effects operator|(Effect a, Effect b) { return Effects(a) | Effects(b); }

Effects parseEffects(const std::string& list);  // "diffuse,shadow,glossy"; throws Error
std::string effectsToString(Effects effects);

struct EffectErrors {
  double diffuse = std::numeric_limits<double>::quiet_NaN();
  double shadow = std::numeric_limits<double>::quiet_NaN();
  double glossy = std::numeric_limits<double>::quiet_NaN();
  double worst(Effects effects) const;
};

// A receiver the lights are fitted on (refit.h, sun_angles.h): a normal (diffuse) or a ground point under the
// sphere (shadow), the probe's answer there, and its set's weight: 1 / the set's sum of squared luminance
// truth, so a set's weighted squared residuals are its relative error^2.
struct Receiver {
  Vec3 at;
  bool ground = false;
  Rgb truth{};
  double weight = 0;
  Cap sphere;  // ground points: the cap the sphere hides
};

struct EvaluatorOptions {
  int maxWidth =
      2048;  // probe samples: pixels up to this width, cells of whole pixels beyond (exact rgb sums)
  bool forRefit = false;                     // also the fit normals the irradiance refit needs
  SunProfile sunProfile = SunProfile::Cone;  // how the renderer spreads a sun's light over its angle (cone.h)
  SunCones sunCones = SunCones::Free;        // how wide a fitted cone may be (cone.h)
  int fitNormals = 1024;                     // with forRefit, how many (a Fibonacci sphere)
};

class Evaluator {
 public:
  Evaluator(const Probe& probe, Effects effects, EvaluatorOptions options = {});
  // The same with the probe's samples summed from the cells of its working grid when they tile the samples'
  // cells (a coarse grid whose cell size divides theirs: at 8K, cells of 4 px for samples of 16), instead of
  // another pass over the pixels; else from the pixels. The samples' sums are the same up to rounding.
  Evaluator(const Probe& probe, const MomentTable& grid, Effects effects, EvaluatorOptions options = {});

  Effects effects() const { return effects_; }
  EffectErrors evaluate(const std::vector<Light>& lights) const;
  // Per effect, the root of the sum of squares of the truth's luminance over its points (the errors'
  // denominators): the errors of lamps against a part of the probe, times this part's over the whole
  // probe's, are their errors against the whole (sources.h).
  EffectErrors truthNorms() const;

  // The sample points and the truth there (exposed for tests and the irradiance refit).
  const std::vector<Vec3>& normals() const { return normals_; }
  const std::vector<Rgb>& diffuseTruth() const { return diffuse_; }
  const std::vector<Vec3>& groundPoints() const { return points_; }
  const std::vector<Rgb>& shadowTruth() const { return shadow_; }
  // A denser, different set of normals the irradiance refit is fitted on (so it is judged on points it did
  // not see).
  const std::vector<Vec3>& fitNormals() const { return fitNormals_; }
  const std::vector<Rgb>& fitTruth() const { return fitTruth_; }
  // With shadows: 400 ground points the fits use, a 20 x 20 grid over the same square (none on the 16 x 16).
  const std::vector<Vec3>& fitGroundPoints() const { return fitPoints_; }
  const std::vector<Rgb>& fitShadowTruth() const { return fitShadow_; }
  // With shadows and forRefit: 1024 ground points, a 32 x 32 grid over the same square, for fits with the
  // refit (none on the 16 x 16 either).
  const std::vector<Vec3>& refitGroundPoints() const { return refitPoints_; }
  // The receivers a fit uses: the fit normals (or, without them, the 256 normals: their only use then is to
  // keep an angle fit from trading shading for shadow) and, with shadows, the fit ground points; `refit`: the
  // refit's 32 x 32 ground points instead of the 20 x 20 (when the evaluator has them). The refit solves for
  // three colours a light, so it fits on 1024 points: on 400 it overfit them (its estimated shadow error
  // doubled on some probes), while the angle fit alone, one number a light, keeps the 400
  // (docs/results/shadows.md).
  std::vector<Receiver> fitReceivers(bool refit = false) const;
  double kernel(const Light& light, const Receiver& r) const;
  // The fits' objective: the weighted squared residual of the lights' luminance on the receivers (each set's
  // relative error^2), summed over every receiver (trial_fit.h computes the same for trials, faster).
  double fitError(const std::vector<Receiver>& receivers, const std::vector<Light>& lights) const;
  // The directions of the probe's `count` brightest samples (by luminance), brightest first: where a light
  // the refit places anew may go (refit.cpp).
  std::vector<Vec3> brightestDirections(std::size_t count) const;
  // The light's kernel at every receiver, times `scale` (its cone prepared once).
  void kernels(const Light& light, const std::vector<Receiver>& receivers, double scale,
               std::vector<double>& out) const;
  // The same at receivers[which[i]] only, into out[i] (out as long as which).
  void kernels(const Light& light, const std::vector<Receiver>& receivers, std::span<const int> which,
               double scale, std::span<double> out) const;

  // The lights' answers: closed form for points, over each light's cone for suns with an angle (cone.h, in
  // the options' sun profile).
  Rgb lightsDiffuse(const std::vector<Light>& lights, const Vec3& n) const;
  Rgb lightsShadow(const std::vector<Light>& lights, const Vec3& p) const;
  Rgb lightsGlossy(const std::vector<Light>& lights, const Vec3& r, int exponent) const;
  // One light's kernels: what a unit rgb gives a surface of normal n (diffuse), the ground point p under the
  // sphere (shadow), a Phong lobe around r.
  double diffuseKernel(const Light& light, const Vec3& n) const;
  double shadowKernel(const Light& light, const Vec3& p) const;
  double glossyKernel(const Light& light, const Vec3& r, int exponent) const;
  SunProfile sunProfile() const { return profile_; }
  SunCones sunCones() const { return cones_; }
  double maxSunAngle() const;  // the widest angle the profile draws: pi for a cone, 178 degrees for a disc
  // The widest angle a sun towards `direction` may take: maxSunAngle(), and with SunCones::AboveHorizon no
  // wider than horizonAngle(direction).
  double widestSunAngle(const Vec3& direction) const;
  // Visibility of direction d from ground point p past the unit sphere at (0, 0, 1).
  static bool visible(const Vec3& p, const Vec3& d);

  static constexpr int kGlossyExponents[2] = {8, 64};

 private:
  Evaluator(const Probe& probe, const MomentTable* grid, Effects effects, EvaluatorOptions options);

  Effects effects_;
  SunProfile profile_ = SunProfile::Cone;
  SunCones cones_ = SunCones::Free;
  std::vector<Vec3> directions_;  // probe samples: unit directions
  std::vector<Rgb> radiance_;     // and their L dOmega

  std::vector<Vec3> normals_, points_, fitNormals_, fitPoints_, refitPoints_;
  std::vector<Cap> pointCaps_;  // the sphere's cap from each ground point
  std::vector<Rgb> diffuse_, shadow_, fitTruth_, fitShadow_, refitShadow_;
  std::vector<Rgb> glossy_[2];
};

}  // namespace probelights
