// The count chosen for an error tolerance.
#include <gtest/gtest.h>

#include <cmath>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/image_file.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(AutoCount, FindsTheSmallestCountThatMeetsTheTolerance) {
  Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  Evaluator ev(probe, kDiffuse);
  auto r = autoCount(probe, ev, BakeOptions{}, 0.02);
  ASSERT_TRUE(r.met);
  EXPECT_LE(r.errors.diffuse, 0.02);
  EXPECT_EQ(static_cast<int>(r.bake.lights.size()), r.lights);
  BakeOptions fewer;
  fewer.lights = r.lights - 1;
  EXPECT_GT(ev.evaluate(bake(probe, fewer).lights).diffuse, 0.02);  // one light fewer misses it
  auto never = autoCount(probe, ev, BakeOptions{}, 1e-9, {}, 8);
  EXPECT_FALSE(never.met);
}

TEST(AutoCount, AMissKeepsTheCountWithTheLowestError) {
  // Shadows of many narrow lights can be worse than of a few: when the tolerance is missed, the result is the
  // count with the lowest error tried, never a larger count that did worse.
  Probe probe = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
  Evaluator ev(probe, kDiffuse | kShadow, {256, false});
  auto r = autoCount(probe, ev, BakeOptions{}, 1e-9, {}, 1024);
  ASSERT_FALSE(r.met);
  double lowest = 1e300;
  int at = 0;
  for (auto [n, e] : r.tried)
    if (e < lowest) lowest = e, at = n;
  EXPECT_EQ(r.lights, at);
  EXPECT_DOUBLE_EQ(r.errors.worst(kDiffuse | kShadow), lowest);
  EXPECT_EQ(static_cast<int>(r.bake.lights.size()), r.lights);
  for (auto [n, e] : r.tried) EXPECT_TRUE(n < r.lights || e >= lowest);
  EXPECT_LE(r.tried.back().first, 4 * r.lights);  // stopped two doublings past the best
}

}  // namespace
}  // namespace probelights
