// _probelights: the thin Python shell over the core (see ../../README.md, "From Python").
// Built twice (native/CMakeLists.txt): the full module also reads files (bake_file, PROBELIGHTS_MODULE_IO=1);
// the add-on's portable build takes pixels only and links no OpenImageIO. One function per core entry point;
// the GIL is released around every long call; core errors become probelights.Error (a ValueError) with the
// core's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/evaluate.h"
#include "probelights/probe.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"
#include "probelights/tradeoff.h"

namespace py = pybind11;
using namespace probelights;

namespace {

BakeOptions bakeOptions(const std::string& method, int lights, const std::string& centroid,
                        const std::string& resolution, bool horizon, int bands = 8, double epsilon = 0.01) {
  BakeOptions o;
  o.splitAtHorizon = horizon;
  o.shBands = bands;
  o.shEpsilon = epsilon;
  o.method = parseMethod(method);
  o.lights = lights;
  o.centroid = parseCentroid(centroid);
  o.resolution = WorkingResolution::parse(resolution);
  return o;
}

py::array_t<double> matrix(const std::vector<Light>& lights, int columns, auto&& row) {
  py::array_t<double> a({static_cast<py::ssize_t>(lights.size()), static_cast<py::ssize_t>(columns)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < lights.size(); ++i) {
    auto values = row(lights[i]);
    for (int k = 0; k < columns; ++k) m(i, k) = values[k];
  }
  return a;
}

py::array_t<double> vector(const std::vector<Light>& lights, auto&& value) {
  py::array_t<double> a(static_cast<py::ssize_t>(lights.size()));
  auto m = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < lights.size(); ++i) m(i) = value(lights[i]);
  return a;
}

py::dict toDict(const Probe& probe, const BakeOptions& o, const BakeResult& r) {
  py::dict d;
  d["direction"] = matrix(r.lights, 3, [](const Light& l) {
    return std::array{l.direction.x, l.direction.y, l.direction.z};
  });
  d["rgb"] = matrix(r.lights, 3, [](const Light& l) { return l.rgb; });
  d["solid_angle"] = vector(r.lights, [](const Light& l) { return l.solidAngle; });
  d["angular_radius"] = vector(r.lights, [](const Light& l) { return l.angularRadius; });
  d["energy_share"] = vector(r.lights, [](const Light& l) { return l.energyShare; });
  py::array_t<int> rect({static_cast<py::ssize_t>(r.lights.size()), py::ssize_t{4}});
  auto m = rect.mutable_unchecked<2>();
  for (std::size_t i = 0; i < r.lights.size(); ++i) {
    const Rect& q = r.lights[i].rect;
    m(i, 0) = q.x0, m(i, 1) = q.y0, m(i, 2) = q.x1, m(i, 3) = q.y1;
  }
  d["rect"] = rect;
  d["total_rgb"] = py::array_t<double>(3, r.totalRgb.data());
  d["method"] = toString(o.method);
  d["projection"] = toString(probe.projection().kind());
  d["width"] = probe.width();
  d["height"] = probe.height();
  d["cell_size"] = r.cellSize;
  d["horizon_split"] = r.horizonSplit;
  d["negative_samples"] = probe.report().negativeSamples;
  d["non_finite_samples"] = probe.report().nonFiniteSamples;
  std::vector<std::string> notes = probe.report().notes;
  notes.insert(notes.end(), r.notes.begin(), r.notes.end());
  d["notes"] = notes;
  d["timings_ms"] =
      py::dict(py::arg("tables") = r.timings.tablesMs, py::arg("partition") = r.timings.partitionMs,
               py::arg("lights") = r.timings.lightsMs);
  return d;
}

using Pixels = py::array_t<float, py::array::forcecast>;

// pixels: float32 H x W (grey) or H x W x C (C = 1, 2 grey+alpha, 3 RGB, 4+ RGB + ignored), rows top to
// bottom. Any row and pixel strides (e.g. a flipped view arr[::-1]) are read in place; other dtypes are
// converted.
ImageView viewOf(Pixels& pixels) {
  if (pixels.ndim() != 2 && pixels.ndim() != 3)
    throw Error("pixels must be a H x W or H x W x C array, got " + std::to_string(pixels.ndim()) +
                " dimensions");
  const int channels = pixels.ndim() == 3 ? static_cast<int>(pixels.shape(2)) : 1;
  if (pixels.ndim() == 3 && pixels.shape(2) > 1 &&
      pixels.strides(2) != static_cast<py::ssize_t>(sizeof(float)))
    pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  for (int k = 0; k < 2; ++k)
    if (pixels.strides(k) % static_cast<py::ssize_t>(sizeof(float)) != 0)
      pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  return ImageView{pixels.data(),
                   static_cast<int>(pixels.shape(1)),
                   static_cast<int>(pixels.shape(0)),
                   channels,
                   pixels.strides(0) / static_cast<py::ssize_t>(sizeof(float)),
                   pixels.strides(1) / static_cast<py::ssize_t>(sizeof(float))};
}

// The accuracy options (tradeoff.h): errors are added to the dict as "errors" {effect: rms}, "energy_shift",
// "auto_count" {met, lights, tried}.
void addEvaluation(py::dict& d, const EvaluatedBake& e) {
  if (!e.evaluated) return;
  py::dict errors;
  if (e.effects & kDiffuse) errors["diffuse"] = e.errors.diffuse;
  if (e.effects & kShadow) errors["shadow"] = e.errors.shadow;
  if (e.effects & kGlossy) errors["glossy"] = e.errors.glossy;
  d["errors"] = errors;
  d["energy_shift"] = e.energyShift;
  if (e.autoCount)
    d["auto_count"] =
        py::dict(py::arg("met") = e.met, py::arg("lights") = e.lights, py::arg("tried") = e.tried);
}

AccuracyOptions accuracyOptions(const std::string& effects, bool evaluate, bool refit, double maxError,
                                int evaluatorWidth, bool moveDirections) {
  return {parseEffects(effects), evaluate, refit || moveDirections, maxError, evaluatorWidth, moveDirections};
}

py::dict bakePixels(Pixels pixels, const std::string& projection, const std::string& method, int lights,
                    const std::string& centroid, const std::string& resolution, bool horizon, int bands,
                    double epsilon, const std::string& effects, bool evaluate, bool refit,
                    bool moveDirections, double maxError, int evaluatorWidth, const std::string& nonfinite) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const BakeOptions options = bakeOptions(method, lights, centroid, resolution, horizon, bands, epsilon);
  const NonFinitePolicy policy = parseNonFinitePolicy(nonfinite);
  const AccuracyOptions accuracy =
      accuracyOptions(effects, evaluate, refit, maxError, evaluatorWidth, moveDirections);
  std::optional<Probe> probe;
  EvaluatedBake result;
  {
    py::gil_scoped_release release;
    probe.emplace(view, kind, policy);
    result = bakeEvaluated(*probe, options, accuracy);
  }
  BakeOptions used = options;
  used.lights = result.lights;
  py::dict d = toDict(*probe, used, result.bake);
  addEvaluation(d, result);
  return d;
}

#if PROBELIGHTS_MODULE_IO
py::dict bakeFile(const std::string& path, const std::string& projection, const std::string& method,
                  int lights, const std::string& centroid, const std::string& resolution, bool horizon,
                  int bands, double epsilon, const std::string& nonfinite) {
  ProbeOptions probeOptions;
  probeOptions.projection = parseProjectionChoice(projection);
  probeOptions.nonFinite = parseNonFinitePolicy(nonfinite);
  const BakeOptions options = bakeOptions(method, lights, centroid, resolution, horizon, bands, epsilon);
  std::optional<Probe> probe;
  BakeResult result;
  {
    py::gil_scoped_release release;
    probe.emplace(Probe::load(path, probeOptions));
    result = bake(*probe, options);
  }
  py::dict d = toDict(*probe, options, result);
  d["path"] = path;
  return d;
}
#endif

// The tradeoff grid (tradeoff.h) as a list of dicts: method, lights, made, resolution, refit, bake_ms, and
// the errors.
py::list tradeoffRows(Pixels pixels, const std::string& projection, const std::string& effects,
                      const std::vector<int>& counts, const std::vector<std::string>& methods, bool refit,
                      int evaluatorWidth, const std::string& nonfinite) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const NonFinitePolicy policy = parseNonFinitePolicy(nonfinite);
  TradeoffOptions options;
  options.counts = counts;
  options.methods.clear();
  for (const auto& m : methods) options.methods.push_back(parseMethod(m));
  options.resolutions = {WorkingResolution{}};  // auto
  options.refit = refit;
  const unsigned e = parseEffects(effects);
  std::vector<TradeoffRow> rows;
  {
    py::gil_scoped_release release;
    Probe probe(view, kind, policy);
    Evaluator evaluator(probe, e, EvaluatorOptions{evaluatorWidth, refit});
    rows = tradeoff(probe, evaluator, options);
  }
  py::list out;
  for (const TradeoffRow& r : rows) {
    py::dict d(py::arg("method") = toString(r.method), py::arg("lights") = r.lights, py::arg("made") = r.made,
               py::arg("resolution") = r.resolution, py::arg("refit") = r.refit,
               py::arg("bake_ms") = r.bakeMs);
    if (e & kDiffuse) d["diffuse"] = r.errors.diffuse;
    if (e & kShadow) d["shadow"] = r.errors.shadow;
    if (e & kGlossy) d["glossy"] = r.errors.glossy;
    out.append(d);
  }
  return out;
}

// SH coefficients (bands^2 x 3) of the radiance, or of the irradiance.
py::array_t<double> shProject(Pixels pixels, int bands, const std::string& projection,
                              const std::string& window, bool irradiance, const std::string& nonfinite) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const ShWindow w = parseShWindow(window);
  const NonFinitePolicy policy = parseNonFinitePolicy(nonfinite);
  ShCoefficients sh;
  {
    py::gil_scoped_release release;
    Probe probe(view, kind, policy);
    sh = projectProbe(probe, bands);
    applyWindow(sh, w);
    if (irradiance) sh = irradianceCoefficients(sh);
  }
  py::array_t<double> out({static_cast<py::ssize_t>(sh.c.size()), py::ssize_t{3}});
  auto m = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < sh.c.size(); ++i)
    for (int k = 0; k < 3; ++k) m(i, k) = sh.c[i][k];
  return out;
}

// Directions (N, 3) and pdfs (N,) from the SH importance sampler of the probe's luminance; u (N, 2) in
// [0,1)^2 or, if not given, `samples` points from a seeded generator.
py::tuple shSample(Pixels pixels, int bands, double epsilon, int samples, int depth, std::uint64_t seed,
                   const std::string& projection, const std::string& nonfinite) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const NonFinitePolicy policy = parseNonFinitePolicy(nonfinite);
  std::vector<ShSampler::Sample> drawn;
  {
    py::gil_scoped_release release;
    Probe probe(view, kind, policy);
    drawn =
        ShSampler(bands, projectProbe(probe, bands).luminance(), epsilon, depth).sampleSeeded(samples, seed);
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

PYBIND11_MODULE(_probelights, m) {
  m.doc() = "probelights: turn an HDR light probe into N lights that carry exactly its energy";
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.def("tradeoff", &tradeoffRows, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        py::arg("effects") = "diffuse,shadow",
        py::arg("counts") = std::vector<int>{4, 8, 16, 32, 64, 128, 256},
        py::arg("methods") = std::vector<std::string>{"median-cut", "variance", "sh"},
        py::arg("refit") = true, py::arg("evaluator_width") = 2048, py::arg("nonfinite") = "error",
        "What accuracy costs in time: one row per (method, count, refit) with bake_ms and each effect's "
        "error.");
  m.def("bake", &bakePixels, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        py::arg("method") = "variance", py::arg("lights") = 16, py::arg("centroid") = "energy",
        py::arg("resolution") = "auto", py::arg("horizon") = false, py::arg("bands") = 8,
        py::arg("epsilon") = 0.01, py::arg("effects") = "diffuse", py::arg("evaluate") = false,
        py::arg("refit") = false, py::arg("move_directions") = false, py::arg("max_error") = 0.0,
        py::arg("evaluator_width") = 2048, py::arg("nonfinite") = "error",
        "Bake a probe given as a float32 H x W x C array (rows top to bottom; not copied). Returns a dict of "
        "numpy "
        "arrays: direction (N,3), rgb (N,3), solid_angle, angular_radius, energy_share (N,), rect (N,4), "
        "total_rgb (3,), "
        "and metadata (notes, timings_ms, cell_size, ...). evaluate/refit/max_error add 'errors' on "
        "`effects`.");
#if PROBELIGHTS_MODULE_IO
  m.def("bake_file", &bakeFile, py::arg("path"), py::kw_only(), py::arg("projection") = "auto",
        py::arg("method") = "variance", py::arg("lights") = 16, py::arg("centroid") = "energy",
        py::arg("resolution") = "auto", py::arg("horizon") = false, py::arg("bands") = 8,
        py::arg("epsilon") = 0.01, py::arg("nonfinite") = "error",
        "Read a probe with OpenImageIO and bake it; the same dict as bake(), plus 'path'.");
#endif
  m.def(
      "sh_project", &shProject, py::arg("pixels"), py::kw_only(), py::arg("bands"),
      py::arg("projection") = "latlong", py::arg("window") = "none", py::arg("irradiance") = false,
      py::arg("nonfinite") = "error",
      "Real SH coefficients (bands^2 x 3; Sloan order, orthonormal, Condon-Shortley phase, theta from +Z).");
  m.def(
      "sh_sample", &shSample, py::arg("pixels"), py::kw_only(), py::arg("bands"), py::arg("epsilon") = 0.01,
      py::arg("samples") = 1024, py::arg("depth") = 8, py::arg("seed") = 1, py::arg("projection") = "latlong",
      py::arg("nonfinite") = "error",
      "(directions (N,3), pdf (N,)) from the SH importance sampler of the probe's luminance (Berger 2011).");
  m.attr("__version__") = PROBELIGHTS_VERSION;
  // "full": reads files with OpenImageIO (bake_file); "pixels": the portable build inside the Blender add-on,
  // which links nothing but the C library and takes pixels only.
  m.attr("build") = PROBELIGHTS_MODULE_IO ? "full" : "pixels";
}
