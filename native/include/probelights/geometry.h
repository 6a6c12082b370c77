// Small geometric types shared by every stage: directions, colours, pixel rectangles.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

namespace probelights {

inline constexpr double kPi = std::numbers::pi;

struct Vec3 {
  double x = 0, y = 0, z = 0;

  Vec3& operator+=(const Vec3& o) {
    x += o.x;
    y += o.y;
    z += o.z;
    return *this;
  }
  friend Vec3 operator+(Vec3 a, const Vec3& b) { return a += b; }
  friend Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3 operator*(double s, const Vec3& v) { return {s * v.x, s * v.y, s * v.z}; }
  friend double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
  double length() const { return std::sqrt(dot(*this, *this)); }
};

using Rgb = std::array<double, 3>;

// Rec. 709 luminance, the energy every partition balances.
inline double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
inline double luminance(const Rgb& c) { return luminance(c[0], c[1], c[2]); }

// A half-open rectangle [x0, x1) x [y0, y1) of pixels or working-grid cells; y grows downwards.
struct Rect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  long long area() const { return static_cast<long long>(width()) * height(); }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool operator==(const Rect&) const = default;
};

}  // namespace probelights
