// What the add-on's one click costs after the bake, stage by stage, on the bundled probe (1K) at 16 and 64
// lights with its settings (evaluator 512 wide, energy^2 centroids, refit with directions, fitted angles):
//   BM_Evaluator      the evaluator for the refit: samples, the diffuse and shadow truths
//   BM_FitAngles      fitSunAngles on the bake's lights (the first of finishLights' two)
//   BM_Refit          refitIrradiance with directions moved (colours, dark lights placed, 3 rounds of moves)
//   BM_FinishLights   all of finishLights (angles, refit, angles again, colours again, the keep test)
//   BM_Kernels        one light's kernels on the fit receivers (2048): a fit's unit of work
// and before them, what an 8K click's bake pays on the pixels (the bundled probe blown up to 8192 x 4096
// RGBA, Blender's layout, rows bottom first read through a flipped view as the add-on does):
//   BM_Click8KProbe   the probe from the buffer (its pixels checked: NaN/Inf, negatives)
//   BM_Click8KGrid    the working grid (auto: 2048 x 1024 cells, energy^2 sums)
//   build/bin/probelights_fit_bench
#include <benchmark/benchmark.h>

#include <map>
#include <optional>
#include <utility>

#include "probelights/bake.h"
#include "probelights/image_file.h"

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
  Click& c = cache.try_emplace(lights, loadProbe(PROBELIGHTS_BUNDLED_PROBE)).first->second;
  c.options.lights = lights;
  c.options.centroid = CentroidWeight::Energy2;
  c.grid.emplace(c.probe, c.options);
  c.evaluator.emplace(c.probe, *c.grid->table(), kDiffuse | kShadow, clickEvaluator());
  c.lights = c.grid->bake(c.probe, c.options).lights;
  return c;
}

// The bundled probe, each pixel repeated 8 x 8, as Blender hands an 8K RGBA world image to the add-on.
const std::vector<float>& blender8K() {
  static const std::vector<float> pixels = [] {
    const Probe small = loadProbe(PROBELIGHTS_BUNDLED_PROBE);
    const int W = 8 * small.width(), H = 8 * small.height();
    std::vector<float> p(static_cast<std::size_t>(W) * H * 4);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const Rgb L = small.light(x / 8, y / 8);
        float* q = &p[(static_cast<std::size_t>(H - 1 - y) * W + x) * 4];
        q[0] = static_cast<float>(L[0]), q[1] = static_cast<float>(L[1]), q[2] = static_cast<float>(L[2]);
        q[3] = 1;
      }
    return p;
  }();
  return pixels;
}

ImageView blender8KView() {
  const int W = 8192, H = 4096;
  const std::vector<float>& p = blender8K();
  ImageView v{p.data() + static_cast<std::size_t>(H - 1) * W * 4, W, H, 4};
  v.rowStride = -static_cast<std::ptrdiff_t>(W) * 4;
  return v;
}

void BM_Click8KProbe(benchmark::State& state) {
  const ImageView view = blender8KView();
  for (auto _ : state) benchmark::DoNotOptimize(Probe(view, ProjectionKind::LatLong));
}

void BM_Click8KGrid(benchmark::State& state) {
  const Probe probe(blender8KView(), ProjectionKind::LatLong);
  BakeOptions options;
  options.centroid = CentroidWeight::Energy2;
  for (auto _ : state) benchmark::DoNotOptimize(WorkingGrid(probe, options));
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
  for (auto _ : state)
    benchmark::DoNotOptimize(
        refitIrradiance(*c.evaluator, start, nullptr, RefitOptions{.moveDirections = true}));
}

void BM_FinishLights(benchmark::State& state) {
  Click& c = click(static_cast<int>(state.range(0)));
  std::vector<Light> out;
  for (auto _ : state) out = finishLights(*c.evaluator, c.lights, FinishOptions{SunAngles::Fit, true, true});
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

BENCHMARK(BM_Click8KProbe)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Click8KGrid)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Evaluator)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FitAngles)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Refit)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FinishLights)->Arg(16)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Kernels)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
