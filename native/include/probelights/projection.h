// How the pixels of a probe map to directions on the sphere, and the exact solid angle each pixel covers.
//
// World frame is Blender's: Z up, right-handed. Image coordinates (u, v) are in [0, 1], u from the left edge,
// v from the top edge; a pixel (x, y) has its centre at u = (x + 0.5) / width, v = (y + 0.5) / height.
//
//  - LatLong (equirectangular, Blender's Environment Texture "Equirectangular"):
//      phi = 2 pi (0.5 - u), elevation = pi/2 - pi v,
//      direction = (cos(el) cos(phi), cos(el) sin(phi), sin(el)).
//    The solid angle of pixel row y is exact: (2 pi / W) (cos(pi y / H) - cos(pi (y + 1) / H)).
//  - MirrorBall (Blender's "Mirror Ball", Cycles' mirrorball_to_direction): the image is a chrome ball
//    seen by an orthographic camera looking along +Y; disc coordinates a = 2u - 1 (right = +X),
//    b = 1 - 2v (up = +Z); the ball normal is n = (a, -s, b) with s = sqrt(1 - a^2 - b^2) and the
//    reflected direction is
//      d = (2 s a, 1 - 2 s^2, 2 s b);
//    the centre sees -Y (back towards the camera), the rim sees +Y. The map is equal-area: the cap of
//    directions within angle theta of -Y comes from the disc of radius r = sin(theta / 2) and has solid angle
//    4 pi r^2, so a pixel's solid angle is exactly 4 x (area of the pixel inside the unit disc), computed in
//    closed form.
//  - Angular (Debevec's angular map light probe format): same orientation as the mirror ball (centre -Y,
//    right +X, up +Z) but the angle from the centre direction grows linearly with the radius:
//    theta = pi r, so
//      d = (sin(theta) a / r, -cos(theta), sin(theta) b / r).
//    Its area density is dOmega/dA = pi sin(pi r) / r; a pixel's solid angle is integrated by Gauss-Legendre
//    quadrature, accurate to ~1e-10 relative inside the disc and ~1e-7 on the rim (sub-divided there).
// Pixels outside the disc of a ball or angular probe have no direction and zero solid angle: they carry
// nothing.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "probelights/geometry.h"

namespace probelights {

enum class ProjectionKind { LatLong, MirrorBall, Angular };

std::string toString(ProjectionKind kind);                // "latlong", "mirror-ball", "angular"
ProjectionKind parseProjection(const std::string& name);  // throws Error naming the choices

class Projection {
 public:
  Projection(ProjectionKind kind, int width, int height);

  ProjectionKind kind() const { return kind_; }
  int width() const { return width_; }
  int height() const { return height_; }

  // Direction of image point (u, v); nullopt outside the disc of a ball or angular probe.
  std::optional<Vec3> direction(double u, double v) const;
  // Image point (u, v) that sees direction d (any length > 0); the inverse of direction().
  std::array<double, 2> imagePosition(const Vec3& d) const;

  // Direction (unit, or zero outside the disc) and exact solid angle of pixels [x0, x1) of row y.
  void rowGeometry(int y, int x0, int x1, std::span<Vec3> directions, std::span<double> solidAngles) const;
  double pixelSolidAngle(int x, int y) const;

  // Lat-long only: the per-column cos/sin of phi and the row's cos/sin of elevation and pixel solid angle.
  struct LatLongRow {
    const double* cosPhi;
    const double* sinPhi;
    double cosEl, sinEl, solidAngle;
  };
  LatLongRow latLongRow(int y) const {
    return {cosPhi_.data(), sinPhi_.data(), cosEl_[y], sinEl_[y], rowSolidAngle_[y]};
  }

  // The width and height of a pixel rectangle measured on the sphere, in radians, as median cut compares
  // them: for a lat-long region the width is scaled by cos(latitude) at the region's middle row (Debevec
  // 2005).
  std::array<double, 2> extentOnSphere(const Rect& pixels) const;

 private:
  ProjectionKind kind_;
  int width_, height_;
  // Lat-long: per-column cos/sin of phi, per-row cos/sin of elevation and row solid angle.
  std::vector<double> cosPhi_, sinPhi_, cosEl_, sinEl_, rowSolidAngle_;
};

// Area of the axis-aligned rectangle [a0, a1] x [b0, b1] inside the unit disc, in closed form (exposed for
// tests).
double rectangleAreaInUnitDisc(double a0, double a1, double b0, double b1);

}  // namespace probelights
