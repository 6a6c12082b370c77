#include "probelights/spherical_harmonics.h"

#include <algorithm>
#include <cmath>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/names.h"

namespace probelights {

namespace {
int legendreIndex(int l, int m) { return l * (l + 1) / 2 + m; }
constexpr double kSqrt2 = 1.4142135623730951;
}  // namespace

namespace {
constexpr NameTable<ShWindow, 3> kWindows{
    {{ShWindow::None, "none"}, {ShWindow::Hanning, "hanning"}, {ShWindow::Lanczos, "lanczos"}}};
}  // namespace

std::string toString(ShWindow window) { return nameOf(kWindows, window); }
ShWindow parseShWindow(const std::string& name) { return parseName(kWindows, "window", name); }

void normalizedLegendre(int bands, double z, std::span<double> out) {
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  for (int m = 0; m < bands; ++m) {
    double mm = m == 0 ? 1.0 / std::sqrt(4.0 * kPi)
                       : -std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * s * out[legendreIndex(m - 1, m - 1)];
    out[legendreIndex(m, m)] = mm;
    if (m + 1 < bands) out[legendreIndex(m + 1, m)] = std::sqrt(2.0 * m + 3.0) * z * mm;
    for (int l = m + 2; l < bands; ++l) {
      double a = std::sqrt((4.0 * l * l - 1.0) / (static_cast<double>(l) * l - static_cast<double>(m) * m));
      double b = std::sqrt(((l - 1.0) * (l - 1.0) - static_cast<double>(m) * m) /
                           (4.0 * (l - 1.0) * (l - 1.0) - 1.0));
      out[legendreIndex(l, m)] = a * (z * out[legendreIndex(l - 1, m)] - b * out[legendreIndex(l - 2, m)]);
    }
  }
}

void shBasis(int bands, const Vec3& d, std::span<double> out) {
  std::vector<double> legendre(static_cast<std::size_t>(bands) * (bands + 1) / 2);
  normalizedLegendre(bands, std::clamp(d.z, -1.0, 1.0), legendre);
  const double phi = std::atan2(d.y, d.x);
  for (int m = 0; m < bands; ++m) {
    const double c = std::cos(m * phi), s = std::sin(m * phi);
    for (int l = m; l < bands; ++l) {
      const double n = legendre[legendreIndex(l, m)];
      if (m == 0) {
        out[shIndex(l, 0)] = n;
      } else {
        out[shIndex(l, m)] = kSqrt2 * n * c;
        out[shIndex(l, -m)] = kSqrt2 * n * s;
      }
    }
  }
}

Rgb ShCoefficients::evaluate(const Vec3& d) const {
  std::vector<double> y(shCount(bands));
  shBasis(bands, d, y);
  Rgb v{};
  for (int i = 0; i < shCount(bands); ++i)
    for (int k = 0; k < 3; ++k) v[k] += c[i][k] * y[i];
  return v;
}

std::vector<double> ShCoefficients::luminance() const {
  std::vector<double> y(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) y[i] = probelights::luminance(c[i]);
  return y;
}

ShCoefficients projectProbe(const Probe& probe, int bands) {
  if (bands < 1) throw Error("asked for " + std::to_string(bands) + " SH bands: ask for at least 1");
  // The projection costs bands^2 per pixel (and the sampler's tables as much again): 64 bands take seconds
  // on a 1K probe, 256 took minutes with nothing to show. 64 bands resolve features of ~3 degrees, finer
  // than any light count the sampler is asked for.
  if (bands > kMaxShBands)
    throw Error("asked for " + std::to_string(bands) + " SH bands: at most " + std::to_string(kMaxShBands));
  const int W = probe.width(), H = probe.height(), n = shCount(bands);
  const Projection& projection = probe.projection();
  // Per-row partial sums, added in row order (parallelReduce): deterministic whatever the thread count.
  ShCoefficients sh{bands, std::vector<Rgb>(n)};
  auto add = [&](ShCoefficients& total, const std::vector<Rgb>& row, std::int64_t) {
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) total.c[i][k] += row[i][k];
  };
  if (projection.kind() == ProjectionKind::LatLong) {
    // Exact for a probe that is constant over each pixel: c_lm = sum_p L_p * integral over pixel p of Y_lm,
    // and the pixel integral is separable, (integral of N_l^|m| dz over the row) x (integral of trig(m phi)
    // over the column), both in closed form (ShRectIntegrator). So a uniform probe gives exactly 0 above band
    // 0.
    const ShRectIntegrator basis(bands, std::vector<double>(n, 0.0));
    const int trig = 2 * bands - 1;
    std::vector<double> phiInt(static_cast<std::size_t>(W) * trig);
    for (int x = 0; x < W; ++x)  // column x spans phi from 2pi(0.5 - (x+1)/W) to 2pi(0.5 - x/W)
      basis.phiIntegrals(2.0 * kPi * (0.5 - (x + 1.0) / W), 2.0 * kPi * (0.5 - static_cast<double>(x) / W),
                         std::span<double>(phiInt.data() + static_cast<std::size_t>(x) * trig, trig));
    sh = parallelReduce(
        H, std::move(sh),
        [&](std::int64_t y) {
          std::vector<Rgb> a(trig);
          for (int x = 0; x < W; ++x) {
            const Rgb L = probe.radiance(x, static_cast<int>(y));
            if (L[0] == 0 && L[1] == 0 && L[2] == 0) continue;
            const double* p = phiInt.data() + static_cast<std::size_t>(x) * trig;
            for (int j = 0; j < trig; ++j)
              for (int k = 0; k < 3; ++k) a[j][k] += L[k] * p[j];
          }
          std::vector<double> zInt(static_cast<std::size_t>(bands) * (bands + 1) / 2);
          basis.zIntegrals(std::cos(kPi * (y + 1.0) / H), std::cos(kPi * static_cast<double>(y) / H), zInt);
          std::vector<Rgb> out(n);
          for (int l = 0; l < bands; ++l)
            for (int m = -l; m <= l; ++m) {
              const double z = zInt[legendreIndex(l, std::abs(m))];
              for (int k = 0; k < 3; ++k) out[shIndex(l, m)][k] += z * a[bands - 1 + m][k];
            }
          return out;
        },
        add);
  } else {
    sh = parallelReduce(
        H, std::move(sh),
        [&](std::int64_t y) {
          std::vector<Vec3> dirs(W);
          std::vector<double> omega(W), basis(n);
          projection.rowGeometry(static_cast<int>(y), 0, W, dirs, omega);
          std::vector<Rgb> out(n);
          for (int x = 0; x < W; ++x) {
            if (omega[x] <= 0) continue;
            const Rgb L = probe.radiance(x, static_cast<int>(y));
            shBasis(bands, dirs[x], basis);
            for (int i = 0; i < n; ++i)
              for (int k = 0; k < 3; ++k) out[i][k] += L[k] * omega[x] * basis[i];
          }
          return out;
        },
        add);
  }
  return sh;
}

void applyWindow(ShCoefficients& sh, ShWindow window) {
  for (int l = 0; l < sh.bands; ++l) {
    double t = static_cast<double>(l) / sh.bands, w = 1.0;
    if (window == ShWindow::Hanning) w = 0.5 * (1.0 + std::cos(kPi * t));
    if (window == ShWindow::Lanczos) w = l == 0 ? 1.0 : std::sin(kPi * t) / (kPi * t);
    for (int m = -l; m <= l; ++m)
      for (double& v : sh.c[shIndex(l, m)]) v *= w;
  }
}

double irradianceFactor(int l) {
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  // C(l, l/2) / 2^l, built as a product so it neither overflows nor underflows.
  double central = 1.0;
  for (int k = 1; k <= l / 2; ++k) central *= static_cast<double>(l / 2 + k) / (4.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * central;
}

ShCoefficients irradianceCoefficients(const ShCoefficients& radiance) {
  ShCoefficients e = radiance;
  for (int l = 0; l < e.bands; ++l)
    for (int m = -l; m <= l; ++m)
      for (double& v : e.c[shIndex(l, m)]) v *= irradianceFactor(l);
  return e;
}

ShRectIntegrator::ShRectIntegrator(int bands, std::vector<double> coefficients)
    : bands_(bands), coefficients_(std::move(coefficients)) {
  if (static_cast<int>(coefficients_.size()) != shCount(bands))
    throw Error("SH integrator: " + std::to_string(coefficients_.size()) + " coefficients for " +
                std::to_string(bands) + " bands");
  fourier_.resize(static_cast<std::size_t>(bands) * (bands + 1) / 2);
  std::vector<double> legendre(fourier_.size());
  for (int l = 0; l < bands; ++l) {
    // N_l^m(cos theta) is a trigonometric polynomial of degree <= l: sample it at M = 2l + 2 points and take
    // the DFT.
    const int M = 2 * l + 2;
    std::vector<std::vector<double>> samples(l + 1, std::vector<double>(M));
    for (int j = 0; j < M; ++j) {
      double theta = 2.0 * kPi * j / M;
      normalizedLegendre(l + 1, std::cos(theta), legendre);
      // sin(theta) < 0 for theta > pi: N_l^m carries sin^m(theta), continued as the polynomial in sin, so
      // flip odd m.
      double sign = std::sin(theta) < 0 ? -1.0 : 1.0;
      for (int m = 0; m <= l; ++m) samples[m][j] = legendre[legendreIndex(l, m)] * (m % 2 == 1 ? sign : 1.0);
    }
    for (int m = 0; m <= l; ++m) {
      std::vector<double>& f = fourier_[legendreIndex(l, m)];
      f.assign(l + 1, 0.0);
      for (int k = 0; k <= l; ++k) {
        double s = 0;
        for (int j = 0; j < M; ++j) {
          double angle = 2.0 * kPi * k * j / M;
          s += samples[m][j] * (m % 2 == 0 ? std::cos(angle) : std::sin(angle));
        }
        f[k] = s * (k == 0 ? 1.0 : 2.0) / M;
      }
    }
  }
}

double ShRectIntegrator::thetaAntiderivative(int l, int m, double theta) const {
  // Antiderivative of N_l^m(cos theta) sin(theta) from its Fourier series.
  const std::vector<double>& f = fourier_[legendreIndex(l, m)];
  double F = 0;
  for (int k = 0; k < static_cast<int>(f.size()); ++k) {
    if (f[k] == 0) continue;
    if (m % 2 == 0) {  // cos(k t) sin(t) = [sin((k+1)t) - sin((k-1)t)] / 2
      double a = -std::cos((k + 1) * theta) / (k + 1);
      double b = k == 1 ? 0.0 : -std::cos((k - 1) * theta) / (k - 1);
      F += f[k] * 0.5 * (a - b);
    } else {  // sin(k t) sin(t) = [cos((k-1)t) - cos((k+1)t)] / 2
      double a = k == 1 ? theta : std::sin((k - 1) * theta) / (k - 1);
      double b = std::sin((k + 1) * theta) / (k + 1);
      F += f[k] * 0.5 * (a - b);
    }
  }
  return F;
}

void ShRectIntegrator::zIntegrals(double z0, double z1, std::span<double> out) const {
  const double t0 = std::acos(std::clamp(z0, -1.0, 1.0)), t1 = std::acos(std::clamp(z1, -1.0, 1.0));
  for (int l = 0; l < bands_; ++l)
    for (int m = 0; m <= l; ++m)
      out[legendreIndex(l, m)] = thetaAntiderivative(l, m, t0) - thetaAntiderivative(l, m, t1);
}

void ShRectIntegrator::phiIntegrals(double phi0, double phi1, std::span<double> out) const {
  // out[bands-1+m]: integral of sqrt2 cos(m phi) (m > 0), 1 (m = 0), sqrt2 sin(|m| phi) (m < 0).
  for (int m = -(bands_ - 1); m < bands_; ++m) {
    double v;
    if (m == 0)
      v = phi1 - phi0;
    else if (m > 0)
      v = kSqrt2 * (std::sin(m * phi1) - std::sin(m * phi0)) / m;
    else
      v = kSqrt2 * (std::cos(-m * phi0) - std::cos(-m * phi1)) / (-m);
    out[bands_ - 1 + m] = v;
  }
}

double ShRectIntegrator::combine(std::span<const double> z, std::span<const double> phi) const {
  double s = 0;
  for (int l = 0; l < bands_; ++l)
    for (int m = -l; m <= l; ++m)
      s += coefficients_[shIndex(l, m)] * z[legendreIndex(l, std::abs(m))] * phi[bands_ - 1 + m];
  return s;
}

double ShRectIntegrator::integral(double z0, double z1, double phi0, double phi1) const {
  std::vector<double> z(fourier_.size()), phi(2 * bands_ - 1);
  zIntegrals(z0, z1, z);
  phiIntegrals(phi0, phi1, phi);
  return combine(z, phi);
}

}  // namespace probelights
