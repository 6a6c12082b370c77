// What the module's parts share (module.cpp registers them): Python's view of the core's text, paths, pixels,
// results and error remedies. Every function here runs with the GIL held.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "probelights/error.h"
#include "probelights/lights.h"
#include "probelights/probe.h"
#include "probelights/request.h"
#include "probelights/result_layout.h"

namespace probelights::shell {

namespace py = pybind11;

// pixels: float32 H x W (grey) or H x W x C (C = 1, 2 grey+alpha, 3 RGB, 4+ RGB + ignored), rows top to
// bottom. Any row and pixel strides (e.g. a flipped view arr[::-1]) are read in place; other dtypes are
// converted.
using Pixels = py::array_t<float, py::array::forcecast>;
ImageView viewOf(Pixels& pixels);

// A failure's remedy (error.h) in the module's words: "nonfinite='zero'", "projection='latlong',
// 'mirror-ball' or 'angular'".
std::string spelled(const Remedy& remedy);

// Text for Python: UTF-8, or as os.fsdecode has bytes that are not (a file name's; surrogates, so that the
// str names the same file again) rather than a UnicodeDecodeError that loses the result.
py::str fsText(const std::string& s);

// A path from Python as the file system has it: str (with os.fsdecode's surrogates for bytes that are not
// UTF-8), bytes or os.PathLike, through os.fsencode; a NUL in it is refused (the file system would cut it).
std::string fsPath(const py::handle& p);

// Writes the core's result layout (result_layout.h) into nested dicts; a table becomes a dict of numpy
// arrays, one per column ((N,) for a scalar column, (N, width) otherwise), so its keys are the JSON rows'
// keys.
class DictWriter : public ResultWriter {
 public:
  explicit DictWriter(py::dict root) { stack_.push_back(root); }
  void begin(const char* key) override;
  void end() override { stack_.pop_back(); }
  void null(const char* key) override { stack_.back()[key] = py::none(); }
  void number(const char* key, double v) override { stack_.back()[key] = v; }
  void integer(const char* key, long long v) override { stack_.back()[key] = v; }
  void boolean(const char* key, bool v) override { stack_.back()[key] = v; }
  void text(const char* key, const std::string& v) override { stack_.back()[key] = fsText(v); }
  void notes(const char* key, const std::vector<Note>& v) override;
  void numbers(const char* key, std::span<const double> v) override;
  void table(const char* key, std::size_t rows, const std::vector<ResultColumn>& columns) override;

 private:
  std::vector<py::dict> stack_;
};

// A bake's result in the layout the CLI's JSON has, with the residual image (sources) as a numpy array.
py::dict toDict(const std::string& path, const Probe& probe, const BakeOptions& options,
                const EvaluatedBake& bake, double loadMs = 0);

// A keyword's value as its option's text (request.h): a switch from a bool, a number as Python writes it (its
// repr reads back as the same double), a word as it is, a list or tuple of those joined by commas.
std::string optionText(const std::string& name, const std::string& takes, const py::handle& value);

// What the keywords ask for, every other option at its default (request.h, tradeoff.h: one table for the
// module and the CLI). Options are applied in the table's order, whatever the keywords' order; an unknown
// keyword is an Error naming them all.
template <class Target>
Target fromKeywords(const std::vector<TableOption<Target>>& table, const py::kwargs& kwargs) {
  for (const auto& item : kwargs) {
    const std::string key = item.first.cast<std::string>();
    bool known = false;
    for (const TableOption<Target>& o : table) known = known || o.name == key;
    if (!known) {
      std::string names;
      for (const TableOption<Target>& o : table) names += (names.empty() ? "" : ", ") + o.name;
      throw Error("unknown option '" + key + "': the options are projection, " + names);
    }
  }
  Target target;
  for (const TableOption<Target>& o : table)
    if (kwargs.contains(o.name.c_str()))
      o.set(target, o.name,
            optionText(o.name, o.isSwitch() ? "True or False" : o.values, kwargs[o.name.c_str()]));
  return target;
}

// One option's line of a docstring: "name=default: what it does (values)".
std::string optionDoc(const std::string& name, const std::string& values, const std::string& help,
                      const std::string& value, bool isSwitch);

// The keywords of a table with their defaults and what they do: the docstrings of bake, bake_file, bake_files
// and tradeoff end with it.
template <class Target>
std::string optionsDoc(const std::vector<TableOption<Target>>& table) {
  std::string doc = "\n\nOptions (keyword=default):";
  const Target defaults;
  for (const TableOption<Target>& o : table)
    doc += optionDoc(o.name, o.values, o.help, o.get(defaults), o.isSwitch());
  return doc;
}

// The module's functions by area, each registering its own (module.cpp calls them in turn).
void defineBake(py::module_& m);      // bake, bake_file, bake_files, _command (bake_functions.cpp)
void defineAnalysis(py::module_& m);  // evaluate, tradeoff, sh_project, sh_sample (analysis_functions.cpp)
void defineExport(py::module_& m);    // gltf, usd (export_functions.cpp)
void defineSequence(py::module_& m);  // SequenceBaker (sequence_functions.cpp)

// A result's lights (the dict bake() returns under "lights": its direction and rgb columns; angle and
// solid_angle when present) as the exporters (light_export.h) and the evaluator take them.
std::vector<Light> exportedLights(const py::dict& lights);

// Every registered placement method's name (placement.h).
std::vector<std::string> methodNames();

}  // namespace probelights::shell
