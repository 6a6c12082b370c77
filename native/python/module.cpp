// _probelights: the thin Python shell over the core (see ../../README.md, "From Python").
// One function per core entry point; the GIL is released around every long call; core errors become
// probelights.Error (a ValueError) with the core's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "probelights/bake.h"
#include "probelights/error.h"
#include "probelights/probe.h"

namespace py = pybind11;
using namespace probelights;

namespace {

template <class T>
T parseOr(const std::optional<T>& v, const std::string& what, const std::string& got, const std::string& choices) {
  if (!v) throw Error("unknown " + what + " '" + got + "': use " + choices);
  return *v;
}

BakeOptions bakeOptions(const std::string& method, int lights, const std::string& centroid,
                        const std::string& resolution, bool horizon) {
  BakeOptions o;
  o.splitAtHorizon = horizon;
  o.method = parseOr(parseMethod(method), "method", method, "median-cut or variance");
  o.lights = lights;
  if (centroid == "energy") o.centroid = CentroidWeight::Energy;
  else if (centroid == "energy2") o.centroid = CentroidWeight::Energy2;
  else throw Error("unknown centroid '" + centroid + "': use energy or energy2");
  o.resolution = parseOr(WorkingResolution::parse(resolution), "resolution", resolution, "full, auto or a width");
  return o;
}

NonFinitePolicy nonFinitePolicy(const std::string& name) {
  if (name == "error") return NonFinitePolicy::Error;
  if (name == "zero") return NonFinitePolicy::Zero;
  throw Error("unknown non-finite policy '" + name + "': use error or zero");
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
  d["direction"] = matrix(r.lights, 3, [](const Light& l) { return std::array{l.direction.x, l.direction.y, l.direction.z}; });
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
  d["timings_ms"] = py::dict(py::arg("tables") = r.timings.tablesMs, py::arg("partition") = r.timings.partitionMs,
                             py::arg("lights") = r.timings.lightsMs);
  return d;
}

// pixels: float32 H x W (grey) or H x W x C (C = 1, 2 grey+alpha, 3 RGB, 4+ RGB + ignored), rows top to bottom.
// Any row and pixel strides (e.g. a flipped view arr[::-1]) are read in place; other dtypes are converted.
py::dict bakePixels(py::array_t<float, py::array::forcecast> pixels, const std::string& projection,
                    const std::string& method, int lights, const std::string& centroid, const std::string& resolution,
                    bool horizon, const std::string& nonfinite) {
  if (pixels.ndim() != 2 && pixels.ndim() != 3)
    throw Error("pixels must be a H x W or H x W x C array, got " + std::to_string(pixels.ndim()) + " dimensions");
  const int channels = pixels.ndim() == 3 ? static_cast<int>(pixels.shape(2)) : 1;
  if (pixels.ndim() == 3 && pixels.shape(2) > 1 && pixels.strides(2) != static_cast<py::ssize_t>(sizeof(float)))
    pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  for (int k = 0; k < 2; ++k)
    if (pixels.strides(k) % static_cast<py::ssize_t>(sizeof(float)) != 0)
      pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  ImageView view{pixels.data(), static_cast<int>(pixels.shape(1)), static_cast<int>(pixels.shape(0)), channels,
                 pixels.strides(0) / static_cast<py::ssize_t>(sizeof(float)),
                 pixels.strides(1) / static_cast<py::ssize_t>(sizeof(float))};
  const auto kind = parseOr(parseProjection(projection), "projection", projection, "latlong, mirror-ball or angular");
  const BakeOptions options = bakeOptions(method, lights, centroid, resolution, horizon);
  const NonFinitePolicy policy = nonFinitePolicy(nonfinite);
  std::optional<Probe> probe;
  BakeResult result;
  {
    py::gil_scoped_release release;
    probe.emplace(view, kind, policy);
    result = bake(*probe, options);
  }
  return toDict(*probe, options, result);
}

py::dict bakeFile(const std::string& path, const std::string& projection, const std::string& method, int lights,
                  const std::string& centroid, const std::string& resolution, bool horizon,
                  const std::string& nonfinite) {
  ProbeOptions probeOptions;
  probeOptions.projection =
      parseOr(parseProjectionChoice(projection), "projection", projection, "auto, latlong, mirror-ball or angular");
  probeOptions.nonFinite = nonFinitePolicy(nonfinite);
  const BakeOptions options = bakeOptions(method, lights, centroid, resolution, horizon);
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

}  // namespace

PYBIND11_MODULE(_probelights, m) {
  m.doc() = "probelights: turn an HDR light probe into N lights that carry exactly its energy";
  py::register_exception<Error>(m, "Error", PyExc_ValueError);
  m.def("bake", &bakePixels, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        py::arg("method") = "variance", py::arg("lights") = 16, py::arg("centroid") = "energy",
        py::arg("resolution") = "auto", py::arg("horizon") = false, py::arg("nonfinite") = "error",
        "Bake a probe given as a float32 H x W x C array (rows top to bottom; not copied). Returns a dict of numpy "
        "arrays: direction (N,3), rgb (N,3), solid_angle, angular_radius, energy_share (N,), rect (N,4), total_rgb (3,), "
        "and metadata (notes, timings_ms, cell_size, ...).");
  m.def("bake_file", &bakeFile, py::arg("path"), py::kw_only(), py::arg("projection") = "auto",
        py::arg("method") = "variance", py::arg("lights") = 16, py::arg("centroid") = "energy",
        py::arg("resolution") = "auto", py::arg("horizon") = false, py::arg("nonfinite") = "error",
        "Read a probe with OpenImageIO and bake it; the same dict as bake(), plus 'path'.");
  m.attr("__version__") = "0.1.0";
}
