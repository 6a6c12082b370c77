// A light as the renderer draws it: a Cycles sun of full angle 2a is a cone of half-angle a around its
// direction with uniform radiance, scaled so that a surface facing it receives its strength (Blender 4.0 and
// later normalize it so; for 3.4 the add-on divides the strength by 3.4's factor, conversion.py). A light's
// effect on a surface is then its rgb times a kernel of the cone: what this file computes. Angle 0 is a point
// direction (the kernels are then the point light's, bit for bit).
#pragma once

#include <string>

#include "probelights/geometry.h"

namespace probelights {

// How radiance spreads over a sun's cone, per renderer (checked in each Blender by
// tests/blender/test_render.py; docs/results/renders.md):
//   Cone: uniform (Cycles 4.0 and later: a uniform cone, normalized so a facing surface gets the strength);
//   TangentDisc: Cycles 3.x draws a sun of angle 2a as a disc of radius tan(a) at unit distance, uniform over
//     the disc, so radiance grows as 1 / cos^3 of the angle from the axis (a facing surface gets
//     2 cos(a) / (1 + cos(a)) of the strength, which the add-on divides out).
enum class SunProfile { Cone, TangentDisc };
std::string toString(SunProfile profile);             // "cone", "disc"
SunProfile parseSunProfile(const std::string& name);  // throws Error naming the choices

// How wide a sun's cone may be drawn:
//   Free: as wide as the profile draws;
//   AboveHorizon: never across the horizon (half-angle <= |elevation|: a sun above it stays above, one
//     below it below). EEVEE (4.2+) darkens a whole sun by the part of its cone below the horizon of the
//     floor it lights (it shadows that part, where Cycles gives it the floor's cosine, 0; docs/decisions.md).
enum class SunCones { Free, AboveHorizon };
std::string toString(SunCones cones);             // "free", "above-horizon"
SunCones parseSunCones(const std::string& name);  // throws Error naming the choices
// The widest full angle of a cone around `direction` (any length) that does not cross the horizon:
// 2 |elevation|.
double horizonAngle(const Vec3& direction);

// A spherical cap: the directions within `radius` (radians) of the unit `axis`, with the radius' cosine and
// sine (makeCap fills them).
struct Cap {
  Vec3 axis;
  double radius = 0, cosRadius = 1, sinRadius = 0;
};
Cap makeCap(const Vec3& axis, double radius);

// The cap a sphere of `radius` centred at `centre` covers seen from `point` (outside it).
Cap sphereCap(const Vec3& point, const Vec3& centre, double radius);

// A light's cone, prepared once for many receivers: its axis and a frame around it, the half-angle (clamped
// for the disc profile) with its cosine and sine, and the profile's facing irradiance.
struct Cone {
  Vec3 axis, e1, e2;
  double half = 0, cosHalf = 1, sinHalf = 0, facing = 0;
  SunProfile profile = SunProfile::Cone;
};
Cone makeCone(const Vec3& axis, double angle, SunProfile profile = SunProfile::Cone);
double coneIrradiance(const Cone& cone, const Vec3& normal, const Cap* occluder = nullptr);
// Whether the cap hides any of the cone (when not, the cone's irradiance is the same as without it).
bool overlaps(const Cone& cone, const Cap& cap);
// The same with every occluded cone integrated by the ring quadrature (the tests' reference for the closed
// form below).
double coneIrradianceByRings(const Cone& cone, const Vec3& normal, const Cap* occluder);

// Irradiance on a surface of unit normal `normal` from a unit-strength cone of full angle `angle` (radians,
// [0, pi]) along the unit `axis`, the directions inside `occluder` (if given) hidden:
//   (1 / (pi sin^2 a)) * integral over the cone, outside the occluder, of max(0, normal . w) dw.
// The occluder must lie in front of the surface (normal . w >= 0 on it), as a sphere resting on a plane does
// for points of the plane. A uniform cone (Cycles 4.0+) is closed-form: n . axis when it lies wholly above
// the horizon, 0 below, Snyder's formula for a cap cut by the horizon, less what the occluder hides: n . the
// integral of w over the two caps' intersection, from the arcs that bound it (Arvo's vector irradiance,
// cone.cpp); exact, and faster than the quadrature (docs/decisions.md). The disc profile where an occluder
// or the horizon cuts it is exact up to one-dimensional quadrature: rings around the axis, each ring's
// visible arcs and their cosine integral in closed form, Gauss-Legendre over the ring angle split where an
// arc appears (a smoothstep substitution on each piece takes away the square-root ends): errors ~1e-8, at
// most ~1e-6
// (tests: brute force, and the closed forms against the rings).
// With SunProfile::TangentDisc the radiance is weighted by 1 / cos^3 over the cone and normalized the same
// way (facing surface: 1); its angle is kept below 178 degrees (tan a finite).
double coneIrradiance(const Vec3& axis, double angle, const Vec3& normal, const Cap* occluder = nullptr,
                      SunProfile profile = SunProfile::Cone);

// A normalized Phong lobe (e + 1) / (2 pi) max(0, r . w)^e integrated over the same cone (radiance
// 1 / (pi sin^2 a)), by quadrature (Gauss-Legendre over the ring angle in two pieces, 32 points around each
// ring; within 1e-3, tested).
double coneGlossy(const Vec3& axis, double angle, const Vec3& reflected, int exponent,
                  SunProfile profile = SunProfile::Cone);

}  // namespace probelights
