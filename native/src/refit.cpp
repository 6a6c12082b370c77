#include "probelights/refit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "parallel.h"
#include "probelights/error.h"
#include "probelights/nnls.h"
#include "trial_fit.h"

namespace probelights {

namespace {

constexpr std::size_t kMaxMoved = 64;
constexpr std::size_t kPlaceAtBrightest = 256;

Vec3 rotateAbout(const Vec3& d, const Vec3& axis, double angle) {  // Rodrigues' rotation
  const Vec3 k = (1.0 / axis.length()) * axis;
  const Vec3 kxd{k.y * d.z - k.z * d.y, k.z * d.x - k.x * d.z, k.x * d.y - k.y * d.x};
  return std::cos(angle) * d + std::sin(angle) * kxd + (dot(k, d) * (1 - std::cos(angle))) * k;
}

// Coordinate descent on the lights' directions against the receivers' luminance (weighted: each set's
// relative error^2), colours fixed: each light tries four moves (trial_fit.h), in order, each from the
// direction the moves before it left; the ones not yet tried are scored together from the current direction,
// again after a move is taken (one batch and a quarter a light on average), so the moves are the same as one
// by one.
void moveDirections(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
                    std::vector<Light>& lights) {
  // The brightest kMaxMoved lights move; past them a light is a small part of the light and a move buys
  // little for its cost.
  std::vector<std::size_t> order(lights.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return luminance(lights[a].rgb) > luminance(lights[b].rgb);
  });
  if (order.size() > kMaxMoved) order.resize(kMaxMoved);
  TrialFit fit(evaluator, receivers, lights, order);
  for (double step : {4.0, 2.0, 1.0, 0.5})
    for (std::size_t index : order) {
      Light& l = lights[index];
      const Vec3 d = l.direction;
      const Vec3 t1 = std::abs(d.z) < 0.9 ? Vec3{-d.y, d.x, 0} : Vec3{0, -d.z, d.y};
      const Vec3 t2{d.y * t1.z - d.z * t1.y, d.z * t1.x - d.x * t1.z, d.x * t1.y - d.y * t1.x};
      const std::array<std::pair<Vec3, double>, 4> moves{{{t1, step}, {t1, -step}, {t2, step}, {t2, -step}}};
      for (std::size_t first = 0; first < moves.size();) {
        std::vector<Light> trials{l};
        for (std::size_t c = first; c < moves.size(); ++c) {
          trials.push_back(l);
          trials.back().direction = rotateAbout(l.direction, moves[c].first, moves[c].second * kPi / 180);
        }
        const std::vector<double> f = fit.objectives(index, trials);
        std::size_t next = moves.size();
        for (std::size_t t = 1; t < trials.size(); ++t)
          if (f[t] < f[0]) {
            fit.accept(index, t);
            l.direction = trials[t].direction;
            next = first + t;
            break;
          }
        first = next;
      }
    }
}

}  // namespace

void solveColours(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
                  std::vector<Light>& lights, const Rgb* total) {
  const int m = static_cast<int>(receivers.size()), n = static_cast<int>(lights.size());
  if (n == 0) return;
  const bool hold = total && ((*total)[0] > 0 || (*total)[1] > 0 || (*total)[2] > 0);
  const int rows = m + (hold ? 1 : 0);
  // Weighted least squares: each row scaled by the square root of its set's weight.
  std::vector<double> A(static_cast<std::size_t>(rows) * n);
  parallelFor(n, [&](std::int64_t j) {  // a light's column at once (its cone prepared once)
    std::vector<double> column;
    evaluator.kernels(lights[j], receivers, 1.0, column);
    for (int i = 0; i < m; ++i) A[i * n + j] = std::sqrt(receivers[i].weight) * column[i];
  });
  std::vector<std::vector<double>> b(3, std::vector<double>(rows));
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < m; ++i) b[c][i] = std::sqrt(receivers[i].weight) * receivers[i].truth[c];
  if (hold) {
    // The sum as one more row, sum_j x_j = total, weighted kHoldWeight times the columns' root mean square
    // norm: a penalty (Lawson & Hanson 1974, ch. 22, equality constraints by weighting) that leaves the sum a
    // small fraction of the refit's usual shift off; the scaling below makes it exact. A larger weight would
    // square into the normal equations' condition for no visible gain.
    constexpr double kHoldWeight = 10;
    double squares = 0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(m) * n; ++k) squares += A[k] * A[k];
    const double weight = kHoldWeight * std::sqrt(squares / n);
    for (int j = 0; j < n; ++j) A[static_cast<std::size_t>(m) * n + j] = weight;
    for (int c = 0; c < 3; ++c) b[c][m] = weight * std::max(0.0, (*total)[c]);
  }
  const std::vector<std::vector<double>> x = nonNegativeLeastSquares(A, rows, n, b);
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (int j = 0; j < n; ++j) sum += x[c][j];
    const double scale = hold && (*total)[c] > 0 && sum > 0 ? (*total)[c] / sum : 1.0;
    for (int j = 0; j < n; ++j) lights[j].rgb[c] = x[c][j] * scale;
  }
}

bool placeDarkLights(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
                     std::vector<Light>& lights) {
  std::vector<std::size_t> dark;
  for (std::size_t j = 0; j < lights.size(); ++j)
    if (!(luminance(lights[j].rgb) > 0)) dark.push_back(j);
  if (dark.empty()) return false;
  const std::size_t m = receivers.size();
  std::vector<double> residual(m), term;
  for (std::size_t i = 0; i < m; ++i) residual[i] = luminance(receivers[i].truth);
  for (const Light& l : lights) {
    evaluator.kernels(l, receivers, luminance(l.rgb), term);
    for (std::size_t i = 0; i < m; ++i) residual[i] -= term[i];
  }
  std::vector<Vec3> candidates = evaluator.brightestDirections(kPlaceAtBrightest);
  candidates.insert(candidates.end(), evaluator.normals().begin(), evaluator.normals().end());
  std::vector<std::vector<double>> columns(candidates.size());
  parallelFor(static_cast<std::int64_t>(candidates.size()), [&](std::int64_t c) {
    Light point;
    point.direction = candidates[c];
    evaluator.kernels(point, receivers, 1.0, columns[c]);
  });
  bool moved = false;
  for (std::size_t j : dark) {
    double best = 0, bestScale = 0;
    std::size_t bestCandidate = candidates.size();
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      double kr = 0, kk = 0;
      for (std::size_t i = 0; i < m; ++i) {
        kr += receivers[i].weight * columns[c][i] * residual[i];
        kk += receivers[i].weight * columns[c][i] * columns[c][i];
      }
      if (kr > 0 && kk > 0 && kr * kr / kk > best)
        best = kr * kr / kk, bestCandidate = c, bestScale = kr / kk;
    }
    if (bestCandidate == candidates.size()) break;
    lights[j].direction = candidates[bestCandidate];
    lights[j].angle = 0;
    for (std::size_t i = 0; i < m; ++i) residual[i] -= bestScale * columns[bestCandidate][i];
    moved = true;
  }
  return moved;
}

std::vector<Light> refitIrradiance(const Evaluator& evaluator, const std::vector<Light>& lights,
                                   double* energyShift, const RefitOptions& options) {
  // Fitted on the evaluator's fit receivers (its fit normals, 1024 unless asked, and 1024 ground points with
  // shadows), not the points the error is measured on, so the error of a refit is not flattered.
  if (evaluator.fitNormals().empty())
    throw Error("the irradiance refit needs an evaluator made for it (diffuse, forRefit)");
  const std::vector<Receiver> receivers = evaluator.fitReceivers(true);
  if (lights.size() > kMaxRefitLights)
    throw Error("the irradiance refit takes at most " + std::to_string(kMaxRefitLights) + " lights, got " +
                std::to_string(lights.size()));
  const int n = static_cast<int>(lights.size());
  std::vector<Light> out = lights;
  if (n == 0) return out;
  Rgb sum{};
  for (const Light& l : lights)
    for (int c = 0; c < 3; ++c) sum[c] += l.rgb[c];
  const Rgb* held = options.keepEnergy ? &sum : nullptr;
  solveColours(evaluator, receivers, out, held);
  if (placeDarkLights(evaluator, receivers, out)) solveColours(evaluator, receivers, out, held);
  const int rounds = options.moveRounds > 0                  ? options.moveRounds
                     : lights.size() <= kThreeMoveRoundsUpTo ? 3
                                                             : 2;
  for (int round = 0; options.moveDirections && round < rounds; ++round) {
    moveDirections(evaluator, receivers, out);
    solveColours(evaluator, receivers, out, held);
  }
  double before = 0, after = 0;
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) before += lights[j].rgb[c], after += out[j].rgb[c];
  double total = 0;
  for (const Light& l : out) total += luminance(l.rgb);
  for (Light& l : out) l.energyShare = total > 0 ? luminance(l.rgb) / total : 0.0;
  if (energyShift) *energyShift = before > 0 ? after / before - 1.0 : 0.0;
  return out;
}

}  // namespace probelights
