#include "probelights/sources.h"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/memory.h"

namespace probelights {

namespace {

// The luminance of a pixel's positive channels: what the level is compared with.
double positiveLuminance(const Rgb& l) {
  return luminance(std::max(l[0], 0.0), std::max(l[1], 0.0), std::max(l[2], 0.0));
}

// Row y's solid angles (exact, per pixel; zero outside a ball's or angular map's disc).
void rowSolidAngles(const Probe& probe, int y, std::vector<Vec3>& dirs, std::vector<double>& omega) {
  const int W = probe.width();
  dirs.resize(W);
  omega.resize(W);
  probe.projection().rowGeometry(y, 0, W, dirs, omega);
}

// The level T at which the pixels above it carry `share` of the luminous energy: E(T) = sum over pixels of
// max(0, Y - T) dw falls from the total at T = 0 to 0 at the brightest pixel, linearly between consecutive
// pixel luminances; with the pixels sorted brightest first and S_k, W_k the sums of Y dw and dw over the
// first k, E(T) = S_k - T W_k for T between the k-th and (k+1)-th luminance.
double levelForShare(std::vector<std::pair<double, double>> pixels, double total, double share) {
  std::sort(pixels.begin(), pixels.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  const double target = share * total;
  double S = 0, W = 0;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    S += pixels[k].first * pixels[k].second;
    W += pixels[k].second;
    const double next = k + 1 < pixels.size() ? pixels[k + 1].first : 0.0;
    if (S - next * W >= target) return std::max(next, (S - target) / W);
  }
  return 0;
}

}  // namespace

SourceSplit splitSources(const Probe& probe, const SourceLevel& how) {
  probe.requirePixels("splitting the probe's sources from its residual");
  const bool byLevel = how.level > 0, byShare = how.share > 0;
  if (byLevel == byShare || !std::isfinite(how.level) || !std::isfinite(how.share) || how.share >= 1)
    throw Error("the sources are chosen by a level above 0 or by a share between 0 and 1, one of the two");
  const int W = probe.width(), H = probe.height();

  // Pass 1: each row's luminous energy (and, for a share, every lit pixel's luminance and solid angle).
  std::vector<double> rowEnergy(H, 0.0);
  std::vector<std::vector<std::pair<double, double>>> rowPixels(byShare ? H : 0);
  parallelFor(H, [&](std::int64_t yy) {
    const int y = static_cast<int>(yy);
    thread_local std::vector<Vec3> dirs;
    thread_local std::vector<double> omega;
    rowSolidAngles(probe, y, dirs, omega);
    double e = 0;
    for (int x = 0; x < W; ++x) {
      const double Y = positiveLuminance(probe.light(x, y));
      e += Y * omega[x];
      if (byShare && Y > 0 && omega[x] > 0) rowPixels[y].emplace_back(Y, omega[x]);
    }
    rowEnergy[y] = e;
  });
  double total = 0;
  for (double e : rowEnergy) total += e;

  SourceSplit out;
  out.meanLuminance = total / (4 * kPi);
  if (byLevel) {
    out.level = how.level * out.meanLuminance;
  } else {
    std::vector<std::pair<double, double>> pixels;
    for (auto& row : rowPixels) pixels.insert(pixels.end(), row.begin(), row.end());
    rowPixels = {};
    out.level = levelForShare(std::move(pixels), total, how.share);
  }
  const double T = out.level;

  // Pass 2: R and X, and their sums per row (added in row order: the same bits however many threads ran).
  const std::size_t n = static_cast<std::size_t>(W) * H * 3;
  auto residual = std::make_shared<Image>(), sources = std::make_shared<Image>();
  for (Image* image : {residual.get(), sources.get()}) {
    image->pixels = keptArray<float>(n);
    image->width = W, image->height = H, image->channels = 3;
  }
  struct RowSums {
    Rgb r{}, x{};
    double sourceEnergy = 0;
  };
  std::vector<RowSums> rows(H);
  parallelFor(H, [&](std::int64_t yy) {
    const int y = static_cast<int>(yy);
    thread_local std::vector<Vec3> dirs;
    thread_local std::vector<double> omega;
    rowSolidAngles(probe, y, dirs, omega);
    float* const rRow = residual->pixels.get() + static_cast<std::size_t>(y) * W * 3;
    float* const xRow = sources->pixels.get() + static_cast<std::size_t>(y) * W * 3;
    RowSums s;
    for (int x = 0; x < W; ++x) {
      const Rgb l = probe.light(x, y);  // each a float's value: exact
      const double Y = positiveLuminance(l);
      const double scale = Y > T ? T / Y : 1.0;
      float kept[3];
      for (int c = 0; c < 3; ++c) {
        const float L = static_cast<float>(l[c]);
        const float R = L > 0 ? static_cast<float>(L * scale) : 0.0f;
        float X = L - R;  // exact, or (when R < L / 2) X >= L / 2 ...
        kept[c] = L - X;  // ... and then this is exact: kept + X = L
        // X's rounding can leave kept above R by up to half of X's last place (a sun's pixel of 55552 kept at
        // 5.6247 became 5.625), so above the level: X one place up brings kept below R, still exact.
        if (kept[c] > R && X < L) kept[c] = L - (X = std::nextafter(X, L));
        xRow[3 * x + c] = X;
        rRow[3 * x + c] = kept[c];
        s.r[c] += kept[c] * omega[x];
        s.x[c] += X * omega[x];
      }
      s.sourceEnergy += std::max(0.0, Y - T) * omega[x];
    }
    rows[y] = s;
  });
  double sourceEnergy = 0;
  for (const RowSums& s : rows) {
    for (int c = 0; c < 3; ++c) out.residualRgb[c] += s.r[c], out.sourcesRgb[c] += s.x[c];
    sourceEnergy += s.sourceEnergy;
  }
  out.share = total > 0 ? sourceEnergy / total : 0.0;
  out.residual = std::move(residual);
  out.sources = std::move(sources);
  return out;
}

int darkestSeam(const Probe& probe, const Image& sources) {
  if (probe.projection().kind() != ProjectionKind::LatLong) return 0;  // no seam: the others are discs
  const int W = sources.width, H = sources.height;
  // Down each column in bands of rows, a band's sums per thread, then the bands added in order: the same
  // bits whatever the thread count. A lat-long row's pixels share one solid angle.
  constexpr int kBand = 64;
  const int bands = (H + kBand - 1) / kBand;
  std::vector<std::vector<double>> bandSums(bands);
  parallelFor(bands, [&](std::int64_t b) {
    std::vector<double> sums(W, 0.0);
    for (int y = static_cast<int>(b) * kBand; y < std::min(H, static_cast<int>(b + 1) * kBand); ++y) {
      const double omega = probe.projection().pixelSolidAngle(0, y);
      const float* row = sources.pixels.get() + static_cast<std::size_t>(y) * W * 3;
      for (int x = 0; x < W; ++x)
        sums[x] += std::abs(luminance(row[3 * x], row[3 * x + 1], row[3 * x + 2])) * omega;
    }
    bandSums[b] = std::move(sums);
  });
  std::vector<double> column(W, 0.0);
  for (const auto& sums : bandSums)
    for (int x = 0; x < W; ++x) column[x] += sums[x];
  int best = 0;
  double least = column[W - 1] + column[0];
  for (int b = 1; b < W; ++b)
    if (const double e = column[b - 1] + column[b]; e < least) least = e, best = b;
  return best;
}

void rollColumns(Image& image, int b) {
  const int W = image.width, C = image.channels;
  if (W <= 0 || (b %= W) == 0) return;
  if (b < 0) b += W;
  parallelFor(image.height, [&](std::int64_t y) {
    float* row = image.pixels.get() + static_cast<std::size_t>(y) * W * C;
    std::rotate(row, row + static_cast<std::size_t>(b) * C, row + static_cast<std::size_t>(W) * C);
  });
}

}  // namespace probelights
