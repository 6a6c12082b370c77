#include "probelights/batch.h"

#include <glob.h>

#include <algorithm>
#include <filesystem>
#include <future>
#include <set>

#include "probelights/grid_load.h"
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
      item.probe.emplace(Probe::load(path, options));
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
      for (const auto& entry : fs::directory_iterator(input, ec))
        if (entry.is_regular_file(ec) && isImageFile(entry.path())) files.push_back(entry.path().string());
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
                  const std::function<void(LoadedProbe&)>& consume, const BakeOptions* grid) {
  if (paths.empty()) return;
  std::future<LoadedProbe> next = std::async(std::launch::async, load, paths[0], options, grid);
  for (std::size_t i = 0; i < paths.size(); ++i) {
    LoadedProbe current = next.get();
    if (i + 1 < paths.size()) next = std::async(std::launch::async, load, paths[i + 1], options, grid);
    consume(current);
  }
}

}  // namespace probelights
