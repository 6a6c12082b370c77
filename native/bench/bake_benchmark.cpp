// What accuracy costs in time: table build + partition + light sums against light count, probe size, method
// and working resolution, next to the cost of one pass that sums the image (the floor any bake pays).
//
//   build/bin/probelights_bench                                  everything
//   build/bin/probelights_bench --benchmark_filter='8192'        one size
// Probes are synthetic (sky gradient, ground, a 3x3-pixel sun ~1e5 x the sky) so every size is available.
// Each bake also reports, from the same run, what bounds it on this machine: `x_sum_pass` (its time over one
// pass that sums the image in memory), `fresh_MB` (memory it touched for the first time: minor page faults x
// page size) and `touch_ms` (what first-touching that much costs here, from BM_FirstTouch's measurement).
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>

#include "../src/parallel.h"
#include "probelights/placement.h"

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

double sumImage(const ImageView& v) {
  std::vector<double> rows(v.height);
  parallelFor(v.height, [&](std::int64_t y) {
    const float* p = v.pixel(0, static_cast<int>(y));
    double s = 0;
    for (int i = 0; i < v.width * 3; ++i) s += p[i];
    rows[y] = s;
  });
  double total = 0;
  for (double r : rows) total += r;
  return total;
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The fastest of 5 sum passes over a probe already in memory (ms).
double sumPassMs(const Probe& probe) {
  double best = 1e300;
  for (int i = 0; i < 5; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(sumImage(probe.view()));
    best = std::min(best, msSince(t0));
  }
  return best;
}

// Writing 256 MB the process has never touched (malloc'd, so mmap'd fresh), on one thread: ms per MB, best of
// 3.
double firstTouchMsPerMb() {
  static const double cost = [] {
    const std::size_t mb = 256;
    double best = 1e300;
    for (int i = 0; i < 3; ++i) {
      char* p = static_cast<char*>(std::malloc(mb << 20));
      auto t0 = std::chrono::steady_clock::now();
      std::memset(p, 1, mb << 20);
      best = std::min(best, msSince(t0) / mb);
      benchmark::DoNotOptimize(p);
      std::free(p);
    }
    return best;
  }();
  return cost;
}

long minorFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// One pass that sums the image: the floor for anything that reads every pixel once.
void BM_SumImage(benchmark::State& state) {
  const Probe& probe = sunnyProbe(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(sumImage(probe.view()));
}

// What first-touching fresh memory costs on this machine (the kernel hands out zeroed pages one fault at a
// time).
void BM_FirstTouch(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(firstTouchMsPerMb());
  state.counters["ms_per_MB"] = firstTouchMsPerMb();
}

// Args: probe width, light count, method (0 median cut, 1 variance), working resolution (0 full, 1 auto).
void BM_Bake(benchmark::State& state) {
  const Probe& probe = sunnyProbe(static_cast<int>(state.range(0)));
  BakeOptions o;
  o.lights = static_cast<int>(state.range(1));
  o.method = state.range(2) == 0 ? Method::MedianCut : Method::Variance;
  o.resolution.mode = state.range(3) == 0 ? WorkingResolution::Mode::Full : WorkingResolution::Mode::Auto;
  double tables = 0, partition = 0, lights = 0, total = 0;
  long faults = 0;
  for (auto _ : state) {
    long f0 = minorFaults();
    auto t0 = std::chrono::steady_clock::now();
    BakeResult r = bake(probe, o);
    total += msSince(t0);
    faults += minorFaults() - f0;
    tables += r.timings.tablesMs, partition += r.timings.partitionMs, lights += r.timings.lightsMs;
    benchmark::DoNotOptimize(r.lights.data());
  }
  double n = static_cast<double>(state.iterations());
  state.counters["tables_ms"] = tables / n;
  state.counters["partition_ms"] = partition / n;
  state.counters["lights_ms"] = lights / n;
  state.counters["x_sum_pass"] = total / n / sumPassMs(probe);
  double freshMb = static_cast<double>(faults) / n * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1 << 20);
  state.counters["fresh_MB"] = freshMb;
  state.counters["touch_ms"] = freshMb * firstTouchMsPerMb();
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
BENCHMARK(BM_FirstTouch)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_Bake)
    ->Apply(bakeGrid)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->ArgNames({"width", "lights", "method", "auto"});

}  // namespace

BENCHMARK_MAIN();
