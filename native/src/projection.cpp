#include "probelights/projection.h"

#include <algorithm>
#include <cassert>

#include "probelights/names.h"

namespace probelights {

namespace {
constexpr NameTable<ProjectionKind, 8> kProjections{{{ProjectionKind::LatLong, "latlong"},
                                                     {ProjectionKind::LatLong, "lat-long"},
                                                     {ProjectionKind::LatLong, "equirectangular"},
                                                     {ProjectionKind::MirrorBall, "mirror-ball"},
                                                     {ProjectionKind::MirrorBall, "mirrorball"},
                                                     {ProjectionKind::MirrorBall, "ball"},
                                                     {ProjectionKind::Angular, "angular"},
                                                     {ProjectionKind::Angular, "angular-map"}}};
}  // namespace

std::string toString(ProjectionKind kind) { return nameOf(kProjections, kind); }
ProjectionKind parseProjection(const std::string& name) {
  return parseName(kProjections, "projection", name);
}

namespace {

// Integral of sqrt(1 - t^2) from -1 to x: (x sqrt(1 - x^2) + asin x) / 2 + pi / 4.
double circleSegmentPrimitive(double x) {
  x = std::clamp(x, -1.0, 1.0);
  return 0.5 * (x * std::sqrt(std::max(0.0, 1.0 - x * x)) + std::asin(x)) + 0.25 * kPi;
}

// Area of {(a, b) in the unit disc : a <= A, b <= B}. Over a in [-1, A] the slice length is
// max(0, min(B, s) + s) with s = sqrt(1 - a^2): 2s where B >= s, B + s where -s <= B < s, 0 below.
double discCornerArea(double A, double B) {
  A = std::clamp(A, -1.0, 1.0);
  B = std::clamp(B, -1.0, 1.0);
  const double c = std::sqrt(std::max(0.0, 1.0 - B * B));  // where |B| = s
  auto upper = [&](double lo, double hi) {                 // integral of (B + s) over [lo, hi]
    return hi > lo ? B * (hi - lo) + circleSegmentPrimitive(hi) - circleSegmentPrimitive(lo) : 0.0;
  };
  auto full = [&](double lo, double hi) {  // integral of 2s over [lo, hi]
    return hi > lo ? 2.0 * (circleSegmentPrimitive(hi) - circleSegmentPrimitive(lo)) : 0.0;
  };
  double area = upper(-c, std::min(A, c));
  if (B >= 0) area += full(-1.0, std::min(A, -c)) + full(c, A);
  return area;
}

// Gauss-Legendre nodes and weights on [0, 1], 3 points: exact for polynomials of degree 5.
constexpr double kGLNode[3] = {0.1127016653792583, 0.5, 0.8872983346207417};
constexpr double kGLWeight[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};

// Angular map area density dOmega / dA = pi sin(pi r) / r (disc radius 1), 0 outside the disc.
double angularDensity(double a, double b) {
  double r = std::sqrt(a * a + b * b);
  if (r >= 1.0) return 0.0;
  if (r < 1e-8) return kPi * kPi;
  return kPi * std::sin(kPi * r) / r;
}

// Integral of the angular density over [a0, a1] x [b0, b1] by a 3x3 Gauss-Legendre rule, exact to ~1e-10
// where the density is smooth (inside the disc). A cell the rim crosses is split in four, down to 1/32 of a
// pixel; the density falls to 0 at the rim (~pi^2 (1 - r)), so what the finest cells miss is ~1e-7 of a rim
// pixel.
double angularIntegral(double a0, double a1, double b0, double b1, int depth) {
  auto r2 = [](double a, double b) { return a * a + b * b; };
  double nearA = (a0 <= 0 && a1 >= 0) ? 0.0 : std::min(std::abs(a0), std::abs(a1));
  double nearB = (b0 <= 0 && b1 >= 0) ? 0.0 : std::min(std::abs(b0), std::abs(b1));
  if (r2(nearA, nearB) >= 1.0) return 0.0;  // wholly outside
  double farA = std::max(std::abs(a0), std::abs(a1)), farB = std::max(std::abs(b0), std::abs(b1));
  if (r2(farA, farB) > 1.0 && depth > 0) {  // the rim crosses the cell
    double am = 0.5 * (a0 + a1), bm = 0.5 * (b0 + b1);
    return angularIntegral(a0, am, b0, bm, depth - 1) + angularIntegral(am, a1, b0, bm, depth - 1) +
           angularIntegral(a0, am, bm, b1, depth - 1) + angularIntegral(am, a1, bm, b1, depth - 1);
  }
  double sum = 0, da = a1 - a0, db = b1 - b0;
  for (int p = 0; p < 3; ++p)
    for (int q = 0; q < 3; ++q)
      sum += kGLWeight[p] * kGLWeight[q] * angularDensity(a0 + kGLNode[p] * da, b0 + kGLNode[q] * db);
  return sum * da * db;
}

}  // namespace

double rectangleAreaInUnitDisc(double a0, double a1, double b0, double b1) {
  double area =
      discCornerArea(a1, b1) - discCornerArea(a0, b1) - discCornerArea(a1, b0) + discCornerArea(a0, b0);
  return std::max(0.0, area);
}

Projection::Projection(ProjectionKind kind, int width, int height)
    : kind_(kind), width_(width), height_(height) {
  if (kind_ != ProjectionKind::LatLong) return;
  cosPhi_.resize(width);
  sinPhi_.resize(width);
  for (int x = 0; x < width; ++x) {
    double phi = 2.0 * kPi * (0.5 - (x + 0.5) / width);
    cosPhi_[x] = std::cos(phi);
    sinPhi_[x] = std::sin(phi);
  }
  cosEl_.resize(height);
  sinEl_.resize(height);
  rowSolidAngle_.resize(height);
  for (int y = 0; y < height; ++y) {
    double el = 0.5 * kPi - kPi * (y + 0.5) / height;
    cosEl_[y] = std::cos(el);
    sinEl_[y] = std::sin(el);
    // Integral of cos(el) d(el) d(phi) over the row: dphi * (sin(el_top) - sin(el_bottom)).
    rowSolidAngle_[y] = 2.0 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
  }
}

std::optional<Vec3> Projection::direction(double u, double v) const {
  switch (kind_) {
    case ProjectionKind::LatLong: {
      double phi = 2.0 * kPi * (0.5 - u), el = 0.5 * kPi - kPi * v;
      return Vec3{std::cos(el) * std::cos(phi), std::cos(el) * std::sin(phi), std::sin(el)};
    }
    case ProjectionKind::MirrorBall: {
      double a = 2.0 * u - 1.0, b = 1.0 - 2.0 * v, r2 = a * a + b * b;
      if (r2 > 1.0) return std::nullopt;
      double s = std::sqrt(1.0 - r2);
      return Vec3{2.0 * s * a, 1.0 - 2.0 * s * s, 2.0 * s * b};
    }
    case ProjectionKind::Angular: {
      double a = 2.0 * u - 1.0, b = 1.0 - 2.0 * v, r = std::sqrt(a * a + b * b);
      if (r > 1.0) return std::nullopt;
      if (r < 1e-12) return Vec3{0, -1, 0};
      double theta = kPi * r, s = std::sin(theta) / r;
      return Vec3{s * a, -std::cos(theta), s * b};
    }
  }
  return std::nullopt;
}

std::array<double, 2> Projection::imagePosition(const Vec3& dir) const {
  double len = dir.length();
  Vec3 d = len > 0 ? (1.0 / len) * dir : Vec3{0, -1, 0};
  switch (kind_) {
    case ProjectionKind::LatLong: {
      double phi = std::atan2(d.y, d.x), el = std::asin(std::clamp(d.z, -1.0, 1.0));
      double u = 0.5 - phi / (2.0 * kPi);
      return {u - std::floor(u), 0.5 - el / kPi};
    }
    case ProjectionKind::MirrorBall: {
      // Inverse of the reflection (Cycles' direction_to_mirrorball): n is the half-vector of d and (0, -1,
      // 0).
      double div = 2.0 * std::sqrt(std::max(0.5 * (1.0 - d.y), 0.0));
      double a = div > 0 ? d.x / div : 0.0, b = div > 0 ? d.z / div : 0.0;
      return {0.5 * (a + 1.0), 0.5 * (1.0 - b)};
    }
    case ProjectionKind::Angular: {
      double theta = std::acos(std::clamp(-d.y, -1.0, 1.0)), h = std::sqrt(d.x * d.x + d.z * d.z);
      if (h < 1e-15)
        return {0.5, theta > 1.0 ? 0.0 : 0.5};  // -Y is the centre; +Y is the whole rim: take its top
      double r = theta / kPi;
      return {0.5 * (r * d.x / h + 1.0), 0.5 * (1.0 - r * d.z / h)};
    }
  }
  return {0, 0};
}

double Projection::pixelSolidAngle(int x, int y) const {
  if (kind_ == ProjectionKind::LatLong) return rowSolidAngle_[y];
  // Disc coordinates of the pixel's edges.
  double a0 = 2.0 * x / width_ - 1.0, a1 = 2.0 * (x + 1) / width_ - 1.0;
  double b0 = 1.0 - 2.0 * (y + 1) / height_, b1 = 1.0 - 2.0 * y / height_;
  if (kind_ == ProjectionKind::MirrorBall) return 4.0 * rectangleAreaInUnitDisc(a0, a1, b0, b1);
  return angularIntegral(a0, a1, b0, b1, 5);
}

void Projection::rowGeometry(int y, int x0, int x1, std::span<Vec3> dirs,
                             std::span<double> solidAngles) const {
  assert(static_cast<int>(dirs.size()) >= x1 - x0 && static_cast<int>(solidAngles.size()) >= x1 - x0);
  if (kind_ == ProjectionKind::LatLong) {
    const double ce = cosEl_[y], se = sinEl_[y], dw = rowSolidAngle_[y];
    for (int x = x0; x < x1; ++x) {
      dirs[x - x0] = {ce * cosPhi_[x], ce * sinPhi_[x], se};
      solidAngles[x - x0] = dw;
    }
    return;
  }
  const double v = (y + 0.5) / height_;
  for (int x = x0; x < x1; ++x) {
    double omega = pixelSolidAngle(x, y);
    // A pixel whose centre is just outside the disc but a sliver of it inside: take the direction at the rim.
    double a = 2.0 * (x + 0.5) / width_ - 1.0, b = 1.0 - 2.0 * v, r = std::sqrt(a * a + b * b);
    double shrink = r > 1.0 - 1e-9 ? (1.0 - 1e-9) / r : 1.0;
    auto d = direction(0.5 * (shrink * a + 1.0), 0.5 * (1.0 - shrink * b));
    dirs[x - x0] = omega > 0 ? *d : Vec3{};
    solidAngles[x - x0] = omega;
  }
}

std::array<double, 2> Projection::extentOnSphere(const Rect& r) const {
  if (kind_ == ProjectionKind::LatLong) {
    double midEl = 0.5 * kPi - kPi * (0.5 * (r.y0 + r.y1)) / height_;
    return {r.width() * 2.0 * kPi / width_ * std::cos(midEl), r.height() * kPi / height_};
  }
  // Ball and angular maps: the disc is (about) uniform in angle near its centre; compare disc lengths.
  return {r.width() * 2.0 / width_, r.height() * 2.0 / height_};
}

}  // namespace probelights
