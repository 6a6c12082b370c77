// probelights bake PROBE [options]: N lights that carry exactly the probe's energy (usage in main.cpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "bake_args.h"
#include "commands.h"
#include "json_output.h"
#include "options.h"
#include "probelights/bake_file.h"
#include "probelights/evaluate.h"
#include "probelights/image_file.h"
#include "probelights/names.h"
#include "probelights/placement.h"
#include "probelights/preview.h"
#include "probelights/stopwatch.h"
#include "write_whole.h"

namespace probelights::cli {

namespace {

// The probe's path as the .usda at `usd` names it: relative to the .usda's folder, "./" or "../" first (USD
// anchors such paths to the layer's folder), or absolute when no relative path leads there.
std::string assetPathFrom(const std::string& usd, const std::string& probe) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path target = fs::absolute(probe, ec).lexically_normal();
  const fs::path folder = fs::absolute(usd, ec).lexically_normal().parent_path();
  const fs::path relative = target.lexically_relative(folder);
  if (relative.empty()) return target.generic_string();
  const std::string text = relative.generic_string();
  return text.rfind("../", 0) == 0 ? text : "./" + text;
}

// The exporters' flags: "--gltf, --usd or --csv" (each followed by `after`), or joined by `between`.
std::string exportFlags(const std::string& between = "", const std::string& after = "") {
  std::vector<std::string> flags;
  for (const Exporter& e : exporters()) flags.push_back("--" + e.name + after);
  if (between.empty()) return listOf(flags);
  std::string out;
  for (const std::string& f : flags) out += (out.empty() ? "" : between) + f;
  return out;
}

BakeArgs parseBakeArgs(const std::vector<std::string>& argv) {
  BakeArgs a;
  // The bake's options, from the table the module shares (request.h), then the command's own.
  TableOptions<BakeRequest> given(requestOptions());
  std::vector<Option> table;
  given.addTo(table, {{"lights", "-n"}});
  table.push_back(flag({"--both-cuts"}, [&] { given.give("cuts", "both"); }));
  table.push_back({{"--projection"},
                   [&](const std::string& v) { a.request.probe.projection = parseProjectionChoice(v); }});
  table.push_back({{"-o", "--output"}, [&](const std::string& v) { a.output = nonEmpty("-o", v); }});
  table.push_back({{"--preview"}, [&](const std::string& v) { a.preview = nonEmpty("--preview", v); }});
  for (const Exporter& e : exporters()) {
    const std::string flag = "--" + e.name;
    table.push_back(
        {{flag}, [&a, &e, flag](const std::string& v) { a.exports.emplace_back(&e, nonEmpty(flag, v)); }});
  }
  table.push_back({{"--residual"}, [&](const std::string& v) { a.residual = nonEmpty("--residual", v); }});
  bool dome = false;
  table.push_back({{"--usd-dome"}, [&](const std::string& v) {
                     if (v != "none" && v != "reflections" && v != "residual")
                       throw UsageError("--usd-dome takes none, reflections or residual, got '" + v + "'");
                     a.dome = v;
                     dome = true;
                   }});
  bool lightType = false, distance = false;
  table.push_back({{"--light-type"}, [&](const std::string& v) {
                     a.exportAs.kind = parseExportKind("--light-type", v);
                     lightType = true;
                   }});
  table.push_back({{"--distance"}, [&](const std::string& v) {
                     a.exportAs.distance = checkedDistance("--distance", parseReal("--distance", v));
                     distance = true;
                   }});
  table.push_back({{"--out-dir"}, [&](const std::string& v) { a.outDir = nonEmpty("--out-dir", v); }});
  table.push_back(flag({"--previews"}, [&] { a.previews = true; }));
  table.push_back(flag({"-q", "--quiet"}, [&] { a.quiet = true; }));
  const std::vector<std::string> probes = parseOptions(argv, table);
  given.apply(a.request);
  const bool domeFormat =
      std::any_of(a.exports.begin(), a.exports.end(), [](const auto& x) { return x.first->dome; });
  if ((lightType || distance) && a.exports.empty())
    throw UsageError("--light-type and --distance say how the lights are written: add " +
                     exportFlags("", " FILE"));
  if (dome && !domeFormat) throw UsageError("--usd-dome says what --usd writes: add --usd FILE");
  if (a.dome == "residual" && a.residual.empty())
    throw UsageError("--usd-dome residual shows the residual that --residual FILE writes: add it");
  if (distance && a.exportAs.kind != ExportKind::Point)
    throw UsageError("--distance places point lights: add --light-type point");
  // The command line refuses 0, a tolerance that asks nothing.
  if (given.has("max_error") && a.request.accuracy.maxError == 0)
    throw UsageError("--max-error takes an error above 0 (e.g. 1% or 0.01); leave it out to choose --lights");
  a.request.keepPixels = !a.preview.empty() || a.previews;
  if (a.outDir.empty()) {
    if (a.previews)
      throw UsageError("--previews goes with --out-dir (a library bake); one probe takes --preview FILE");
    a.probe = oneProbe(probes, "bake");
    std::vector<std::string> outputs{a.output, a.preview, a.residual};
    for (const auto& x : a.exports) outputs.push_back(x.second);
    refuseOverwritingProbe(a.probe, outputs);
    // The residual without a level: the lamps take what is above 10 x the mean luminance.
    if (!a.residual.empty() && !a.request.takesSources()) a.request.sources = {kDefaultSourceLevel, 0};
  } else {
    if (!a.output.empty() || !a.preview.empty() || !a.exports.empty() || !a.residual.empty())
      throw UsageError(
          "with --out-dir each probe's JSON (and --previews) goes there: drop -o / --preview / " +
          exportFlags(" / ") + " / --residual");
    if (probes.empty()) throw UsageError("no probes given: probelights bake PROBE... --out-dir DIR");
    a.probes = probes;
  }
  return a;
}

void printSummary(const BakeArgs& a, const Probe& probe, const EvaluatedBake& ev, double loadMs) {
  const BakeResult& r = ev.bake;
  std::printf("probe      %s  %dx%d %s\n", a.probe.c_str(), probe.width(), probe.height(),
              toString(probe.projection().kind()).c_str());
  for (const auto& note : probe.report().notes) std::printf("note       %s\n", note.line().c_str());
  for (const auto& note : r.notes) std::printf("note       %s\n", note.line().c_str());
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
  // With sources, the lamps and the residual together give back the probe's light.
  Rgb total = r.totalRgb;
  if (ev.sources) {
    total = probe.hasPixels() ? probe.integral() : total;
    for (int k = 0; k < 3; ++k) sum[k] += ev.sources->residualRgb[k];
  }
  double worst = 0;
  for (int k = 0; k < 3; ++k)
    if (total[k] > 0) worst = std::max(worst, std::abs(sum[k] - total[k]) / total[k]);
  const bool allPositive = total[0] > 0 && total[1] > 0 && total[2] > 0;
  if (ev.sources)
    std::printf(
        "\nsources    the lamps take the light above %.4g (%.3g x the mean luminance): %.1f%% of it; the "
        "residual keeps the rest\n",
        ev.sources->level, ev.sources->level / ev.sources->meanLuminance, 100 * ev.sources->share);
  std::printf("%senergy     probe integral (%.6g, %.6g, %.6g), %s (%.6g, %.6g, %.6g), max rel. diff %.1e%s\n",
              ev.sources ? "" : "\n", total[0], total[1], total[2],
              ev.sources ? "lamps + residual" : "lights sum", sum[0], sum[1], sum[2], worst,
              allPositive ? "" : " (of the channels above 0; see the note)");
  if (ev.evaluated) {
    std::printf("error      ");
    if (ev.effects & kDiffuse) std::printf("diffuse %.2f%%  ", 100 * ev.errors.diffuse);
    if (ev.effects & kShadow) std::printf("shadow %.2f%%  ", 100 * ev.errors.shadow);
    if (ev.effects & kGlossy) std::printf("glossy %.2f%%  ", 100 * ev.errors.glossy);
    std::printf("(relative RMS of luminance vs the probe%s)%s; sun angles: %s\n",
                ev.sources ? ", the residual's own light exact" : "", ev.refit ? ", lights refit" : "",
                toString(ev.sunAngles).c_str());
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

std::string bakeOptionsUsage() {
  return tableUsage(requestOptions(), BakeRequest{},
                    [](const std::string& name) { return std::string(name == "lights" ? ", -n" : ""); });
}

std::string exportOptionsUsage() {
  std::string out;
  for (const Exporter& e : exporters())
    out += usageLines("  --" + e.name + " FILE", "write the lights as " + e.help + " (docs/export.md)");
  std::vector<std::string> kinds;
  for (const LightKind& k : lightKinds()) kinds.push_back(k.name);
  std::string kindWords;
  for (const std::string& k : kinds) kindWords += (kindWords.empty() ? "" : "|") + k;
  char distance[32];
  std::snprintf(distance, sizeof distance, "%g", ExportOptions{}.distance);
  return out +
         usageLines(
             "  --usd-dome none|reflections|residual",
             "a DomeLight: reflections, the probe for reflections alone with the lamps for diffuse light "
             "alone (as the add-on splits them); residual, what --residual FILE keeps, with the lamps "
             "of the sources (default none)") +
         usageLines("  --light-type " + kindWords,
                    "what " + exportFlags() + " write (default " + kinds[0] + ")") +
         usageLines("  --distance M",
                    "--light-type point: metres from the origin (default " + std::string(distance) + ")");
}

int bakeCommand(const std::vector<std::string>& argv) {
  BakeArgs a = parseBakeArgs(argv);
  if (!a.outDir.empty()) return bakeLibrary(a);
  const BakedFile baked = bakeFile(a.probe, a.request);
  const Probe& probe = *baked.probe;
  const EvaluatedBake& done = *baked.result;
  if (a.dome != "none" && probe.projection().kind() != ProjectionKind::LatLong)
    throw Error("--usd-dome " + a.dome + " shows a lat-long dome; '" + a.probe + "' is " +
                toString(probe.projection().kind()) + ": convert it to lat-long first, or drop --usd-dome");
  if (!a.output.empty()) {
    writeJson(bakeToJson({a.probe, probe, a.request.bake, done, baked.loadMs}), a.output, 2);
    if (a.output == "-") a.quiet = true;
  }
  if (!a.preview.empty())
    writeImageWhole(a.preview, [&](const std::string& tmp) { writePreview(probe, done.bake, tmp); });
  if (!a.residual.empty())
    writeImageWhole(a.residual,
                    [&](const std::string& tmp) { writeImage(done.sources->residual->view(), tmp); });
  Rgb dropped{};
  std::vector<std::string> clamping;  // the flags whose files dropped channels below zero
  const char* generator = "probelights " PROBELIGHTS_VERSION;
  for (const auto& [format, file] : a.exports) {
    ExportOptions as = a.exportAs;
    if (format->dome && a.dome != "none") {
      const bool residual = a.dome == "residual";
      as.dome = assetPathFrom(file, residual ? a.residual : a.probe);
      as.domeTakes = residual ? ExportOptions::Dome::Residual : ExportOptions::Dome::Reflections;
    }
    Rgb clamped{};
    writeWhole(file, format->write(done.bake.lights, as, generator, &clamped));
    if (clamped[0] < 0 || clamped[1] < 0 || clamped[2] < 0) {
      dropped = clamped;  // the same lights for every format: the same channels dropped
      clamping.push_back("--" + format->name);
    }
  }
  if (!a.quiet) {
    printSummary(a, probe, done, baked.loadMs);
    if (!clamping.empty())
      std::printf(
          "note       %s: the lights cannot be negative there; channels below zero written as 0 (rgb %.4g, "
          "%.4g, %.4g W/m^2 left out)\n",
          listOf(clamping).c_str(), dropped[0], dropped[1], dropped[2]);
  }
  return 0;
}

}  // namespace probelights::cli
