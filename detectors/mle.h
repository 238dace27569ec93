// Maximum-likelihood selection (MLE): per hypothesis, the negative log-likelihood of the
// pose history with exponential forgetting, and the hypothesis that minimises it.
//
// Recursion (TAPM thesis eq. 4.10 and appendix A.2, with the full Gaussian log-likelihood
// instead of the thesis's 1/2 (ln|S| + y'S^-1 y), which differs from it by the constant
// (dim/2) ln 2 pi per sample and so ranks the hypotheses the same):
//
//   J_k(t) = lambda J_k(t-1) - log p(y(t) | H_k, Z(t-1)),   J_k(0) = 0.
//
// A sample n steps back carries weight lambda^n, so J is an exponentially weighted sum with
// an effective memory of 1/(1 - lambda) samples (1000 at the default 0.999). Under a fixed
// true hypothesis the differences J_k - J_true settle at (mean per-sample log-likelihood
// difference) / (1 - lambda) instead of growing without bound (TAPM thesis fig. 4.4 vs 5.6),
// so a newly true hypothesis overtakes the old one after a bounded number of samples.
// lambda = 1 is the plain cumulative NLL.
//
// Verdict: score = J_0..J_{N-1} [nats]; hypothesis = argmin (ties: lowest index). Alarm
// rule: a failure hypothesis k != 0 has been the argmin continuously for at least `hold`
// seconds of evidence time, and now J_0 - J_k > `margin`, i.e. the data are more than
// e^margin times likelier under "line k failed" than under "intact" (over the forgetting
// window). Level, not latch, like the DHT's alarm.
//
// Bad state: a non-finite log-likelihood throws SolverError; a hypothesis-count mismatch
// aborts (programmer's error). Step() allocates nothing; Update() only copies the score
// into the returned Verdict.
#pragma once

#include <string_view>
#include <vector>

#include "detectors/detector.h"

namespace moorsim::detectors {

struct MleOptions {
  /// lambda in (0, 1]; memory about 1 / (1 - lambda) samples. TAPM thesis section 4.6.3 uses
  /// 0.999; on the coupled thesis plant (waves, current, the thesis's PI, a mixing observer
  /// bank) that memory of ~1000 s holds the intact model's lead from before a break for
  /// 200-300 s after it (no line is named sooner than 180 s after its break, in two wave
  /// realisations), while 0.99 alarms within 86 s on every line with no false alarm in
  /// 2 x 3600 s of no failure (benchmarks/README.md).
  double forgetting_factor = 0.99;
  /// [s] How long a failure hypothesis must have been the argmin; >= 0. 10 s is 1.4 peak
  /// wave periods of the seed sea state (7 s).
  double hold = 10.0;
  /// [nats] Required lead of the failure hypothesis over the intact one, J_0 - J_k; >= 0.
  /// 5 nats is a likelihood ratio of e^5 = 150 to 1 over the forgetting memory. With
  /// lambda = 0.99 on the thesis plant: 0 nats gives 36 false alarms in the runs above,
  /// 5 none; 10 delays the last detection to 144 s.
  double margin = 5.0;
};

class Mle final : public Detector {
 public:
  explicit Mle(const MleOptions& options = {});

  std::string_view type() const override { return "mle"; }
  void Reset(int hypotheses) override;
  Verdict Update(const Evidence& evidence) override;
  /// Update() without the copy: the verdict stays valid until the next Step/Reset.
  const Verdict& Step(const Evidence& evidence);

  const MleOptions& options() const { return options_; }
  /// J_0..J_{N-1} [nats] (the verdict's score).
  const std::vector<double>& negative_log_likelihood() const { return verdict_.score; }

 private:
  MleOptions options_;
  Verdict verdict_;
  int leader_ = 0;           // the argmin at the previous sample
  double leader_since_ = 0;  // [s] when it became the argmin
  bool started_ = false;
};

}  // namespace moorsim::detectors
