#include "probelights/cone.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "probelights/names.h"

namespace probelights {

namespace {
constexpr NameTable<SunProfile, 2> kProfiles{{{SunProfile::Cone, "cone"}, {SunProfile::TangentDisc, "disc"}}};
constexpr NameTable<SunCones, 2> kCones{
    {{SunCones::Free, "free"}, {SunCones::AboveHorizon, "above-horizon"}}};
constexpr double kMaxDiscHalfAngle = 89 * kPi / 180;

// The profile's radiance weight at angle t from the axis, and its facing irradiance over a cone of
// half-angle a: 2 pi integral of cos t sin t w(t) dt.
double profileWeight(SunProfile p, double cosT) {
  return p == SunProfile::Cone ? 1.0 : 1 / (cosT * cosT * cosT);
}
double facingIrradiance(SunProfile p, double a) {
  if (p == SunProfile::Cone) return kPi * std::sin(a) * std::sin(a);
  return 2 * kPi * (1 / std::cos(a) - 1);
}

// n-point Gauss-Legendre on [0, 1] (Newton on the Legendre polynomial's roots).
struct GaussLegendre {
  std::vector<double> nodes, weights;
  explicit GaussLegendre(int n) : nodes(n), weights(n) {
    for (int i = 0; i < n; ++i) {
      double x = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 1;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = x;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1, p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      nodes[i] = 0.5 * (1 - x);
      weights[i] = 1 / ((1 - x * x) * dp * dp);
    }
  }
};

const GaussLegendre& rule() {
  static const GaussLegendre r(8);  // pieces are smooth: 8 points give ~1e-8 (1e-6 at worst, tested)
  return r;
}

struct Frame {
  Vec3 e1, e2;
};

Frame frameAround(const Vec3& l) {
  const Vec3 up = std::abs(l.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  Vec3 e1{up.y * l.z - up.z * l.y, up.z * l.x - up.x * l.z, up.x * l.y - up.y * l.x};
  e1 = (1.0 / e1.length()) * e1;
  const Vec3 e2{l.y * e1.z - l.z * e1.y, l.z * e1.x - l.x * e1.z, l.x * e1.y - l.y * e1.x};
  return {e1, e2};
}

double angleBetween(double along, double across) { return std::atan2(across, along); }

// Integral of f(t) over [t0, t1] by Gauss-Legendre after t = t0 + (t1 - t0) (3u^2 - 2u^3): the substitution's
// derivative vanishes at both ends, which turns the square-root behaviour of an arc that opens there into a
// smooth integrand.
template <class F>
double smoothPiece(double t0, double t1, F&& f) {
  const double span = t1 - t0;
  double s = 0;
  const GaussLegendre& gl = rule();
  for (std::size_t i = 0; i < gl.nodes.size(); ++i) {
    const double u = gl.nodes[i];
    s += gl.weights[i] * f(t0 + span * u * u * (3 - 2 * u)) * 6 * u * (1 - u);
  }
  return s * span;
}

}  // namespace

std::string toString(SunProfile profile) { return std::string(nameOf(kProfiles, profile)); }
SunProfile parseSunProfile(const std::string& name) { return parseName(kProfiles, "sun profile", name); }
std::string toString(SunCones cones) { return std::string(nameOf(kCones, cones)); }
SunCones parseSunCones(const std::string& name) { return parseName(kCones, "sun cones", name); }

double horizonAngle(const Vec3& d) {
  const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  return length > 0 ? 2 * std::asin(std::min(1.0, std::abs(d.z) / length)) : 0.0;
}

Cap makeCap(const Vec3& axis, double radius) { return {axis, radius, std::cos(radius), std::sin(radius)}; }

Cap sphereCap(const Vec3& point, const Vec3& centre, double radius) {
  const Vec3 v = centre - point;
  const double d = v.length(), s = std::min(1.0, radius / d);
  return {(1.0 / d) * v, std::asin(s), std::sqrt(1 - s * s), s};
}

Cone makeCone(const Vec3& axis, double angle, SunProfile profile) {
  Cone c;
  c.axis = axis, c.profile = profile;
  c.half = profile == SunProfile::Cone ? 0.5 * angle : std::min(0.5 * angle, kMaxDiscHalfAngle);
  if (!(c.half > 0)) return c.half = 0, c;
  const Frame f = frameAround(axis);
  c.e1 = f.e1, c.e2 = f.e2;
  c.cosHalf = std::cos(c.half), c.sinHalf = std::sin(c.half);
  c.facing = facingIrradiance(profile, c.half);
  return c;
}

double coneIrradiance(const Vec3& axis, double angle, const Vec3& normal, const Cap* occluder,
                      SunProfile profile) {
  return coneIrradiance(makeCone(axis, angle, profile), normal, occluder);
}

namespace {

// n . (integral of w dw over the intersection of caps A and B), by the boundary form of the vector
// irradiance: integral over a region of w dw = 1/2 of the loop integral of w x dw around its edge (Arvo
// 1995). Along a circle of angular radius r about c, from phi0 to phi1 (frame e1, e2 about c), that is
// 1/2 [sin^2 r (phi1 - phi0) c - cos r sin r ((sin phi1 - sin phi0) e1 - (cos phi1 - cos phi0) e2)]; the
// intersection's edge is the arc of each circle inside the other cap, symmetric about the plane of the two
// axes, so each arc of half-width psi gives sin^2 r psi c - cos r sin r sin psi u (u: towards the other
// axis, across c).
double capIntersectionMoment(const Vec3& n, const Vec3& a, double alpha, double cosA, double sinA,
                             const Cap& b) {
  const double ct = std::clamp(dot(a, b.axis), -1.0, 1.0);
  const Vec3 across = b.axis - ct * a;  // b's part across a: length sin theta (accurate for small theta)
  const double st = across.length();
  // Apart: theta >= alpha + g; one inside the other: theta <= |alpha - g|. By the cosines (no atan2).
  if (!(b.radius > 0) || (alpha + b.radius < kPi && ct <= cosA * b.cosRadius - sinA * b.sinRadius)) return 0;
  if (ct >= cosA * b.cosRadius + sinA * b.sinRadius)
    return alpha >= b.radius ? kPi * b.sinRadius * b.sinRadius * dot(n, b.axis)       // b inside a
                             : kPi * sinA * sinA * dot(n, a);                         // a inside b
  if (!(st > 0)) return kPi * (sinA * sinA - b.sinRadius * b.sinRadius) * dot(n, a);  // opposite: a band
  // The arcs' half-widths: the points of a's circle inside b satisfy cos(phi - phiB) > (cos g - cos a cos
  // theta) / (sin a sin theta), and the other way round.
  const double cA = std::clamp((b.cosRadius - cosA * ct) / (sinA * st), -1.0, 1.0);
  const double cB = std::clamp((cosA - b.cosRadius * ct) / (b.sinRadius * st), -1.0, 1.0);
  const double psiA = std::acos(cA), psiB = std::acos(cB);
  const Vec3 towardsB = (1.0 / st) * across, towardsA = (1.0 / st) * (a - ct * b.axis);
  return sinA * sinA * psiA * dot(n, a) - cosA * sinA * std::sqrt(1 - cA * cA) * dot(n, towardsB) +
         b.sinRadius * b.sinRadius * psiB * dot(n, b.axis) -
         b.cosRadius * b.sinRadius * std::sqrt(1 - cB * cB) * dot(n, towardsA);
}

// coneIrradiance; `rings`: the ring quadrature for every cone an occluder overlaps (tests hold the closed
// forms against it).
double irradiance(const Cone& cone, const Vec3& normal, const Cap* occluder, bool rings) {
  const Vec3& axis = cone.axis;
  const double a = cone.half;
  const double nl = dot(normal, axis);
  if (!(a > 0)) {
    if (nl <= 0) return 0;
    if (occluder && dot(axis, occluder->axis) > occluder->cosRadius) return 0;
    return nl;
  }
  const double cl = occluder ? dot(occluder->axis, axis) : 0.0;
  const bool occluded = occluder && overlaps(cone, *occluder);
  if (!occluded || (cone.profile == SunProfile::Cone && !rings)) {
    // The whole cone in front (pi sin^2 a (n . axis), normalized: n . axis) or behind, or cut by the horizon;
    // an occluder (in front of the surface) takes away the integral of n . w over its intersection with the
    // cone, in closed form too.
    double lit = 0;
    const double sinN = std::sqrt(std::max(0.0, 1 - nl * nl));
    if (nl * cone.cosHalf - sinN * cone.sinHalf >= 0) {
      lit = nl;  // cos(thetaN + a) >= 0
    } else if (nl * cone.cosHalf + sinN * cone.sinHalf <= 0) {
      return 0;  // cos(thetaN - a) <= 0: nothing in front, so no occluder either
    } else if (cone.profile == SunProfile::Cone && sinN > 0) {
      // A uniform cap cut by the horizon, in closed form (Snyder 1996, as in Lagarde & de Rousiers 2014,
      // "Moving Frostbite to PBR", sphere lights): x = cot a, y = -x cot thetaN,
      // z = sin thetaN sqrt(1 - y^2), E = (cos thetaN acos(y) - x z) sin^2 a + atan(z / x), over
      // pi sin^2 a. Tested against the quadrature.
      const double s2 = cone.sinHalf * cone.sinHalf, x = cone.cosHalf / cone.sinHalf;
      const double y = std::clamp(-x * nl / sinN, -1.0, 1.0), z = sinN * std::sqrt(1 - y * y);
      lit = ((nl * std::acos(y) - x * z) * s2 + std::atan2(z, x)) / (kPi * s2);
    } else {
      lit = -1;  // the disc cut by the horizon: by rings below
    }
    if (lit >= 0) {
      if (!occluded) return lit;
      const double hidden = capIntersectionMoment(normal, axis, a, cone.cosHalf, cone.sinHalf, *occluder) /
                            (kPi * cone.sinHalf * cone.sinHalf);
      return std::max(0.0, lit - hidden);
    }
  }
  const double n1 = dot(normal, cone.e1), n2 = dot(normal, cone.e2), bn = std::sqrt(n1 * n1 + n2 * n2);
  double c1 = 0, c2 = 0, bc = 0, beta = 0, g = 0, cosG = 1, cosDelta = 0;
  if (occluded) {
    c1 = dot(occluder->axis, cone.e1), c2 = dot(occluder->axis, cone.e2);
    bc = std::sqrt(c1 * c1 + c2 * c2);
    beta = angleBetween(cl, bc);
    g = occluder->radius, cosG = occluder->cosRadius;
    cosDelta = bc > 0 && bn > 0 ? (c1 * n1 + c2 * n2) / (bc * bn) : 0.0;
  }
  const SunProfile profile = cone.profile;
  // One ring at angle t from the axis: w = cos t axis + sin t (cos phi e1 + sin phi e2), and
  // n . w = A + B cos(phi - phiN). Its integral over the ring's lit arc, less the occluded arc.
  auto ring = [&](double t) {
    const double ct = std::cos(t), st = std::sin(t);
    const double A = nl * ct, B = bn * st;
    double lit;
    if (B <= std::abs(A)) {
      lit = A > 0 ? 2 * kPi * A : 0.0;
    } else {  // sin(acos(c)) = sqrt(1 - c^2)
      const double c = std::clamp(-A / B, -1.0, 1.0);
      lit = 2 * A * std::acos(c) + 2 * B * std::sqrt(1 - c * c);
    }
    if (occluded) {
      const double Ac = cl * ct, Bc = bc * st;
      double psi, sinPsi;
      if (Bc <= 1e-300) {
        psi = Ac >= cosG ? kPi : 0.0, sinPsi = 0;
      } else {
        const double c = std::clamp((cosG - Ac) / Bc, -1.0, 1.0);
        psi = std::acos(c), sinPsi = std::sqrt(1 - c * c);
      }
      lit -= 2 * A * psi + 2 * B * cosDelta * sinPsi;
    }
    return std::max(0.0, lit) * st * profileWeight(profile, ct);
  };
  // Pieces split where an arc opens or closes: the horizon of the normal, the occluder's near and far edges.
  std::array<double, 6> cuts{};
  int count = 0;
  cuts[count++] = 0;
  auto cut = [&](double t) {
    if (t > 0 && t < a) cuts[count++] = t;
  };
  cut(angleBetween(bn, std::abs(nl)));  // where the ring meets the horizon: tan t = |nl| / bn
  if (occluded) cut(std::abs(beta - g)), cut(beta + g);
  cuts[count++] = a;
  for (int i = 1; i < count; ++i)  // a handful: insertion sort
    for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);
  double sum = 0;
  for (int i = 0; i + 1 < count; ++i)
    if (cuts[i + 1] > cuts[i]) sum += smoothPiece(cuts[i], cuts[i + 1], ring);
  return sum / cone.facing;
}

}  // namespace

bool overlaps(const Cone& cone, const Cap& cap) {
  // The angle between their axes below a + g, i.e. its cosine above cos(a + g) (always when a + g >= pi).
  return cone.half + cap.radius >= kPi ||
         dot(cap.axis, cone.axis) > cone.cosHalf * cap.cosRadius - cone.sinHalf * cap.sinRadius;
}

double coneIrradiance(const Cone& cone, const Vec3& normal, const Cap* occluder) {
  return irradiance(cone, normal, occluder, false);
}

double coneIrradianceByRings(const Cone& cone, const Vec3& normal, const Cap* occluder) {
  return irradiance(cone, normal, occluder, true);
}

double coneGlossy(const Vec3& axis, double angle, const Vec3& reflected, int exponent, SunProfile profile) {
  const double a = profile == SunProfile::Cone ? 0.5 * angle : std::min(0.5 * angle, kMaxDiscHalfAngle);
  const double norm = (exponent + 1) / (2 * kPi);
  auto lobe = [&](double c) {  // c^exponent by squaring (no pow: the add-on's module stays on glibc 2.28)
    if (c <= 0) return 0.0;
    double v = 1, b = c;
    for (int e = exponent; e > 0; e >>= 1, b *= b)
      if (e & 1) v *= b;
    return v;
  };
  if (!(a > 0)) return norm * lobe(dot(reflected, axis));
  const Frame f = frameAround(axis);
  const double rl = dot(reflected, axis), r1 = dot(reflected, f.e1), r2 = dot(reflected, f.e2);
  constexpr int kAround = 32;
  auto ring = [&](double t) {
    const double ct = std::cos(t), st = std::sin(t);
    double s = 0;
    for (int k = 0; k < kAround; ++k) {
      const double phi = 2 * kPi * (k + 0.5) / kAround;
      s += lobe(rl * ct + st * (r1 * std::cos(phi) + r2 * std::sin(phi)));
    }
    return s * (2 * kPi / kAround) * st * profileWeight(profile, ct);
  };
  double sum = 0;
  for (int half = 0; half < 2; ++half) sum += smoothPiece(half * 0.5 * a, (half + 1) * 0.5 * a, ring);
  return norm * sum / facingIrradiance(profile, a);
}

}  // namespace probelights
