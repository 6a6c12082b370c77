// The fits' trial step (native/src/trial_fit.h): each trial's objective from the closed forms' moments and
// the kernels where its reach needs them equals the plain sum over every receiver, and accepting a trial
// leaves the same sum as computing the lights' answers afresh.
#include "../../native/src/trial_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "probelights/placement.h"
#include "test_probes.h"

namespace probelights {
namespace {

// The plain objective over every receiver, light j replaced by `trial`.
double bruteForce(const Evaluator& ev, const std::vector<Receiver>& receivers, std::vector<Light> lights,
                  std::size_t j, const Light& trial) {
  lights[j] = trial;
  return ev.fitError(receivers, lights);
}

Vec3 rotated(const Vec3& d, double degrees, std::mt19937& rng) {
  std::normal_distribution<double> g;
  Vec3 axis{g(rng), g(rng), g(rng)};
  axis = axis - dot(axis, d) * d;
  axis = (1.0 / axis.length()) * axis;
  const double a = degrees * kPi / 180;
  return std::cos(a) * d + std::sin(a) * axis;
}

void expectObjectivesMatch(SunProfile profile) {
  auto t = testing::makeProbe(256, 128, ProjectionKind::LatLong, [](int x, int y) {
    const bool sun = std::abs(x - 90) < 3 && std::abs(y - 40) < 3;
    return Rgb{sun ? 4000.0 : 0.4 + 0.2 * (y > 64), sun ? 3800.0 : 0.5, sun ? 3000.0 : 0.9 - 0.5 * (y > 64)};
  });
  EvaluatorOptions options{256, true, profile};
  const Evaluator ev(t.probe, kDiffuse | kShadow, options);
  const std::vector<Receiver> receivers = ev.fitReceivers(true);
  BakeOptions o;
  o.lights = 8;
  std::vector<Light> lights = bake(t.probe, o).lights;
  lights[3].angle = 0;  // a point light among suns
  std::vector<std::size_t> fitted{0, 1, 2, 3, 4, 5, 6, 7};
  TrialFit fit(ev, receivers, lights, fitted);
  std::mt19937 rng(7);
  for (std::size_t j : fitted) {
    // The light as it is, other angles (0, narrow, past 90 and 180 degrees), moves, moves with angles.
    std::vector<Light> trials(7, lights[j]);
    trials[1].angle = 0;
    trials[2].angle = 2 * kPi / 180;
    trials[3].angle = 100 * kPi / 180;
    trials[4].angle = (profile == SunProfile::Cone ? 180 : 178) * kPi / 180;
    trials[5].direction = rotated(lights[j].direction, 3, rng);
    trials[6].direction = rotated(lights[j].direction, 40, rng), trials[6].angle = 25 * kPi / 180;
    const std::vector<double> f = fit.objectives(j, trials);
    for (std::size_t c = 0; c < trials.size(); ++c) {
      const double want = bruteForce(ev, receivers, lights, j, trials[c]);
      EXPECT_NEAR(f[c], want, 1e-11 * want) << "light " << j << ", trial " << c;
    }
    // Accepting a trial: the next objectives start from the lights' answers with it.
    const std::size_t taken = 5 + j % 2;
    fit.accept(j, taken);
    lights[j] = trials[taken];
    const std::vector<double> again = fit.objectives(j, {lights[j]});
    const double want = bruteForce(ev, receivers, lights, j, lights[j]);
    EXPECT_NEAR(again[0], want, 1e-11 * want);
  }
}

TEST(TrialFit, ObjectivesEqualTheSumOverEveryReceiver) { expectObjectivesMatch(SunProfile::Cone); }

TEST(TrialFit, ObjectivesEqualTheSumOverEveryReceiverForBlenderThreesDisc) {
  expectObjectivesMatch(SunProfile::TangentDisc);
}

}  // namespace
}  // namespace probelights
