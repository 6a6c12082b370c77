// The lights as other renderers read them: glTF 2.0's KHR_lights_punctual and USD's UsdLux (docs/export.md).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "probelights/lights.h"

namespace probelights {

enum class ExportKind { Sun, Point };

// The kinds of light every shell offers, described once (kLightKinds, light_export.cpp): the CLI's
// --light-type, the module's light_type= and light_kinds, the add-on's menu (scripts/addon_tables.py writes
// them into addon/probe_lights/core_tables.json, which the add-on reads before its native module loads).
struct LightKind {
  ExportKind kind;
  std::string name;         // the word every shell takes: "sun"
  std::string label;        // a menu's entry: "Sun"
  std::string description;  // one line: what the lamps are
  bool fittedAngle;         // drawn with the angle fitted to its region's light (soft shadows); else a point
  bool onDome;              // only its direction matters; else it sits `distance` metres from the origin
};
const std::vector<LightKind>& lightKinds();

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

// A light kind by its word (lightKinds), and the distances the shells take (above 0, at most 1e9 m); a bad
// one is an Error naming `option`.
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

// The lights of a sequence's frames (sequence.h: light k the same light in every frame) as one USD layer
// whose lights carry time samples, a sample a frame at its frame number (startTimeCode and endTimeCode the
// first and last, timeCodesPerSecond `framesPerSecond`): light k is the prim of usdDocument's light k, its
// colour, intensity, angle (or radius) and orient (or translate) animated. No dome. Every frame must hold
// as many lights as the first (an Error otherwise).
std::string usdAnimation(const std::vector<std::pair<int, std::vector<Light>>>& frames,
                         const ExportOptions& options, const std::string& generator,
                         double framesPerSecond = 24);

// The same frames as one self-contained glTF 2.0 document (its buffer a base64 data URI): gltfDocument's
// lights and nodes of the first frame and one animation, a key a frame at time frame / framesPerSecond
// (seconds), straight between keys: each node's rotation (a sun) or translation (a point), and through
// KHR_animation_pointer each light's colour and intensity (glTF has no other way to animate a light). A sun's
// key is the last key turned by the shortest arc to its new direction, so between keys it sweeps the great
// circle (usdAnimation's orients too). Every frame must hold as many lights as the first (an Error
// otherwise).
std::string gltfAnimation(const std::vector<std::pair<int, std::vector<Light>>>& frames,
                          const ExportOptions& options, const std::string& generator,
                          double framesPerSecond = 24);

// A format the lights are written in, registered once in kExporters (light_export.cpp): the CLI's --NAME FILE
// (and --NAME-dome when it takes a dome), the module's export(lights, "NAME", ...) and exporters. Adding one:
// its writer and its row there, its tests (LightExport.EveryRegisteredFormat... already holds it to the
// basics), its section in docs/export.md.
struct Exporter {
  std::string name;  // "gltf": the CLI's --gltf FILE, the module's format="gltf"
  std::string help;  // what it writes, one sentence (the usage text, the module's docstring)
  bool dome;         // takes ExportOptions::dome (a DomeLight of the probe or the residual)
  std::string (*write)(const std::vector<Light>& lights, const ExportOptions& options,
                       const std::string& generator, Rgb* clampedRgb);  // the text; channels below zero as 0
};
const std::vector<Exporter>& exporters();
const Exporter& exporter(const std::string& name);  // an Error naming the formats when there is none

// CSV (comma-separated, a header row, one row per light: spreadsheets, game engines' data tables), Blender's
// frame as it is (Z up, metres): name, type, x y z (a sun's unit direction towards the light; a point's
// position, `distance` metres out), r g b (a sun's irradiance on a facing surface, W/m^2; a point's radiant
// intensity E d^2, W/sr, giving the origin the irradiance E), the fitted cone's angle (degrees) and solid
// angle (sr).
std::string csvDocument(const std::vector<Light>& lights, const ExportOptions& options,
                        const std::string& generator, Rgb* clampedRgb = nullptr);

}  // namespace probelights
