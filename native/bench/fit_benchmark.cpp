// What the add-on's one click costs after the bake, stage by stage, on the bundled probe (1K) at 16 and 64
// lights with its settings (evaluator 512 wide, energy^2 centroids, refit with directions, fitted angles):
//   BM_Evaluator      the evaluator for the refit: samples, the diffuse and shadow truths
//   BM_FitAngles      fitSunAngles on the bake's lights (the first of finishLights' two)
//   BM_Refit          refitIrradiance with directions moved (colours, dark lights placed, 3 rounds of moves)
//   BM_FinishLights   all of finishLights (angles, refit, angles again, colours again, the keep test)
//   BM_Kernels        one light's kernels on the fit receivers (2048): a fit's unit of work
//   build/bin/probelights_fit_bench
#include <benchmark/benchmark.h>

#include <map>
#include <optional>
#include <utility>

#include "probelights/accuracy.h"

namespace {

using namespace probelights;

struct Click {
  explicit Click(Probe p) : probe(std::move(p)) {}
  Probe probe;
  BakeOptions options;
  std::optional<WorkingGrid> grid;
  std::optional<Evaluator> evaluator;
  std::vector<Light> lights;
};

EvaluatorOptions clickEvaluator() { return {512, true, SunProfile::Cone}; }

Click& click(int lights) {
  static std::map<int, Click> cache;
  auto it = cache.find(lights);
  if (it != cache.end()) return it->second;
  Click& c = cache.try_emplace(lights, Probe::load(PROBELIGHTS_BUNDLED_PROBE)).first->second;
  c.options.lights = lights;
  c.options.centroid = CentroidWeight::Energy2;
  c.grid.emplace(c.probe, c.options);
  c.evaluator.emplace(c.probe, *c.grid->table(), kDiffuse | kShadow, clickEvaluator());
  c.lights = c.grid->bake(c.probe, c.options).lights;
  return c;
}

void BM_Evaluator(benchmark::State& state) {
  Click& c = click(16);
  for (auto _ : state) {
    Evaluator e(c.probe, *c.grid->table(), kDiffuse | kShadow, clickEvaluator());
    benchmark::DoNotOptimize(e);
  }
}

void BM_FitAngles(benchmark::State& state) {
  Click& c = click(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    std::vector<Light> lights = c.lights;
    fitSunAngles(*c.evaluator, lights, true);
    benchmark::DoNotOptimize(lights);
  }
}

void BM_Refit(benchmark::State& state) {
  Click& c = click(static_cast<int>(state.range(0)));
  std::vector<Light> start = c.lights;
  fitSunAngles(*c.evaluator, start, true);
  for (auto _ : state) benchmark::DoNotOptimize(refitIrradiance(*c.evaluator, start, nullptr, true));
}

void BM_FinishLights(benchmark::State& state) {
  Click& c = click(static_cast<int>(state.range(0)));
  std::vector<Light> out;
  for (auto _ : state) out = finishLights(*c.evaluator, c.lights, true, true, SunAngles::Fit);
  const EffectErrors e = c.evaluator->evaluate(out);
  state.counters["diffuse_pct"] = 100 * e.diffuse;
  state.counters["shadow_pct"] = 100 * e.shadow;
}

void BM_Kernels(benchmark::State& state) {
  Click& c = click(64);
  const std::vector<Receiver> receivers = c.evaluator->fitReceivers(true);
  std::vector<Light> lights = c.lights;
  fitSunAngles(*c.evaluator, lights, true);
  std::vector<double> out;
  for (auto _ : state)
    for (const Light& l : lights) c.evaluator->kernels(l, receivers, 1.0, out);
  state.counters["ns_per_kernel"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * lights.size() * receivers.size(),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Evaluator)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FitAngles)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Refit)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FinishLights)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Kernels)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
