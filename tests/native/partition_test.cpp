// partitionSphere with the papers' cut rules: median cut's equal-energy regions (Debevec 2005) and where
// median cut and variance minimization (Viriyothai & Debevec 2009) make their first cut.
#include <gtest/gtest.h>

#include <algorithm>

#include "probelights/placement.h"
#include "test_probes.h"

namespace probelights {
namespace {

using testing::bakeWith;
using testing::makeProbe;
using testing::uniformProbe;

const WorkingResolution kFull{WorkingResolution::Mode::Full, 0};

TEST(MedianCut, PowerOfTwoGivesEqualEnergyRegionsOnAUniformProbe) {
  auto t = uniformProbe(1024, 512, ProjectionKind::LatLong, {1, 1, 1});
  for (int n : {2, 4, 16, 64}) {
    auto r = bakeWith(t.probe, Method::MedianCut, n, kFull, /*horizon=*/false);  // the paper's algorithm
    ASSERT_EQ(static_cast<int>(r.lights.size()), n);
    for (const Light& l : r.lights) EXPECT_NEAR(l.energyShare * n, 1.0, 0.03) << n << " lights";
  }
}

// Viriyothai & Debevec 2009, Figure 2: two unequal sources side by side. Median cut's equal-energy cut passes
// through the brighter one; variance minimization cuts between them.
TEST(PartitionSphere, MedianCutSplitsTheBrighterSourceVarianceSeparatesThem) {
  const int W = 512, H = 256, ax = 150, bx = 360, cy = 128, radius = 12;
  auto inDisc = [&](int x, int y, int cx) {
    return (x - cx) * (x - cx) + (y - cy) * (y - cy) <= radius * radius;
  };
  auto t = makeProbe(W, H, ProjectionKind::LatLong, [&](int x, int y) {
    if (inDisc(x, y, ax)) return Rgb{10, 10, 10};
    if (inDisc(x, y, bx)) return Rgb{4, 4, 4};
    return Rgb{0, 0, 0};
  });
  auto mc = bakeWith(t.probe, Method::MedianCut, 2, kFull, /*horizon=*/false);
  ASSERT_FALSE(mc.cuts.empty());
  EXPECT_EQ(mc.cuts[0].axis, Axis::X);
  EXPECT_GT(mc.cuts[0].position, ax - radius);
  EXPECT_LE(mc.cuts[0].position, ax + radius);

  auto vm = bakeWith(t.probe, Method::Variance, 2, kFull, /*horizon=*/false);
  ASSERT_FALSE(vm.cuts.empty());
  EXPECT_EQ(vm.cuts[0].axis, Axis::X);
  EXPECT_GT(vm.cuts[0].position, ax + radius);
  EXPECT_LE(vm.cuts[0].position, bx - radius);
  // So with two lights variance minimization puts one on each source.
  ASSERT_EQ(vm.lights.size(), 2u);
  auto uv0 = t.probe.projection().imagePosition(vm.lights[0].direction);
  auto uv1 = t.probe.projection().imagePosition(vm.lights[1].direction);
  EXPECT_NEAR(std::min(uv0[0], uv1[0]) * W, ax + 0.5, 1.0);
  EXPECT_NEAR(std::max(uv0[0], uv1[0]) * W, bx + 0.5, 1.0);
}

}  // namespace
}  // namespace probelights
