// Dynamic hypothesis testing (DHT): the Bayesian posterior probability of every hypothesis
// given the pose history, updated one sample at a time.
//
// Recursion (Hassani et al. 2018, eq. 47, with the Gaussian likelihood of eq. 51):
//
//   h_k(t+1) = p(y(t+1) | H_k, Z(t)) h_k(t) / sum_i p(y(t+1) | H_i, Z(t)) h_i(t),
//
// where log p(y(t+1) | H_k, Z(t)) is the `log_likelihood` of hypothesis k in the evidence.
// The product is formed in log space, a_k = log h_k + log_likelihood_k, and normalised by
// log-sum-exp (subtract max_k a_k before exponentiating), so likelihoods of -1e4 nats or
// less neither underflow nor lose the differences between hypotheses.
//
// Probability floor (TAPM thesis section 4.6.2: without one, a hypothesis that has been
// unlikely for a long time needs arbitrarily long to recover when it becomes true). After
// each normalisation every probability below p_min is raised to exactly p_min and all
// others are scaled by one common factor so that the total is 1 again; if that scaling
// takes another probability below p_min, it is floored too and the factor recomputed (at
// most N passes). So after every update h_k >= p_min exactly, sum_k h_k = 1 to rounding,
// and the ratios between the hypotheses above the floor are the Bayesian ones. This needs
// N p_min < 1 (Reset() checks). The thesis's code (appendix A.1) instead takes
// max(h, p_min) and divides by the sum, which leaves floored entries slightly below p_min.
// Theorem 1 of Hassani et al. 2018 (the h_k stay a probability distribution) thus holds with
// the floor, and Theorem 2 (the true hypothesis's h_k -> 1 when it is distinguishable) holds
// up to the floor: h_true -> 1 - (N - 1) p_min.
//
// Verdict: score = the posterior h_0..h_{N-1}; hypothesis = argmax (ties: lowest index).
// Alarm rule: a failure hypothesis k != 0 is the argmax with h_k >= `threshold`, and the
// same k has met that condition continuously for at least `hold` seconds of evidence time
// (evidence.t - t_start >= hold, t_start = the first sample of the run of samples that met
// it). The alarm is a level, not a latch: it drops when the condition breaks and re-arms
// after another `hold` seconds.
//
// Bad state: a non-finite log-likelihood throws SolverError naming the hypothesis and t; a
// mismatch between the evidence's hypothesis count and Reset()'s is a programmer's error
// (always-on check, abort). Update() allocates nothing after Reset() except the copy of
// the score into the returned Verdict, which the interface's by-value return requires;
// Step() returns a reference and allocates nothing.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "detectors/detector.h"

namespace moorsim::detectors {

struct DhtOptions {
  /// p_min: no probability falls below it (TAPM thesis section 4.6.2 uses 1e-9, as
  /// does moorsim, docs/design.md section 9). In (0, 1) and N p_min < 1.
  double floor = 1e-9;
  /// The posterior a failure hypothesis must reach for the alarm, in (0, 1): 0.99 means
  /// 99:1 odds against all other hypotheses together.
  double threshold = 0.99;
  /// [s] How long the same failure hypothesis must stay above `threshold` before the
  /// alarm; >= 0. The TAPM thesis saw the DHT flick between hypotheses for tens of seconds
  /// after a break (chapter 5: line 7 "oscillating between lines 3 and 4"); 10 s, about
  /// 1.4 peak wave periods (7 s), keeps wave-frequency excursions of the posterior from
  /// raising the alarm while adding little to the thesis's ~1 min detection times.
  double hold = 10.0;
  /// Prior probability of the intact hypothesis, in (0, 1); the rest is shared equally by
  /// the failure hypotheses. Unset: uniform 1/N over all hypotheses (TAPM thesis appendix A.1).
  std::optional<double> prior_intact;
};

class Dht final : public Detector {
 public:
  explicit Dht(const DhtOptions& options = {});

  std::string_view type() const override { return "dht"; }
  /// Sizes everything for `hypotheses` >= 1 and sets the prior. Throws InputError if
  /// hypotheses * floor >= 1 (no distribution can respect the floor).
  void Reset(int hypotheses) override;
  Verdict Update(const Evidence& evidence) override;
  /// Update() without the copy: the verdict stays valid until the next Step/Reset.
  const Verdict& Step(const Evidence& evidence);

  const DhtOptions& options() const { return options_; }
  /// The posterior's alarm threshold.
  std::optional<double> AlarmThreshold() const override { return options_.threshold; }
  /// The posterior h_0..h_{N-1} (the same numbers as the verdict's score).
  const std::vector<double>& posterior() const { return verdict_.score; }

 private:
  DhtOptions options_;
  Verdict verdict_;
  std::vector<double> log_weight_;  // a_k scratch
  std::vector<char> floored_;       // scratch of the floor rule
  int held_hypothesis_ = 0;         // 0 = nothing held
  double held_since_ = 0.0;         // [s]
};

namespace internal {

/// The floor rule above, in place: `probability` sums to 1 on entry and holds no value
/// below `floor` on exit; `floored` is scratch of the same size. Requires
/// size * floor < 1.
void ApplyProbabilityFloor(double floor, std::vector<double>& probability,
                           std::vector<char>& floored);

}  // namespace internal

}  // namespace moorsim::detectors
