#include "probelights/light_export.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include "probelights/error.h"

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

std::string numbers(std::initializer_list<double> vs) {
  std::string out = "[";
  for (double v : vs) out += (out.size() > 1 ? ", " : "") + number(v);
  return out + "]";
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

}  // namespace

ExportKind parseExportKind(const std::string& option, const std::string& text) {
  if (text == "sun") return ExportKind::Sun;
  if (text == "point") return ExportKind::Point;
  throw Error(option + " takes sun or point, got '" + text + "'");
}

double checkedDistance(const std::string& option, double metres) {
  if (!(metres > 0) || metres > 1e9)
    throw Error(option + " takes metres above 0 (e.g. 10), got " + number(metres));
  return metres;
}

std::string gltfDocument(const std::vector<Light>& lights, const ExportOptions& options,
                         const std::string& generator, Rgb* clampedRgb) {
  if (clampedRgb) *clampedRgb = {0, 0, 0};
  const std::string asset = "{\n  \"asset\": {\"version\": \"2.0\", \"generator\": \"" + generator + "\"},\n";
  // glTF's arrays, when present, hold at least one item: no lights is a scene with no nodes.
  if (lights.empty()) return asset + "  \"scene\": 0,\n  \"scenes\": [{\"name\": \"probelights\"}]\n}\n";
  const bool sun = options.kind == ExportKind::Sun;
  std::string defs, nodes, indices;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& l = lights[i];
    Rgb rgb = l.rgb;
    for (int c = 0; c < 3; ++c) {
      if (rgb[c] < 0 || !std::isfinite(rgb[c])) {
        if (clampedRgb && std::isfinite(rgb[c])) (*clampedRgb)[c] += rgb[c];
        rgb[c] = 0;
      }
    }
    const double peak = std::max({rgb[0], rgb[1], rgb[2]});
    const Vec3 d = toGltf(l.direction);
    const double n = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    const Vec3 u = n > 0 ? Vec3{d.x / n, d.y / n, d.z / n} : Vec3{0, 1, 0};
    std::string name = std::to_string(i);
    name = (sun ? "sun_" : "point_") + std::string(name.size() < 3 ? 3 - name.size() : 0, '0') + name;
    const double intensity = (sun ? peak : peak * options.distance * options.distance) * kLumensPerWatt;
    const std::string colour =
        peak > 0 ? numbers({rgb[0] / peak, rgb[1] / peak, rgb[2] / peak}) : "[1, 1, 1]";
    defs += std::string(i ? ",\n" : "") + "        {\"name\": \"" + name + "\", \"type\": \"" +
            (sun ? "directional" : "point") + "\", \"color\": " + colour +
            ", \"intensity\": " + number(intensity) + ", \"extras\": {\"angle\": " + number(l.angle) +
            ", \"solid_angle\": " + number(l.solidAngle) + "}}";
    const auto q = turnZTo(u);
    nodes += std::string(i ? ",\n" : "") + "    {\"name\": \"" + name + "\", ";
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

}  // namespace probelights
