// What accuracy costs in time: table build + partition + light sums against light count, probe size, method
// and working resolution, next to the cost of one pass that sums the image (the floor any bake pays).
//
//   build/bin/probelights_bench                                  everything
//   build/bin/probelights_bench --benchmark_filter='8192'        one size
// Probes are synthetic (sky gradient, ground, a 3x3-pixel sun ~1e5 x the sky) so every size is available.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "../src/parallel.h"
#include "probelights/bake.h"

namespace {

using namespace probelights;

struct BenchProbe {
  std::vector<float> pixels;
  std::unique_ptr<Probe> probe;
};

const Probe& sunnyProbe(int width) {
  static std::map<int, BenchProbe> cache;
  auto it = cache.find(width);
  if (it != cache.end()) return *it->second.probe;
  BenchProbe& b = cache[width];
  const int W = width, H = width / 2;
  b.pixels.resize(static_cast<std::size_t>(W) * H * 3);
  parallelFor(H, [&](std::int64_t y) {
    double v = (y + 0.5) / H;
    for (int x = 0; x < W; ++x) {
      float* p = &b.pixels[(static_cast<std::size_t>(y) * W + x) * 3];
      bool sun = std::abs(x - W / 3) <= 1 && std::abs(static_cast<int>(y) - H / 5) <= 1;
      if (sun)
        p[0] = 5e4f, p[1] = 4.5e4f, p[2] = 4e4f;
      else if (v > 0.5)
        p[0] = 0.1f + 0.05f * (x % 13) / 13.0f, p[1] = 0.12f, p[2] = 0.08f;
      else
        p[0] = static_cast<float>(0.3 * (1 - v)), p[1] = static_cast<float>(0.5 * (1 - v)), p[2] = 1.0f;
    }
  });
  b.probe = std::make_unique<Probe>(ImageView{b.pixels.data(), W, H, 3}, ProjectionKind::LatLong);
  return *b.probe;
}

// One pass that sums the image: the floor for anything that reads every pixel once.
void BM_SumImage(benchmark::State& state) {
  const Probe& probe = sunnyProbe(static_cast<int>(state.range(0)));
  const ImageView& v = probe.view();
  for (auto _ : state) {
    std::vector<double> rows(v.height);
    parallelFor(v.height, [&](std::int64_t y) {
      const float* p = v.pixel(0, static_cast<int>(y));
      double s = 0;
      for (int i = 0; i < v.width * 3; ++i) s += p[i];
      rows[y] = s;
    });
    double total = 0;
    for (double r : rows) total += r;
    benchmark::DoNotOptimize(total);
  }
}

// Args: probe width, light count, method (0 median cut, 1 variance), working resolution (0 full, 1 auto).
void BM_Bake(benchmark::State& state) {
  const Probe& probe = sunnyProbe(static_cast<int>(state.range(0)));
  BakeOptions o;
  o.lights = static_cast<int>(state.range(1));
  o.method = state.range(2) == 0 ? Method::MedianCut : Method::Variance;
  o.resolution.mode = state.range(3) == 0 ? WorkingResolution::Mode::Full : WorkingResolution::Mode::Auto;
  double tables = 0, partition = 0, lights = 0;
  for (auto _ : state) {
    BakeResult r = bake(probe, o);
    tables += r.timings.tablesMs, partition += r.timings.partitionMs, lights += r.timings.lightsMs;
    benchmark::DoNotOptimize(r.lights.data());
  }
  double n = static_cast<double>(state.iterations());
  state.counters["tables_ms"] = tables / n;
  state.counters["partition_ms"] = partition / n;
  state.counters["lights_ms"] = lights / n;
  state.SetLabel(std::string(o.method == Method::MedianCut ? "median-cut" : "variance") + " " +
                 o.resolution.toString());
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int w : {1024, 2048, 4096, 8192}) b->Arg(w);
}

void bakeGrid(benchmark::internal::Benchmark* b) {
  for (int w : {1024, 2048, 4096, 8192})
    for (int n : {4, 16, 64, 256, 1024})
      for (int method : {0, 1})
        for (int res : {0, 1}) {
          if (w <= 2048 && res == 1) continue;  // auto is full resolution up to 2048 wide
          b->Args({w, n, method, res});
        }
}

BENCHMARK(BM_SumImage)->Apply(sizes)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Bake)
    ->Apply(bakeGrid)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ArgNames({"width", "lights", "method", "auto"});

}  // namespace

BENCHMARK_MAIN();
