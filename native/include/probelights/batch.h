// Many probes in one process (a whole HDRI library): the inputs expanded to files, and a pipeline that loads
// the next probe on a second thread while the caller bakes the current one. In probelights_io (it reads files
// with OpenImageIO); the CLI's `probelights bake --out-dir` and the module's bake_files() run on it.
#pragma once

#include <functional>
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

// Calls consume(item) for each path in order, until it returns false; while it runs, the next probe is being
// loaded (read and validated) on another thread, so a library bakes in about max(load, bake) per probe
// rather than the sum.
// A probe that fails to load arrives with its error; the others go on. With `grid`, each probe is read band
// by band into the working grid that bake needs (loadGrid: item.table), for bakes that need nothing else.
void forEachProbe(const std::vector<std::string>& paths, const ProbeOptions& options,
                  const std::function<bool(LoadedProbe&)>& consume, const BakeOptions* grid = nullptr);

}  // namespace probelights
