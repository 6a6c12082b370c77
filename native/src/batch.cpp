#include "probelights/batch.h"

#include <glob.h>

#include <algorithm>
#include <filesystem>
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

LoadedProbe loadForBatch(const std::string& path, const ProbeOptions& options, const BakeOptions* grid) {
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
  } catch (const Error& e) {
    item.error = e.what(), item.remedy = e.sharedRemedy();
  } catch (const std::exception& e) {
    item.error = e.what();
  }
  item.loadMs = clock.ms();
  return item;
}

}  // namespace probelights
