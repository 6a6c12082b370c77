// The module's measuring functions: the evaluator's errors of any lights (evaluate.h), the tradeoff grid
// (tradeoff.h), SH projection and importance sampling (spherical_harmonics.h, sh_sampler.h).
#include <pybind11/stl.h>

#include <cmath>

#include "probelights/evaluate.h"
#include "probelights/placement.h"
#include "probelights/sh_request.h"
#include "probelights/tradeoff.h"
#include "shell.h"

namespace probelights::shell {
namespace {

// The errors of any lights against a probe (request.h: evaluateGiven), its keywords the evaluate table's
// options (the CLI's evaluate options).
py::dict evaluateLights(Pixels pixels, const py::dict& lightsDict, const std::string& projection,
                        const py::kwargs& options) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const EvaluateRequest request = fromKeywords(evaluateOptions(), options);
  const std::vector<Light> lights = exportedLights(lightsDict);
  EffectErrors errors;
  {
    py::gil_scoped_release release;
    const Probe probe(view, kind, request.judging.probe.nonFinite);
    errors = evaluateGiven(probe, lights, request);
  }
  const Effects e = request.judging.accuracy.effects;
  py::dict d;
  if (e & kDiffuse) d["diffuse"] = errors.diffuse;
  if (e & kShadow) d["shadow"] = errors.shadow;
  if (e & kGlossy) d["glossy"] = errors.glossy;
  return d;
}

// The tradeoff grid (tradeoff.h) in the layout of the CLI's tradeoff JSON (result_layout.h), its keywords
// the tradeoff table's options (the CLI's tradeoff options).
py::dict tradeoffRows(Pixels pixels, const std::string& projection, const py::kwargs& options) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const TradeoffRequest request = fromKeywords(tradeoffOptions(), options);
  std::vector<TradeoffRow> rows;
  std::optional<Probe> probe;
  {
    py::gil_scoped_release release;
    probe.emplace(view, kind, request.judging.probe.nonFinite);
    rows = tradeoff(*probe, request);
  }
  py::dict d;
  DictWriter writer(d);
  writeTradeoff(writer, {"", *probe, request.judging.accuracy.effects, rows});
  return d;
}

// SH coefficients (bands^2 x 3) of the radiance, or of the irradiance (sh_request.h's table).
py::array_t<double> shProjectPixels(Pixels pixels, const std::string& projection, const py::kwargs& options) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const ShRequest request = fromKeywords(shOptions(), options);
  requireBands(request.bands);
  ShCoefficients sh;
  {
    py::gil_scoped_release release;
    sh = shProject(Probe(view, kind, request.probe.nonFinite), request);
  }
  py::array_t<double> out({static_cast<py::ssize_t>(sh.c.size()), py::ssize_t{3}});
  auto m = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < sh.c.size(); ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = sh.c[i][k];
  return out;
}

// Directions (N, 3) and pdfs (N,) from the SH importance sampler of the probe's luminance, seeded
// (sh_request.h's table).
py::tuple shSamplePixels(Pixels pixels, const std::string& projection, const py::kwargs& options) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const SampleRequest request = fromKeywords(sampleOptions(), options);
  requireBands(request.bands);
  std::vector<ShSampler::Sample> drawn;
  {
    py::gil_scoped_release release;
    drawn = shSamples(Probe(view, kind, request.probe.nonFinite), request);
  }
  py::array_t<double> dirs({static_cast<py::ssize_t>(drawn.size()), py::ssize_t{3}}),
      pdfs(static_cast<py::ssize_t>(drawn.size()));
  auto d = dirs.mutable_unchecked<2>();
  auto p = pdfs.mutable_unchecked<1>();
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    const auto& s = drawn[i];
    d(i, 0) = s.direction.x, d(i, 1) = s.direction.y, d(i, 2) = s.direction.z, p(i) = s.pdf;
  }
  return py::make_tuple(dirs, pdfs);
}

}  // namespace

void defineAnalysis(py::module_& m) {
  static const std::string tradeoffDoc =
      "tradeoff(pixels, *, projection='latlong', **options): what accuracy costs in time, in the layout of "
      "the CLI's tradeoff JSON: source, effects, error, and rows: a dict of columns (method, lights, made, "
      "resolution, refit, bake_ms, each effect's error), one entry per (method, count, resolution, refit). "
      "preset= makes each row as that recipe's bake would." +
      optionsDoc(tradeoffOptions());
  m.def("tradeoff", &tradeoffRows, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        tradeoffDoc.c_str());
  static const std::string evaluateDoc =
      "evaluate(pixels, lights, *, projection='latlong', **options): the errors (relative RMS of luminance, "
      "evaluate.h) of any lights against the probe: a dict {effect: error}. lights: a dict of arrays as a "
      "bake's result has them, direction (N,3), rgb (N,3) (sum of L dOmega) and angle (N,), a sun's full "
      "cone angle in radians (0 or absent: points). A bake's own lights, judged as it was (the same "
      "options, or its preset), give its evaluation's errors." +
      optionsDoc(evaluateOptions());
  m.def("evaluate", &evaluateLights, py::arg("pixels"), py::arg("lights"), py::kw_only(),
        py::arg("projection") = "latlong", evaluateDoc.c_str());
  static const std::string shDoc =
      "sh_project(pixels, *, projection='latlong', **options): real SH coefficients (bands^2 x 3; Sloan "
      "order, orthonormal, Condon-Shortley phase, theta from +Z)." +
      optionsDoc(shOptions());
  m.def("sh_project", &shProjectPixels, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        shDoc.c_str());
  static const std::string sampleDoc =
      "sh_sample(pixels, *, projection='latlong', **options): (directions (N,3), pdf (N,)) from the SH "
      "importance sampler of the probe's luminance (Jarosz et al. 2009 warping, Berger's epsilon clamp)." +
      optionsDoc(sampleOptions());
  m.def("sh_sample", &shSamplePixels, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        sampleDoc.c_str());
}

}  // namespace probelights::shell
