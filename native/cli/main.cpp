// probelights: the command-line tool, thin over the library.
//   probelights bake PROBE [options]     turn a light probe into N lights (see usage())
// Exit codes: 0 success, 2 bad input or request (one line on stderr), 1 an unexpected internal failure.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "json_output.h"
#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/evaluate.h"
#include "probelights/preview.h"
#include "probelights/probe.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"
#include "probelights/tradeoff.h"

namespace {

using namespace probelights;
using cli::Evaluation;

const char* kUsage =
    R"(usage: probelights bake PROBE [options]      N lights that carry exactly the probe's energy
       probelights sh PROBE --bands B [--irradiance] [--window none|hanning|lanczos] [-o sh.json]
       probelights sample PROBE --bands B --epsilon E --samples N [--depth K] [--seed S] [-o samples.json]
       probelights tradeoff PROBE [--effects diffuse,shadow,glossy] [--counts 1,2,4,...] [--methods ...]
                              [--no-refit] [-o tradeoff.json] [--plot tradeoff.png]

PROBE is any image OpenImageIO reads. sh: real SH coefficients (Sloan order, orthonormal, Condon-Shortley phase,
theta from +Z) of the radiance, or with --irradiance of the irradiance. sample: directions and pdfs from the
SH importance sampler (Jarosz et al. 2009 warping with Berger's epsilon clamping) of the probe's luminance.

options:
  --method median-cut|variance|sh   partition algorithm (default variance); sh = SH importance warping
  --bands B, --epsilon E            sh: SH bands (default 8) and Berger's epsilon (default 0.01)
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
  --refit                           re-solve the lights' colours (non-negative least squares) so their
                                    diffuse irradiance matches the probe's; reports the energy shift
  --refit-directions                the refit also moves the lights' directions (lower error at few lights)
  --max-error E                     the fewest lights whose error is at most E (e.g. 1% or 0.01) on --effects
  --effects diffuse,shadow,glossy   effects to evaluate (default diffuse); evaluating prints their errors
  --evaluate                        evaluate the lights on --effects without choosing the count
  -q, --quiet                       no summary on standard output
  (sh, sample: --projection and --nonfinite as above; JSON goes to -o FILE or standard output)
)";

struct UsageError : Error {
  using Error::Error;
};

double parseReal(const std::string& flag, const std::string& text) {
  try {
    std::size_t used = 0;
    double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects a number, got '" + text + "'");
}

struct Args {
  std::string probe, output, preview;
  ProbeOptions probeOptions;
  BakeOptions bake;
  bool quiet = false;
  bool refit = false, evaluate = false, moveDirections = false;
  double maxError = 0;  // 0: not asked
  unsigned effects = kDiffuse;
};

double parseTolerance(const std::string& flag, const std::string& text) {
  bool percent = !text.empty() && text.back() == '%';
  double v = parseReal(flag, percent ? text.substr(0, text.size() - 1) : text);
  if (percent) v /= 100;
  if (!(v > 0 && v < 1)) throw UsageError(flag + " takes a tolerance such as 1% or 0.01, got '" + text + "'");
  return v;
}

int parseCount(const std::string& flag, const std::string& text) {
  try {
    std::size_t used = 0;
    long long n = std::stoll(text, &used);
    if (used == text.size() && n >= -1000000000LL && n <= 1000000000LL) return static_cast<int>(n);
  } catch (const std::exception&) {
  }
  throw UsageError(flag + " expects a whole number, got '" + text + "'");
}

// Walks the arguments of a command: "--flag value" and "--flag=value" alike.
class ArgReader {
 public:
  explicit ArgReader(const std::vector<std::string>& argv) : argv_(argv) {}
  bool next() {
    if (++i_ >= argv_.size()) return false;
    const std::string& a = argv_[i_];
    const auto eq = a.find('=');
    inline_ = a.rfind("--", 0) == 0 && eq != std::string::npos;
    arg_ = inline_ ? a.substr(0, eq) : a;
    value_ = inline_ ? a.substr(eq + 1) : std::string();
    return true;
  }
  const std::string& arg() const { return arg_; }
  std::string value() {
    if (inline_) return value_;
    if (i_ + 1 >= argv_.size()) throw UsageError(arg_ + " needs a value");
    return argv_[++i_];
  }
  // The probe path (the one positional argument), or an unknown option.
  void positional(std::string& probe) const {
    if (!arg_.empty() && arg_[0] == '-' && arg_ != "-")
      throw UsageError("unknown option '" + arg_ + "' (see probelights --help)");
    if (!probe.empty()) throw UsageError("one probe at a time: got '" + probe + "' and '" + arg_ + "'");
    probe = arg_;
  }

 private:
  const std::vector<std::string>& argv_;
  std::size_t i_ = static_cast<std::size_t>(-1);
  bool inline_ = false;
  std::string arg_, value_;
};

ProjectionChoice projectionArg(const std::string& v) {
  auto p = parseProjectionChoice(v);
  if (!p) throw UsageError("unknown projection '" + v + "': use auto, latlong, mirror-ball or angular");
  return *p;
}

NonFinitePolicy nonFiniteArg(const std::string& v) {
  if (v == "error") return NonFinitePolicy::Error;
  if (v == "zero") return NonFinitePolicy::Zero;
  throw UsageError("unknown --nonfinite policy '" + v + "': use error or zero");
}

Method methodArg(const std::string& v) {
  auto m = parseMethod(v);
  if (!m) throw UsageError("unknown method '" + v + "': use median-cut, variance or sh");
  return *m;
}

Args parseBakeArgs(const std::vector<std::string>& argv) {
  Args a;
  ArgReader r(argv);
  while (r.next()) {
    const std::string& arg = r.arg();
    if (arg == "--method")
      a.bake.method = methodArg(r.value());
    else if (arg == "--lights" || arg == "-n")
      a.bake.lights = parseCount(arg, r.value());
    else if (arg == "--projection")
      a.probeOptions.projection = projectionArg(r.value());
    else if (arg == "--nonfinite")
      a.probeOptions.nonFinite = nonFiniteArg(r.value());
    else if (arg == "--centroid") {
      std::string v = r.value();
      if (v != "energy" && v != "energy2")
        throw UsageError("unknown centroid '" + v + "': use energy or energy2");
      a.bake.centroid = v == "energy" ? CentroidWeight::Energy : CentroidWeight::Energy2;
    } else if (arg == "--resolution") {
      std::string v = r.value();
      auto res = WorkingResolution::parse(v);
      if (!res) throw UsageError("unknown resolution '" + v + "': use full, auto or a width in pixels");
      a.bake.resolution = *res;
    } else if (arg == "--bands")
      a.bake.shBands = parseCount(arg, r.value());
    else if (arg == "--epsilon")
      a.bake.shEpsilon = parseReal(arg, r.value());
    else if (arg == "--horizon") {
      std::string v = r.value();
      if (v != "on" && v != "off") throw UsageError("--horizon takes on or off, got '" + v + "'");
      a.bake.splitAtHorizon = v == "on";
    } else if (arg == "-o" || arg == "--output")
      a.output = r.value();
    else if (arg == "--preview")
      a.preview = r.value();
    else if (arg == "-q" || arg == "--quiet")
      a.quiet = true;
    else if (arg == "--refit")
      a.refit = true;
    else if (arg == "--refit-directions")
      a.refit = a.moveDirections = true;
    else if (arg == "--evaluate")
      a.evaluate = true;
    else if (arg == "--max-error")
      a.maxError = parseTolerance(arg, r.value());
    else if (arg == "--effects")
      a.effects = parseEffects(r.value());
    else
      r.positional(a.probe);
  }
  if (a.probe.empty()) throw UsageError("no probe given: probelights bake PROBE");
  if (a.bake.lights < 1)
    throw UsageError("asked for " + std::to_string(a.bake.lights) + " lights: ask for at least 1");
  return a;
}

void printSummary(const Args& a, const Probe& probe, const BakeResult& r, double loadMs,
                  const Evaluation& ev) {
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
  if (ev.done) {
    std::printf("error      ");
    if (ev.effects & kDiffuse) std::printf("diffuse %.2f%%  ", 100 * ev.errors.diffuse);
    if (ev.effects & kShadow) std::printf("shadow %.2f%%  ", 100 * ev.errors.shadow);
    if (ev.effects & kGlossy) std::printf("glossy %.2f%%  ", 100 * ev.errors.glossy);
    std::printf("(relative RMS of luminance vs the probe)%s\n", ev.refit ? ", lights refit" : "");
    if (ev.refit && !ev.autoCount) std::printf("refit      energy shift %+.2f%%\n", 100 * ev.energyShift);
  }
  std::printf("time (ms)  load %.1f  tables %.1f  partition %.1f  lights %.1f  (bake %.1f)\n", loadMs,
              r.timings.tablesMs, r.timings.partitionMs, r.timings.lightsMs,
              r.timings.tablesMs + r.timings.partitionMs + r.timings.lightsMs);
}

int bakeCommand(const std::vector<std::string>& argv) {
  Args a = parseBakeArgs(argv);
  auto t0 = std::chrono::steady_clock::now();
  Probe probe = Probe::load(a.probe, a.probeOptions);
  double loadMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  EvaluatedBake done =
      bakeEvaluated(probe, a.bake, {a.effects, a.evaluate, a.refit, a.maxError, 2048, a.moveDirections});
  BakeResult result = std::move(done.bake);
  a.bake.lights = done.lights;
  Evaluation evaluation;
  evaluation.done = done.evaluated, evaluation.autoCount = done.autoCount, evaluation.met = done.met;
  evaluation.tried = done.tried, evaluation.errors = done.errors, evaluation.energyShift = done.energyShift;
  evaluation.effects = done.effects;
  evaluation.refit = a.refit;

  if (!a.output.empty()) {
    std::string text = cli::bakeToJson(a.probe, probe, a.bake, result, loadMs, evaluation).dump(2) + "\n";
    if (a.output == "-") {
      std::fwrite(text.data(), 1, text.size(), stdout);
      a.quiet = true;
    } else {
      std::ofstream out(a.output);
      if (!(out << text)) throw Error("cannot write '" + a.output + "'");
    }
  }
  if (!a.preview.empty()) writePreview(probe, result, a.preview);
  if (!a.quiet) printSummary(a, probe, result, loadMs, evaluation);
  return 0;
}

// Options shared by the sh and sample commands.
struct ShArgs {
  std::string probe, output = "-";
  ProbeOptions probeOptions;
  int bands = 0, samples = 0, depth = 8;
  double epsilon = -1;
  std::uint64_t seed = 1;
  bool irradiance = false;
  ShWindow window = ShWindow::None;
};

ShArgs parseShArgs(const std::vector<std::string>& argv, bool sampling) {
  ShArgs a;
  ArgReader r(argv);
  while (r.next()) {
    const std::string& arg = r.arg();
    if (arg == "--bands")
      a.bands = parseCount(arg, r.value());
    else if (arg == "--samples" && sampling)
      a.samples = parseCount(arg, r.value());
    else if (arg == "--depth" && sampling)
      a.depth = parseCount(arg, r.value());
    else if (arg == "--seed" && sampling)
      a.seed = static_cast<std::uint64_t>(parseCount(arg, r.value()));
    else if (arg == "--epsilon" && sampling)
      a.epsilon = parseReal(arg, r.value());
    else if (arg == "--irradiance" && !sampling)
      a.irradiance = true;
    else if (arg == "--window" && !sampling) {
      std::string v = r.value();
      auto w = parseShWindow(v);
      if (!w) throw UsageError("unknown window '" + v + "': use none, hanning or lanczos");
      a.window = *w;
    } else if (arg == "--projection")
      a.probeOptions.projection = projectionArg(r.value());
    else if (arg == "--nonfinite")
      a.probeOptions.nonFinite = nonFiniteArg(r.value());
    else if (arg == "-o" || arg == "--output")
      a.output = r.value();
    else
      r.positional(a.probe);
  }
  if (a.probe.empty())
    throw UsageError(std::string("no probe given: probelights ") + (sampling ? "sample" : "sh") + " PROBE");
  if (a.bands < 1) throw UsageError("--bands B (at least 1) is required");
  if (sampling && a.samples < 1) throw UsageError("--samples N (at least 1) is required");
  if (sampling && a.epsilon < 0) throw UsageError("--epsilon E (in [0, 0.5]) is required");
  return a;
}

void writeJson(const nlohmann::json& j, const std::string& output) {
  std::string text = j.dump(output == "-" ? -1 : 1) + "\n";
  if (output == "-") {
    std::fwrite(text.data(), 1, text.size(), stdout);
    return;
  }
  std::ofstream out(output);
  if (!(out << text)) throw Error("cannot write '" + output + "'");
}

nlohmann::json sourceJson(const std::string& path, const Probe& probe) {
  return {{"path", path},
          {"width", probe.width()},
          {"height", probe.height()},
          {"projection", toString(probe.projection().kind())}};
}

constexpr const char* kConvention =
    "real SH, index l(l+1)+m, orthonormal, Condon-Shortley phase (Sloan 2008); theta from +Z, phi = atan2(y, "
    "x)";

int shCommand(const std::vector<std::string>& argv) {
  ShArgs a = parseShArgs(argv, false);
  Probe probe = Probe::load(a.probe, a.probeOptions);
  ShCoefficients sh = projectProbe(probe, a.bands);
  applyWindow(sh, a.window);
  if (a.irradiance) sh = irradianceCoefficients(sh);
  nlohmann::json c = nlohmann::json::array();
  for (const Rgb& v : sh.c) c.push_back(v);
  writeJson({{"source", sourceJson(a.probe, probe)},
             {"bands", a.bands},
             {"convention", kConvention},
             {"quantity", a.irradiance ? "irradiance" : "radiance"},
             {"window", a.window == ShWindow::None      ? "none"
                        : a.window == ShWindow::Hanning ? "hanning"
                                                        : "lanczos"},
             {"coefficients", c}},
            a.output);
  return 0;
}

int sampleCommand(const std::vector<std::string>& argv) {
  ShArgs a = parseShArgs(argv, true);
  Probe probe = Probe::load(a.probe, a.probeOptions);
  ShSampler sampler(a.bands, projectProbe(probe, a.bands).luminance(), a.epsilon, a.depth);
  std::mt19937_64 rng(a.seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  nlohmann::json dirs = nlohmann::json::array(), pdfs = nlohmann::json::array();
  for (int i = 0; i < a.samples; ++i) {
    auto s = sampler.sample({u(rng), u(rng)});
    dirs.push_back({s.direction.x, s.direction.y, s.direction.z});
    pdfs.push_back(s.pdf);
  }
  writeJson({{"source", sourceJson(a.probe, probe)},
             {"bands", a.bands},
             {"epsilon", a.epsilon},
             {"depth", a.depth},
             {"seed", a.seed},
             {"convention", kConvention},
             {"directions", dirs},
             {"pdf", pdfs}},
            a.output);
  return 0;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) items.push_back(item);
  return items;
}

int tradeoffCommand(const std::vector<std::string>& argv) {
  std::string probePath, output, plot;
  ProbeOptions probeOptions;
  TradeoffOptions options;
  unsigned effects = kDiffuse | kShadow;
  ArgReader r(argv);
  while (r.next()) {
    const std::string& arg = r.arg();
    if (arg == "--effects")
      effects = parseEffects(r.value());
    else if (arg == "--counts") {
      options.counts.clear();
      for (const auto& c : splitList(r.value())) {
        int n = parseCount("--counts", c);
        if (n < 1) throw UsageError("--counts takes light counts of at least 1");
        options.counts.push_back(n);
      }
    } else if (arg == "--methods") {
      options.methods.clear();
      for (const auto& m : splitList(r.value())) options.methods.push_back(methodArg(m));
    } else if (arg == "--no-refit")
      options.refit = false;
    else if (arg == "-o" || arg == "--output")
      output = r.value();
    else if (arg == "--plot")
      plot = r.value();
    else if (arg == "--projection")
      probeOptions.projection = projectionArg(r.value());
    else
      r.positional(probePath);
  }
  if (probePath.empty()) throw UsageError("no probe given: probelights tradeoff PROBE");
  auto t0 = std::chrono::steady_clock::now();
  Probe probe = Probe::load(probePath, probeOptions);
  Evaluator evaluator(probe, effects, EvaluatorOptions{2048, options.refit});
  double truthMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  auto rows = tradeoff(probe, evaluator, options);
  std::printf("probe %s %dx%d; effects %s; ground truth %.0f ms; error = relative RMS of luminance\n\n",
              probePath.c_str(), probe.width(), probe.height(), effectsToString(effects).c_str(), truthMs);
  std::printf("%-11s %6s %6s %5s %10s", "method", "lights", "res", "refit", "bake ms");
  for (auto [bit, name] :
       {std::pair{kDiffuse, "diffuse"}, std::pair{kShadow, "shadow"}, std::pair{kGlossy, "glossy"}})
    if (effects & bit) std::printf(" %9s", name);
  std::printf("\n");
  nlohmann::json table = nlohmann::json::array();
  for (const TradeoffRow& r : rows) {
    std::printf("%-11s %6d %6s %5s %10.2f", toString(r.method).c_str(), r.made, r.resolution.c_str(),
                r.refit ? "yes" : "no", r.bakeMs);
    nlohmann::json row{{"method", toString(r.method)}, {"lights", r.lights}, {"made", r.made},
                       {"resolution", r.resolution},   {"refit", r.refit},   {"bake_ms", r.bakeMs}};
    for (auto [bit, name, value] :
         {std::tuple{kDiffuse, "diffuse", r.errors.diffuse}, std::tuple{kShadow, "shadow", r.errors.shadow},
          std::tuple{kGlossy, "glossy", r.errors.glossy}})
      if (effects & bit) std::printf(" %8.3f%%", 100 * value), row[name] = value;
    std::printf("\n");
    table.push_back(row);
  }
  if (!output.empty())
    writeJson({{"source", sourceJson(probePath, probe)},
               {"effects", effectsToString(effects)},
               {"error", "relative RMS of luminance over the effect's sample points"},
               {"rows", table}},
              output);
  if (!plot.empty()) {
    writeTradeoffPlot(rows, effects,
                      std::filesystem::path(probePath).filename().string() + ": error vs bake time", plot);
    std::printf("\nplot: %s\n", plot.c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (!args.empty() && args[0] == "--version") {
      std::puts("probelights " PROBELIGHTS_VERSION);
      return 0;
    }
    if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
      std::fputs(kUsage, args.empty() ? stderr : stdout);
      return args.empty() ? 2 : 0;
    }
    if (args[0] == "tradeoff") {
      std::vector<std::string> rest(args.begin() + 1, args.end());
      for (const auto& s : rest)
        if (s == "--help" || s == "-h") return std::fputs(kUsage, stdout), 0;
      return tradeoffCommand(rest);
    }
    if (args[0] == "sh" || args[0] == "sample") {
      std::vector<std::string> rest(args.begin() + 1, args.end());
      for (const auto& s : rest)
        if (s == "--help" || s == "-h") return std::fputs(kUsage, stdout), 0;
      return args[0] == "sh" ? shCommand(rest) : sampleCommand(rest);
    }
    if (args[0] == "bake") {
      std::vector<std::string> rest(args.begin() + 1, args.end());
      for (const auto& s : rest)
        if (s == "--help" || s == "-h") return std::fputs(kUsage, stdout), 0;
      return bakeCommand(rest);
    }
    throw UsageError("unknown command '" + args[0] +
                     "': use bake, sh, sample or tradeoff (see probelights --help)");
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
