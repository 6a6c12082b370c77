// The module's exporters: text of a bake's lights in each registered format (light_export.h's exporters()).
#include "probelights/light_export.h"
#include "shell.h"

namespace probelights::shell {
namespace {

const char* kGenerator = "probelights " PROBELIGHTS_VERSION;

// The text of `format`; reflections or residual: a dome's asset path, for a format that takes one.
std::string exportText(const py::dict& lights, const std::string& format, const std::string& lightType,
                       double distance, const std::string& reflections, const std::string& residual) {
  const Exporter& e = exporter(format);
  ExportOptions options;
  options.kind = parseExportKind("light_type", lightType);
  options.distance = checkedDistance("distance", distance);
  if (!reflections.empty() && !residual.empty())
    throw Error(format + " takes one dome: reflections (the probe) or residual, not both");
  if (!e.dome && !(reflections.empty() && residual.empty()))
    throw Error(format + " has no dome: drop reflections= and residual=");
  options.dome = residual.empty() ? reflections : residual;
  options.domeTakes = residual.empty() ? ExportOptions::Dome::Reflections : ExportOptions::Dome::Residual;
  return e.write(exportedLights(lights), options, kGenerator, nullptr);
}

}  // namespace

void defineExport(py::module_& m) {
  std::string formats;
  py::list names, kinds;
  for (const Exporter& e : exporters()) {
    formats += "\n  " + e.name + (e.dome ? " (reflections=, residual=)" : "") + ": " + e.help + ".";
    names.append(e.name);
  }
  for (const LightKind& k : lightKinds()) {
    py::dict kind;
    kind["name"] = k.name;
    kind["label"] = k.label;
    kind["description"] = k.description;
    kind["fitted_angle"] = k.fittedAngle;
    kind["on_dome"] = k.onDome;
    kinds.append(kind);
  }
  m.attr("exporters") = names;
  m.attr("light_kinds") = kinds;
  m.attr("default_distance") = ExportOptions{}.distance;
  const auto distance = ExportOptions{}.distance;
  const std::string common =
      " Suns, or point lights `distance` metres out (light_type='point'). reflections: an asset path "
      "(relative to where the file will be, './' or '../' first, or absolute) of the lat-long probe, shown "
      "by a "
      "DomeLight for reflections alone while the lights take diffuse light alone; or residual: the path of a "
      "residual image saved from a bake with sources, shown by a DomeLight that lights with the lamps "
      "(docs/export.md).";
  m.def(
      "export", &exportText, py::arg("lights"), py::arg("format"), py::kw_only(),
      py::arg("light_type") = "sun", py::arg("distance") = distance, py::arg("reflections") = "",
      py::arg("residual") = "",
      ("Text of a bake's lights (its result's 'lights') in `format`, one of `exporters`:" + formats + common)
          .c_str());
  m.def(
      "gltf",
      [](const py::dict& lights, const std::string& lightType, double distance) {
        return exportText(lights, "gltf", lightType, distance, "", "");
      },
      py::arg("lights"), py::kw_only(), py::arg("light_type") = "sun", py::arg("distance") = distance,
      ("export(lights, 'gltf', ...): " + exporter("gltf").help + ".").c_str());
  m.def(
      "usd",
      [](const py::dict& lights, const std::string& lightType, double distance,
         const std::string& reflections, const std::string& residual) {
        return exportText(lights, "usd", lightType, distance, reflections, residual);
      },
      py::arg("lights"), py::kw_only(), py::arg("light_type") = "sun", py::arg("distance") = distance,
      py::arg("reflections") = "", py::arg("residual") = "",
      ("export(lights, 'usd', ...): " + exporter("usd").help + "." + common).c_str());
}

}  // namespace probelights::shell
