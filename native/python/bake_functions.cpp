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

py::dict bakePixels(Pixels pixels, const std::string& projection, const py::kwargs& options) {
  const ImageView view = viewOf(pixels);
  const auto kind = parseProjection(projection);
  const BakeRequest request = fromKeywords(requestOptions(), options);
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
  BakeRequest request = fromKeywords(requestOptions(), options);
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

}  // namespace

void defineBake(py::module_& m) {
  static const std::string bakeDoc =
      "bake(pixels, *, projection='latlong', **options): bake a probe given as a float32 H x W x C array "
      "(rows top to bottom; not copied). Returns the layout the CLI's JSON has (result_layout.h): source, "
      "method, ..., lights: a dict of numpy arrays (direction (N,3), rgb (N,3), solid_angle, angular_radius, "
      "energy_share (N,), rect (N,4)), total_rgb (3,), timings_ms, notes, and evaluation (errors on "
      "`effects`) "
      "when evaluate/refit/max_error ask for it." +
      optionsDoc(requestOptions());
  m.def("bake", &bakePixels, py::arg("pixels"), py::kw_only(), py::arg("projection") = "latlong",
        bakeDoc.c_str());
#if PROBELIGHTS_MODULE_IO
  static const std::string fileDoc =
      "bake_file(path, *, projection='auto', **options): read a probe with OpenImageIO and bake it: the same "
      "dict as bake(), with source.path and timings_ms.load set." +
      optionsDoc(requestOptions());
  static const std::string filesDoc =
      "bake_files(paths, *, projection='auto', **options): bake many probes (files, directories, globs) in "
      "order, the next loading while one bakes: a list of bake_file's dicts, with {'source': {'path'}, "
      "'error'} for a probe that failed." +
      optionsDoc(requestOptions());
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
