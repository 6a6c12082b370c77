#include "probelights/batch.h"

#ifndef _WIN32
#include <glob.h>
#endif

#include <algorithm>
#include <cctype>
#include <cstring>
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

#ifdef _WIN32
namespace {

// Windows' shells pass wildcards on (POSIX shells expand them; glob() does for a quoted one): `*`, `?` and
// `[abc]` in a pattern's file name, matched case-insensitively as Windows names are; its folder is taken as
// it is.
bool wildcardMatch(const char* p, const char* s) {
  auto low = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  for (; *p; ++p, ++s) {
    if (*p == '*') {
      for (const char* t = s;; ++t) {
        if (wildcardMatch(p + 1, t)) return true;
        if (!*t) return false;
      }
    }
    if (!*s) return false;
    if (*p == '[') {
      const char* end = std::strchr(p + 1, ']');
      if (!end) return low(*s) == '[' && wildcardMatch(p + 1, s + 1);
      if (std::find_if(p + 1, end, [&](char c) { return low(c) == low(*s); }) == end) return false;
      p = end;
    } else if (*p != '?' && low(*p) != low(*s)) {
      return false;
    }
  }
  return !*s;
}

std::vector<std::string> matchingFiles(const std::string& pattern) {
  namespace fs = std::filesystem;
  const fs::path path(pattern);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const std::string name = path.filename().string();
  std::vector<std::string> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (wildcardMatch(name.c_str(), it->path().filename().string().c_str()))
      found.push_back(
          (path.has_parent_path() ? dir / it->path().filename() : it->path().filename()).string());
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace
#endif

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
#ifdef _WIN32
      const std::vector<std::string> matches = matchingFiles(input);
      if (matches.empty()) add(input);  // matches nothing: its load says so
      for (const auto& m : matches) add(m);
#else
      glob_t g{};
      if (glob(input.c_str(), 0, nullptr, &g) == 0)
        for (std::size_t i = 0; i < g.gl_pathc; ++i) add(g.gl_pathv[i]);
      else
        add(input);  // matches nothing: its load says so
      globfree(&g);
#endif
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
