// Many probes in one process (a whole HDRI library): the inputs expanded to files, a probe's load for a
// library, and the pipeline (runAhead) that works on the next probes on threads of their own while the caller
// takes the current one. In probelights_io (it reads files with OpenImageIO); bakeFiles (bake_file.h), under
// the CLI's `probelights bake --out-dir` and the module's bake_files(), runs on it.
#pragma once

#include <algorithm>
#include <deque>
#include <functional>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "probelights/moment_table.h"
#include "probelights/placement.h"
#include "probelights/probe.h"

namespace probelights {

// Files, directories (their image files, sorted; not recursive) and glob patterns, in order, each file once.
// An input that names nothing is kept as it is, so that its load reports it.
std::vector<std::string> expandProbePaths(const std::vector<std::string>& inputs);

struct LoadedProbe {
  std::string path;
  std::optional<Probe> probe;        // empty when it could not be loaded
  std::optional<MomentTable> table;  // its working grid, when read into one (loadGrid)
  double tablesMs = 0;               // building that grid, part of loadMs
  std::string error;                 // why, one line
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

// Runs work(i) for i = 0, 1, ..., n - 1 on threads of their own, at most ahead(latest result) of them under
// way at once, and hands each result to consume on the calling thread, in order, until consume returns false
// (the works under way then finish and are dropped).
template <class Item, class Work, class Ahead, class Consume>
void runAhead(std::size_t n, Work work, Ahead ahead, Consume consume) {
  std::deque<std::future<Item>> running;
  std::size_t next = 0;
  auto launch = [&] { running.push_back(std::async(std::launch::async, work, next++)); };
  if (n > 0) launch();
  while (!running.empty()) {
    Item current = running.front().get();
    running.pop_front();
    const std::size_t depth = std::max<std::size_t>(1, ahead(current));
    while (running.size() < depth && next < n) launch();
    if (!consume(current)) break;
  }
}

}  // namespace probelights
