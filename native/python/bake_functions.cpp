// The module's bake functions: bake (pixels), bake_file and bake_files (files, the full module alone) and the
// package's command line, their keywords the request table's options (request.h), the GIL released while they
// bake.
#include <pybind11/stl.h>

#include "probelights/placement.h"
#include "shell.h"
#if PROBELIGHTS_MODULE_IO
#include "probelights/bake_file.h"
#include "probelights/batch.h"
#endif

#if PROBELIGHTS_MODULE_CLI
namespace probelights::cli {
int run(const std::vector<std::string>& args);  // native/cli/command_line.cpp
}
#endif

namespace probelights::shell {
namespace {

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

}  // namespace

void defineBake(py::module_& m) {
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
}

}  // namespace probelights::shell
