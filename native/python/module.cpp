// _probelights: the thin Python shell over the core (see ../../README.md, "From Python").
// Built twice (native/CMakeLists.txt): the full module also reads files (bake_file, PROBELIGHTS_MODULE_IO=1);
// the add-on's portable build takes pixels only and links no OpenImageIO. One function per core entry point;
// the GIL is released around every long call; core errors become probelights.Error (a ValueError) with the
// core's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>

#include "probelights/placement.h"
#if PROBELIGHTS_MODULE_IO
#include "probelights/bake_file.h"
#include "probelights/batch.h"
#endif
#include "probelights/error.h"
#include "probelights/evaluate.h"
#include "probelights/light_export.h"
#include "probelights/memory.h"
#include "probelights/names.h"
#include "probelights/probe.h"
#include "probelights/refit.h"
#include "probelights/request.h"
#include "probelights/result_layout.h"
#include "probelights/sh_sampler.h"
#include "probelights/spherical_harmonics.h"
#include "probelights/tradeoff.h"

#if PROBELIGHTS_MODULE_CLI
namespace probelights::cli {
int run(const std::vector<std::string>& args);  // native/cli/command_line.cpp
}
#endif

namespace py = pybind11;
using namespace probelights;

namespace {

// A failure's remedy (error.h) in the module's words: "nonfinite='zero'", "projection='latlong',
// 'mirror-ball' or 'angular'".
std::string spelled(const Remedy& remedy) {
  std::vector<std::string> values;
  for (const std::string& v : remedy.values) values.push_back("'" + v + "'");
  return remedy.option + "=" + listOf(values);
}

// Text for Python: UTF-8, or as os.fsdecode has bytes that are not (a file name's; surrogates, so that the
// str names the same file again) rather than a UnicodeDecodeError that loses the result.
py::str fsText(const std::string& s) {
  PyObject* o = PyUnicode_DecodeFSDefaultAndSize(s.data(), static_cast<Py_ssize_t>(s.size()));
  if (!o) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(o);
}

// Writes the core's result layout (result_layout.h) into nested dicts; a table becomes a dict of numpy
// arrays, one per column ((N,) for a scalar column, (N, width) otherwise), so its keys are the JSON rows'
// keys.
class DictWriter : public ResultWriter {
 public:
  explicit DictWriter(py::dict root) { stack_.push_back(root); }
  void begin(const char* key) override {
    py::dict d;
    stack_.back()[key] = d;
    stack_.push_back(d);
  }
  void end() override { stack_.pop_back(); }
  void null(const char* key) override { stack_.back()[key] = py::none(); }
  void number(const char* key, double v) override { stack_.back()[key] = v; }
  void integer(const char* key, long long v) override { stack_.back()[key] = v; }
  void boolean(const char* key, bool v) override { stack_.back()[key] = v; }
  void text(const char* key, const std::string& v) override { stack_.back()[key] = fsText(v); }
  void notes(const char* key, const std::vector<Note>& v) override {
    py::list list;
    for (const Note& n : v)
      list.append(py::dict(py::arg("kind") = toString(n.kind), py::arg("text") = fsText(n.text),
                           py::arg("detail") = fsText(n.detail)));
    stack_.back()[key] = list;
  }
  void numbers(const char* key, std::span<const double> v) override {
    stack_.back()[key] = py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());
  }
  void table(const char* key, std::size_t rows, const std::vector<ResultColumn>& columns) override {
    py::dict t;
    double values[16];
    for (const ResultColumn& c : columns) {
      if (c.kind == ResultColumn::Kind::Text) {
        py::list words;
        for (std::size_t i = 0; i < rows; ++i) words.append(c.text(i));
        t[c.key] = words;
        continue;
      }
      std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(rows)};
      if (c.width > 1) shape.push_back(c.width);
      auto fill = [&](auto array) {
        auto* data = array.mutable_data();
        for (std::size_t i = 0; i < rows; ++i) {
          c.fill(i, values);
          for (int k = 0; k < c.width; ++k)
            data[i * c.width + k] = static_cast<std::remove_reference_t<decltype(data[0])>>(values[k]);
        }
        t[c.key] = array;
      };
      if (c.kind == ResultColumn::Kind::Integer)
        fill(py::array_t<long long>(shape));
      else if (c.kind == ResultColumn::Kind::Boolean)
        fill(py::array_t<bool>(shape));
      else
        fill(py::array_t<double>(shape));
    }
    stack_.back()[key] = t;
  }

 private:
  std::vector<py::dict> stack_;
};

#if PROBELIGHTS_MODULE_IO
// A path from Python as the file system has it: str (with os.fsdecode's surrogates for bytes that are not
// UTF-8), bytes or os.PathLike, through os.fsencode; a NUL in it is refused (the file system would cut it).
std::string fsPath(const py::handle& p) {
  const std::string s = py::module_::import("os").attr("fsencode")(p).cast<std::string>();
  if (s.find('\0') != std::string::npos) throw Error("a path holds a NUL character");
  return s;
}
#endif

py::dict toDict(const std::string& path, const Probe& probe, const BakeOptions& options,
                const EvaluatedBake& bake, double loadMs = 0) {
  py::dict d;
  DictWriter writer(d);
  writeBake(writer, {path, probe, options, bake, loadMs});
  if (bake.sources) {
    // The residual image itself (H x W x 3 float32, read-only), sharing the bake's memory.
    const auto image = bake.sources->residual;
    auto* keep = new std::shared_ptr<const Image>(image);
    py::capsule owner(keep, [](void* p) { delete static_cast<std::shared_ptr<const Image>*>(p); });
    const auto f = static_cast<py::ssize_t>(sizeof(float));
    py::array_t<float> residual(
        {static_cast<py::ssize_t>(image->height), static_cast<py::ssize_t>(image->width), py::ssize_t{3}},
        {image->width * 3 * f, 3 * f, f}, image->pixels.get(), owner);
    residual.attr("flags").attr("writeable") = false;
    d["sources"].cast<py::dict>()["residual"] = residual;
  }
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
  // A stride that is not a whole number of floats, or 0 (a broadcast view repeats one row or pixel; the
  // view's 0 means "contiguous" and would read past the array): copied into a C-contiguous array first.
  for (int k = 0; k < 2; ++k)
    if (pixels.strides(k) % static_cast<py::ssize_t>(sizeof(float)) != 0 || pixels.strides(k) == 0)
      pixels = py::array_t<float, py::array::forcecast | py::array::c_style>::ensure(pixels);
  return ImageView{pixels.data(),
                   static_cast<int>(pixels.shape(1)),
                   static_cast<int>(pixels.shape(0)),
                   channels,
                   pixels.strides(0) / static_cast<py::ssize_t>(sizeof(float)),
                   pixels.strides(1) / static_cast<py::ssize_t>(sizeof(float))};
}

// A keyword's value as its option's text (request.h): a switch from a bool, a number as Python writes it (its
// repr reads back as the same double), a word as it is.
std::string optionText(const std::string& name, const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__index__")) return py::str(py::int_(py::reinterpret_borrow<py::object>(value)));
  if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
  throw Error(name + " takes " +
              (requestOption(name).isSwitch() ? "True or False" : requestOption(name).values) + ", got a " +
              py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
}

// The request the keywords ask for, every other option at its default (request.h: one table for the module
// and the CLI). Options are applied in the table's order, whatever the keywords' order.
BakeRequest requestFrom(const py::kwargs& kwargs) {
  for (const auto& item : kwargs) {
    const std::string key = item.first.cast<std::string>();
    bool known = false;
    for (const RequestOption& o : requestOptions()) known = known || o.name == key;
    if (!known) {
      std::string names;
      for (const RequestOption& o : requestOptions()) names += (names.empty() ? "" : ", ") + o.name;
      throw Error("unknown option '" + key + "': the options are projection, " + names);
    }
  }
  BakeRequest request;
  for (const RequestOption& o : requestOptions())
    if (kwargs.contains(o.name.c_str())) o.set(request, o.name, optionText(o.name, kwargs[o.name.c_str()]));
  return request;
}

py::dict bakePixels(Pixels pixels, const std::string& projection, const py::kwargs& options) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const BakeRequest request = requestFrom(options);
  std::optional<Probe> probe;
  EvaluatedBake result;
  {
    py::gil_scoped_release release;
    result = bakeBuffer(view, kind, request, probe);
  }
  return toDict("", *probe, request.bake, result);
}

#if PROBELIGHTS_MODULE_IO
BakeRequest fileRequest(const std::string& projection, const py::kwargs& options) {
  BakeRequest request = requestFrom(options);
  request.probe.projection = parseProjectionChoice(projection);
  return request;
}

py::dict pyBakeFile(const py::object& pathObject, const std::string& projection, const py::kwargs& options) {
  const std::string path = fsPath(pathObject);
  const BakeRequest request = fileRequest(projection, options);
  std::optional<BakedFile> baked;
  {
    py::gil_scoped_release release;
    baked.emplace(bakeFile(path, request));
  }
  return toDict(path, *baked->probe, request.bake, *baked->result, baked->loadMs);
}

// Many probes (files, directories, globs): a list with bake_file's dict per probe, or {"source": {"path"},
// "error"} for one that failed (the others go on). The next probe loads while the current one bakes.
py::list pyBakeFiles(const py::object& paths, const std::string& projection, const py::kwargs& options) {
  // A list (any iterable) of paths; one path alone is taken as a list of one.
  std::vector<std::string> inputs;
  const py::module_ os = py::module_::import("os");
  if (py::isinstance<py::str>(paths) || py::isinstance<py::bytes>(paths) ||
      py::isinstance(paths, os.attr("PathLike")))
    inputs.push_back(fsPath(paths));
  else
    for (const py::handle p : paths) inputs.push_back(fsPath(p));
  if (inputs.empty()) throw Error("bake_files needs at least one path (a file, folder or glob)");
  const BakeRequest request = fileRequest(projection, options);
  py::list out;
  {
    py::gil_scoped_release release;
    bakeFiles(expandProbePaths(inputs), request, [&](BakedFile& item) {
      py::gil_scoped_acquire acquire;
      if (item.result) {
        out.append(toDict(item.path, *item.probe, request.bake, *item.result, item.loadMs));
      } else {
        py::dict failed;
        failed["source"] = py::dict(py::arg("path") = fsText(item.path));
        failed["error"] = fsText(describe(item.error, item.remedy.get(), spelled));
        out.append(failed);
      }
      return true;
    });
  }
  return out;
}
#endif

// The bake options' keywords with their defaults and what they do, from request.h's table: the docstrings
// of bake, bake_file and bake_files end with it.
std::string optionsDoc() {
  std::string doc = "\n\nOptions (keyword=default):";
  const BakeRequest defaults;
  for (const RequestOption& o : requestOptions()) {
    const std::string value = o.get(defaults);
    // A switch, or an on|off option, is a bool here; a word in quotes; a number as it is.
    const bool onOff = o.isSwitch() || o.values == "on|off";
    const bool word =
        !onOff && (o.values.find('|') != std::string::npos || o.values.find(',') != std::string::npos);
    const std::string shown = onOff ? (value == "on" ? "True" : "False") : word ? "'" + value + "'" : value;
    doc += "\n  " + o.name + "=" + shown + ": " + o.help +
           (onOff || o.values.size() < 2 ? "" : " (" + o.values + ")");
  }
  return doc;
}

// A result's lights (the dict bake() returns under "lights": its direction and rgb columns; angle and
// solid_angle when present) as the exporters (light_export.h) take them.
std::vector<Light> exportedLights(const py::dict& lights) {
  auto column = [&](const char* key, py::ssize_t width, bool required) {
    if (!lights.contains(key)) {
      if (required)
        throw Error(std::string("lights has no '") + key + "' (pass the 'lights' of a bake's result)");
      return py::array_t<double, py::array::c_style | py::array::forcecast>();
    }
    auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(lights[key]);
    if (!a || (width == 1 ? a.ndim() != 1 : (a.ndim() != 2 || a.shape(1) != width)))
      throw Error(std::string("lights['") + key + "'] must be an array of shape (N" +
                  (width == 1 ? "" : ", " + std::to_string(width)) + ")");
    return a;
  };
  const auto direction = column("direction", 3, true), rgb = column("rgb", 3, true);
  const auto angle = column("angle", 1, false), solidAngle = column("solid_angle", 1, false);
  const py::ssize_t n = direction.shape(0);
  if (rgb.shape(0) != n || (angle.size() && angle.shape(0) != n) ||
      (solidAngle.size() && solidAngle.shape(0) != n))
    throw Error("lights' columns differ in length");
  std::vector<Light> out(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    Light& l = out[static_cast<std::size_t>(i)];
    l.direction = {direction.at(i, 0), direction.at(i, 1), direction.at(i, 2)};
    l.rgb = {rgb.at(i, 0), rgb.at(i, 1), rgb.at(i, 2)};
    if (angle.size()) l.angle = angle.at(i);
    if (solidAngle.size()) l.solidAngle = solidAngle.at(i);
  }
  return out;
}

ExportOptions exportOptions(const std::string& lightType, double distance) {
  ExportOptions options;
  options.kind = parseExportKind("light_type", lightType);
  options.distance = checkedDistance("distance", distance);
  return options;
}

std::string gltfText(const py::dict& lights, const std::string& lightType, double distance) {
  return gltfDocument(exportedLights(lights), exportOptions(lightType, distance),
                      "probelights " PROBELIGHTS_VERSION);
}

std::string usdText(const py::dict& lights, const std::string& lightType, double distance,
                    const std::string& reflections, const std::string& residual) {
  ExportOptions options = exportOptions(lightType, distance);
  if (!reflections.empty() && !residual.empty())
    throw Error("usd takes one dome: reflections (the probe) or residual, not both");
  options.dome = residual.empty() ? reflections : residual;
  options.domeTakes = residual.empty() ? ExportOptions::Dome::Reflections : ExportOptions::Dome::Residual;
  return usdDocument(exportedLights(lights), options, "probelights " PROBELIGHTS_VERSION);
}

// The errors of any lights against a probe (evaluate.h): a bake's, a user's own, another tool's. Each light
// is drawn as the bake draws it: a direction, its rgb (sum of L dOmega) and, if given, a sun's cone angle.
// Bad lights are refused, one line naming the first: they would give NaN errors, not a measurement.
py::dict evaluateLights(Pixels pixels, const py::dict& lightsDict, const std::string& projection,
                        const std::string& effects, int evaluatorWidth, const std::string& sunProfile,
                        const std::string& sunCones, const std::string& nonfinite) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const NonFinitePolicy policy = parseNonFinitePolicy(nonfinite);
  const Effects e = parseEffects(effects);
  if (evaluatorWidth < 1)
    throw Error("evaluator_width takes a width of at least 1 pixel, got '" + std::to_string(evaluatorWidth) +
                "'");
  const EvaluatorOptions options{evaluatorWidth, false, parseSunProfile(sunProfile), parseSunCones(sunCones)};
  std::vector<Light> lights = exportedLights(lightsDict);
  if (lights.empty()) throw Error("lights is empty: evaluate takes at least one light");
  for (std::size_t i = 0; i < lights.size(); ++i) {
    Light& l = lights[i];
    const std::string which = "light " + std::to_string(i) + " ";
    const double n = l.direction.length();
    if (!std::isfinite(n) || n <= 0) throw Error(which + "has no direction (zero or not finite)");
    l.direction = (1 / n) * l.direction;
    for (double c : l.rgb)
      if (!std::isfinite(c)) throw Error(which + "has an rgb that is not finite");
    if (!std::isfinite(l.angle) || l.angle < 0 || l.angle > kPi)
      throw Error(which + "has an angle outside [0, pi] radians");
  }
  EffectErrors errors;
  {
    py::gil_scoped_release release;
    const Probe probe(view, kind, policy);
    errors = Evaluator(probe, e, options).evaluate(lights);
  }
  py::dict d;
  if (e & kDiffuse) d["diffuse"] = errors.diffuse;
  if (e & kShadow) d["shadow"] = errors.shadow;
  if (e & kGlossy) d["glossy"] = errors.glossy;
  return d;
}

// Every registered placement method's name (placement.h).
std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const PlacementMethod& m : placementMethods()) names.push_back(m.name);
  return names;
}

// The tradeoff grid (tradeoff.h) in the layout of the CLI's tradeoff JSON (result_layout.h).
py::dict tradeoffRows(Pixels pixels, const std::string& projection, const std::string& effects,
                      const std::vector<int>& counts, const std::vector<std::string>& methods, bool refit,
                      int evaluatorWidth, const std::string& sunProfile, const std::string& sunCones,
                      const std::string& nonfinite) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const NonFinitePolicy policy = parseNonFinitePolicy(nonfinite);
  TradeoffOptions options;
  options.counts = counts;
  options.methods.clear();
  for (const auto& m : methods) options.methods.push_back(parseMethod(m));
  options.resolutions = {WorkingResolution{}};  // auto
  options.refit = refit;
  const Effects e = parseEffects(effects);
  std::vector<TradeoffRow> rows;
  std::optional<Probe> probe;
  {
    py::gil_scoped_release release;
    probe.emplace(view, kind, policy);
    Evaluator evaluator(
        *probe, e,
        EvaluatorOptions{evaluatorWidth, refit, parseSunProfile(sunProfile), parseSunCones(sunCones)});
    rows = tradeoff(*probe, evaluator, options);
  }
  py::dict d;
  DictWriter writer(d);
  writeTradeoff(writer, {"", *probe, e, rows});
  return d;
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
  // Its message as fsText has it (a path in it need not be UTF-8): tried before register_exception's.
  static py::handle errorType = m.attr("Error");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      // The message with its remedy in the module's words; the shells that word it their own way (the
      // add-on's panel) read `reason` (the failure alone) and `remedy` ((purpose, option, values) or None).
      py::object error = py::reinterpret_borrow<py::object>(errorType)(fsText(describe(e, spelled)));
      error.attr("reason") = fsText(e.what());
      const Remedy* remedy = e.remedy();
      error.attr("remedy") =
          remedy ? py::object(py::make_tuple(remedy->purpose, remedy->option, remedy->values)) : py::none();
      PyErr_SetObject(errorType.ptr(), error.ptr());
    }
  });
  m.def(
      "tradeoff", &tradeoffRows, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
      py::arg("effects") = "diffuse,shadow", py::arg("counts") = std::vector<int>{4, 8, 16, 32, 64, 128, 256},
      py::arg("methods") = methodNames(), py::arg("refit") = true, py::arg("evaluator_width") = 2048,
      py::arg("sun_profile") = "cone", py::arg("sun_cones") = "free", py::arg("nonfinite") = "error",
      "What accuracy costs in time, in the layout of the CLI's tradeoff JSON: source, effects, error, and "
      "rows: a dict of columns (method, lights, made, resolution, refit, bake_ms, each effect's error), one "
      "entry per (method, count, refit).");
  static const std::string bakeDoc =
      "bake(pixels, *, projection='latlong', **options): bake a probe given as a float32 H x W x C array "
      "(rows top to bottom; not copied). Returns the layout the CLI's JSON has (result_layout.h): source, "
      "method, ..., lights: a dict of numpy arrays (direction (N,3), rgb (N,3), solid_angle, angular_radius, "
      "energy_share (N,), rect (N,4)), total_rgb (3,), timings_ms, notes, and evaluation (errors on "
      "`effects`) "
      "when evaluate/refit/max_error ask for it." +
      optionsDoc();
  m.def("bake", &bakePixels, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        bakeDoc.c_str());
#if PROBELIGHTS_MODULE_IO
  static const std::string fileDoc =
      "bake_file(path, *, projection='auto', **options): read a probe with OpenImageIO and bake it: the same "
      "dict as bake(), with source.path and timings_ms.load set." +
      optionsDoc();
  static const std::string filesDoc =
      "bake_files(paths, *, projection='auto', **options): bake many probes (files, directories, globs) in "
      "order, the next loading while one bakes: a list of bake_file's dicts, with {'source': {'path'}, "
      "'error'} for a probe that failed." +
      optionsDoc();
  m.def("bake_file", &pyBakeFile, py::arg("path"), py::kw_only(), py::arg("projection") = "auto",
        fileDoc.c_str());
  m.def("bake_files", &pyBakeFiles, py::arg("paths"), py::kw_only(), py::arg("projection") = "auto",
        filesDoc.c_str());
#endif
#if PROBELIGHTS_MODULE_CLI
  // The Python package's `probelights` command (python/probelights/_command.py): arguments as bytes
  // (os.fsencode), so that any file name reaches the command as the program would get it; the exit code back.
  m.def(
      "_command",
      [](const std::vector<py::bytes>& argv) {
        std::vector<std::string> args(argv.begin(), argv.end());
        py::gil_scoped_release release;
        return cli::run(args);
      },
      py::arg("args"), "Run the probelights command line with these arguments; its exit code.");
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
  m.def(
      "touch_pages",
      [](py::array_t<float, py::array::c_style> buffer) {
        py::buffer_info info = buffer.request(true);
        py::gil_scoped_release release;
        touchPages(info.ptr, static_cast<std::size_t>(info.size) * sizeof(float));
      },
      py::arg("buffer"),
      "Map a new float32 buffer's memory from all threads (one write of 0 per page), before a "
      "single-threaded "
      "writer fills it: the kernel's first-touch cost is paid in parallel.");
  m.def(
      "gltf", &gltfText, py::arg("lights"), py::kw_only(), py::arg("light_type") = "sun",
      py::arg("distance") = 10.0,
      "glTF 2.0 text (KHR_lights_punctual, Y up) of a bake's lights (its result's 'lights'): suns in lux, or "
      "point lights `distance` metres out in candela, at 683 lm/W as Blender's glTF importer reads them.");
  m.def(
      "usd", &usdText, py::arg("lights"), py::kw_only(), py::arg("light_type") = "sun",
      py::arg("distance") = 10.0, py::arg("reflections") = "", py::arg("residual") = "",
      "USD text (usda, UsdLux, Z up, metres) of a bake's lights: DistantLights normalized, intensity in lux "
      "(the probe's values read as nits), or SphereLights `distance` metres out. reflections: an asset path "
      "(relative to where the file will be, './' or '../' first, or absolute) of the lat-long probe, shown "
      "by a DomeLight for reflections alone while the lights take diffuse light alone; or residual: the path "
      "of a residual image saved from a bake with sources, shown by a DomeLight that lights with the lamps "
      "(docs/export.md).");
  m.def("evaluate", &evaluateLights, py::arg("pixels"), py::arg("lights"), py::kw_only(),
        py::arg("projection") = "latlong", py::arg("effects") = "diffuse,shadow",
        py::arg("evaluator_width") = 2048, py::arg("sun_profile") = "cone", py::arg("sun_cones") = "free",
        py::arg("nonfinite") = "error",
        "The errors (relative RMS of luminance, evaluate.h) of any lights against the probe on `effects`: "
        "a dict {effect: error}. lights: a dict of arrays as a bake's result has them, direction (N,3), "
        "rgb (N,3) (sum of L dOmega) and angle (N,), a sun's full cone angle in radians (0 or absent: "
        "points). A bake's own lights give its evaluation's errors.");
  m.def(
      "release_memory", [] { releaseKeptBuffers(); },
      "Give back the table buffers kept for the next bake (memory.h: up to two, e.g. 84 MB each for 2K "
      "probes "
      "at full resolution).");
  m.attr("__version__") = PROBELIGHTS_VERSION;
  m.attr("max_refit_lights") = kMaxRefitLights;  // the most lights a bake with refit=True takes
  m.attr("methods") = methodNames();             // every placement method's name, as method= takes it
  // "full": reads files with OpenImageIO (bake_file); "pixels": the portable build inside the Blender add-on,
  // which links nothing but the C library and takes pixels only.
  m.attr("build") = PROBELIGHTS_MODULE_IO ? "full" : "pixels";
}
