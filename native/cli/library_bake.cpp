// probelights bake PROBE... --out-dir DIR: a whole HDRI library in one process. The next probe loads while
// the current one bakes (batch.h); each result is written whole or not at all (a temporary file renamed); a
// probe that fails is reported on one line and the rest go on; on a terminal a progress line says how far it
// is.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "bake_args.h"
#include "json_output.h"
#include "options.h"
#include "probelights/batch.h"
#include "probelights/preview.h"
#include "probelights/stopwatch.h"

namespace probelights::cli {

namespace {

namespace fs = std::filesystem;

// Writes `text` to `path` through a temporary file in the same folder, so a reader never sees half of it.
void writeWhole(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".part";
  {
    std::ofstream out(tmp);
    if (!(out << text) || !(out.flush())) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw Error("cannot write '" + path.string() + "'");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw Error("cannot write '" + path.string() + "': " + ec.message());
}

// The output folder, made if missing and checked writable before any work (nothing is left behind).
void prepareOutDir(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw Error("cannot write to output directory '" + dir.string() +
                "': " + (ec ? ec.message() : std::string("not a directory")));
  const fs::path probe = dir / ".probelights-write-test";
  {
    std::ofstream out(probe);
    if (!(out << "x")) throw Error("cannot write to output directory '" + dir.string() + "'");
  }
  fs::remove(probe, ec);
}

// One output name per probe: its file name without the extension, made unique with _2, _3, ...
std::vector<std::string> outputNames(const std::vector<std::string>& paths) {
  std::map<std::string, int> used;
  std::vector<std::string> names;
  for (const auto& p : paths) {
    std::string stem = fs::path(p).stem().string();
    if (stem.empty()) stem = "probe";
    const int n = ++used[stem];
    names.push_back(n == 1 ? stem : stem + "_" + std::to_string(n));
  }
  return names;
}

}  // namespace

int bakeLibrary(const BakeArgs& a) {
  const std::vector<std::string> paths = expandProbePaths(a.probes);
  if (paths.empty()) throw UsageError("no probes found in the inputs given");
  const fs::path dir(a.outDir);
  prepareOutDir(dir);
  const std::vector<std::string> names = outputNames(paths);
  const bool terminal = isatty(STDERR_FILENO) && !a.quiet;
  Stopwatch wall;
  double loadMs = 0, bakeMs = 0;
  int done = 0, failed = 0;
  nlohmann::json entries = nlohmann::json::array();
  std::size_t index = 0;
  const bool gridOnly = bakesFromGridAlone(a);
  auto bakeOne = [&](LoadedProbe& item) {
    const std::string& name = names[index++];
    nlohmann::json entry{{"probe", item.path}, {"load_ms", item.loadMs}};
    loadMs += item.loadMs;
    std::string error = item.error;
    if (item.probe) {
      try {
        Stopwatch clock;
        const EvaluatedBake result =
            item.table ? bakeOnGrid(*item.probe, *item.table, item.tablesMs, a.bake, a.accuracy.sunAngles)
                       : bakeEvaluated(*item.probe, a.bake, a.accuracy);
        const double ms = clock.ms();
        bakeMs += ms;
        writeWhole(dir / (name + ".json"),
                   bakeToJson({item.path, *item.probe, a.bake, result, item.loadMs}).dump(2) + "\n");
        if (a.previews) writePreview(*item.probe, result.bake, (dir / (name + ".png")).string());
        entry["output"] = name + ".json";
        entry["lights"] = result.bake.lights.size();
        entry["bake_ms"] = ms;
        if (result.evaluated) entry["worst_error"] = result.errors.worst(result.effects);
      } catch (const std::exception& e) {
        error = e.what();
      }
    }
    ++done;
    if (!error.empty()) {
      ++failed;
      entry["error"] = error;
      if (terminal) std::fputs("\r\033[K", stderr);
      std::fprintf(stderr, "probelights: error: %s\n", error.c_str());
    }
    entries.push_back(entry);
    if (terminal) {
      const double rate = done / (wall.ms() / 1000.0);
      std::fprintf(stderr, "\r\033[K%d/%zu probes, %.1f per second, %.0f s left", done, paths.size(), rate,
                   (paths.size() - done) / rate);
      std::fflush(stderr);
    }
  };
  forEachProbe(paths, a.probeOptions, bakeOne, gridOnly ? &a.bake : nullptr);
  if (terminal) std::fputs("\r\033[K", stderr);
  const double seconds = wall.ms() / 1000.0;
  writeWhole(dir / "summary.json", nlohmann::json{{"probes", paths.size()},
                                                  {"baked", done - failed},
                                                  {"failed", failed},
                                                  {"seconds", seconds},
                                                  {"load_ms", loadMs},
                                                  {"bake_ms", bakeMs},
                                                  {"results", entries}}
                                           .dump(2) +
                                       "\n");
  if (!a.quiet)
    std::printf("baked %d of %zu probes into %s in %.2f s (loading %.2f s and baking %.2f s, overlapped)%s\n",
                done - failed, paths.size(), dir.string().c_str(), seconds, loadMs / 1000, bakeMs / 1000,
                failed ? (", " + std::to_string(failed) + " failed").c_str() : "");
  return failed ? 3 : 0;
}

}  // namespace probelights::cli
