// What `probelights bake` takes (bake_command.cpp parses it): one probe, or with --out-dir a library of them
// (library_bake.cpp).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "probelights/light_export.h"
#include "probelights/request.h"

namespace probelights::cli {

struct BakeArgs {
  std::string probe, output, preview, residual;                  // one probe
  std::vector<std::pair<const Exporter*, std::string>> exports;  // --gltf FILE, --usd FILE, ... (exporters())
  ExportOptions exportAs;                                        // how they write the lights
  std::string dome = "none";                                     // --usd-dome none|reflections|residual
  std::vector<std::string> probes;                               // a library: files, directories, globs
  std::string outDir;
  bool previews = false;
  BakeRequest request;  // the bake (request.h); keepPixels when a preview is asked for
  bool quiet = false;
};

// The bake options' lines of the usage text, from request.h's table (names, values, defaults, help), and the
// export options' from light_export.h's (exporters(), lightKinds()).
std::string bakeOptionsUsage();
std::string exportOptionsUsage();

// Bakes every probe into a.outDir: <name>.json (and <name>.png) each, and summary.json. Returns 0 when all
// were baked, 3 when some failed (each said on one line; the others are baked).
int bakeLibrary(const BakeArgs& a);

}  // namespace probelights::cli
