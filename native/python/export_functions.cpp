// The module's exporters: glTF and USD text of a bake's lights (light_export.h).
#include "probelights/light_export.h"
#include "shell.h"

namespace probelights::shell {
namespace {

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

}  // namespace

void defineExport(py::module_& m) {
  m.def(
      "gltf", &gltfText, py::arg("lights"), py::kw_only(), py::arg("light_type") = "sun",
      py::arg("distance") = ExportOptions{}.distance,
      "glTF 2.0 text (KHR_lights_punctual, Y up) of a bake's lights (its result's 'lights'): suns in lux, or "
      "point lights `distance` metres out in candela, at 683 lm/W as Blender's glTF importer reads them.");
  m.def(
      "usd", &usdText, py::arg("lights"), py::kw_only(), py::arg("light_type") = "sun",
      py::arg("distance") = ExportOptions{}.distance, py::arg("reflections") = "", py::arg("residual") = "",
      "USD text (usda, UsdLux, Z up, metres) of a bake's lights: DistantLights normalized, intensity in lux "
      "(the probe's values read as nits), or SphereLights `distance` metres out. reflections: an asset path "
      "(relative to where the file will be, './' or '../' first, or absolute) of the lat-long probe, shown "
      "by a DomeLight for reflections alone while the lights take diffuse light alone; or residual: the path "
      "of a residual image saved from a bake with sources, shown by a DomeLight that lights with the lamps "
      "(docs/export.md).");
}

}  // namespace probelights::shell
