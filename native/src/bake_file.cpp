#include "probelights/bake_file.h"

#include "probelights/batch.h"
#include "probelights/grid_load.h"
#include "probelights/image_file.h"
#include "probelights/stopwatch.h"

namespace probelights {

BakedFile bakeFile(const std::string& path, const BakeRequest& request) {
  BakedFile out;
  out.path = path;
  Stopwatch load;
  std::optional<GridProbe> grid;
  if (readsIntoGridAlone(request)) {
    // Read band by band straight into the working grid: the image is never held whole.
    grid.emplace(loadGrid(path, request.probe, request.bake));
    out.probe.emplace(std::move(grid->probe));
  } else {
    out.probe.emplace(loadProbe(path, request.probe));
  }
  out.loadMs = load.ms();
  Stopwatch bake;
  out.result = bakeLoaded(*out.probe, request, grid ? &grid->table : nullptr, grid ? grid->tablesMs : 0);
  out.bakeMs = bake.ms();
  return out;
}

void bakeFiles(const std::vector<std::string>& paths, const BakeRequest& request,
               const std::function<bool(BakedFile&)>& consume) {
  auto bakeOne = [&](LoadedProbe& item) {
    BakedFile out;
    out.path = item.path;
    out.error = item.error;
    out.loadMs = item.loadMs;
    if (item.probe) {
      try {
        Stopwatch bake;
        out.result = bakeLoaded(*item.probe, request, item.table ? &*item.table : nullptr, item.tablesMs);
        out.bakeMs = bake.ms();
      } catch (const std::exception& e) {
        out.error = e.what();
      }
      out.probe = std::move(item.probe);
    }
    return consume(out);
  };
  forEachProbe(paths, request.probe, bakeOne, readsIntoGridAlone(request) ? &request.bake : nullptr);
}

}  // namespace probelights
