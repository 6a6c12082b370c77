// runAhead (batch.h): the library's pipeline. Its order, its bounds on works at once and results waiting, a
// consume that stalls while the works go on, a stop, and a work's exception. Synchronized with condition
// variables, not with time: a bound is checked on every work; a wait is bounded only so that a broken
// pipeline fails instead of hanging.
#include "probelights/batch.h"

#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace probelights {
namespace {

// Counts the works running and finished, and lets a test wait for a number of finished works.
struct Tally {
  std::mutex mutex;
  std::condition_variable changed;
  int running = 0, mostRunning = 0, started = 0, finished = 0;

  int work(std::size_t i) {
    {
      std::lock_guard lock(mutex);
      ++started;
      mostRunning = std::max(mostRunning, ++running);
    }
    {
      std::lock_guard lock(mutex);
      --running;
      ++finished;
    }
    changed.notify_all();
    return static_cast<int>(i);
  }
  bool waitFinished(int n) {
    std::unique_lock lock(mutex);
    return changed.wait_for(lock, std::chrono::seconds(60), [&] { return finished >= n; });
  }
};

TEST(RunAhead, HandsEveryResultOnInOrder) {
  Tally tally;
  std::vector<int> seen;
  runAhead<int>(
      50, [&](std::size_t i) { return tally.work(i); }, [](int) { return 3; },
      [&](int v) {
        seen.push_back(v);
        return true;
      });
  ASSERT_EQ(seen.size(), 50u);
  for (int i = 0; i < 50; ++i) EXPECT_EQ(seen[i], i);
  EXPECT_LE(tally.mostRunning, 3);
}

TEST(RunAhead, WorksGoOnWhileConsumeStalls) {
  // ahead 2: while the first result's consume waits, the next four (2 running + 2 waiting) are worked.
  Tally tally;
  std::vector<int> seen;
  runAhead<int>(
      10, [&](std::size_t i) { return tally.work(i); }, [](int) { return 2; },
      [&](int v) {
        if (v == 0) {
          EXPECT_TRUE(tally.waitFinished(5)) << "the works stopped while consume was busy";
        }
        seen.push_back(v);
        return true;
      });
  EXPECT_EQ(seen.size(), 10u);
  EXPECT_LE(tally.mostRunning, 2);
}

TEST(RunAhead, OneAheadKeepsOneResultWaiting) {
  // ahead 1 (a large probe): the next one is worked while consume runs, and no more.
  Tally tally;
  int startedDuringFirst = 0;
  runAhead<int>(
      5, [&](std::size_t i) { return tally.work(i); }, [](int) { return 1; },
      [&](int v) {
        if (v == 0) {
          EXPECT_TRUE(tally.waitFinished(2));
          std::lock_guard lock(tally.mutex);
          startedDuringFirst = tally.started;
        }
        return true;
      });
  EXPECT_EQ(startedDuringFirst, 2);
  EXPECT_EQ(tally.mostRunning, 1);
}

TEST(RunAhead, StopsWhenConsumeSaysSo) {
  Tally tally;
  int consumed = 0;
  runAhead<int>(
      1000, [&](std::size_t i) { return tally.work(i); }, [](int) { return 2; },
      [&](int v) {
        ++consumed;
        return v < 3;
      });
  EXPECT_EQ(consumed, 4);
  // Item 3 was taken; at most 4 more were started after it (2 running + 2 waiting).
  EXPECT_LE(tally.started, 8);
}

TEST(RunAhead, AWorksExceptionIsThrownWhenItsResultIsDue) {
  std::vector<int> seen;
  EXPECT_THROW(runAhead<int>(
                   10,
                   [](std::size_t i) {
                     if (i == 2) throw std::runtime_error("work 2");
                     return static_cast<int>(i);
                   },
                   [](int) { return 2; },
                   [&](int v) {
                     seen.push_back(v);
                     return true;
                   }),
               std::runtime_error);
  EXPECT_EQ(seen, (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace probelights
