#include "probelights/tradeoff.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "probelights/error.h"
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
      const WorkingGrid grid(probe, b);
      for (int n : o.counts) {
        b.lights = n;
        BakeResult r = grid.bake(probe, b);
        const auto resName = usesWorkingGrid(method) ? std::optional<WorkingResolution>(res) : std::nullopt;
        // A row's time includes what finishing its lights took (the angle fit, the refit).
        Stopwatch plain;
        const auto lights = finishLights(evaluator, r.lights, false, false, o.sunAngles);
        rows.push_back({method, n, static_cast<int>(lights.size()), resName, false, bakeMs(r) + plain.ms(),
                        evaluator.evaluate(lights)});
        if (o.refit && (evaluator.effects() & kDiffuse) && r.lights.size() <= kMaxRefitLights) {
          Stopwatch t;
          auto refit = finishLights(evaluator, r.lights, true, /*moveDirections=*/true, o.sunAngles);
          rows.push_back({method, n, static_cast<int>(refit.size()), resName, true, bakeMs(r) + t.ms(),
                          evaluator.evaluate(refit)});
        }
      }
    }
  return rows;
}

}  // namespace probelights
