#include "probelights/sun_angles.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "probelights/error.h"
#include "probelights/names.h"
#include "trial_fit.h"

namespace probelights {

namespace {
constexpr NameTable<SunAngles, 3> kSunAngles{
    {{SunAngles::Fit, "fit"}, {SunAngles::Spread, "spread"}, {SunAngles::Points, "points"}}};

constexpr std::size_t kMaxFitted = 64;
constexpr double kSmallest =
    0.5 * kPi / 180;  // the spread of a one-pixel region is ~0: start from half a degree
}  // namespace

std::string toString(SunAngles angles) { return std::string(nameOf(kSunAngles, angles)); }
SunAngles parseSunAngles(const std::string& name) { return parseName(kSunAngles, "sun angles", name); }

void fitSunAngles(const Evaluator& evaluator, std::vector<Light>& lights, bool refitReceivers, int rounds) {
  if (!(evaluator.effects() & kShadow)) throw Error("fitting sun angles needs the shadow effect evaluated");
  // The fit receivers (evaluate.h): ground points under the sphere and normals, each set weighted so the
  // objective is shadow error^2 + diffuse error^2 (on points the errors are not measured on).
  const std::vector<Receiver> receivers = evaluator.fitReceivers(refitReceivers);
  // Every light within its widest angle first (the ones past the fitted ones keep their spread's angle), so
  // the fit starts from lights the evaluator may draw.
  keepSunCones(evaluator.sunCones(), lights);
  if (receivers.empty() || lights.empty()) return;

  std::vector<std::size_t> order(lights.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return luminance(lights[a].rgb) > luminance(lights[b].rgb);
  });
  // The brightest kMaxFitted lights are fitted; past them each light is a small part of the light and keeps
  // its spread's angle (a 1024-light fit would cost seconds for nothing visible).
  if (order.size() > kMaxFitted) order.resize(kMaxFitted);
  TrialFit fit(evaluator, receivers, lights, order);
  for (int round = 0; round < rounds; ++round)
    for (std::size_t i : order) {
      Light& light = lights[i];
      if (!(luminance(light.rgb) > 0)) continue;
      const double start = std::max(light.angularRadius, kSmallest);
      const double widest = evaluator.widestSunAngle(light.direction);
      // The light as it is and the candidates (trial_fit.h); the best if better than the light as it is.
      auto tryAngles = [&](const std::vector<double>& angles) {
        std::vector<Light> trials(angles.size() + 1, light);
        for (std::size_t c = 0; c < angles.size(); ++c) trials[c + 1].angle = angles[c];
        const std::vector<double> f = fit.objectives(i, trials);
        const std::size_t best = static_cast<std::size_t>(std::min_element(f.begin(), f.end()) - f.begin());
        if (best == 0 || !(f[best] < f[0])) return;
        fit.accept(i, best);
        light.angle = trials[best].angle;
      };
      std::vector<double> coarse{0.0};
      // Half-octave steps from start / 8 to start * 4 (no exp2 or pow: the add-on's module stays on glibc
      // 2.28).
      double step = start / 8;
      for (int k = -6; k <= 4; ++k, step *= std::numbers::sqrt2) coarse.push_back(std::min(widest, step));
      tryAngles(coarse);
      constexpr double kQuarterOctave = 1.189207115002721;  // 2^(1/4)
      if (light.angle > 0)
        tryAngles({light.angle / kQuarterOctave, std::min(widest, light.angle * kQuarterOctave)});
    }
}

void keepSunCones(SunCones cones, std::vector<Light>& lights) {
  if (cones != SunCones::AboveHorizon) return;
  for (Light& l : lights) l.angle = std::min(l.angle, horizonAngle(l.direction));
}

bool applySunAngles(SunAngles choice, const Evaluator* evaluator, std::vector<Light>& lights,
                    bool refitReceivers, int rounds) {
  switch (choice) {
    case SunAngles::Points:
      for (Light& l : lights) l.angle = 0;
      return false;
    case SunAngles::Spread:
      if (evaluator) keepSunCones(evaluator->sunCones(), lights);
      return false;
    case SunAngles::Fit:
      if (!evaluator || !(evaluator->effects() & kShadow)) {
        if (evaluator) keepSunCones(evaluator->sunCones(), lights);
        return false;
      }
      fitSunAngles(*evaluator, lights, refitReceivers, rounds);
      return true;
  }
  return false;
}

}  // namespace probelights
