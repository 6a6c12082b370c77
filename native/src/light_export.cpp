#include "probelights/light_export.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include "probelights/error.h"
#include "probelights/geometry.h"
#include "probelights/names.h"

namespace probelights {

namespace {

// Shortest text that reads back as the same double (std::to_chars), as JSON takes it.
std::string number(double v) {
  if (!std::isfinite(v)) v = 0;
  if (v == 0) return "0";
  std::array<char, 32> text{};
  const auto end = std::to_chars(text.data(), text.data() + text.size(), v).ptr;
  return std::string(text.data(), end);
}

// "[a, b, c]" (JSON's arrays), or with other brackets "(a, b, c)" (usda's tuples).
std::string numbers(std::initializer_list<double> vs, char open = '[', char close = ']') {
  std::string out(1, open);
  for (double v : vs) out += (out.size() > 1 ? ", " : "") + number(v);
  return out + close;
}

// Text inside a usda string: quotes and backslashes escaped, line breaks as spaces.
std::string usdString(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return out;
}

// A usda asset path: @path@, or @@@path@@@ for one holding an @ (usda's two forms).
std::string assetPath(const std::string& path) {
  if (path.find("@@@") != std::string::npos || path.find_first_of("\n\r") != std::string::npos)
    throw Error("cannot name '" + path + "' in a USD file (it holds @@@ or a line break)");
  return path.find('@') == std::string::npos ? "@" + path + "@" : "@@@" + path + "@@@";
}

// Blender's frame (Z up) to glTF's (Y up).
Vec3 toGltf(const Vec3& v) { return {v.x, v.z, -v.y}; }

// The unit quaternion (x, y, z, w) of the shortest turn taking +Z to the unit vector d: half-way between them
// (q = (z x d, 1 + z.d), normalized); d = -Z turns half a circle about X.
std::array<double, 4> turnZTo(const Vec3& d) {
  const double w = 1 + d.z;
  if (w < 1e-12) return {1, 0, 0, 0};
  const double x = -d.y, y = d.x;  // (0, 0, 1) x d
  const double n = std::sqrt(x * x + y * y + w * w);
  return {x / n, y / n, 0, w / n};
}

// A light as both formats write it: its rgb with channels below zero (or not finite) as 0, the sum of what
// was dropped added to `clamped` (when given), its largest channel and its unit direction (Blender's frame).
struct Written {
  Rgb rgb;
  double peak;
  Vec3 direction;
  std::string name;
};

std::vector<Written> written(const std::vector<Light>& lights, ExportKind kind, Rgb* clamped) {
  if (clamped) *clamped = {0, 0, 0};
  std::vector<Written> out;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    Written w{l.rgb, 0, {0, 0, 1}, ""};
    for (int c = 0; c < 3; ++c) {
      if (w.rgb[c] < 0 || !std::isfinite(w.rgb[c])) {
        if (clamped && std::isfinite(w.rgb[c])) (*clamped)[c] += w.rgb[c];
        w.rgb[c] = 0;
      }
    }
    w.peak = std::max({w.rgb[0], w.rgb[1], w.rgb[2]});
    const Vec3& d = l.direction;
    const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    if (n > 0 && std::isfinite(n)) w.direction = {d.x / n, d.y / n, d.z / n};
    const std::string index = std::to_string(i);
    w.name = (kind == ExportKind::Sun ? "sun_" : "point_") +
             std::string(index.size() < 3 ? 3 - index.size() : 0, '0') + index;
    out.push_back(std::move(w));
  }
  return out;
}

// The light's colour: its rgb over its largest channel (white when it has none).
std::array<double, 3> colourOf(const Written& w) {
  if (!(w.peak > 0)) return {1, 1, 1};
  return {w.rgb[0] / w.peak, w.rgb[1] / w.peak, w.rgb[2] / w.peak};
}

}  // namespace

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

std::string usdAnimation(const std::vector<std::pair<int, std::vector<Light>>>& frames,
                         const ExportOptions& options, const std::string& generator, double framesPerSecond) {
  if (frames.empty()) throw Error("an animated USD layer needs at least one frame");
  const std::size_t n = frames.front().second.size();
  for (const auto& [frame, lights] : frames)
    if (lights.size() != n) throw Error("every frame of an animated USD layer has the same lights");
  if (!(framesPerSecond > 0 && std::isfinite(framesPerSecond)))
    throw Error("frames per second must be above 0");
  const bool sun = options.kind == ExportKind::Sun;
  const double d = options.distance;
  constexpr double kSunDiameter = 0.53 * kPi / 180;  // as usdDocument draws a point light's radius
  std::vector<std::vector<Written>> all;
  for (const auto& [frame, lights] : frames) all.push_back(written(lights, options.kind, nullptr));
  auto tuple = [](std::initializer_list<double> vs) { return numbers(vs, '(', ')'); };
  // One attribute's time samples, { frame: value, ... }, a value a frame from `value(frame index, light)`.
  auto samples = [&](const std::string& declaration, std::size_t i, auto&& value) {
    std::string out = "        " + declaration + ".timeSamples = {\n";
    for (std::size_t f = 0; f < frames.size(); ++f)
      out += "            " + std::to_string(frames[f].first) + ": " + value(f, i) + ",\n";
    return out + "        }\n";
  };
  auto angleOf = [&](std::size_t f, std::size_t i) {
    const double a = frames[f].second[i].angle;
    return std::isfinite(a) && a > 0 ? std::min(a, kPi) : 0.0;
  };
  std::string out = "#usda 1.0\n(\n    defaultPrim = \"probelights\"\n    doc = \"" + usdString(generator) +
                    "\"\n    endTimeCode = " + std::to_string(frames.back().first) +
                    "\n    metersPerUnit = 1\n    startTimeCode = " + std::to_string(frames.front().first) +
                    "\n    timeCodesPerSecond = " + number(framesPerSecond) +
                    "\n    upAxis = \"Z\"\n)\n\ndef Xform \"probelights\"\n{\n";
  for (std::size_t i = 0; i < n; ++i) {
    out += std::string(i ? "\n" : "") + "    def " + (sun ? "DistantLight" : "SphereLight") + " \"" +
           all[0][i].name + "\"\n    {\n";
    if (sun)
      out += samples("float inputs:angle", i,
                     [&](std::size_t f, std::size_t k) { return number(angleOf(f, k) * 180 / kPi); });
    out += samples("color3f inputs:color", i, [&](std::size_t f, std::size_t k) {
      const auto c = colourOf(all[f][k]);
      return tuple({c[0], c[1], c[2]});
    });
    out += samples("float inputs:intensity", i, [&](std::size_t f, std::size_t k) {
      return number(sun ? all[f][k].peak : 4 * all[f][k].peak * d * d);
    });
    out += "        bool inputs:normalize = 1\n";
    if (!sun)
      out += samples("float inputs:radius", i, [&](std::size_t f, std::size_t k) {
        return number(d * std::sin(std::max(angleOf(f, k), kSunDiameter) / 2));
      });
    if (sun) {
      out += samples("quatf xformOp:orient", i, [&](std::size_t f, std::size_t k) {
        const auto q = turnZTo(all[f][k].direction);  // (x, y, z, w); USD writes (w, x, y, z)
        return tuple({q[3], q[0], q[1], q[2]});
      });
      out += "        uniform token[] xformOpOrder = [\"xformOp:orient\"]\n";
    } else {
      out += samples("double3 xformOp:translate", i, [&](std::size_t f, std::size_t k) {
        const Vec3& w = all[f][k].direction;
        return tuple({w.x * d, w.y * d, w.z * d});
      });
      out += "        uniform token[] xformOpOrder = [\"xformOp:translate\"]\n";
    }
    out += "    }\n";
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
