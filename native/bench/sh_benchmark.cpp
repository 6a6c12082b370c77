// Spherical harmonics: what the SH sampler buys a Monte Carlo renderer, and what it costs.
//   build/bin/probelights_sh_bench
// BM_IrradianceVariance: per-sample variance of the irradiance estimator on real sunny probes (exact, no
// random numbers; sh_variance.h) for uniform sampling, the function offset until positive (Jarosz et al.'s
// remedy) and Berger's epsilon clamping, as counters; "x_uniform" and "x_offset" are how many times fewer
// samples the clamped sampler needs for the same noise. BM_Project / BM_Sample: the time a projection and a
// sample cost.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <random>

#include "probelights/image_file.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"
#include "probelights_reference/offset_until_positive.h"
#include "probelights_reference/sh_variance.h"

namespace {

using namespace probelights;

const char* kProbes[] = {PROBELIGHTS_BUNDLED_PROBE, PROBELIGHTS_SHARED_HDRI "/KernerEnvLatLong.exr",
                         PROBELIGHTS_SHARED_HDRI "/thatch_chapel_1k.hdr"};

const Probe& probe(int i) {
  static std::map<int, Probe> cache;
  auto it = cache.find(i);
  if (it == cache.end()) it = cache.emplace(i, loadProbe(kProbes[i])).first;
  return it->second;
}

const Vec3 kNormals[] = {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}};
const char* kNormalNames[] = {"up", "horizontal", "down"};

// Args: probe index, bands, 100 x epsilon, normal index.
void BM_IrradianceVariance(benchmark::State& state) {
  const int index = static_cast<int>(state.range(0)), bands = static_cast<int>(state.range(1));
  const double epsilon = state.range(2) / 100.0;
  const Vec3 normal = kNormals[state.range(3)];
  if (!std::filesystem::exists(kProbes[index])) {
    state.SkipWithError("probe not found");
    return;
  }
  const Probe& p = probe(index);
  std::vector<double> c = projectProbe(p, bands).luminance();
  ShSampler berger(bands, c, epsilon, 8), offset(bands, reference::offsetUntilPositive(bands, c), 0.0, 8);
  reference::EstimatorVariance u{}, o{}, b{};
  for (auto _ : state) {
    u = reference::irradianceEstimatorVariance(p, normal, [](const Vec3&) { return 1 / (4 * kPi); });
    o = reference::irradianceEstimatorVariance(p, normal, [&](const Vec3& d) { return offset.pdf(d); });
    b = reference::irradianceEstimatorVariance(p, normal, [&](const Vec3& d) { return berger.pdf(d); });
  }
  const double e2 = u.irradiance * u.irradiance;
  state.counters["relvar_uniform"] = u.variance / e2;
  state.counters["relvar_offset"] = o.variance / e2;
  state.counters["relvar_sh"] = b.variance / e2;
  state.counters["x_uniform"] = u.variance / b.variance;
  state.counters["x_offset"] = o.variance / b.variance;
  state.SetLabel(std::filesystem::path(kProbes[index]).filename().string() + ", normal " +
                 kNormalNames[state.range(3)] + ", depth 8");
}

void BM_Project(benchmark::State& state) {
  const Probe& p = probe(0);
  for (auto _ : state) benchmark::DoNotOptimize(projectProbe(p, static_cast<int>(state.range(0))).c.data());
}

void BM_Sample(benchmark::State& state) {
  const int bands = static_cast<int>(state.range(0));
  ShSampler sampler(bands, projectProbe(probe(0), bands).luminance(), 0.01, 8);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  for (auto _ : state) benchmark::DoNotOptimize(sampler.sample({u(rng), u(rng)}).pdf);
}

BENCHMARK(BM_IrradianceVariance)
    ->ArgsProduct({{0, 1, 2}, {4, 8, 12}, {1, 10}, {0, 1, 2}})
    ->ArgNames({"probe", "bands", "eps_x100", "normal"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_Project)->Arg(4)->Arg(8)->Arg(16)->Arg(20)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Sample)->Arg(4)->Arg(8)->Arg(16);

}  // namespace

BENCHMARK_MAIN();
