#include "probelights/tradeoff.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "probelights/error.h"
#include "probelights/names.h"
#include "probelights/stopwatch.h"

namespace probelights {

namespace {
double bakeMs(const BakeResult& r) { return r.timings.tablesMs + r.timings.partitionMs + r.timings.lightsMs; }
}  // namespace

std::vector<TradeoffRow> tradeoff(const Probe& probe, const Evaluator& evaluator, const TradeoffOptions& o) {
  for (int n : o.counts) checkLightCount(n);
  std::vector<TradeoffRow> rows;
  for (Method method : o.methods)
    for (const WorkingResolution& res : o.resolutions) {
      // A method that cuts no working grid (sh): one resolution is enough.
      if (!usesWorkingGrid(method) && &res != &o.resolutions.front()) continue;
      // One working grid per resolution for every count; each row's time still includes its build, so a row
      // says what one bake at that count costs.
      BakeOptions b;
      b.method = method;
      b.resolution = res;
      b.centroid = o.centroid;
      const WorkingGrid grid(probe, b);
      for (int n : o.counts) {
        b.lights = n;
        BakeResult r = grid.bake(probe, b);
        const auto resName = usesWorkingGrid(method) ? std::optional<WorkingResolution>(res) : std::nullopt;
        // A row's time includes what finishing its lights took (the angle fit, the refit).
        Stopwatch plain;
        const auto lights = finishLights(evaluator, r.lights, FinishOptions{o.sunAngles});
        rows.push_back({method, n, static_cast<int>(lights.size()), resName, false, bakeMs(r) + plain.ms(),
                        evaluator.evaluate(lights)});
        const FinishOptions refitted{o.sunAngles, true, /*moveDirections=*/true};
        if (o.refit && (evaluator.effects() & kDiffuse) && refitted.refits(r.lights.size())) {
          Stopwatch t;
          auto refit = finishLights(evaluator, r.lights, refitted);
          rows.push_back({method, n, static_cast<int>(refit.size()), resName, true, bakeMs(r) + t.ms(),
                          evaluator.evaluate(refit)});
        }
      }
    }
  return rows;
}

BakeRequest tradeoffJudging() {
  BakeRequest r;
  r.accuracy.effects = kDiffuse | kShadow;
  r.accuracy.refit = true;
  return r;
}

namespace {

// A comma-separated list of `parse`d items ("4,16,64"), none empty.
template <class T, class Parse>
std::vector<T> listOption(const std::string& option, const std::string& text, Parse parse) {
  std::vector<T> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    if (item.empty()) throw Error(option + " takes a comma-separated list, got '" + text + "'");
    out.push_back(parse(item));
    at = comma + 1;
  }
  return out;
}

template <class T, class Show>
std::string listText(const std::vector<T>& items, Show show) {
  std::string out;
  for (const T& item : items) {
    if (!out.empty()) out += ',';
    out += show(item);
  }
  return out;
}

std::vector<TradeoffOption> makeTradeoffOptions() {
  using T = TradeoffRequest;
  using S = const std::string&;
  std::vector<TradeoffOption> table{
      {"counts", "N,N,...", "the light counts of the grid",
       [](T& t, S o, S v) { t.grid.counts = listOption<int>(o, v, [&](S c) { return parseCount(o, c); }); },
       [](const T& t) { return listText(t.grid.counts, [](int n) { return std::to_string(n); }); }, ""},
      {"methods", "M,M,...", "the cuts of the grid (the --method names)",
       [](T& t, S o, S v) { t.grid.methods = listOption<Method>(o, v, [](S m) { return parseMethod(m); }); },
       [](const T& t) { return listText(t.grid.methods, [](Method m) { return toString(m); }); }, ""},
      {"resolutions", "R,R,...", "the working resolutions of the grid (the --resolution values)",
       [](T& t, S o, S v) {
         t.grid.resolutions =
             listOption<WorkingResolution>(o, v, [](S r) { return WorkingResolution::parse(r); });
       },
       [](const T& t) {
         return listText(t.grid.resolutions, [](const WorkingResolution& r) { return r.toString(); });
       },
       ""},
  };
  for (const char* name : {"preset", "effects", "refit", "evaluator_width", "centroid", "sun_angles",
                           "sun_profile", "sun_cones", "nonfinite"})
    table.push_back(judgingOption<TradeoffRequest>(name));
  return table;
}

}  // namespace

const std::vector<TradeoffOption>& tradeoffOptions() {
  static const std::vector<TradeoffOption> options = makeTradeoffOptions();
  return options;
}

const TradeoffOption& tradeoffOption(const std::string& name) { return tableOption(tradeoffOptions(), name); }

std::vector<TradeoffRow> tradeoff(const Probe& probe, const TradeoffRequest& request, double* evaluatorMs) {
  const AccuracyOptions& a = request.judging.accuracy;
  TradeoffOptions grid = request.grid;
  grid.refit = a.refit;
  grid.sunAngles = a.sunAngles;
  grid.centroid = request.judging.bake.centroid;
  Stopwatch truth;
  const Evaluator evaluator(probe, a.effects,
                            EvaluatorOptions{a.evaluatorWidth, a.refit, a.sunProfile, a.sunCones});
  if (evaluatorMs) *evaluatorMs = truth.ms();
  return tradeoff(probe, evaluator, grid);
}

}  // namespace probelights
