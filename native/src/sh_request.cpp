#include "probelights/sh_request.h"

#include <string>

#include "probelights/error.h"

namespace probelights {

namespace {

using S = const std::string&;

template <class T>
TableOption<T> bandsOption(const char* help) {
  return {"bands",
          "B",
          help,
          [](T& t, S o, S v) { t.bands = parseCount(o, v); },
          [](const T& t) { return t.bands > 0 ? std::to_string(t.bands) : std::string(); },
          ""};
}

template <class T>
TableOption<T> nonfiniteOption() {
  const RequestOption& o = requestOption("nonfinite");
  return {o.name,
          o.values,
          o.help,
          [](T& t, S, S v) { t.probe.nonFinite = parseNonFinitePolicy(v); },
          [](const T& t) { return toString(t.probe.nonFinite); },
          ""};
}

}  // namespace

void requireBands(int bands) {
  if (bands < 1) throw Error("no SH bands given", Remedy{"give them", "bands", {"B (at least 1)"}});
}

const std::vector<ShOption>& shOptions() {
  using T = ShRequest;
  static const std::vector<ShOption> options{
      bandsOption<T>("SH bands (required): bands^2 coefficients per channel"),
      {"window", "none|hanning|lanczos", "ringing suppression of the coefficients",
       [](T& t, S, S v) { t.window = parseShWindow(v); }, [](const T& t) { return toString(t.window); }, ""},
      {"irradiance", "",
       "the irradiance's coefficients (convolved with the clamped cosine) in place of the radiance's",
       [](T& t, S o, S v) { t.irradiance = parseSwitch(o, v); },
       [](const T& t) { return onOff(t.irradiance); }, ""},
      nonfiniteOption<T>(),
  };
  return options;
}

ShCoefficients shProject(const Probe& probe, const ShRequest& request) {
  requireBands(request.bands);
  ShCoefficients sh = projectProbe(probe, request.bands);
  applyWindow(sh, request.window);
  return request.irradiance ? irradianceCoefficients(sh) : sh;
}

const std::vector<SampleOption>& sampleOptions() {
  using T = SampleRequest;
  static const std::vector<SampleOption> options{
      bandsOption<T>("SH bands (required) of the luminance the sampler follows"),
      {"epsilon", "E",
       "Berger's clamp of each warp step to [epsilon, 1 - epsilon], in [0, 0.5]: every part of the sphere "
       "sampled",
       [](T& t, S o, S v) { t.epsilon = parseReal(o, v); }, [](const T& t) { return realText(t.epsilon); },
       ""},
      {"samples", "N", "how many directions", [](T& t, S o, S v) { t.samples = parseCount(o, v); },
       [](const T& t) { return std::to_string(t.samples); }, ""},
      {"depth", "K", "the warp's levels", [](T& t, S o, S v) { t.depth = parseCount(o, v); },
       [](const T& t) { return std::to_string(t.depth); }, ""},
      {"seed", "S", "the generator's seed: the same seed, the same samples",
       [](T& t, S o, S v) { t.seed = static_cast<std::uint64_t>(parseCount(o, v)); },
       [](const T& t) { return std::to_string(t.seed); }, ""},
      nonfiniteOption<T>(),
  };
  return options;
}

std::vector<ShSampler::Sample> shSamples(const Probe& probe, const SampleRequest& request) {
  requireBands(request.bands);
  return ShSampler(request.bands, projectProbe(probe, request.bands).luminance(), request.epsilon,
                   request.depth)
      .sampleSeeded(request.samples, request.seed);
}

}  // namespace probelights
