// Kept table buffers (memory.h): a table's buffer serves the next table that fits, and bakes on reused
// buffers give the same lights.
#include "probelights/memory.h"

#include <gtest/gtest.h>

#include <vector>

#include "probelights/placement.h"
#include "test_probes.h"

namespace probelights {
namespace {

TEST(KeptBuffers, AFreedBufferServesTheNextArrayThatFitsAndReleaseGivesThemBack) {
  releaseKeptBuffers();
  const double* first = nullptr;
  {
    KeptArray<double> a = keptArray<double>(1000);
    first = a.get();
  }
  {
    KeptArray<double> b = keptArray<double>(900);  // fits, and is at least half of it: the same memory
    EXPECT_EQ(b.get(), first);
  }
  {
    KeptArray<double> small = keptArray<double>(100);  // under half: a new buffer (the kept one stays kept)
    EXPECT_NE(small.get(), first);
  }
  releaseKeptBuffers();
  KeptArray<double> big = keptArray<double>(1 << 20);
  big[(1 << 20) - 1] = 1.0;  // usable to its end
  EXPECT_EQ(big[(1 << 20) - 1], 1.0);
}

TEST(KeptBuffers, FourSmallBuffersAreKeptButAtMostThreeBigOnes) {
  releaseKeptBuffers();
  constexpr std::size_t kSmall = std::size_t{6} << 20, kBig = std::size_t{40} << 20;
  {
    // A library of small probes: three in flight, each an image and a table.
    std::vector<KeptArray<char>> inFlight;
    for (int i = 0; i < 4; ++i) inFlight.push_back(keptArray<char>(kSmall));
  }
  EXPECT_EQ(keptBytes(), 4 * kSmall);
  {
    std::vector<KeptArray<char>> again;
    for (int i = 0; i < 4; ++i) again.push_back(keptArray<char>(kSmall));
    EXPECT_EQ(keptBytes(), 0u);  // all four served from the kept ones
  }
  releaseKeptBuffers();
  {
    // A click at 8K: a table, cell sums and energy^2 sums, all big (and a fourth big one too many).
    std::vector<KeptArray<char>> big;
    for (int i = 0; i < 4; ++i) big.push_back(keptArray<char>(kBig));
    big.push_back(keptArray<char>(kSmall));
  }
  EXPECT_EQ(keptBytes(), 3 * kBig + kSmall);
  {
    std::vector<KeptArray<char>> again;
    for (int i = 0; i < 3; ++i) again.push_back(keptArray<char>(kBig));
    EXPECT_EQ(keptBytes(), kSmall);  // the next click takes the three big ones kept
  }
  releaseKeptBuffers();
  EXPECT_EQ(keptBytes(), 0u);
}

TEST(KeptBuffers, BakesOnReusedBuffersGiveTheSameLights) {
  auto t = testing::makeProbe(256, 128, ProjectionKind::LatLong, [](int x, int y) {
    return Rgb{0.1 + (x * 7 % 11), 0.2 + (y % 5), std::abs(x - 80) < 2 && std::abs(y - 30) < 2 ? 900.0 : 1.0};
  });
  releaseKeptBuffers();
  for (WorkingResolution res : {WorkingResolution{WorkingResolution::Mode::Full, 0},
                                WorkingResolution{WorkingResolution::Mode::Width, 64}}) {
    BakeOptions o;
    o.lights = 20;
    o.resolution = res;
    const BakeResult fresh = bake(t.probe, o);
    for (int i = 0; i < 3; ++i) {  // the tables now come from the buffers the last bake gave back
      const BakeResult again = bake(t.probe, o);
      ASSERT_EQ(again.lights.size(), fresh.lights.size());
      for (std::size_t k = 0; k < fresh.lights.size(); ++k) {
        EXPECT_EQ(again.lights[k].rgb, fresh.lights[k].rgb);
        EXPECT_EQ(again.lights[k].direction.x, fresh.lights[k].direction.x);
        EXPECT_EQ(again.lights[k].rect, fresh.lights[k].rect);
      }
    }
  }
  releaseKeptBuffers();
}

}  // namespace
}  // namespace probelights
