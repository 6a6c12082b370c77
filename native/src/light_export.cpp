#include "probelights/light_export.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "export_text.h"
#include "probelights/error.h"
#include "probelights/geometry.h"
#include "probelights/names.h"

namespace probelights {

using namespace exporttext;

const std::vector<LightKind>& lightKinds() {
  static const std::vector<LightKind> kLightKinds{
      {ExportKind::Sun, "sun", "Sun",
       "Sun lamps: parallel light, each with a soft shadow fitted to its region's light", true, true},
      {ExportKind::Point, "point", "Point", "Point lamps on a sphere around the origin", false, false},
  };
  return kLightKinds;
}

ExportKind parseExportKind(const std::string& option, const std::string& text) {
  std::vector<std::string> words;
  for (const LightKind& k : lightKinds()) {
    if (k.name == text) return k.kind;
    words.push_back(k.name);
  }
  throw Error(option + " takes " + listOf(words) + ", got '" + text + "'");
}

double checkedDistance(const std::string& option, double metres) {
  if (!(metres > 0) || metres > 1e9)
    throw Error(option + " takes metres above 0 (e.g. 10), got " + number(metres));
  return metres;
}

std::string gltfDocument(const std::vector<Light>& lights, const ExportOptions& options,
                         const std::string& generator, Rgb* clampedRgb) {
  const std::vector<Written> all = written(lights, options.kind, clampedRgb);
  const std::string asset = "{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"" + generator + "\"},\n";
  // glTF's arrays, when present, hold at least one item: no lights is a scene with no nodes.
  if (lights.empty()) return asset + "  \"scene\": 0,\n  \"scenes\": [{\"name\": \"probelights\"}]\n}\n";
  const bool sun = options.kind == ExportKind::Sun;
  std::string defs, nodes, indices;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Written& w = all[i];
    const Light& l = lights[i];
    const Vec3 u = toGltf(w.direction);
    const double intensity = (sun ? w.peak : w.peak * options.distance * options.distance) * kLumensPerWatt;
    const auto c = colourOf(w);
    defs += std::string(i ? ",\n" : "") + "        {\"name\": \"" + w.name + "\", \"type\": \"" +
            (sun ? "directional" : "point") + "\", \"color\": " + numbers({c[0], c[1], c[2]}) +
            ", \"intensity\": " + number(intensity) + ", \"extras\": {\"angle\": " + number(l.angle) +
            ", \"solid_angle\": " + number(l.solidAngle) + "}}";
    const auto q = turnZTo(u);
    nodes += std::string(i ? ",\n" : "") + "    {\"name\": \"" + w.name + "\", ";
    if (sun)
      nodes += "\"rotation\": " + numbers({q[0], q[1], q[2], q[3]});
    else
      nodes += "\"translation\": " +
               numbers({u.x * options.distance, u.y * options.distance, u.z * options.distance});
    nodes += ", \"extensions\": {\"KHR_lights_punctual\": {\"light\": " + std::to_string(i) + "}}}";
    indices += (i ? ", " : "") + std::to_string(i);
  }
  return asset +
         "  \"extensionsUsed\": [\"KHR_lights_punctual\"],\n"
         "  \"extensions\": {\"KHR_lights_punctual\": {\"lights\": [\n" +
         defs + "\n  ]}},\n  \"scene\": 0,\n  \"scenes\": [{\"name\": \"probelights\", \"nodes\": [" +
         indices + "]}],\n  \"nodes\": [\n" + nodes + "\n  ]\n}\n";
}

std::string usdDocument(const std::vector<Light>& lights, const ExportOptions& options,
                        const std::string& generator, Rgb* clampedRgb) {
  const std::vector<Written> all = written(lights, options.kind, clampedRgb);
  const bool sun = options.kind == ExportKind::Sun, dome = !options.dome.empty();
  const bool split = dome && options.domeTakes == ExportOptions::Dome::Reflections;
  auto tuple = [](std::initializer_list<double> vs) { return numbers(vs, '(', ')'); };
  // The Sun's angular diameter, the smallest a point light is drawn at (radians).
  constexpr double kSunDiameter = 0.53 * kPi / 180;
  std::string out = "#usda 1.0\n(\n    defaultPrim = \"probelights\"\n    doc = \"" + usdString(generator) +
                    "\"\n    metersPerUnit = 1\n    upAxis = \"Z\"\n)\n\ndef Xform \"probelights\"\n{\n";
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Written& w = all[i];
    const Light& l = lights[i];
    const auto c = colourOf(w);
    const double angle = std::isfinite(l.angle) && l.angle > 0 ? std::min(l.angle, kPi) : 0;
    out += std::string(i ? "\n" : "") + "    def " + (sun ? "DistantLight" : "SphereLight") + " \"" + w.name +
           "\"\n    {\n";
    if (sun) out += "        float inputs:angle = " + number(angle * 180 / kPi) + "\n";
    out += "        color3f inputs:color = " + tuple({c[0], c[1], c[2]}) + "\n";
    if (split) out += "        float inputs:diffuse = 1\n";
    const double d = options.distance;
    out += "        float inputs:intensity = " + number(sun ? w.peak : 4 * w.peak * d * d) + "\n";
    out += "        bool inputs:normalize = 1\n";
    if (!sun)
      out +=
          "        float inputs:radius = " + number(d * std::sin(std::max(angle, kSunDiameter) / 2)) + "\n";
    if (split) out += "        float inputs:specular = 0\n";
    out += "        custom double probelights:solidAngle = " + number(l.solidAngle) + "\n";
    if (sun) {
      const auto q = turnZTo(w.direction);  // (x, y, z, w); USD's quaternions are written (w, x, y, z)
      out += "        quatf xformOp:orient = " + tuple({q[3], q[0], q[1], q[2]}) +
             "\n        uniform token[] xformOpOrder = [\"xformOp:orient\"]\n";
    } else {
      out += "        double3 xformOp:translate = " +
             tuple({w.direction.x * d, w.direction.y * d, w.direction.z * d}) +
             "\n        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n";
    }
    out += "    }\n";
  }
  if (dome) {
    // UsdLux's DomeLight keeps its pole on +Y with the image's centre on +Z (OpenEXR's lat-long), whatever
    // the stage's up axis; Blender's lat-long has its pole on +Z and its centre on +X. The turn of 120
    // degrees about (1, 1, 1) takes +X to +Y, +Y to +Z and +Z to +X: the quaternion (0.5, 0.5, 0.5, 0.5).
    out += std::string(all.empty() ? "" : "\n") + "    def DomeLight \"" +
           (split ? "reflections" : "residual") + "\"\n    {\n" +
           (split ? "        float inputs:diffuse = 0\n" : "") + "        float inputs:intensity = 1\n" +
           (split ? "        float inputs:specular = 1\n" : "") +
           "        asset inputs:texture:file = " + assetPath(options.dome) +
           "\n"
           "        token inputs:texture:format = \"latlong\"\n"
           "        quatf xformOp:orient = (0.5, 0.5, 0.5, 0.5)\n"
           "        uniform token[] xformOpOrder = [\"xformOp:orient\"]\n    }\n";
  }
  return out + "}\n";
}

std::string csvDocument(const std::vector<Light>& lights, const ExportOptions& options, const std::string&,
                        Rgb* clampedRgb) {
  const std::vector<Written> all = written(lights, options.kind, clampedRgb);
  const bool sun = options.kind == ExportKind::Sun;
  const double d = options.distance, scale = sun ? 1 : d * d;  // a point's intensity: I = E d^2 (W/sr)
  std::string out = "name,type,x,y,z,r,g,b,angle_deg,solid_angle_sr\n";
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Written& w = all[i];
    const Vec3 at = sun ? w.direction : Vec3{w.direction.x * d, w.direction.y * d, w.direction.z * d};
    const double angle = std::isfinite(lights[i].angle) && lights[i].angle > 0 ? lights[i].angle : 0;
    out += w.name + (sun ? ",sun," : ",point,");
    for (double v :
         {at.x, at.y, at.z, w.rgb[0] * scale, w.rgb[1] * scale, w.rgb[2] * scale, angle * 180 / kPi})
      out += number(v) + ",";
    out += number(lights[i].solidAngle) + "\n";
  }
  return out;
}

// The formats, in the order the usage text and the module list them.
const std::vector<Exporter>& exporters() {
  static const std::vector<Exporter> kExporters{
      {"gltf",
       "glTF 2.0 (KHR_lights_punctual, Y up): suns in lux, points in candela, at 683 lm/W as Blender's "
       "glTF importer reads them",
       false, &gltfDocument},
      {"usd",
       "USD (usda, UsdLux, Z up, metres): DistantLights normalized in lux (the probe's values read as "
       "nits), or SphereLights; a DomeLight of the probe or the residual if asked",
       true, &usdDocument},
      {"csv",
       "CSV, one row per light (Blender's frame, Z up): direction or position, rgb in W/m^2 (suns) or "
       "W/sr (points), angle",
       false, &csvDocument},
  };
  return kExporters;
}

const Exporter& exporter(const std::string& name) {
  std::vector<std::string> names;
  for (const Exporter& e : exporters()) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw Error("unknown format '" + name + "': use " + listOf(names));
}

}  // namespace probelights
