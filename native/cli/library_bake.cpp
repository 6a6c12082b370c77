// probelights bake PROBE... --out-dir DIR: a whole HDRI library in one process. The next probe loads while
// the current one bakes (batch.h); each result is written whole or not at all (a temporary file renamed); a
// probe that fails is reported on one line and the rest go on; on a terminal a progress line says how far it
// is. Nothing is overwritten that a bake did not write (outputNames), and a disk that fills or Ctrl-C stops
// the run with a summary of what was done.
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>
#ifdef _WIN32
#include <io.h>
#else
#include <unistd.h>
#endif

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include "bake_args.h"
#include "json_output.h"
#include "options.h"
#include "probelights/bake_file.h"
#include "probelights/batch.h"
#include "probelights/preview.h"
#include "probelights/stopwatch.h"
#include "write_whole.h"

namespace probelights::cli {

namespace {

namespace fs = std::filesystem;

const char* kGenerator = "probelights " PROBELIGHTS_VERSION;

// Whether the JSON file at `path` is one a bake wrote (a result or a summary), which a new bake may replace.
// Results and summaries of versions before the "generator" key are known by their keys.
bool ourJson(const fs::path& path) {
  std::error_code ec;
  if (fs::file_size(path, ec) > (64u << 20) || ec) return false;
  std::ifstream in(path, std::ios::binary);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object()) return false;
  if (auto g = j.find("generator"); g != j.end())
    return g->is_string() && g->get<std::string>().rfind("probelights", 0) == 0;
  return (j.contains("source") && j.contains("lights") && j.contains("total_rgb")) ||  // a result
         (j.contains("probes") && j.contains("baked") && j.contains("results"));       // a summary
}

// Whether the image at `path` is a preview a bake wrote (its Software tag, preview.h).
bool ourPreview(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  return in && in->spec().get_string_attribute("Software") == kPreviewSoftware;
}

// The output folder, made if missing, and checked before any work by writing to it for real (synced: a
// buffered byte passes on a full disk) and by its free space; a summary.json of somebody else's is refused.
void prepareOutDir(const fs::path& dir, const std::vector<std::string>& inputs) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("cannot write to output directory '" + dir.string() +
                "': " + (ec ? ec.message() : std::string("not a directory")));
  try {
    writeWhole((dir / ".probelights-write-test").string(), std::string(4096, ' '));
  } catch (const Error& e) {
    throw Error("cannot write to output directory '" + dir.string() +
                "': " + std::string(e.what()).substr(std::string(e.what()).rfind(": ") + 2));
  }
  fs::remove(dir / ".probelights-write-test", ec);
  if (const fs::space_info space = fs::space(dir, ec); !ec && space.available < (1u << 20))
    throw Error("cannot write to output directory '" + dir.string() + "': less than 1 MB free");
  const fs::path summary = dir / "summary.json";
  for (const auto& input : inputs)
    if (sameFile(input, summary.string()))
      throw UsageError("'" + summary.string() + "' is one of the probes: choose another --out-dir");
  if (fs::exists(summary, ec) && !ourJson(summary))
    throw UsageError("'" + summary.string() +
                     "' exists and was not written by probelights: choose another --out-dir or move it");
}

// One output name per probe: its file name without the extension, or with _2, _3, ... the first that no
// other probe of this run takes (compared without case: case-insensitive file systems) and whose files in
// the folder are missing or a bake's own (ourJson, ourPreview) and none of the probes. Nothing else in the
// folder is overwritten.
// A name that is UTF-8 as it is; another (a file name's bytes) with '_' for each byte outside ASCII, so that
// the summary (JSON: UTF-8) names the file it wrote.
std::string textName(std::string name) {
  const nlohmann::json j = name;
  try {
    (void)j.dump();
    return name;
  } catch (const nlohmann::json::exception&) {
    for (char& c : name)
      if (static_cast<unsigned char>(c) >= 0x80) c = '_';
    return name;
  }
}

std::vector<std::string> outputNames(const std::vector<std::string>& paths, const fs::path& dir,
                                     bool previews) {
  std::set<std::string> taken{"summary"};
  auto free = [&](const fs::path& file, bool image) {
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(file, ec)) && !fs::exists(file, ec)) return true;
    for (const auto& p : paths)
      if (sameFile(p, file.string())) return false;
    return image ? ourPreview(file) : ourJson(file);
  };
  std::vector<std::string> names;
  for (const auto& p : paths) {
    std::string stem = textName(fs::path(p).stem().string());
    if (stem.empty() || stem[0] == '.') stem = "probe" + stem;
    std::string name = stem;
    for (int n = 2; taken.count(OIIO::Strutil::lower(name)) || !free(dir / (name + ".json"), false) ||
                    (previews && !free(dir / (name + ".png"), true));
         ++n)
      name = stem + "_" + std::to_string(n);
    taken.insert(OIIO::Strutil::lower(name));
    names.push_back(name);
  }
  return names;
}

// A failed write that no later probe's write would escape: stop the run.
bool diskFailure(const std::string& why) {
#ifdef EDQUOT
  for (int e : {ENOSPC, EDQUOT, EROFS, EIO})
#else  // Windows: no disk quotas in errno
  for (int e : {ENOSPC, EROFS, EIO})
#endif
    if (why.find(std::strerror(e)) != std::string::npos) return true;
  return false;
}

}  // namespace

int bakeLibrary(const BakeArgs& a) {
  const std::vector<std::string> paths = expandProbePaths(a.probes);
  if (paths.empty()) throw UsageError("no probes found in the inputs given");
  const fs::path dir(a.outDir);
  prepareOutDir(dir, paths);
  const std::vector<std::string> names = outputNames(paths, dir, a.previews);
  // Ctrl-C: the probe under way finishes, the summary says what was done; a second Ctrl-C ends at once.
  // Either way no half-written file is left.
  static volatile bool interrupted = false;
  removeTemporariesOnSignal(&interrupted);
  bool stopped = false;
#ifdef _WIN32
  const bool terminal = _isatty(_fileno(stderr)) && !a.quiet;
#else
  const bool terminal = isatty(STDERR_FILENO) && !a.quiet;
#endif
  Stopwatch wall;
  double loadMs = 0, bakeMs = 0;
  int done = 0, failed = 0;
  nlohmann::json entries = nlohmann::json::array();
  std::size_t index = 0;
  auto bakeOne = [&](BakedFile& item) -> bool {
    const std::string& name = names[index++];
    nlohmann::json entry{{"probe", item.path}, {"load_ms", item.loadMs}};
    loadMs += item.loadMs;
    std::string error = describe(item.error, item.remedy.get(), spelled);
    if (item.result) {
      try {
        const EvaluatedBake& result = *item.result;
        bakeMs += item.bakeMs;
        if (a.previews) {
          writeImageWhole((dir / (name + ".png")).string(),
                          [&](const std::string& tmp) { writePreview(*item.probe, result.bake, tmp); });
          entry["preview"] = name + ".png";
        }
        writeWhole((dir / (name + ".json")).string(),
                   dumpJson(bakeToJson({item.path, *item.probe, a.request.bake, result, item.loadMs}), 2));
        entry["output"] = name + ".json";
        entry["lights"] = result.bake.lights.size();
        entry["bake_ms"] = item.bakeMs;
        if (result.evaluated) entry["worst_error"] = result.errors.worst(result.effects);
      } catch (const Error& e) {
        error = described(e);
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    ++done;
    if (!error.empty()) {
      ++failed;
      entry["error"] = error;
      if (terminal) std::fputs("\r\033[K", messages());
      std::fprintf(messages(), "probelights: error: %s\n", error.c_str());
      if (diskFailure(error)) stopped = true;
    }
    entries.push_back(entry);
    if (terminal) {
      const double rate = done / (wall.ms() / 1000.0);
      std::fprintf(messages(), "\r\033[K%d/%zu probes, %.1f per second, %.0f s left", done, paths.size(),
                   rate, (paths.size() - done) / rate);
      std::fflush(messages());
    }
    return !stopped && !interrupted;
  };
  bakeFiles(paths, a.request, bakeOne);
  if (terminal) std::fputs("\r\033[K", messages());
  const double seconds = wall.ms() / 1000.0;
  const int skipped = static_cast<int>(paths.size()) - done;
  const char* why = interrupted ? "interrupted" : "stopped: the output directory cannot be written";
  nlohmann::json summary{{"generator", kGenerator}, {"probes", paths.size()}, {"baked", done - failed},
                         {"failed", failed},        {"not_started", skipped}, {"seconds", seconds},
                         {"load_ms", loadMs},       {"bake_ms", bakeMs},      {"results", entries}};
  if (skipped) summary["stopped"] = why;
  try {
    writeWhole((dir / "summary.json").string(), dumpJson(summary, 2));
  } catch (const Error& e) {
    std::fprintf(messages(), "probelights: error: %s\n", e.what());
    return 3;
  }
  if (!a.quiet)
    std::printf(
        "baked %d of %zu probes into %s in %.2f s (loading %.2f s and baking %.2f s, overlapped)%s%s\n",
        done - failed, paths.size(), dir.string().c_str(), seconds, loadMs / 1000, bakeMs / 1000,
        failed ? (", " + std::to_string(failed) + " failed").c_str() : "",
        skipped ? (", " + std::to_string(skipped) + " not started (" + why + ")").c_str() : "");
  if (interrupted) return 130;
  return failed || skipped ? 3 : 0;
}

}  // namespace probelights::cli
