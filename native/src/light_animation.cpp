// The lights of a sequence's frames (sequence.h) as animated USD and glTF documents (light_export.h): the
// single bake's writers' lights and names, a key a frame.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>

#include "export_text.h"
#include "probelights/error.h"
#include "probelights/geometry.h"
#include "probelights/light_export.h"

namespace probelights {

using namespace exporttext;

namespace {

// The lights each frame holds, after the checks both animations make: a frame at least, every frame as many
// lights as the first, frames per second above 0.
std::size_t lightsPerFrame(const std::vector<std::pair<int, std::vector<Light>>>& frames, const char* what,
                           double framesPerSecond) {
  if (frames.empty()) throw Error(std::string("an animated ") + what + " needs at least one frame");
  const std::size_t n = frames.front().second.size();
  for (const auto& [frame, lights] : frames)
    if (lights.size() != n)
      throw Error(std::string("every frame of an animated ") + what + " has the same lights");
  if (!(framesPerSecond > 0 && std::isfinite(framesPerSecond)))
    throw Error("frames per second must be above 0");
  return n;
}

}  // namespace

std::string usdAnimation(const std::vector<std::pair<int, std::vector<Light>>>& frames,
                         const ExportOptions& options, const std::string& generator, double framesPerSecond) {
  const std::size_t n = lightsPerFrame(frames, "USD layer", framesPerSecond);
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
      std::vector<Vec3> path;
      for (const auto& frame : all) path.push_back(frame[i].direction);
      const auto turns = turnsAlong(path);
      out += samples("quatf xformOp:orient", i, [&](std::size_t f, std::size_t) {
        const auto& q = turns[f];  // (x, y, z, w); USD writes (w, x, y, z)
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

namespace {

// RFC 4648 base64 of bytes (a glTF buffer's data URI).
std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned v = bytes[i] << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kDigits[v >> 18 & 63];
    out += kDigits[v >> 12 & 63];
    out += i + 1 < bytes.size() ? kDigits[v >> 6 & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
  }
  return out;
}

// The floats of a glTF buffer, little-endian, each accessor a view of its own.
struct GltfBuffer {
  std::vector<unsigned char> bytes;
  std::string views, accessors;
  int count = 0;
  // Adds `values` (count items of `width` floats: SCALAR, VEC3, VEC4) and returns the accessor's index;
  // with `bounds`, the min and max an animation's input needs.
  int add(const std::vector<float>& values, int width, bool bounds = false) {
    const std::size_t offset = bytes.size();
    for (float v : values) {
      unsigned char b[4];
      std::memcpy(b, &v, 4);
      if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + 4);
      bytes.insert(bytes.end(), b, b + 4);
    }
    const char* type = width == 1 ? "SCALAR" : width == 3 ? "VEC3" : "VEC4";
    views += std::string(count ? ",\n" : "") +
             "    {\"buffer\": 0, \"byteOffset\": " + std::to_string(offset) +
             ", \"byteLength\": " + std::to_string(values.size() * 4) + "}";
    accessors += std::string(count ? ",\n" : "") + "    {\"bufferView\": " + std::to_string(count) +
                 ", \"componentType\": 5126, \"count\": " + std::to_string(values.size() / width) +
                 ", \"type\": \"" + type + "\"";
    if (bounds)
      accessors += ", \"min\": [" + number(*std::min_element(values.begin(), values.end())) +
                   "], \"max\": [" + number(*std::max_element(values.begin(), values.end())) + "]";
    accessors += "}";
    return count++;
  }
};

}  // namespace

std::string gltfAnimation(const std::vector<std::pair<int, std::vector<Light>>>& frames,
                          const ExportOptions& options, const std::string& generator,
                          double framesPerSecond) {
  const std::size_t n = lightsPerFrame(frames, "glTF", framesPerSecond);
  std::string document = gltfDocument(frames.front().second, options, generator);
  if (n == 0) return document;
  const bool sun = options.kind == ExportKind::Sun;
  const double d = options.distance;
  std::vector<std::vector<Written>> all;
  for (const auto& [frame, lights] : frames) all.push_back(written(lights, options.kind, nullptr));
  GltfBuffer buffer;
  std::vector<float> times;
  for (const auto& [frame, lights] : frames) times.push_back(static_cast<float>(frame / framesPerSecond));
  const int input = buffer.add(times, 1, true);
  std::string samplers, channels;
  int sampler = 0;
  auto channel = [&](int accessor, const std::string& target) {
    const std::string comma = sampler ? ",\n" : "";
    samplers += comma + "      {\"input\": " + std::to_string(input) +
                ", \"output\": " + std::to_string(accessor) + ", \"interpolation\": \"LINEAR\"}";
    channels += comma + "      {\"sampler\": " + std::to_string(sampler++) + ", \"target\": " + target + "}";
  };
  for (std::size_t i = 0; i < n; ++i) {
    std::vector<float> moves, colours, intensities;
    std::vector<Vec3> path;
    for (const auto& frame : all) path.push_back(toGltf(frame[i].direction));
    const auto turns = turnsAlong(path);
    for (std::size_t f = 0; f < all.size(); ++f) {
      const Written& w = all[f][i];
      const Vec3& u = path[f];
      if (sun) {
        moves.insert(moves.end(), turns[f].begin(), turns[f].end());
      } else {
        moves.insert(moves.end(),
                     {static_cast<float>(u.x * d), static_cast<float>(u.y * d), static_cast<float>(u.z * d)});
      }
      const auto c = colourOf(w);
      colours.insert(colours.end(), c.begin(), c.end());
      intensities.push_back(static_cast<float>((sun ? w.peak : w.peak * d * d) * kLumensPerWatt));
    }
    const std::string node = std::to_string(i);
    channel(buffer.add(moves, sun ? 4 : 3),
            "{\"node\": " + node + ", \"path\": \"" + (sun ? "rotation" : "translation") + "\"}");
    const std::string pointer =
        "{\"path\": \"pointer\", \"extensions\": {\"KHR_animation_pointer\": "
        "{\"pointer\": \"/extensions/KHR_lights_punctual/lights/" +
        node + "/";
    channel(buffer.add(colours, 3), pointer + "color\"}}}");
    channel(buffer.add(intensities, 1), pointer + "intensity\"}}}");
  }
  // The document's last line is "}": the animation, buffer, views and accessors go before it.
  document.erase(document.rfind('}'));
  document.erase(document.find_last_not_of(" \n") + 1);
  const std::string used = "\"extensionsUsed\": [\"KHR_lights_punctual\"";
  document.replace(document.find(used), used.size(), used + ", \"KHR_animation_pointer\"");
  return document + ",\n  \"animations\": [{\"name\": \"probelights\", \"samplers\": [\n" + samplers +
         "\n    ], \"channels\": [\n" + channels +
         "\n    ]}],\n  \"buffers\": [{\"byteLength\": " + std::to_string(buffer.bytes.size()) +
         ", \"uri\": \"data:application/octet-stream;base64," + base64(buffer.bytes) +
         "\"}],\n  \"bufferViews\": [\n" + buffer.views + "\n  ],\n  \"accessors\": [\n" + buffer.accessors +
         "\n  ]\n}\n";
}

}  // namespace probelights
