// Windowed generalised likelihood ratio (GLR) tests on the intact hypothesis's innovations
// (Lajic et al. 2009, section 4.1): a mean-change test that detects, and a known-signature
// test that isolates.
//
// Whitening. Only hypotheses[0] (all lines intact) is used. Each innovation r is whitened
// by its own covariance S = L L' (L the lower Cholesky factor): w = L^-1 r, so that while
// the intact model is true the w are independent N(0, I). A sample that carries fewer than
// three channels (dimension d < 3) is whitened over the d carried channels only, with the
// Cholesky factor of that block of S, and each component counts only the samples that
// carried it (see CarriedChannels() for how the missing channels are recognised).
//
// (a) Mean change, Lajic et al. 2009, eq. 21, extended to the whitened vector. With the window
// holding the last M samples, for each candidate change time j (the last n_j = k - j + 1 samples,
// 1 <= n_j <= M) and each component c with n_jc > 0 samples:
//
//   g_j = sum_c (sum_{i=j..k} w_ic)^2 / n_jc,        g = max_j g_j.
//
// With every channel carried this is |sum_{i>=j} w_i|^2 / n_j: eq. 21 with sigma = 1 and
// mu_0 = 0, i.e. twice the log-likelihood ratio of "mean nu from j on" (nu estimated) vs
// "mean 0". For a fixed j and no change, g_j ~ chi-square with 3 degrees of freedom (fewer
// if channels are missing). Alarm: g > h. The default h is the chi-square(3) quantile with
// upper tail p_fa / M: by the union bound over the M change times, a white intact residual
// raises a false alarm with probability <= p_fa per sample (and >= chi-square tail at h).
// At the defaults (M = 50, p_fa = 1e-6) h = 38.709. Residuals of a real observer are
// coloured, so the real rate is higher; tune `threshold` on no-failure runs.
//
// (b) Known signature, Lajic et al. 2009, eq. 22 with a constant profile rho = s_k, Q = I in the
// whitened space: s_k is the expected whitened intact innovation while line k is failed
// (SetSignatures). The likelihood ratio maximised over the amplitude nu >= 0 gives, per
// failure hypothesis k,
//
//   T_k = max_j  max(0, sum_c s_kc sum_{i>=j} w_ic)^2 / (sum_c n_jc s_kc^2)
//
// (with all channels: max(0, s_k . sum w)^2 / (n_j |s_k|^2)), twice eq. 22's value so that
// it is chi-square(1)-scaled like (a). The amplitude is one-sided because a parted line
// removes its force, it cannot push back: with the two-sided square, opposite lines (1 and
// 3, the seed case's anchors at 0 and 180 deg) would look the same. A zero signature gives 0.
// Without signatures the isolation falls back to the windowed log-likelihoods of all
// hypotheses: T_k = 2 (sum over the window of log_likelihood_k - log_likelihood_0), the
// hypothesis that explained the last M samples best.
//
// Verdict: score[0] = g, score[k] = T_k (k >= 1); hypothesis = the isolated line
// argmax_{k>=1} T_k (ties: lowest index) while g > h, else 0; alarm = g has stayed above h
// for at least `hold` seconds of evidence time (a level: it drops as soon as g <= h and
// re-arms after another `hold`). The residuals are Evidence::nominal's when the observer
// bank provides it (an unmixed intact filter), else hypotheses[0]'s.
//
// Bad state: a non-finite innovation or covariance, or a covariance whose carried block is
// not positive definite, throws SolverError with t. Cost O(M (N + 3)) per sample; Step()
// allocates nothing after Reset() and SetSignatures().
#pragma once

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/types.h"
#include "detectors/detector.h"

namespace moorsim::detectors {

struct GlrOptions {
  /// M: the number of samples the window holds (Lajic et al. 2009, section 4.2: M = 50); >= 2.
  int window = 50;
  /// Per-sample false-alarm probability the default threshold is derived from, for white
  /// residuals (union bound over the window), in (0, 1). 1e-6 at a 1 Hz detector: about 1 %
  /// chance of one false alarm in a 3 h run of white residuals.
  double false_alarm_probability = 1e-6;
  /// h: the alarm threshold on g, > 0. Unset: GlrDefaultThreshold(false_alarm_probability,
  /// window).
  std::optional<double> threshold;
  /// [s] How long g must stay above h before the alarm, >= 0 (0: at once, Lajic et al.'s rule).
  double hold = 0.0;
};

class Glr final : public Detector {
 public:
  explicit Glr(const GlrOptions& options = {});

  std::string_view type() const override { return "glr"; }
  void Reset(int hypotheses) override;
  Verdict Update(const Evidence& evidence) override;
  /// Update() without the copy: the verdict stays valid until the next Step/Reset.
  const Verdict& Step(const Evidence& evidence);

  /// The failure signatures: signatures[k - 1] is s_k, the mean of the whitened intact
  /// innovation (WhitenInnovation of the intact model's expected innovation) while
  /// hypothesis k holds, for k = 1..N-1. Empty: no signatures (log-likelihood isolation).
  /// If Reset() has run, the size must be N - 1 (always-on check); Reset() checks it too.
  void SetSignatures(std::vector<Vec3> signatures);
  /// SetSignatures() with the source's signatures over the detector's window.
  void Prepare(const SignatureSource& source) override {
    SetSignatures(source.Signatures(options_.window));
  }
  std::optional<double> AlarmThreshold() const override { return threshold_; }

  /// h, the alarm threshold on g.
  double threshold() const { return threshold_; }
  const GlrOptions& options() const { return options_; }
  /// Samples now in the window (<= M).
  int filled() const { return filled_; }
  /// g_j for the change time `samples` samples back (the last `samples` samples), for
  /// 1 <= samples <= filled(): the fixed-j statistic, chi-square(3) with no change.
  double MeanChangeStatistic(int samples) const;
  /// n_j of the change time that maximised g at the last sample (0 before any sample).
  int change_samples() const { return change_samples_; }

 private:
  int Slot(int back) const;  // ring index of the sample `back` steps before the newest

  GlrOptions options_;
  double threshold_ = 0.0;
  int hypotheses_ = 0;
  std::vector<Vec3> signatures_;
  Eigen::Matrix<double, 3, Eigen::Dynamic> whitened_;  // 3 x M ring of w
  Eigen::Matrix<double, 3, Eigen::Dynamic> carried_;   // 3 x M ring, 1 where carried
  Eigen::MatrixXd log_likelihood_;                     // N x M ring (fallback isolation)
  bool exceeding_ = false;                             // g > h at the last sample
  double exceeding_since_ = 0.0;
  int newest_ = -1;
  int filled_ = 0;
  int change_samples_ = 0;
  Verdict verdict_;
};

/// P(X > x) for X chi-square with `dof` in {1, 2, 3} degrees of freedom (closed forms:
/// erfc(sqrt(x/2)); exp(-x/2); erfc(sqrt(x/2)) + sqrt(2x/pi) exp(-x/2)). 1 for x <= 0.
double ChiSquareSurvival(int dof, double x);

/// h with ChiSquareSurvival(3, h) = false_alarm_probability / window (bisection to 1e-12
/// relative): the default GLR threshold.
double GlrDefaultThreshold(double false_alarm_probability, int window);

/// Which innovation channels (x, y, psi) a sample carries. HypothesisEvidence gives only
/// their number; an observer that gets no measurement on a channel makes no innovation
/// there, so for dimension d < 3 the channels whose innovation is exactly 0 are read as
/// the missing ones. nullopt if that does not single out exactly 3 - d channels (or d is
/// outside 0..3): the GLR then treats the sample as carrying nothing.
std::optional<std::array<bool, 3>> CarriedChannels(const HypothesisEvidence& evidence);

/// The GLR's whitening, w = L^-1 v for S = L L', over the `carried` channels only (the
/// block of S they span; the other components of w are 0). Use it to compute signatures:
/// s_k = WhitenInnovation(S_0, expected intact innovation under hypothesis k). Returns
/// nullopt if that block of S is not positive definite or not finite.
std::optional<Vec3> WhitenInnovation(const Mat3& covariance, const Vec3& v,
                                     const std::array<bool, 3>& carried = {true, true, true});

}  // namespace moorsim::detectors
