#include "probelights/bake_file.h"

#include <algorithm>
#include <thread>

#include "probelights/batch.h"
#include "probelights/grid_load.h"
#include "probelights/image_file.h"
#include "probelights/one_thread.h"
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
  const BakeOptions* grid = readsIntoGridAlone(request) ? &request.bake : nullptr;
  auto bake = [&](BakedFile& out, LoadedProbe& item) {
    try {
      Stopwatch clock;
      out.result = bakeLoaded(*item.probe, request, item.table ? &*item.table : nullptr, item.tablesMs);
      out.bakeMs = clock.ms();
    } catch (const Error& e) {
      out.error = e.what(), out.remedy = e.sharedRemedy();
    } catch (const std::exception& e) {
      out.error = e.what();
    }
  };
  // A small probe is loaded and baked on one thread, as many probes at once as there are cores: each bake on
  // its own thread gives the same bits as one spread over the pool (one_thread.h), and a 1K probe's bake is
  // too short to share (100 1K probes, 64 lights: docs/decisions.md). A large one is baked here on every
  // core while the next loads.
  struct Work {
    BakedFile out;
    std::optional<LoadedProbe> large;  // loaded, to be baked on the calling thread
  };
  const std::size_t cores = std::max(2u, std::thread::hardware_concurrency());
  runAhead<Work>(
      paths.size(),
      [&](std::size_t i) {
        Work w;
        LoadedProbe item = loadForBatch(paths[i], request.probe, grid);
        w.out.path = item.path;
        w.out.error = item.error, w.out.remedy = item.remedy;
        w.out.loadMs = item.loadMs;
        if (!item.probe) return w;
        if (item.probe->width() > kSmallProbeWidth) {
          w.large.emplace(std::move(item));
          return w;
        }
        const OnOneThread oneThread;
        bake(w.out, item);
        w.out.probe = std::move(item.probe);
        return w;
      },
      [&](const Work& w) { return w.large ? 1 : cores; },
      [&](Work& w) {
        if (w.large) {
          bake(w.out, *w.large);
          w.out.probe = std::move(w.large->probe);
          w.large.reset();
        }
        return consume(w.out);
      });
}

}  // namespace probelights
