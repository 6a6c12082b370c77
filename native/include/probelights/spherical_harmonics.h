// Real spherical harmonics: basis, projection of a probe, windowing, irradiance, exact integrals over
// rectangles.
//
// Convention (Sloan, "Stupid Spherical Harmonics Tricks", 2008): orthonormal real SH with the Condon-Shortley
// phase, index i = l (l + 1) + m for band l = 0..bands-1 and -l <= m <= l, angles in Blender's frame: theta
// from +Z (up), phi = atan2(y, x). With N_l^m the normalized associated Legendre function,
//   Y_l^0  = N_l^0(cos theta),
//   Y_l^m  = sqrt(2) N_l^m(cos theta) cos(m phi),
//   Y_l^-m = sqrt(2) N_l^m(cos theta) sin(m phi)
// so that Y_1^-1 = -sqrt(3/4pi) y, Y_1^0 = sqrt(3/4pi) z, Y_1^1 = -sqrt(3/4pi) x.
// N_l^m is computed by the fully normalized recurrence (stable to hundreds of bands: no factorials, no
// cancellation):
//   N_0^0     = 1/sqrt(4 pi),
//   N_m^m     = -sqrt((2m+1)/(2m)) sin(theta) N_{m-1}^{m-1},
//   N_{m+1}^m = sqrt(2m+3) z N_m^m,
//   N_l^m     = a (z N_{l-1}^m - b N_{l-2}^m),
//               a = sqrt((4l^2-1)/(l^2-m^2)),  b = sqrt(((l-1)^2-m^2)/(4(l-1)^2-1)).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "probelights/geometry.h"
#include "probelights/probe.h"

namespace probelights {

inline int shCount(int bands) { return bands * bands; }
// The most bands a projection takes (spherical_harmonics.cpp says why).
inline constexpr int kMaxShBands = 64;
inline int shIndex(int l, int m) { return l * (l + 1) + m; }

// All bands^2 basis functions at unit direction d.
void shBasis(int bands, const Vec3& d, std::span<double> out);
// N_l^m(z) for 0 <= m <= l < bands, at index l (l + 1) / 2 + m.
void normalizedLegendre(int bands, double z, std::span<double> out);

enum class ShWindow { None, Hanning, Lanczos };
std::string toString(ShWindow window);            // "none", "hanning", "lanczos"
ShWindow parseShWindow(const std::string& name);  // throws Error naming the choices

struct ShCoefficients {
  int bands = 0;
  std::vector<Rgb> c;  // bands^2 RGB coefficients

  Rgb evaluate(const Vec3& d) const;
  std::vector<double> luminance() const;  // Rec. 709 combination: the scalar function samplers use
};

// c_i = integral of L Y_i over the sphere. Lat-long probes: exact for pixels of constant radiance (the pixel
// integrals of Y_i are separable and analytic); mirror-ball and angular probes: L Y_i(pixel centre) x the
// pixel's exact solid angle.
ShCoefficients projectProbe(const Probe& probe, int bands);
// Multiplies band l by a window against ringing: Hanning (1 + cos(pi l / bands)) / 2, Lanczos sinc(l /
// bands).
void applyWindow(ShCoefficients& sh, ShWindow window);
// Irradiance (Ramamoorthi & Hanrahan 2001): E_lm = A_l L_lm with
//   A_0 = pi,  A_1 = 2pi/3,
//   A_l = 2pi (-1)^(l/2-1) / ((l+2)(l-1)) * C(l, l/2) / 2^l  (even l),  A_l = 0  (odd l > 1).
ShCoefficients irradianceCoefficients(const ShCoefficients& radiance);
double irradianceFactor(int l);

// Exact integrals of a scalar SH expansion over rectangles [z0, z1] x [phi0, phi1] of the (cos theta, phi)
// domain, which is area-preserving (dOmega = dz dphi), so a density there is a density on the sphere.
// Separable and analytic: the phi integral of cos/sin(m phi) is elementary; N_l^m(cos theta) is a
// trigonometric polynomial of degree l in theta, whose Fourier coefficients are found exactly (a DFT of 2l+2
// samples is exact for such a polynomial), so its integral dz = sin(theta) dtheta has a closed-form
// antiderivative.
class ShRectIntegrator {
 public:
  ShRectIntegrator(int bands, std::vector<double> coefficients);
  int bands() const { return bands_; }
  const std::vector<double>& coefficients() const { return coefficients_; }
  double integral(double z0, double z1, double phi0, double phi1) const;
  // Per-basis-function integrals over z in [z0, z1] (index l(l+1)/2 + m, m >= 0) and over phi (index
  // bands-1+m).
  void zIntegrals(double z0, double z1, std::span<double> out) const;
  void phiIntegrals(double phi0, double phi1, std::span<double> out) const;
  double combine(std::span<const double> z, std::span<const double> phi) const;

 private:
  double thetaAntiderivative(int l, int m, double theta) const;
  int bands_;
  std::vector<double> coefficients_;
  std::vector<std::vector<double>>
      fourier_;  // per (l, m>=0): coefficients of cos(k theta) (m even) or sin (m odd)
};

}  // namespace probelights
