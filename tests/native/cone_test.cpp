// Lights as the renderer draws them (cone.h): the ring quadrature against brute-force sums over the cone, the
// point limit, and closed forms.
#include "probelights/cone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace probelights {
namespace {

Vec3 unit(double x, double y, double z) {
  const Vec3 v{x, y, z};
  return (1.0 / v.length()) * v;
}

// The cone's kernel by brute force: a midpoint grid of n x n cells equal in solid angle (cos t uniform in
// [cos a, 1], phi uniform), each direction tested against the normal and the occluder.
double bruteForce(const Vec3& l, double angle, const Vec3& n, const Cap* occluder, int cells,
                  SunProfile profile = SunProfile::Cone) {
  const double a = 0.5 * angle, ca = std::cos(a);
  const Vec3 up = std::abs(l.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  Vec3 e1 = unit(up.y * l.z - up.z * l.y, up.z * l.x - up.x * l.z, up.x * l.y - up.y * l.x);
  Vec3 e2{l.y * e1.z - l.z * e1.y, l.z * e1.x - l.x * e1.z, l.x * e1.y - l.y * e1.x};
  const double cosG = occluder ? std::cos(occluder->radius) : 2.0;
  double sum = 0;
  for (int i = 0; i < cells; ++i) {
    const double ct = ca + (1 - ca) * (i + 0.5) / cells, st = std::sqrt(1 - ct * ct);
    for (int j = 0; j < cells; ++j) {
      const double phi = 2 * kPi * (j + 0.5) / cells;
      const Vec3 w = ct * l + (st * std::cos(phi)) * e1 + (st * std::sin(phi)) * e2;
      if (occluder && dot(w, occluder->axis) > cosG) continue;
      const double weight = profile == SunProfile::Cone ? 1.0 : 1 / (ct * ct * ct);
      sum += std::max(0.0, dot(n, w)) * weight;
    }
  }
  const double solidAngle = 2 * kPi * (1 - ca), sa = std::sin(a);
  const double facing = profile == SunProfile::Cone ? kPi * sa * sa : 2 * kPi * (1 / ca - 1);
  return sum * solidAngle / (double(cells) * cells) / facing;
}

TEST(Cone, IrradianceMatchesBruteForceSampling) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), angle(0.02, 2.5);
  int shadowed = 0, grazing = 0;
  for (int k = 0; k < 40; ++k) {
    const Vec3 n = unit(0, 0, 1);
    const Vec3 l = unit(u(rng), u(rng), 0.6 * u(rng) + 0.3);
    const double full = angle(rng);
    // A ground point under the unit sphere resting on the plane at the origin: the evaluator's occluder,
    // always in front of the plane.
    const Vec3 p{2.2 * u(rng), 2.2 * u(rng), 0};
    const Cap sphere = sphereCap(p, {0, 0, 1}, 1.0);
    const Cap* occ = k % 4 == 3 ? nullptr : &sphere;
    const double got = coneIrradiance(l, full, n, occ), want = bruteForce(l, full, n, occ, 1200);
    EXPECT_NEAR(got, want, 1e-4) << "case " << k << " angle " << full;
    if (occ && got < coneIrradiance(l, full, n) - 1e-3) ++shadowed;
    if (std::acos(l.z) + 0.5 * full > 0.5 * kPi) ++grazing;
  }
  // The cases cover partly shadowed and horizon-crossing cones.
  EXPECT_GE(shadowed, 8);
  EXPECT_GE(grazing, 8);
}

TEST(Cone, AnyNormalWithoutOccluderMatchesBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1), angle(0.05, 3.0);
  for (int k = 0; k < 30; ++k) {
    const Vec3 n = unit(u(rng), u(rng), u(rng)), l = unit(u(rng), u(rng), u(rng));
    const double full = angle(rng);
    EXPECT_NEAR(coneIrradiance(l, full, n), bruteForce(l, full, n, nullptr, 1000), 1e-4) << "case " << k;
  }
}

TEST(Cone, TheHorizonClosedFormEqualsTheQuadrature) {
  // An unoccluded uniform cone cut by the horizon takes the closed form; an occluder of negligible radius in
  // the cone sends the same case through the ring quadrature.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), angle(0.01, 3.1);
  int cut = 0;
  for (int k = 0; k < 200; ++k) {
    const Vec3 n = unit(u(rng), u(rng), u(rng)), l = unit(u(rng), u(rng), u(rng));
    const double full = angle(rng);
    const Cap speck = makeCap(l, 1e-12);
    const double closed = coneIrradiance(l, full, n),
                 quadrature = coneIrradianceByRings(makeCone(l, full), n, &speck);
    EXPECT_NEAR(closed, quadrature, 1e-6) << "case " << k;
    if (closed > 1e-9 && std::abs(closed - dot(n, l)) > 1e-9) ++cut;
  }
  EXPECT_GE(cut, 40);  // the cases cross the horizon
}

TEST(Cone, TheOcclusionClosedFormEqualsTheQuadrature) {
  // The uniform cone less the occluder's part in closed form (the two caps' intersection by its edge) against
  // the ring quadrature: ground points under the sphere, and made-up caps in front of the surface of every
  // size, overlapping partly, one inside the other, and tiny cones.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1), unit01(0, 1);
  int partly = 0, inside = 0, covered = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 n{0, 0, 1};
    const Vec3 l = unit(u(rng), u(rng), 1.2 * u(rng) + 0.2);
    const double full = k % 10 == 0 ? 1e-4 * unit01(rng) : 3.1 * unit01(rng) * unit01(rng);
    Cap cap;
    if (k % 2 == 0) {
      cap = sphereCap({2.5 * u(rng), 2.5 * u(rng), 0}, {0, 0, 1}, 1.0);
    } else {  // a cap wholly above the horizon
      const Vec3 c = unit(u(rng), u(rng), unit01(rng) + 0.05);
      cap = makeCap(c, std::min(std::asin(c.z), 1.5) * unit01(rng));
    }
    const Cone cone = makeCone(l, full);
    const double closed = coneIrradiance(cone, n, &cap), rings = coneIrradianceByRings(cone, n, &cap);
    EXPECT_NEAR(closed, rings, 1e-6) << "case " << k << " angle " << full;
    const double open = coneIrradiance(cone, n), theta = std::acos(std::clamp(dot(l, cap.axis), -1.0, 1.0));
    if (closed < open - 1e-6 && closed > 1e-6) ++partly;
    if (theta + cap.radius < 0.5 * full && closed > 1e-6) ++inside;
    if (theta + 0.5 * full < cap.radius && open > 0) {
      ++covered;
      EXPECT_NEAR(closed, 0.0, 1e-12);
    }
  }
  EXPECT_GE(partly, 300);
  EXPECT_GE(inside, 30);
  EXPECT_GE(covered, 30);
}

TEST(Cone, Blender3sDiscMatchesBruteForce) {
  // Cycles 3.x: uniform over a tangent disc, radiance 1 / cos^3 t; a facing surface still gets 1.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1), angle(0.05, 2.4);
  for (int k = 0; k < 16; ++k) {
    const Vec3 l = unit(u(rng), u(rng), 0.6 * u(rng) + 0.3), n{0, 0, 1};
    const double full = angle(rng);
    const Vec3 p{2.2 * u(rng), 2.2 * u(rng), 0};
    const Cap sphere = sphereCap(p, {0, 0, 1}, 1.0);
    EXPECT_NEAR(coneIrradiance(l, full, n, &sphere, SunProfile::TangentDisc),
                bruteForce(l, full, n, &sphere, 1000, SunProfile::TangentDisc), 1e-4)
        << "case " << k;
  }
  EXPECT_NEAR(coneIrradiance({0, 0, 1}, 1.5, {0, 0, 1}, nullptr, SunProfile::TangentDisc), 1.0, 1e-12);
  // The same cone gives a shadow edge of another shape: the disc weights its rim.
  const Cap edge = makeCap(unit(0.3, 0, 1), 0.3);
  EXPECT_GT(std::abs(coneIrradiance({0, 0, 1}, 1.2, {0, 0, 1}, &edge, SunProfile::TangentDisc) -
                     coneIrradiance({0, 0, 1}, 1.2, {0, 0, 1}, &edge)),
            1e-3);
}

TEST(Cone, AngleZeroIsThePointLight) {
  const Vec3 l = unit(0.3, -0.2, 0.9), n = unit(0.1, 0.2, 1.0);
  EXPECT_EQ(coneIrradiance(l, 0.0, n), dot(n, l));
  EXPECT_EQ(coneIrradiance(l, 0.0, unit(0, 0, -1)), 0.0);
  const Cap hiding = makeCap(l, 0.1), beside = makeCap(unit(-0.3, 0.2, 0.9), 0.1);
  EXPECT_EQ(coneIrradiance(l, 0.0, n, &hiding), 0.0);
  EXPECT_EQ(coneIrradiance(l, 0.0, n, &beside), dot(n, l));
  // And a small cone is close to it.
  EXPECT_NEAR(coneIrradiance(l, 1e-3, n), dot(n, l), 1e-6);
  EXPECT_NEAR(coneGlossy(l, 0.0, n, 8), 9 / (2 * kPi) * std::pow(dot(n, l), 8), 1e-12);
}

TEST(Cone, ACapInFrontGivesItsCosine) {
  // A uniform cap entirely in front of a surface: integral of n . w = pi sin^2 a (n . axis), normalized to 1.
  const Vec3 l = unit(0.2, 0.1, 1.0), n{0, 0, 1};
  for (double full : {0.1, 0.5, 1.0, 1.5}) EXPECT_NEAR(coneIrradiance(l, full, n), l.z, 1e-12);
}

TEST(Cone, TheHemisphereUnderTheSphereIsTheClosedForm) {
  // A sun of 180 degrees straight up is the uniform upper hemisphere (radiance 1 / pi). A ground point sees
  // it less the cap of the unit sphere resting on the plane: half-angle g = asin(1 / D), axis at angle b from
  // the zenith, touching the horizon, so its projected solid angle is pi sin^2(g) cos(b).
  for (double x : {0.2, 0.7, 1.5, 2.4})
    for (double y : {0.0, 0.9}) {
      const Vec3 p{x, y, 0}, toCentre = Vec3{0, 0, 1} - p;
      const double D = toCentre.length(), sing = 1 / D, cosb = toCentre.z / D;
      const Cap sphere = sphereCap(p, {0, 0, 1}, 1.0);
      EXPECT_NEAR(coneIrradiance({0, 0, 1}, kPi, {0, 0, 1}, &sphere), 1 - sing * sing * cosb, 5e-6)
          << x << "," << y;
    }
}

TEST(Cone, GlossyMatchesBruteForce) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1), angle(0.05, 1.2);
  for (int k = 0; k < 12; ++k) {
    const Vec3 l = unit(u(rng), u(rng), u(rng));
    const Vec3 r = unit(l.x + 0.3 * u(rng), l.y + 0.3 * u(rng), l.z + 0.3 * u(rng));
    const double full = angle(rng), a = 0.5 * full, ca = std::cos(a);
    for (int e : {8, 64}) {
      // Brute force on a grid equal in solid angle.
      const int cells = 600;
      const Vec3 up = std::abs(l.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
      Vec3 e1 = unit(up.y * l.z - up.z * l.y, up.z * l.x - up.x * l.z, up.x * l.y - up.y * l.x);
      Vec3 e2{l.y * e1.z - l.z * e1.y, l.z * e1.x - l.x * e1.z, l.x * e1.y - l.y * e1.x};
      double sum = 0;
      for (int i = 0; i < cells; ++i) {
        const double ct = ca + (1 - ca) * (i + 0.5) / cells, st = std::sqrt(1 - ct * ct);
        for (int j = 0; j < cells; ++j) {
          const double phi = 2 * kPi * (j + 0.5) / cells;
          const double c = dot(r, ct * l + (st * std::cos(phi)) * e1 + (st * std::sin(phi)) * e2);
          if (c > 0) sum += std::pow(c, e);
        }
      }
      const double want = (e + 1) / (2 * kPi) * sum * 2 * kPi * (1 - ca) / (double(cells) * cells) /
                          (kPi * std::sin(a) * std::sin(a));
      const double got = coneGlossy(l, full, r, e);
      EXPECT_NEAR(got, want, 1e-3 * std::max(1.0, want)) << "case " << k << " exponent " << e;
    }
  }
}

}  // namespace
}  // namespace probelights
