// What `probelights bake` takes (bake_command.cpp parses it): one probe, or with --out-dir a library of them
// (library_bake.cpp).
#pragma once

#include <string>
#include <vector>

#include "probelights/accuracy.h"
#include "probelights/probe.h"

namespace probelights::cli {

struct BakeArgs {
  std::string probe, output, preview;  // one probe
  std::vector<std::string> probes;     // a library: files, directories, globs
  std::string outDir;
  bool previews = false;
  ProbeOptions probeOptions;
  BakeOptions bake;
  AccuracyOptions accuracy;
  bool quiet = false;
};

// Whether the bake needs nothing of the probe but its working grid (bakesOnGridAlone, and no preview): then
// the probe is read band by band straight into the grid (grid_load.h) and never held whole.
bool bakesFromGridAlone(const BakeArgs& a);

// Bakes every probe into a.outDir: <name>.json (and <name>.png) each, and summary.json. Returns 0 when all
// were baked, 3 when some failed (each said on one line; the others are baked).
int bakeLibrary(const BakeArgs& a);

}  // namespace probelights::cli
