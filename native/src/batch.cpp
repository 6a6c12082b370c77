#include "probelights/batch.h"

#include <glob.h>

#include <algorithm>
#include <deque>
#include <filesystem>
#include <future>
#include <set>

#include "probelights/error.h"
#include "probelights/grid_load.h"
#include "probelights/image_file.h"
#include "probelights/one_thread.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {

bool isImageFile(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  static const std::set<std::string> kImages{".hdr", ".exr",  ".pfm", ".tif",  ".tiff", ".png",
                                             ".jpg", ".jpeg", ".dds", ".hdri", ".rgbe"};
  return kImages.count(ext) > 0;
}

LoadedProbe load(const std::string& path, const ProbeOptions& options, const BakeOptions* grid) {
  // Loads run side by side with each other and the bakes, so each keeps to its own thread (one_thread.h):
  // threads that would otherwise share every core only contend (docs/decisions.md).
  const OnOneThread oneThread;
  LoadedProbe item;
  item.path = path;
  Stopwatch clock;
  try {
    if (grid) {
      GridProbe g = loadGrid(path, options, *grid);
      item.probe.emplace(std::move(g.probe));
      item.table.emplace(std::move(g.table));
      item.tablesMs = g.tablesMs;
    } else {
      item.probe.emplace(loadProbe(path, options));
    }
  } catch (const std::exception& e) {
    item.error = e.what();
  }
  item.loadMs = clock.ms();
  return item;
}

}  // namespace

std::vector<std::string> expandProbePaths(const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  std::set<std::string> seen;
  auto add = [&](const std::string& p) {
    if (seen.insert(p).second) out.push_back(p);
  };
  for (const std::string& input : inputs) {
    std::error_code ec;
    if (fs::is_directory(input, ec)) {
      std::vector<std::string> files;
      fs::directory_iterator it(input, ec);
      if (ec) throw Error("cannot read folder '" + input + "': " + ec.message());
      for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec) throw Error("cannot read folder '" + input + "': " + ec.message());
        if (it->is_regular_file(ec) && isImageFile(it->path())) files.push_back(it->path().string());
      }
      std::sort(files.begin(), files.end());
      for (const auto& f : files) add(f);
    } else if (!fs::exists(input, ec) && input.find_first_of("*?[") != std::string::npos) {
      glob_t g{};
      if (glob(input.c_str(), 0, nullptr, &g) == 0)
        for (std::size_t i = 0; i < g.gl_pathc; ++i) add(g.gl_pathv[i]);
      else
        add(input);  // matches nothing: its load says so
      globfree(&g);
    } else {
      add(input);
    }
  }
  return out;
}

void forEachProbe(const std::vector<std::string>& paths, const ProbeOptions& options,
                  const std::function<bool(LoadedProbe&)>& consume, const BakeOptions* grid) {
  // Loads run ahead of the bakes on their own threads: one probe ahead, or two while the probes are small
  // (a serial decoder such as Radiance's RLE keeps one core busy per file, and a 1K bake is shorter than its
  // load: two loads ahead keep every core busy, a third adds nothing; docs/decisions.md). At 8K a second
  // whole image in memory is not worth it.
  constexpr int kSmallWidth = 2048;
  std::deque<std::future<LoadedProbe>> ahead;
  std::size_t next = 0;
  auto launch = [&] { ahead.push_back(std::async(std::launch::async, load, paths[next++], options, grid)); };
  launch();
  while (!ahead.empty()) {
    LoadedProbe current = ahead.front().get();
    ahead.pop_front();
    const std::size_t depth = current.probe && current.probe->width() <= kSmallWidth ? 2 : 1;
    while (ahead.size() < depth && next < paths.size()) launch();
    if (!consume(current)) break;  // the loads under way finish as `ahead` is destroyed
  }
}

}  // namespace probelights
