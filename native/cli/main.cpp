// probelights: the command-line tool, thin over the library.
//   probelights bake PROBE [options]     turn a light probe into N lights (see usage())
// Exit codes: 0 success, 2 bad input or request (one line on stderr), 1 an unexpected internal failure.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "json_output.h"
#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/preview.h"
#include "probelights/probe.h"

namespace {

using namespace probelights;

const char* kUsage = R"(usage: probelights bake PROBE [options]

Turns a light probe (any image OpenImageIO reads) into N lights that carry exactly its energy.

options:
  --method median-cut|variance      partition algorithm (default variance)
  --lights N                        number of lights, N >= 1 (default 16)
  --projection auto|latlong|mirror-ball|angular
                                    how the image maps to the sphere (default auto: lat-long for 2:1 images)
  --centroid energy|energy2         weight that places a light in its region (default energy)
  --resolution full|auto|WIDTH      working resolution the cuts are decided on (default auto: full up to
                                    2048 px wide); lights are always summed at full resolution
  --horizon on|off                  lat-long: first cut at the horizon so no light mixes sky and ground
                                    (default off: the papers' algorithms exactly)
  --nonfinite error|zero            NaN/Inf pixels: refuse the probe (default) or read them as 0
  -o, --output FILE                 write the lights as JSON ('-' for standard output)
  --preview FILE                    write a picture of the regions and lights (PNG)
  -q, --quiet                       no summary on standard output
)";

struct UsageError : Error {
  using Error::Error;
};

struct Args {
  std::string probe, output, preview;
  ProbeOptions probeOptions;
  BakeOptions bake;
  bool quiet = false;
};

int parseCount(const std::string& flag, const std::string& text) {
  try {
    std::size_t used = 0;
    long long n = std::stoll(text, &used);
    if (used == text.size() && n >= -1000000000LL && n <= 1000000000LL) return static_cast<int>(n);
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects a whole number, got '" + text + "'");
}

Args parseBakeArgs(const std::vector<std::string>& argv) {
  Args a;
  for (std::size_t i = 0; i < argv.size(); ++i) {
    std::string arg = argv[i], value;
    bool hasInlineValue = false;
    if (arg.rfind("--", 0) == 0 && arg.find('=') != std::string::npos) {
      value = arg.substr(arg.find('=') + 1);
      arg = arg.substr(0, arg.find('='));
      hasInlineValue = true;
    }
    auto next = [&]() -> std::string {
      if (hasInlineValue) return value;
      if (i + 1 >= argv.size()) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--method") {
      std::string v = next();
      auto m = parseMethod(v);
      if (!m) throw UsageError("unknown method '" + v + "': use median-cut or variance");
      a.bake.method = *m;
    } else if (arg == "--lights" || arg == "-n") {
      a.bake.lights = parseCount(arg, next());
    } else if (arg == "--projection") {
      std::string v = next();
      auto p = parseProjectionChoice(v);
      if (!p) throw UsageError("unknown projection '" + v + "': use auto, latlong, mirror-ball or angular");
      a.probeOptions.projection = *p;
    } else if (arg == "--centroid") {
      std::string v = next();
      if (v == "energy")
        a.bake.centroid = CentroidWeight::Energy;
      else if (v == "energy2")
        a.bake.centroid = CentroidWeight::Energy2;
      else
        throw UsageError("unknown centroid '" + v + "': use energy or energy2");
    } else if (arg == "--resolution") {
      std::string v = next();
      auto r = WorkingResolution::parse(v);
      if (!r) throw UsageError("unknown resolution '" + v + "': use full, auto or a width in pixels");
      a.bake.resolution = *r;
    } else if (arg == "--horizon") {
      std::string v = next();
      if (v == "on") a.bake.splitAtHorizon = true;
      else if (v == "off") a.bake.splitAtHorizon = false;
      else throw UsageError("--horizon takes on or off, got '" + v + "'");
    } else if (arg == "--nonfinite") {
      std::string v = next();
      if (v == "error")
        a.probeOptions.nonFinite = NonFinitePolicy::Error;
      else if (v == "zero")
        a.probeOptions.nonFinite = NonFinitePolicy::Zero;
      else
        throw UsageError("unknown --nonfinite policy '" + v + "': use error or zero");
    } else if (arg == "-o" || arg == "--output") {
      a.output = next();
    } else if (arg == "--preview") {
      a.preview = next();
    } else if (arg == "-q" || arg == "--quiet") {
      a.quiet = true;
    } else if (!arg.empty() && arg[0] == '-' && arg != "-") {
      throw UsageError("unknown option '" + arg + "' (see probelights --help)");
    } else if (a.probe.empty()) {
      a.probe = arg;
    } else {
      throw UsageError("one probe at a time: got '" + a.probe + "' and '" + arg + "'");
    }
  }
  if (a.probe.empty()) throw UsageError("no probe given: probelights bake PROBE");
  if (a.bake.lights < 1)
    throw UsageError("asked for " + std::to_string(a.bake.lights) + " lights: ask for at least 1");
  return a;
}

void printSummary(const Args& a, const Probe& probe, const BakeResult& r, double loadMs) {
  std::printf("probe      %s  %dx%d %s\n", a.probe.c_str(), probe.width(), probe.height(),
              toString(probe.projection().kind()).c_str());
  for (const auto& note : probe.report().notes) std::printf("note       %s\n", note.c_str());
  for (const auto& note : r.notes) std::printf("note       %s\n", note.c_str());
  std::printf("method     %s, %zu lights, cuts on a %dx%d grid (cell %d px)\n",
              toString(a.bake.method).c_str(), r.lights.size(), (probe.width() + r.cellSize - 1) / r.cellSize,
              (probe.height() + r.cellSize - 1) / r.cellSize, r.cellSize);
  std::printf("\n   #  direction (x, y, z)          rgb (W/m^2)                      share  radius(deg)\n");
  for (std::size_t i = 0; i < r.lights.size(); ++i) {
    const Light& l = r.lights[i];
    std::printf("%4zu  (%6.3f, %6.3f, %6.3f)  (%9.4g, %9.4g, %9.4g)  %6.2f%%  %8.2f\n", i, l.direction.x,
                l.direction.y, l.direction.z, l.rgb[0], l.rgb[1], l.rgb[2], 100 * l.energyShare,
                l.angularRadius * 180 / kPi);
  }
  Rgb sum{};
  for (const Light& l : r.lights)
    for (int k = 0; k < 3; ++k) sum[k] += l.rgb[k];
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    if (r.totalRgb[k] > 0) worst = std::max(worst, std::abs(sum[k] - r.totalRgb[k]) / r.totalRgb[k]);
  std::printf(
      "\nenergy     probe integral (%.6g, %.6g, %.6g), lights sum (%.6g, %.6g, %.6g), max rel. diff %.1e\n",
      r.totalRgb[0], r.totalRgb[1], r.totalRgb[2], sum[0], sum[1], sum[2], worst);
  std::printf("time (ms)  load %.1f  tables %.1f  partition %.1f  lights %.1f  (bake %.1f)\n", loadMs,
              r.timings.tablesMs, r.timings.partitionMs, r.timings.lightsMs,
              r.timings.tablesMs + r.timings.partitionMs + r.timings.lightsMs);
}

int bakeCommand(const std::vector<std::string>& argv) {
  Args a = parseBakeArgs(argv);
  auto t0 = std::chrono::steady_clock::now();
  Probe probe = Probe::load(a.probe, a.probeOptions);
  double loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  BakeResult result = bake(probe, a.bake);

  if (!a.output.empty()) {
    std::string text = cli::bakeToJson(a.probe, probe, a.bake, result, loadMs).dump(2) + "\n";
    if (a.output == "-") {
      std::fwrite(text.data(), 1, text.size(), stdout);
      a.quiet = true;
    } else {
      std::ofstream out(a.output);
      if (!(out << text)) throw Error("cannot write '" + a.output + "'");
    }
  }
  if (!a.preview.empty()) writePreview(probe, result, a.preview);
  if (!a.quiet) printSummary(a, probe, result, loadMs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::fputs(kUsage, args.empty() ? stderr : stdout);
      return args.empty() ? 2 : 0;
    }
    if (args[0] == "bake") {
      std::vector<std::string> rest(args.begin() + 1, args.end());
      for (const auto& s : rest)
        if (s == "--help" || s == "-h") return std::fputs(kUsage, stdout), 0;
      return bakeCommand(rest);
    }
    throw UsageError("unknown command '" + args[0] + "' (probelights bake PROBE; see probelights --help)");
  } catch (const Error& e) {
    std::fprintf(stderr, "probelights: error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "probelights: error: out of memory (try a coarser --resolution)\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "probelights: internal error: %s\n", e.what());
    return 1;
  }
}
