// Many probes in one process (a whole HDRI library): the inputs expanded to files, a probe's load for a
// library, and the pipeline (runAhead) that works on the next probes on threads of their own while the caller
// takes the current one. In probelights_io (it reads files with OpenImageIO); bakeFiles (bake_file.h), under
// the CLI's `probelights bake --out-dir` and the module's bake_files(), runs on it.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "probelights/error.h"
#include "probelights/moment_table.h"
#include "probelights/placement.h"
#include "probelights/probe.h"

namespace probelights {

// Files, directories (their image files, sorted; not recursive) and glob patterns, in order, each file once.
// An input that names nothing is kept as it is, so that its load reports it.
std::vector<std::string> expandProbePaths(const std::vector<std::string>& inputs);

struct LoadedProbe {
  std::string path;
  std::optional<Probe> probe;            // empty when it could not be loaded
  std::optional<MomentTable> table;      // its working grid, when read into one (loadGrid)
  double tablesMs = 0;                   // building that grid, part of loadMs
  std::string error;                     // why, one line
  std::shared_ptr<const Remedy> remedy;  // what gets past it, when there is something (error.h: describe)
  double loadMs = 0;
};

// Loads the probe at `path` (read and validated; with `grid`, read band by band into the working grid that
// bake needs: item.table) on the calling thread alone (one_thread.h). A probe that cannot be loaded comes
// back with its error.
LoadedProbe loadForBatch(const std::string& path, const ProbeOptions& options, const BakeOptions* grid);

// A library's small probes (up to this width) are loaded and baked one per core, each on its own thread: a
// 1K bake is too short to share out, and two or three such probes in memory cost little. A larger one is
// baked on every core while the next one loads (a second 8K image in memory is not worth it).
constexpr int kSmallProbeWidth = 2048;

// Runs work(i) for i = 0, 1, ..., n - 1 on threads of their own and hands each result to consume on the
// calling thread, in order, until consume returns false (the works under way then finish and are dropped).
// At most ahead(latest result) works run at once (1 before the first result), and as many more results may
// wait for consume when ahead is above 1 (none when it is 1: a large probe's result is all memory can take):
// a consume that stalls (a write synced to a slow disk) does not leave cores idle. Its threads live as long
// as the call, so what a work keeps per thread (its buffers) is kept from one probe to the next. An exception
// from work is thrown here, from the call, when its result is due.
template <class Item, class Work, class Ahead, class Consume>
void runAhead(std::size_t n, Work work, Ahead ahead, Consume consume) {
  struct Slot {
    std::optional<Item> item;
    std::exception_ptr error;
  };
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<Slot> slots;  // results from index `taken` on, in order
  std::size_t next = 0, taken = 0, running = 0, depth = 1;
  bool stop = false;
  // Results waiting for consume (done or under way, from index `taken` on) may be depth + slack.
  auto mayStart = [&] {
    const std::size_t slack = depth > 1 ? depth : 0;
    return next < n && running < depth && next - taken < depth + slack;
  };
  auto worker = [&] {
    std::unique_lock lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return stop || next >= n || mayStart(); });
      if (stop || next >= n) return;
      const std::size_t i = next++;
      ++running;
      slots.resize(next - taken);
      lock.unlock();
      Slot done;
      try {
        done.item.emplace(work(i));
      } catch (...) {
        done.error = std::current_exception();
      }
      lock.lock();
      --running;
      if (done.item) depth = std::max<std::size_t>(1, ahead(*done.item));
      Slot& slot = slots[i - taken];
      if (done.item) slot.item.emplace(std::move(*done.item));
      slot.error = done.error;
      changed.notify_all();
    }
  };
  std::vector<std::thread> threads;
  auto finish = [&] {
    {
      std::lock_guard lock(mutex);
      stop = true;
    }
    changed.notify_all();
    for (std::thread& t : threads) t.join();
  };
  // Enough threads for what may run now (each takes the next index when it may start).
  auto spawn = [&] {
    while (threads.size() < std::min(depth, n)) threads.emplace_back(worker);
  };
  try {
    while (taken < n) {
      Slot current;
      {
        std::unique_lock lock(mutex);
        spawn();
        changed.wait(lock, [&] { return !slots.empty() && (slots.front().item || slots.front().error); });
        if (slots.front().item) current.item.emplace(std::move(*slots.front().item));
        current.error = slots.front().error;
        slots.pop_front();
        ++taken;
        spawn();
        changed.notify_all();
      }
      if (current.error) std::rethrow_exception(current.error);
      if (!consume(*current.item)) break;
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
}

}  // namespace probelights
