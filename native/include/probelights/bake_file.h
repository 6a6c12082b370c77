// Bakes from files, as a request asks (request.h): the one entry that decides how a file is read (band by
// band into the working grid when the bake needs nothing else, else whole) and what runs on it. The CLI's
// bake and library commands and the module's bake_file and bake_files call it. In probelights_io (it reads
// files with OpenImageIO).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "probelights/error.h"
#include "probelights/request.h"

namespace probelights {

struct BakedFile {
  std::string path;
  std::optional<Probe> probe;            // as read (read into the grid alone: without its pixels)
  std::optional<EvaluatedBake> result;   // empty when the probe could not be read or baked
  std::string error;                     // why, one line
  std::shared_ptr<const Remedy> remedy;  // what gets past it, when there is something (error.h: describe)
  double loadMs = 0, bakeMs = 0;
};

// Reads the probe at `path` and bakes it. Throws Error for a probe that cannot be read or baked.
BakedFile bakeFile(const std::string& path, const BakeRequest& request);

// Bakes each of `paths` (expandProbePaths' files) and calls consume with each in turn (its result or its
// error: the others go on), until consume returns false. While consume runs, the next probes are loaded and
// baked (runAhead: small probes one per core, each on its own thread; a large one on every core, here, while
// the next loads).
void bakeFiles(const std::vector<std::string>& paths, const BakeRequest& request,
               const std::function<bool(BakedFile&)>& consume);

}  // namespace probelights
