// The portable build's thread pool (thread_pool.h, behind parallel.h in the Blender add-on's module): every
// item runs once, loops inside loops and loops from two threads at once run too (on the caller), and the
// results are the same as one by one.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "../../native/src/parallel.h"

namespace probelights {
namespace {

TEST(ThreadPool, RunsEveryItemOnce) {
  for (int n : {0, 1, 2, 3, 4, 7, 1000}) {
    for (int round = 0; round < 200; ++round) {  // back to back, as the refit's loops come
      std::vector<std::atomic<int>> runs(n);
      parallelFor(n, [&](std::int64_t i) { runs[i].fetch_add(1); });
      for (int i = 0; i < n; ++i) ASSERT_EQ(runs[i].load(), 1) << "n " << n << " item " << i;
    }
  }
}

TEST(ThreadPool, LoopsInsideLoopsAndFromTwoThreads) {
  std::atomic<long> sum{0};
  parallelFor(8, [&](std::int64_t i) { parallelFor(8, [&](std::int64_t j) { sum += i * 8 + j; }); });
  EXPECT_EQ(sum.load(), 63 * 64 / 2);
  std::vector<long> results(2, 0);
  std::vector<std::thread> callers;
  for (int t = 0; t < 2; ++t)
    callers.emplace_back([&, t] {
      for (int round = 0; round < 300; ++round) {
        std::vector<long> part(64);
        parallelFor(64, [&](std::int64_t i) { part[i] = i * (t + 1); });
        for (long v : part) results[t] += v;
      }
    });
  for (auto& c : callers) c.join();
  EXPECT_EQ(results[0], 300L * 63 * 64 / 2);
  EXPECT_EQ(results[1], 2 * 300L * 63 * 64 / 2);
}

}  // namespace
}  // namespace probelights
