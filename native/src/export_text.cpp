#include "export_text.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "probelights/error.h"

namespace probelights::exporttext {

// Shortest text that reads back as the same double (std::to_chars), as JSON takes it.
std::string number(double v) {
  if (!std::isfinite(v)) v = 0;
  if (v == 0) return "0";
  std::array<char, 32> text{};
  const auto end = std::to_chars(text.data(), text.data() + text.size(), v).ptr;
  return std::string(text.data(), end);
}

// "[a, b, c]" (JSON's arrays), or with other brackets "(a, b, c)" (usda's tuples).
std::string numbers(std::initializer_list<double> vs, char open, char close) {
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

std::vector<std::array<double, 4>> turnsAlong(const std::vector<Vec3>& directions) {
  std::vector<std::array<double, 4>> out;
  for (const Vec3& b : directions) {
    if (out.empty()) {
      out.push_back(turnZTo(b));
      continue;
    }
    const Vec3& a = directions[out.size() - 1];
    // The shortest arc a -> b: (a x b, 1 + a.b) normalized; half a circle about an axis across a when
    // they are opposite.
    std::array<double, 4> arc{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x,
                              1 + a.x * b.x + a.y * b.y + a.z * b.z};
    if (arc[3] < 1e-12) {
      const Vec3 across =
          std::abs(a.x) < 0.9 ? Vec3{0, -a.z, a.y} : Vec3{a.z, 0, -a.x};  // a x (1,0,0) or (0,1,0)
      arc = {across.x, across.y, across.z, 0};
    }
    const double n = std::sqrt(arc[0] * arc[0] + arc[1] * arc[1] + arc[2] * arc[2] + arc[3] * arc[3]);
    for (double& c : arc) c /= n;
    // arc * last (Hamilton product): the last turn, then the arc.
    const auto& q = out.back();
    std::array<double, 4> next{arc[3] * q[0] + arc[0] * q[3] + arc[1] * q[2] - arc[2] * q[1],
                               arc[3] * q[1] - arc[0] * q[2] + arc[1] * q[3] + arc[2] * q[0],
                               arc[3] * q[2] + arc[0] * q[1] - arc[1] * q[0] + arc[2] * q[3],
                               arc[3] * q[3] - arc[0] * q[0] - arc[1] * q[1] - arc[2] * q[2]};
    const double m = std::sqrt(next[0] * next[0] + next[1] * next[1] + next[2] * next[2] + next[3] * next[3]);
    for (double& c : next) c /= m;
    out.push_back(next);
  }
  return out;
}

// (Written: export_text.h.)
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

}  // namespace probelights::exporttext
