#include "trial_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "parallel.h"

namespace probelights {

TrialFit::TrialFit(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
                   const std::vector<Light>& lights, const std::vector<std::size_t>& fitted)
    : evaluator_(evaluator),
      receivers_(receivers),
      target_(receivers.size()),
      sum_(receivers.size(), 0.0),
      terms_(lights.size()) {
  outer_.resize(receivers.size());
  for (std::size_t k = 0; k < receivers.size(); ++k) {
    const Receiver& r = receivers[k];
    const Vec3& n = r.at;
    const double w = r.weight;
    target_[k] = luminance(r.truth);
    outer_[k] = {w * n.x * n.x, w * n.y * n.y, w * n.z * n.z, w * n.x * n.y, w * n.x * n.z, w * n.y * n.z};
  }
  std::vector<char> kept(lights.size(), 0);
  for (std::size_t j : fitted) kept[j] = 1;
  std::vector<std::vector<double>> all(lights.size());
  parallelFor(static_cast<std::int64_t>(lights.size()), [&](std::int64_t j) {
    evaluator.kernels(lights[j], receivers, luminance(lights[j].rgb), all[j]);
  });
  for (std::size_t j = 0; j < lights.size(); ++j) {
    for (std::size_t k = 0; k < receivers.size(); ++k) sum_[k] += all[j][k];
    if (kept[j]) terms_[j].swap(all[j]);
  }
}

namespace {
constexpr std::size_t kChunk = 256;       // receivers a scoring task takes
constexpr std::size_t kSortChunk = 1024;  // receivers a binning task takes

// The closed forms' moments over some receivers: above the horizon sum w r^2, sum w r n and sum w n n^T
// (xx, yy, zz, xy, xz, yz); below it sum w r^2; open ground sum w r^2, sum w r, sum w.
struct Moments {
  double above = 0, below = 0, open0 = 0, open1 = 0, open2 = 0;
  Vec3 b{};
  std::array<double, 6> M{};
  Moments& operator+=(const Moments& o) {
    above += o.above, below += o.below, open0 += o.open0, open1 += o.open1, open2 += o.open2, b += o.b;
    for (int i = 0; i < 6; ++i) M[i] += o.M[i];
    return *this;
  }
  // sum w (r + s K)^2 over them for a trial of direction d and unoccluded irradiance o.
  double objective(double s, const Vec3& d, double o) const {
    const double dMd = M[0] * d.x * d.x + M[1] * d.y * d.y + M[2] * d.z * d.z +
                       2 * (M[3] * d.x * d.y + M[4] * d.x * d.z + M[5] * d.y * d.z);
    return below + (above + 2 * s * dot(d, b) + s * s * dMd) +
           (open0 + 2 * s * o * open1 + s * s * o * o * open2);
  }
};
}  // namespace

std::vector<double> TrialFit::objectives(std::size_t j, const std::vector<Light>& trials) {
  const std::size_t m = receivers_.size(), count = trials.size();
  if (count == 0) return {};
  from_ = trials[0].direction;
  scale_ = luminance(trials[0].rgb);
  // Each trial's reach (a margin for rounding), the trials ranked by it.
  std::vector<double> reach(count);
  directions_.resize(count), open_.resize(count);
  for (std::size_t t = 0; t < count; ++t) {
    const Cone cone = makeCone(trials[t].direction, trials[t].angle, evaluator_.sunProfile());
    const Vec3& d = trials[t].direction;
    const Vec3 cross{from_.y * d.z - from_.z * d.y, from_.z * d.x - from_.x * d.z,
                     from_.x * d.y - from_.y * d.x};
    reach[t] = std::atan2(cross.length(), dot(from_, d)) + cone.half + 1e-7;
    directions_[t] = d;
    open_[t] = coneIrradiance(cone, {0, 0, 1});
  }
  std::vector<std::size_t> byReach(count);
  for (std::size_t t = 0; t < count; ++t) byReach[t] = t;
  std::stable_sort(byReach.begin(), byReach.end(),
                   [&](std::size_t a, std::size_t b) { return reach[a] < reach[b]; });
  rank_.resize(count);
  // Per rank: the |n . d0| below which a normal's horizon may cross the cone (above pi / 2: every normal),
  // and the cone's radius with its cosine and sine (a ground point's cap of radius g overlaps it when
  // axis . d0 > cos(R + g), or always when R + g >= pi: overlaps() in cone.h).
  std::vector<double> band(count), radius(count), cosR(count), sinR(count);
  for (std::size_t p = 0; p < count; ++p) {
    const double r = reach[byReach[p]];
    rank_[byReach[p]] = p;
    band[p] = r < 0.5 * kPi ? std::sin(r) : 2.0;
    radius[p] = r, cosR[p] = std::cos(r), sinR[p] = std::sin(r);
  }
  // Each receiver's bin: the first rank that reaches it (count: none does); the closed forms' moments per
  // bin, summed in chunks of receivers in parallel and then in order (the same sums whatever the threads).
  bin_.resize(m);
  residual_.resize(m);
  const std::vector<double>& term = terms_[j];
  const std::int64_t chunks = static_cast<std::int64_t>((m + kSortChunk - 1) / kSortChunk);
  std::vector<std::vector<Moments>> chunkMoments(static_cast<std::size_t>(chunks));
  parallelFor(chunks, [&](std::int64_t chunk) {
    std::vector<Moments>& moments = chunkMoments[static_cast<std::size_t>(chunk)];
    moments.resize(count + 1);
    const std::size_t end = std::min(m, static_cast<std::size_t>(chunk + 1) * kSortChunk);
    for (std::size_t k = static_cast<std::size_t>(chunk) * kSortChunk; k < end; ++k) {
      const Receiver& r = receivers_[k];
      const double res = residual_[k] = sum_[k] - term[k] - target_[k], w = r.weight, wr = w * res;
      std::size_t q;
      if (!r.ground) {
        const double nd = dot(r.at, from_);
        q = static_cast<std::size_t>(std::upper_bound(band.begin(), band.end(), std::abs(nd)) - band.begin());
        Moments& into = moments[q];
        if (nd > 0) {
          into.above += wr * res, into.b += wr * r.at;
          const std::array<double, 6>& nn = outer_[k];
          for (int i = 0; i < 6; ++i) into.M[i] += nn[i];
        } else {
          into.below += wr * res;
        }
      } else {
        const Cap& cap = r.sphere;
        const double c = dot(cap.axis, from_);
        std::size_t lo = 0, hi = count;  // the first rank whose cone the cap overlaps
        while (lo < hi) {
          const std::size_t mid = (lo + hi) / 2;
          if (radius[mid] + cap.radius >= kPi || c > cosR[mid] * cap.cosRadius - sinR[mid] * cap.sinRadius)
            hi = mid;
          else
            lo = mid + 1;
        }
        q = lo;
        Moments& into = moments[q];
        into.open0 += wr * res, into.open1 += wr, into.open2 += w;
      }
      bin_[k] = q;
    }
  });
  std::vector<Moments> moments(count + 1);
  for (const std::vector<Moments>& part : chunkMoments)
    for (std::size_t q = 0; q <= count; ++q) moments[q] += part[q];
  // The receivers ordered by bin: rank p computes kernels on those of bins <= p, a prefix.
  std::vector<std::size_t> start(count + 2, 0);
  for (std::size_t k = 0; k < m; ++k) ++start[bin_[k] + 1];
  for (std::size_t q = 1; q < start.size(); ++q) start[q] += start[q - 1];
  byBin_.resize(m), place_.resize(m);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < m; ++k) byBin_[place_[k] = fill[bin_[k]]++] = static_cast<int>(k);
  }
  // Past rank p: the bins p + 1 .. count in closed form.
  std::vector<Moments> past(count + 1);
  past[count] = moments[count];
  for (std::size_t q = count; q-- > 0;) (past[q] = past[q + 1]) += moments[q];
  // Each trial's kernels on its prefix, in chunks of receivers (trial, chunk) in parallel; the chunks'
  // sums added in order.
  kernels_.resize(count);
  struct Task {
    std::size_t trial, begin, end;
  };
  std::vector<Task> tasks;
  for (std::size_t t = 0; t < count; ++t) {
    const std::size_t n = start[rank_[t] + 1];
    kernels_[t].resize(n);
    for (std::size_t b = 0; b < n; b += kChunk) tasks.push_back({t, b, std::min(n, b + kChunk)});
  }
  std::vector<double> partial(tasks.size());
  parallelFor(static_cast<std::int64_t>(tasks.size()), [&](std::int64_t i) {
    const Task& task = tasks[static_cast<std::size_t>(i)];
    const std::span<const int> which(byBin_.data() + task.begin, task.end - task.begin);
    const std::span<double> values(kernels_[task.trial].data() + task.begin, task.end - task.begin);
    if (task.trial == 0)  // the light as it is: its term (the same values its kernels give)
      for (std::size_t x = 0; x < which.size(); ++x) values[x] = term[static_cast<std::size_t>(which[x])];
    else
      evaluator_.kernels(trials[task.trial], receivers_, which, scale_, values);
    double f = 0;
    for (std::size_t x = 0; x < which.size(); ++x) {
      const std::size_t k = static_cast<std::size_t>(which[x]);
      const double e = residual_[k] + values[x];
      f += receivers_[k].weight * e * e;
    }
    partial[static_cast<std::size_t>(i)] = f;
  });
  std::vector<double> out(count);
  for (std::size_t t = 0; t < count; ++t)
    out[t] = past[rank_[t] + 1].objective(scale_, directions_[t], open_[t]);
  for (std::size_t i = 0; i < tasks.size(); ++i) out[tasks[i].trial] += partial[i];
  return out;
}

void TrialFit::accept(std::size_t j, std::size_t t) {
  std::vector<double>& term = terms_[j];
  const std::size_t p = rank_[t];
  const Vec3& d = directions_[t];
  const double openTerm = scale_ * open_[t];
  for (std::size_t k = 0; k < receivers_.size(); ++k) {
    const Receiver& r = receivers_[k];
    const double now = bin_[k] <= p           ? kernels_[t][place_[k]]
                       : r.ground             ? openTerm
                       : dot(r.at, from_) > 0 ? scale_ * dot(r.at, d)
                                              : 0.0;
    sum_[k] += now - term[k];
    term[k] = now;
  }
}

}  // namespace probelights
