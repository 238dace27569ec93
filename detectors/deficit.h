// Force-deficit test: a parted line is a lasting loss of restoring force, a wave-drift group
// a passing one. The detector watches the slowly varying load that the intact filter
// estimates (Evidence::load, its bias state b) and asks which line's load has gone missing
// from it, against a disturbance level it learns from the run itself.
//
// Why the bias. The intact model keeps every line. When line k parts, the vessel feels its
// load f_k no more while the model still adds it, so within the filter's bias time (about
// 20-30 s on the seed case) the bias settles f_k lower than before, and stays there as long
// as the line is gone; the intact filter's residuals, which the GLR tests, are white again
// by then. A slowly varying wave-drift group moves the bias too, by up to 4-5 MN in rough
// seas, but for as long as the group lasts (about a minute). Only the horizontal force
// (b_x, b_y) is used: the fairleads sit on the turret at the reference point, so a line's
// load has no moment about it to speak of (`moorsim analyze` puts the heading's share of
// the evidence at 0.1 nats of ~9), while the bias's yaw moment carries the wind's and the
// waves' yaw moments.
//
// Statistics, per sample t_n (all on the 2-vector of horizontal force):
//   x_n      the bias with its lag undone: b_n + T (b_n - b_{n-1}) / (t_n - t_{n-1}), T =
//            `lead`. The filter's bias approaches a new load roughly as a first-order lag, which
//            x inverts for a lag of time constant T; the price is the bias's increments, times
//            T, added to the noise (T = 0: x = b). On the training campaign (benchmarks/
//            README.md) T = 10 s with a 5-sample window halved the median delay in the thesis
//            sea (41 -> 25 s) and raised 5 false alarms an hour, hence the default 0;
//   s_n      mean of x over the last `window` samples (averages the wave-frequency
//            leakage and the filter's noise);
//   e_n      mean over the same window of the wave-frequency motion's energy |C_w xi|^2
//            (horizontal, Evidence::load.wave_motion): the slowly varying wave drift goes
//            with the square of the wave envelope (Newman 1974), and so does this;
//   B, C     baseline and disturbance covariance. With `drift` on, B(e) = mean of s + g (e -
//            mean of e), g the regression of s on e (exponentially weighted covariance of s
//            and e over the variance of e): the part of the drift that the estimated wave
//            motion explains leaves the disturbance. With `drift_direction`, e is the
//            window mean of the three products (x^2, y^2, xy) of the horizontal wave motion
//            and g a 2 x 3 regression: a hull that yaws off the weather meets the waves at
//            another angle, and its drift turns with it (the sway drift grows with the
//            relative angle, on the side the waves come from), which the energy x^2 + y^2
//            cannot tell. Three gains learned from a few minutes of sea fit its groups by
//            chance, so g is shrunk toward the energy-only regression (g_e, g_e, 0) as
//            toward a prior worth `direction_prior` independent values (Zellner's g-prior):
//            g = w g_3 + (1 - w) g_0, w = n / (n + direction_prior), g_3 the three-gain
//            regression (ridged by 1e-3 of e's mean variance), n below. C is the exponentially
//            weighted covariance of s - B(e). Both with time constant `baseline_time`,
//            bias-corrected at the start (a growing-window mean until `baseline_time` has been
//            learned), and floor^2 I added to C. They learn from full windows only and only while
//            no failure is suspected (`delay` below), and they follow the sea state: rough seas
//            raise C and with it the evidence needed (an adaptive threshold in the sense of Ye,
//            Reppa, Godjevac & Negenborn 2021);
//   d_h      the shift of the bias that hypothesis h predicts: -line_load[h] (the load of
//            its failed lines at the pose estimate);
//   n        the independent values C rests on: the learned samples (at most
//            `baseline_time` of them, the weights' memory) over m (below). While n is small
//            C is likely too small (the first minutes of a run in a rough sea learn one or
//            two drift groups), so the test uses C (1 + small_sample / n);
//   z_h      = d_h^T C^-1 D - d_h^T C^-1 d_h / 2,  D = s_n - B(e_n): the log-likelihood ratio
//            [nats] of "the bias moved by d_h" against "the bias did not move", for D
//            Gaussian with covariance C. The amplitude is known (the line's whole load), so a
//            drift group that pushes the other way or twice as hard does not fit. With
//            `min_fraction` a_0 < 1 the shift tested is a d_h, a the maximum-likelihood share
//            d_h^T C^-1 D / d_h^T C^-1 d_h clamped to [a_0, 1] (z_h = a d_h^T C^-1 D -
//            a^2 d_h^T C^-1 d_h / 2): an anchor release, whose chain still hangs from the
//            fairlead, first removes only a share of the load;
//   m        the samples per independent value of D: D follows a slowly varying load, so
//            successive values repeat each other. With rho the lag-1 correlation of the raw
//            sample x about B and C_r its covariance (learned like C), the raw sample's variance
//            inflation is (1 + rho) / (1 - rho) (that of a first-order autoregressive
//            sequence), its long-run covariance ~ that times C_r, which the window mean
//            shares; m = (1 + rho) / (1 - rho) tr C_r / tr C, clamped to [1, 1000] (white
//            bias: m = window). Each sample adds z_h / m nats. With a lead these are x's rho and
//            C_r. Taking b's instead (x and b share the long-run covariance, as the lead's
//            sum over n samples is T (b_n - b_0) / dt, bounded) doubled the training
//            campaign's false alarms at T = 10 s: over the short spans a CUSUM crosses its
//            threshold in, that bounded term is not small.
//   delay    B, C, C_r and rho learn from the samples `learn_delay` samples old, nothing
//            while an alarm stands, and an alarm holds back the samples still waiting
//            (learned only if it turns out false: `relearn` below): a break that is named
//            within the delay enters neither its own baseline nor the disturbance it is
//            judged against. (Dropping on mere suspicion, a sum above half
//            the threshold, was tried: it cut the disturbance's tails out of C and, on a
//            synthetic 1.5 MN disturbance, raised 5-50 times the false alarms.)
//
// Persistence: Page's cumulative sums of that evidence (CUSUM; Basseville & Nikiforov 1993,
// section 2.2), S_h <- max(0, S_h + z_h / m). A lasting deficit adds a fixed amount each
// sample and crosses any threshold; a passing group adds while it lasts and the sum drains
// back afterwards. Rough seas grow C and m, so each sample says less and a break takes longer
// to confirm instead of raising false alarms. Verdict, a latch rather than a level:
//  - raise: max_h S_h > threshold (h >= 1); the alarm names that h;
//  - revise: while the alarm names k, R_j <- max(0, R_j + (z_j - z_k) / m) for every other
//    j; R_j > revision (j likelier than k by that many nats) names j (a line that parts
//    under a standing false alarm is named; the alarm history records the revision);
//  - end: E <- max(0, E - z_k / m) > release (no change likelier than line k by `release`
//    nats): the evidence has reversed with stated confidence; the alarm ends, the sums
//    restart at 0 and learning resumes. A parted line's deficit does not pass, so its alarm
//    stays until the operator resets the detector (Reset());
//  - nothing before `warmup` seconds of load evidence: the baseline learns, and with
//    `warmup_learning` (the default) it learns every warm-up sample at once instead of
//    `learn_delay` samples later. The mooring is taken to be intact while the test cannot
//    alarm (a line already parted then becomes the baseline), and C starts from the whole
//    warm-up instead of its first half minute: on the Hs 6 m training campaign with the
//    turret ahead (benchmarks/README.md, fourteenth round) the alarms in the first
//    minutes after the warm-up went from 5 in 100 intact hours to 2 (warm-up 150 s) and
//    0 (180 s), with the same delays;
//  - two stages (`confirm` > 0, the default): a second, fast copy of the test (window
//    `fast_window`, lead `fast_lead`, the other options the same) runs beside it, learning
//    and latching on its own. Its alarm on line h raises this test's alarm on h as soon as
//    this test's own sum S_h has reached `confirm` nats, far below the threshold, and its
//    revision to h revises this test's alarm once R_h (h over the named line, above) has
//    reached `confirm`; a fast alarm that waits longer than `confirm_time` unconfirmed
//    ends as a false one (below) and the fast test starts over. The fast test sees a break
//    sooner (its short window and lead undo the averaging and the filter's lag) but also
//    many drift groups; the slow sums reject those whose direction and persistence do not
//    fit a parted line. Once raised, the alarm is this test's (revision, end and latch as
//    above);
//  - false alarms teach (`relearn`): the samples that arrive while an alarm stands, and
//    those still waiting in the delay at its onset, are held; when the alarm ends on
//    reversed evidence they were disturbance after all and are learned, except the newest
//    `learn_delay`, which go back to the delay (a break among them is still tested before
//    it could be learned). Without it, every false alarm hides its own cause from C, and
//    the next group like it raises the alarm again. A parted line's alarm does not end, so
//    its samples are never learned.
// score[h] = S_h [nats] (score[0] = 0); hypothesis = the named one while the alarm stands,
// else 0.
//
// Needs the load evidence of the EKF observer bank (NeedsLoadEvidence()); a sample without
// it leaves the state as it was. Cost O(N + window) per sample (twice that in two stages);
// Step() allocates nothing after Reset().
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "detectors/detector.h"

namespace moorsim::detectors {

struct DeficitOptions {
  /// Samples of the bias averaged into s, >= 1.
  int window = 15;
  /// [s] Time constant of the baseline B, the disturbance covariance C and its
  /// correlation, > 0.
  double baseline_time = 900.0;
  /// [N] Least standard deviation of the disturbance in either direction, > 0: keeps
  /// C from collapsing in a flat calm onto the filter's own noise.
  double floor = 1e5;
  /// [nats] Cumulative evidence for a line over no change that raises the alarm, > 0.
  /// 20 rather than 12 took the false alarms at Hs 6 m from 10 to 4 in 120 training hours
  /// at no cost elsewhere, once the revision had its own threshold (sixteenth round,
  /// benchmarks/README.md); held out, 9 in 100 h against 7 for the earlier defaults on
  /// other seeds, so the gain did not carry over at Hs 6 m (at Hs 4 m: 0 against 3).
  double threshold = 20.0;
  /// [nats] Cumulative evidence for another line over the named one that revises the
  /// alarm, > 0.
  double revision = 12.0;
  /// [nats] Cumulative evidence for no change over the named line that ends an alarm, > 0.
  double release = 8.0;
  /// [s] Load evidence before any alarm, >= 0.
  double warmup = 180.0;
  /// Whether the samples of the warm-up are learned at once instead of `learn_delay`
  /// samples later (the mooring is taken to be intact while the test cannot alarm).
  bool warmup_learning = true;
  /// Samples a bias waits before it is learned (dropped if an alarm is raised meanwhile), >= 0.
  int learn_delay = 120;
  /// Whether B follows the wave-motion energy (the drift regression above).
  bool drift = true;
  /// Whether the drift regression takes the wave motion's direction too: regressors x^2,
  /// y^2 and xy of the horizontal wave-frequency motion instead of x^2 + y^2 alone.
  bool drift_direction = false;
  /// The independent values the energy-only regression's prior is worth when
  /// `drift_direction` learns three gains (see g above), >= 0.
  double direction_prior = 3.0;
  /// c in C's small-sample inflation 1 + c / n (n: independent values learned), >= 0.
  double small_sample = 0.0;
  /// [s] Lead T of the bias compensation b + T db/dt (0: the bias as it is), >= 0.
  double lead = 0.0;
  /// Least share of a line's load whose loss is tested, in (0, 1]: 1 tests the whole load;
  /// below 1 the share is estimated (maximum likelihood, clamped to [min_fraction, 1]).
  double min_fraction = 0.7;
  /// When an alarm ends on reversed evidence, learn the samples held while it stood (and
  /// those still waiting at its onset) as the disturbance they turned out to be.
  bool relearn = true;
  /// [nats] Two stages (0: off), >= 0: a fast test (window `fast_window`, lead `fast_lead`,
  /// the other options these) raises the alarm on the line it names once this test's sum
  /// S_h for that line has reached `confirm` (see the verdict above).
  double confirm = 2.0;
  /// [s] How long a fast alarm may wait for `confirm` before the fast test starts over, > 0.
  double confirm_time = 60.0;
  int fast_window = 5;
  double fast_lead = 10.0;
};

class Deficit final : public Detector {
 public:
  /// Throws ContractError on options outside their ranges (the registry checks first).
  explicit Deficit(const DeficitOptions& options = {});

  std::string_view type() const override { return "deficit"; }
  bool NeedsLoadEvidence() const override { return true; }
  void Reset(int hypotheses) override;
  Verdict Update(const Evidence& evidence) override;
  /// Update() without the copy: the verdict stays valid until the next Step/Reset.
  const Verdict& Step(const Evidence& evidence);

  const DeficitOptions& options() const { return options_; }
  /// The wave-motion regressors: (x^2 + y^2, 0, 0), or (x^2, y^2, xy) with
  /// `drift_direction` [m^2].
  using Regressors = Eigen::Vector3d;
  using Gain = Eigen::Matrix<double, 2, 3>;

  /// The learned mean of s and disturbance covariance C [N, N^2] (horizontal force), and
  /// the drift gain g [N/m^2], one column per regressor.
  const Eigen::Vector2d& baseline() const { return baseline_; }
  const Gain& drift_gain() const { return gain_; }
  const Eigen::Matrix2d& disturbance() const { return disturbance_; }
  /// m, the samples per independent value of the window mean (>= 1).
  double samples_per_value() const;

 private:
  using Vec2 = Eigen::Vector2d;
  struct Pending {
    Vec2 mean = Vec2::Zero();
    Vec2 raw = Vec2::Zero();
    Regressors energy = Regressors::Zero();
    double dt = 0.0;
  };
  const Verdict& StepSlow(const Evidence& evidence);
  void Raise(int hypothesis);        // the alarm names `hypothesis`; revision and end start over
  void Hold(const Pending& sample);  // keeps a sample that arrives while an alarm stands
  std::size_t HeldLimit() const;     // the most samples Hold() keeps
  void EndFalseAlarm();              // learns the held samples, then Restart()
  Vec2 Predict(const Regressors& energy) const;  // B(e)
  Regressors WaveRegressors(const Vec3& wave_motion) const;
  double IndependentValues(double samples_per_value) const;  // n
  double DisturbanceInflation(double samples_per_value) const;
  void Learn(const Pending& sample);
  void Restart();

  DeficitOptions options_;
  int hypotheses_ = 0;
  std::vector<Vec2> ring_;  // the last `window` lead-compensated horizontal biases
  Vec2 previous_bias_ = Vec2::Zero();
  std::vector<Regressors> energies_;  // and wave-motion regressors
  int newest_ = -1;
  int filled_ = 0;
  double first_time_ = 0.0;
  double last_time_ = 0.0;
  long samples_ = 0;              // load samples seen
  double learned_ = 0.0;          // [s] learned since the first learned sample
  long learned_samples_ = 0;      // samples learned
  Vec2 baseline_ = Vec2::Zero();  // mean of s
  Regressors energy_mean_ = Regressors::Zero();
  Eigen::Matrix3d energy_covariance_ = Eigen::Matrix3d::Zero();
  Gain cross_ = Gain::Zero();  // covariance of s and e
  Gain gain_ = Gain::Zero();   // g
  Eigen::Matrix2d disturbance_ = Eigen::Matrix2d::Zero();
  Eigen::Matrix2d raw_covariance_ = Eigen::Matrix2d::Zero();  // C_r
  double lag_covariance_ = 0.0;  // tr E[r_n r_{n-1}^T], r = raw bias - B
  Vec2 previous_raw_ = Vec2::Zero();
  std::vector<Pending> delay_;  // ring of the samples waiting to be learned
  std::vector<Pending> held_;   // the samples held since the alarm began (relearn)
  int delay_oldest_ = 0;
  int delay_count_ = 0;
  bool alarm_ = false;
  int named_ = 0;
  std::vector<double> z_;          // this sample's z_h
  std::vector<double> rival_;      // R_j
  double reversal_ = 0.0;          // E
  Verdict verdict_;                // score = S_h
  std::unique_ptr<Deficit> fast_;  // the two-stage verdict's fast test
  int fast_taken_ = 0;             // the fast test's line this test has taken (0: none)
  int fast_pending_ = 0;           // the fast test's line waiting for confirmation (0: none)
  double fast_onset_ = 0.0;        // [s] since when it waits
};

}  // namespace moorsim::detectors
