// The lights as other renderers read them: glTF 2.0's KHR_lights_punctual.
#pragma once

#include <string>
#include <vector>

#include "probelights/lights.h"

namespace probelights {

enum class ExportKind { Sun, Point };

struct ExportOptions {
  ExportKind kind = ExportKind::Sun;
  double distance = 10;  // metres from the origin, point lights (a sun's position does not light anything)
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

}  // namespace probelights
