// probelights bake PROBE [options]: N lights that carry exactly the probe's energy (usage in main.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "bake_args.h"
#include "commands.h"
#include "json_output.h"
#include "options.h"
#include "probelights/accuracy.h"
#include "probelights/bake.h"
#include "probelights/evaluate.h"
#include "probelights/grid_load.h"
#include "probelights/preview.h"
#include "probelights/stopwatch.h"
#include "write_whole.h"

namespace probelights::cli {

namespace {

BakeArgs parseBakeArgs(const std::vector<std::string>& argv) {
  BakeArgs a;
  BakeOptions& b = a.bake;
  AccuracyOptions& acc = a.accuracy;
  std::vector<Option> table{
      {{"--method"}, [&](const std::string& v) { b.method = parseMethod(v); }},
      {{"--lights", "-n"}, [&](const std::string& v) { b.lights = parseCount("--lights", v); }},
      {{"--centroid"}, [&](const std::string& v) { b.centroid = parseCentroid(v); }},
      {{"--resolution"}, [&](const std::string& v) { b.resolution = WorkingResolution::parse(v); }},
      {{"--bands"}, [&](const std::string& v) { b.shBands = parseCount("--bands", v); }},
      {{"--epsilon"}, [&](const std::string& v) { b.shEpsilon = parseReal("--epsilon", v); }},
      {{"--horizon"},
       [&](const std::string& v) {
         if (v != "on" && v != "off") throw UsageError("--horizon takes on or off, got '" + v + "'");
         b.splitAtHorizon = v == "on";
       }},
      {{"-o", "--output"}, [&](const std::string& v) { a.output = nonEmpty("-o", v); }},
      {{"--preview"}, [&](const std::string& v) { a.preview = nonEmpty("--preview", v); }},
      {{"--out-dir"}, [&](const std::string& v) { a.outDir = nonEmpty("--out-dir", v); }},
      flag({"--previews"}, [&] { a.previews = true; }),
      {{"--max-error"},
       [&](const std::string& v) {
         acc.maxError = parseTolerance("--max-error", v);
         if (!(acc.maxError > 0 && acc.maxError < 1))
           throw UsageError("--max-error takes an error between 0 and 100% (e.g. 1%), got '" + v + "'");
       }},
      {{"--effects"}, [&](const std::string& v) { acc.effects = parseEffects(v); }},
      {{"--sun-angles"}, [&](const std::string& v) { acc.sunAngles = parseSunAngles(v); }},
      {{"--sun-profile"}, [&](const std::string& v) { acc.sunProfile = parseSunProfile(v); }},
      flag({"-q", "--quiet"}, [&] { a.quiet = true; }),
      flag({"--refit"}, [&] { acc.refit = true; }),
      flag({"--refit-directions"}, [&] { acc.refit = acc.moveDirections = true; }),
      flag({"--evaluate"}, [&] { acc.evaluate = true; }),
      {{"--cuts"}, [&](const std::string& v) { acc.cuts = parseCutChoice(v); }},
      flag({"--both-cuts"}, [&] { acc.cuts = CutChoice::Both; }),
  };
  addProbeOptions(table, a.probeOptions);
  const std::vector<std::string> probes = parseOptions(argv, table);
  if (a.outDir.empty()) {
    if (a.previews)
      throw UsageError("--previews goes with --out-dir (a library bake); one probe takes --preview FILE");
    a.probe = oneProbe(probes, "bake");
    refuseOverwritingProbe(a.probe, {a.output, a.preview});
  } else {
    if (!a.output.empty() || !a.preview.empty())
      throw UsageError("with --out-dir each probe's JSON (and --previews) goes there: drop -o / --preview");
    if (probes.empty()) throw UsageError("no probes given: probelights bake PROBE... --out-dir DIR");
    a.probes = probes;
  }
  return a;
}

void printSummary(const BakeArgs& a, const Probe& probe, const EvaluatedBake& ev, double loadMs) {
  const BakeResult& r = ev.bake;
  std::printf("probe      %s  %dx%d %s\n", a.probe.c_str(), probe.width(), probe.height(),
              toString(probe.projection().kind()).c_str());
  for (const auto& note : probe.report().notes) std::printf("note       %s\n", note.c_str());
  for (const auto& note : r.notes) std::printf("note       %s\n", note.c_str());
  std::printf("method     %s, %zu lights, cuts on a %dx%d grid (cell %d px)\n", toString(ev.cut).c_str(),
              r.lights.size(), (probe.width() + r.cellSize - 1) / r.cellSize,
              (probe.height() + r.cellSize - 1) / r.cellSize, r.cellSize);
  std::printf(
      "\n   #  direction (x, y, z)          rgb (W/m^2)                      share  radius  angle (deg)\n");
  for (std::size_t i = 0; i < r.lights.size(); ++i) {
    const Light& l = r.lights[i];
    std::printf("%4zu  (%6.3f, %6.3f, %6.3f)  (%9.4g, %9.4g, %9.4g)  %6.2f%%  %6.2f  %6.2f\n", i,
                l.direction.x, l.direction.y, l.direction.z, l.rgb[0], l.rgb[1], l.rgb[2],
                100 * l.energyShare, l.angularRadius * 180 / kPi, l.angle * 180 / kPi);
  }
  Rgb sum{};
  for (const Light& l : r.lights)
    for (int k = 0; k < 3; ++k) sum[k] += l.rgb[k];
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    if (r.totalRgb[k] > 0) worst = std::max(worst, std::abs(sum[k] - r.totalRgb[k]) / r.totalRgb[k]);
  const bool allPositive = r.totalRgb[0] > 0 && r.totalRgb[1] > 0 && r.totalRgb[2] > 0;
  std::printf(
      "\nenergy     probe integral (%.6g, %.6g, %.6g), lights sum (%.6g, %.6g, %.6g), max rel. diff %.1e%s\n",
      r.totalRgb[0], r.totalRgb[1], r.totalRgb[2], sum[0], sum[1], sum[2], worst,
      allPositive ? "" : " (of the channels above 0; see the note)");
  if (ev.evaluated) {
    std::printf("error      ");
    if (ev.effects & kDiffuse) std::printf("diffuse %.2f%%  ", 100 * ev.errors.diffuse);
    if (ev.effects & kShadow) std::printf("shadow %.2f%%  ", 100 * ev.errors.shadow);
    if (ev.effects & kGlossy) std::printf("glossy %.2f%%  ", 100 * ev.errors.glossy);
    std::printf("(relative RMS of luminance vs the probe)%s; sun angles: %s\n",
                ev.refit ? ", lights refit" : "", toString(ev.sunAngles).c_str());
    if (ev.refit && !ev.autoCount) std::printf("refit      energy shift %+.2f%%\n", 100 * ev.energyShift);
  }
  if (probe.hasPixels())
    std::printf("time (ms)  load %.1f  tables %.1f  partition %.1f  lights %.1f  (bake %.1f)\n", loadMs,
                r.timings.tablesMs, r.timings.partitionMs, r.timings.lightsMs,
                r.timings.tablesMs + r.timings.partitionMs + r.timings.lightsMs);
  else  // read band by band: the tables were built while the image was being read
    std::printf("time (ms)  load %.1f (tables %.1f of it, while reading)  partition %.1f  lights %.1f\n",
                loadMs, r.timings.tablesMs, r.timings.partitionMs, r.timings.lightsMs);
}

}  // namespace

bool bakesFromGridAlone(const BakeArgs& a) {
  return bakesOnGridAlone(a.bake, a.accuracy) && a.preview.empty() && !a.previews;
}

int bakeCommand(const std::vector<std::string>& argv) {
  BakeArgs a = parseBakeArgs(argv);
  if (!a.outDir.empty()) return bakeLibrary(a);
  Stopwatch load;
  std::optional<GridProbe> grid;
  if (bakesFromGridAlone(a)) grid.emplace(loadGrid(a.probe, a.probeOptions, a.bake));
  const Probe probe = grid ? std::move(grid->probe) : Probe::load(a.probe, a.probeOptions);
  const double loadMs = load.ms();
  const EvaluatedBake done =
      grid ? bakeOnGrid(probe, grid->table, grid->tablesMs, a.bake, a.accuracy.sunAngles)
           : bakeEvaluated(probe, a.bake, a.accuracy);
  if (!a.output.empty()) {
    writeJson(bakeToJson({a.probe, probe, a.bake, done, loadMs}), a.output, 2);
    if (a.output == "-") a.quiet = true;
  }
  if (!a.preview.empty())
    writeImageWhole(a.preview, [&](const std::string& tmp) { writePreview(probe, done.bake, tmp); });
  if (!a.quiet) printSummary(a, probe, done, loadMs);
  return 0;
}

}  // namespace probelights::cli
