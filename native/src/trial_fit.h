// The step both coordinate descents of the fits take (sun_angles.cpp: a light's angle; refit.cpp: its
// direction): the lights' summed answers on the fit receivers are kept, and one light is replaced by trial
// variants of it (its rgb, another angle or direction), each trial scored by the fits' objective
//   F_t = sum_k w_k (r_k + s K_t(k))^2,   r_k = S_k - T_k - y_k,
// (S: the lights' sum at receiver k, T: the light's own term there, y: the probe's luminance there, s: the
// light's luminance, K_t: the trial's kernel, w: the receiver set's weight; evaluate.h).
//
// Most receivers see every trial in a closed form linear in the trial's direction d_t or in its unoccluded
// irradiance o_t: a normal n whose horizon none of the trials' cones crosses gets n . d_t (above it) or 0
// (below), a ground point whose sphere cap none of the cones overlaps gets o_t (cone.h). Their part of F_t is
// a quadratic from moments summed once a light:
//   above:  sum w (r + s n.d)^2 = sum w r^2 + 2 s d . (sum w r n) + s^2 d^T (sum w n n^T) d
//   open:   sum w (r + s o)^2   = sum w r^2 + 2 s o (sum w r) + s^2 o^2 (sum w)
// Only the rest (the band about a cone's horizon, the ground in and near its shadow: a minority of the
// receivers) is computed kernel by kernel. Whether a receiver is in closed form for a trial is decided by the
// trial's reach: the cone about the light's current direction d0 that holds the trial's cone (its offset from
// d0 plus its half-angle); the receivers are binned by the smallest reach that takes them out of closed form,
// so each trial computes kernels only where its own reach needs them and takes the rest from the moments of
// the bins past its reach. F_t equals the sum over every receiver up to rounding (trial_fit_test.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "probelights/evaluate.h"

namespace probelights {

class TrialFit {
 public:
  // `lights`: all of them (their sum); `fitted`: the ones objectives() and accept() may replace.
  TrialFit(const Evaluator& evaluator, const std::vector<Receiver>& receivers,
           const std::vector<Light>& lights, const std::vector<std::size_t>& fitted);

  // F_t for each trial replacing light j (one of `fitted`; each trial with light j's rgb). trials[0] must be
  // light j as it is (its term stands for its kernels), so the trials are compared with it in the same
  // arithmetic.
  std::vector<double> objectives(std::size_t j, const std::vector<Light>& trials);
  // Light j is now trials[t] of the last objectives(j, trials) call: its term and the sum updated.
  void accept(std::size_t j, std::size_t t);

 private:
  const Evaluator& evaluator_;
  const std::vector<Receiver>& receivers_;
  std::vector<double> target_, sum_;
  std::vector<std::array<double, 6>> outer_;  // per normal: w n n^T (xx, yy, zz, xy, xz, yz)
  std::vector<std::vector<double>> terms_;    // per light: its term at each receiver (fitted lights only)
  // The last objectives() call's: the light's luminance and direction; each trial's rank by reach, direction
  // and unoccluded irradiance; each receiver's bin (the rank of the first trial that reaches it; the trial
  // count if none does) and place in the receivers ordered by bin; that order; each trial's kernels (times
  // the luminance) on its prefix.
  double scale_ = 0;
  Vec3 from_;
  std::vector<std::size_t> rank_;
  std::vector<Vec3> directions_;
  std::vector<double> open_;
  std::vector<std::size_t> bin_, place_;
  std::vector<double> residual_;  // r_k
  std::vector<int> byBin_;
  std::vector<std::vector<double>> kernels_;
};

}  // namespace probelights
