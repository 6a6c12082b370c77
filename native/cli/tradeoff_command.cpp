// probelights tradeoff PROBE: what accuracy costs in time, as a table, JSON and a plot (usage in main.cpp).
#include <cstdio>
#include <filesystem>

#include "commands.h"
#include "json_output.h"
#include "options.h"
#include "probelights/evaluate.h"
#include "probelights/image_file.h"
#include "probelights/tradeoff.h"
#include "tradeoff_plot.h"
#include "write_whole.h"

namespace probelights::cli {

std::string tradeoffOptionsUsage() {
  return tableUsage(tradeoffOptions(), TradeoffRequest{}) + usageLines("  --no-refit", "no refit rows");
}

int tradeoffCommand(const std::vector<std::string>& argv) {
  std::string output, plot;
  // The tradeoff's options, from the table the module shares (tradeoff.h), applied after the command line is
  // read in the table's order (a preset first, the options that change it after), then the command's own.
  TradeoffRequest request;
  TableOptions<TradeoffRequest> given(tradeoffOptions());
  std::vector<Option> table;
  given.addTo(table);
  table.push_back(flag({"--no-refit"}, [&] { given.give("refit", "false"); }));
  table.push_back({{"--projection"}, [&](const std::string& v) {
                     request.judging.probe.projection = parseProjectionChoice(v);
                   }});
  table.push_back({{"-o", "--output"}, [&](const std::string& v) { output = nonEmpty("-o", v); }});
  table.push_back({{"--plot"}, [&](const std::string& v) { plot = nonEmpty("--plot", v); }});
  const std::string probePath = oneProbe(parseOptions(argv, table), "tradeoff");
  given.apply(request);
  refuseOverwritingProbe(probePath, {output, plot});

  Probe probe = loadProbe(probePath, request.judging.probe);
  const Effects effects = request.judging.accuracy.effects;
  double truthMs = 0;
  auto rows = tradeoff(probe, request, &truthMs);
  std::printf("probe %s %dx%d; effects %s; ground truth %.0f ms; error = relative RMS of luminance\n\n",
              probePath.c_str(), probe.width(), probe.height(), effectsToString(effects).c_str(), truthMs);
  std::printf("%-11s %6s %6s %5s %10s", "method", "lights", "res", "refit", "bake ms");
  for (auto [bit, name] :
       {std::pair{kDiffuse, "diffuse"}, std::pair{kShadow, "shadow"}, std::pair{kGlossy, "glossy"}})
    if (effects & bit) std::printf(" %9s", name);
  std::printf("\n");
  for (const TradeoffRow& r : rows) {
    std::printf("%-11s %6d %6s %5s %10.2f", toString(r.method).c_str(), r.made,
                r.resolution ? r.resolution->toString().c_str() : "-", r.refit ? "yes" : "no", r.bakeMs);
    for (auto [bit, value] : {std::pair{kDiffuse, r.errors.diffuse}, std::pair{kShadow, r.errors.shadow},
                              std::pair{kGlossy, r.errors.glossy}})
      if (effects & bit) std::printf(" %8.3f%%", 100 * value);
    std::printf("\n");
  }
  if (!output.empty()) writeJson(tradeoffToJson({probePath, probe, effects, rows}), output);
  if (!plot.empty()) {
    writeImageWhole(plot, [&](const std::string& tmp) {
      writeTradeoffPlot(rows, effects,
                        std::filesystem::path(probePath).filename().string() + ": error vs bake time", tmp);
    });
    std::printf("\nplot: %s\n", plot.c_str());
  }
  return 0;
}

}  // namespace probelights::cli
