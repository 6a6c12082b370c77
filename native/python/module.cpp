// _probelights: the thin Python shell over the core (see ../../README.md, "From Python").
// Built twice (native/CMakeLists.txt): the full module also reads files (bake_file, PROBELIGHTS_MODULE_IO=1);
// the add-on's portable build takes pixels only and links no OpenImageIO. One function per core entry point,
// by area: bake_functions.cpp, analysis_functions.cpp, export_functions.cpp (what they share: shell.h); the
// GIL is released around every long call; core errors become probelights.Error (a ValueError) with the core's
// one-line message.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "probelights/cut_choice.h"
#include "probelights/memory.h"
#include "probelights/refit.h"
#include "shell.h"

namespace py = pybind11;
using namespace probelights;
using namespace probelights::shell;

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
  defineBake(m);
  defineAnalysis(m);
  defineExport(m);
  defineSequence(m);
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
      "release_memory", [] { releaseKeptBuffers(); },
      "Give back the table buffers kept for the next bake (memory.h: up to two, e.g. 84 MB each for 2K "
      "probes "
      "at full resolution).");
  m.attr("__version__") = PROBELIGHTS_VERSION;
  m.attr("max_refit_lights") = kMaxRefitLights;  // the most lights a bake with refit=True takes
  m.attr("methods") = methodNames();             // every placement method's name, as method= takes it
  // A menu's choices of method (cut_choice.h): (name, label, help), the cut choices auto and both first.
  py::list menu;
  for (const MethodChoice& c : methodMenu()) menu.append(py::make_tuple(c.name, c.label, c.help));
  m.attr("method_menu") = menu;
  // "full": reads files with OpenImageIO (bake_file); "pixels": the portable build inside the Blender add-on,
  // which links nothing but the C library and takes pixels only.
  m.attr("build") = PROBELIGHTS_MODULE_IO ? "full" : "pixels";
}
