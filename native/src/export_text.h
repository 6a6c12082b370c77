// The text both light writers share (light_export.cpp: single bakes; light_animation.cpp: sequences):
// numbers as JSON and usda take them, glTF's frame and turns, and each light as the writers see it.
#pragma once

#include <array>
#include <initializer_list>
#include <string>
#include <vector>

#include "probelights/light_export.h"

namespace probelights::exporttext {

// Shortest text that reads back as the same double (std::to_chars), as JSON takes it; 0 for one not finite.
std::string number(double v);
// "[a, b, c]" (JSON's arrays), or with other brackets "(a, b, c)" (usda's tuples).
std::string numbers(std::initializer_list<double> vs, char open = '[', char close = ']');
// Text inside a usda string: quotes and backslashes escaped, line breaks as spaces.
std::string usdString(const std::string& text);
// A usda asset path: @path@, or @@@path@@@ for one holding an @ (usda's two forms).
std::string assetPath(const std::string& path);
// Blender's frame (Z up) to glTF's (Y up).
Vec3 toGltf(const Vec3& v);
// The unit quaternion (x, y, z, w) of the shortest turn taking +Z to the unit vector d.
std::array<double, 4> turnZTo(const Vec3& d);
// The turns (x, y, z, w) taking +Z to each of a light's directions, frame after frame: the first turnZTo,
// each next the last followed by the shortest arc from the last direction to the next (parallel transport),
// so that neighbouring keys differ by that arc alone (their dot product cos(arc / 2) > 0): interpolated, the
// light sweeps the great circle between them, never round the pole where turnZTo's axis flips.
std::vector<std::array<double, 4>> turnsAlong(const std::vector<Vec3>& directions);

// A light as both formats write it: its rgb with channels below zero (or not finite) as 0, the sum of what
// was dropped added to `clamped` (when given), its largest channel and its unit direction (Blender's frame).
struct Written {
  Rgb rgb;
  double peak;
  Vec3 direction;
  std::string name;
};

std::vector<Written> written(const std::vector<Light>& lights, ExportKind kind, Rgb* clamped);
// The light's colour: its rgb over its largest channel (white when it has none).
std::array<double, 3> colourOf(const Written& w);

}  // namespace probelights::exporttext
