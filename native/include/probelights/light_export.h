// The lights as other renderers read them: glTF 2.0's KHR_lights_punctual and USD's UsdLux (docs/export.md).
#pragma once

#include <string>
#include <vector>

#include "probelights/lights.h"

namespace probelights {

enum class ExportKind { Sun, Point };

struct ExportOptions {
  ExportKind kind = ExportKind::Sun;
  double distance = 10;  // metres from the origin, point lights (a sun's position does not light anything)
  // USD only: a DomeLight showing this lat-long image (an asset path as it is to be written: relative to the
  // .usda's folder, "./" or "../" first, or absolute); empty: no dome, the lamps take all of the light.
  //   reflections  the probe itself, for reflections alone, the lamps then lighting diffuse surfaces alone
  //                (UsdLux's diffuse and specular multipliers): the add-on's default split;
  //   residual     what the lamps of the sources leave (sources.h), lighting everything with them.
  std::string dome;
  enum class Dome { Reflections, Residual } domeTakes = Dome::Reflections;
};

// The words of the CLI's --light-type and the module's light_type= ("sun", "point"), and the distances both
// take (above 0, at most 1e9 m); a bad one is an Error naming `option`.
ExportKind parseExportKind(const std::string& option, const std::string& text);
double checkedDistance(const std::string& option, double metres);

// Lumens per watt: the luminous efficacy Blender's glTF importer and exporter divide and multiply by
// (io_scene_gltf2 PBR_WATTS_TO_LUMENS, their "Standard" lighting mode): a light leaves and comes back as
// it was.
inline constexpr double kLumensPerWatt = 683;

// A glTF 2.0 document (JSON text) with one light and one node per light, in glTF's frame (Y up, right-handed:
// Blender's (x, y, z) is glTF's (x, z, -y), as Blender's glTF IO converts):
//   sun    "directional", intensity in lux = the irradiance it gives a facing surface (its largest
//          channel, W/m^2) x kLumensPerWatt, its colour the rgb over that channel (glTF colours are in
//          [0, 1]); the node turned so that its -Z (the way a glTF light shines) points from the light's
//          direction to the origin. glTF has no angle: the fitted cone angle (radians) goes in the extras.
//   point  "point" at `distance` along the direction, intensity in candela = E d^2 x kLumensPerWatt, so
//          that it gives the origin the irradiance E (inverse square law; KHR_lights_punctual: no range).
// A channel below zero (a light that carries a deficit of its region) is written as zero; `clampedRgb` (if
// given) receives the sum of what was dropped.
std::string gltfDocument(const std::vector<Light>& lights, const ExportOptions& options,
                         const std::string& generator, Rgb* clampedRgb = nullptr);

// A USD layer (usda text, Z up, metres: Blender's frame as it is) with one UsdLux light per light under
// /probelights, following the UsdLux schema's "Quantities and Units" (OpenUSD 24.x+: a pixel value of 1 is
// 1 nit, so the probe's values are taken as nits):
//   sun    DistantLight, normalize on: its intensity is the illuminance on a facing surface, the largest
//          channel of the rgb (W/m^2 read as lux, the probe's unit), colour the rgb over it; angle the fitted
//          cone's angular diameter in degrees (0 when none was fitted: parallel light); its -Z (the way a
//          UsdLux light shines) points from the light's direction to the origin (xformOp:orient).
//   point  SphereLight at `distance` along the direction, normalize on (luminance = intensity / 4 pi r^2),
//          so the origin's irradiance is E = intensity / (4 d^2) whatever its radius: intensity = 4 E d^2;
//          radius d sin(angle / 2), the fitted cone seen from the origin (at least the Sun's 0.53 degrees).
// The fitted solid angle goes in a custom attribute, probelights:solidAngle. Negative channels are written
// as zero, as gltfDocument does (`clampedRgb`).
std::string usdDocument(const std::vector<Light>& lights, const ExportOptions& options,
                        const std::string& generator, Rgb* clampedRgb = nullptr);

}  // namespace probelights
