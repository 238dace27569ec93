// Force-deficit test: a parted line is a lasting loss of restoring force, a wave-drift group
// a passing one. The detector watches the slowly varying load that the intact filter
// estimates (Evidence::load, its bias state b) and asks which line's load has gone missing
// from it, against a disturbance level it learns from the run itself. When line k parts the
// intact model still adds its load f_k, so within the filter's bias time (about 20-30 s on
// the seed case) the bias settles f_k lower and stays there; a wave-drift group moves it by
// up to 4-5 MN in rough seas, but only while the group lasts (about a minute). Only the
// horizontal force (b_x, b_y) is used: the fairleads sit on the turret at the reference
// point, so a line's load has next to no moment about it. docs/detectors.md, "The
// force-deficit test in detail", derives each step and gives the measurements behind the
// defaults.
//
// Per sample, on the horizontal force:
//  - x = b + T db/dt, T = `lead` (undoes the bias's first-order lag); s = the mean of x over
//    the last `window` samples; e = the same window's mean of the horizontal wave-frequency
//    motion's energy (with `drift_direction`, of its products x^2, y^2 and xy), which the
//    wave drift follows;
//  - B(e) = mean of s + g (e - mean of e), g the regression of s on e (the drift regression;
//    with `drift_direction` shrunk toward the energy-only gain by `direction_prior`);
//    C = the covariance of s - B(e), plus floor^2 I, times (1 + small_sample / n), n the
//    independent values learned. B and C learn over `baseline_time` from samples
//    `learn_delay` old, and not while an alarm stands;
//  - d_h = -line_load[h], the shift of the bias that hypothesis h predicts (a share a in
//    [min_fraction, 1] of it is tested); D = s - B(e); z_h = d_h^T C^-1 D - d_h^T C^-1 d_h / 2,
//    the log-likelihood ratio [nats] of "the bias moved by d_h" over "it did not move";
//  - m >= 1, the samples per independent value of D (a slowly varying load repeats itself).
//
// Verdict, a latch: Page's CUSUM S_h <- max(0, S_h + z_h / m) raises the alarm on h once
// S_h > `threshold`; while it names k, R_j <- max(0, R_j + (z_j - z_k) / m) > `revision`
// names j instead, and E <- max(0, E - z_k / m) > `release` ends it (with `relearn`, the
// samples held while it stood are then learned as disturbance). A parted line's deficit does
// not pass, so its alarm stays until Reset(). No alarm in the first `warmup` seconds (their
// samples learned at once with `warmup_learning`). With `confirm` > 0 a fast copy of the test
// (`fast_window`, `fast_lead`) proposes a line, and this test raises or revises its alarm
// once its own evidence for that line has reached `confirm` nats.
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
  /// 20 rather than 12 (with `revision` at 12) lowers the false alarms at Hs 6 m on the
  /// training campaigns from 10 to 4 in 120 h with the same delays elsewhere. Held out: 9 in
  /// 100 h at Hs 6 m and none at Hs 4 m, against 7 and 3 for threshold 12 with the warm-up
  /// learned late (another held-out campaign), so at Hs 6 m the gain is within the noise
  /// (docs/detectors.md, "The force-deficit test in detail").
  double threshold = 20.0;
  /// [nats] Cumulative evidence for another line over the named one that revises the
  /// alarm, > 0.
  double revision = 12.0;
  /// [nats] Cumulative evidence for no change over the named line that ends an alarm, > 0.
  double release = 8.0;
  /// [s] Load evidence before any alarm, >= 0.
  double warmup = 180.0;
  /// Whether the samples of the warm-up are learned at once instead of `learn_delay`
  /// samples later (the mooring is taken to be intact while the test cannot alarm), so that
  /// the first minutes after it are judged against the whole warm-up rather than only its
  /// oldest samples.
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
  /// [s] Lead T of the bias compensation b + T db/dt (0: the bias as it is), >= 0. A lead
  /// names breaks sooner but adds T times the bias's increments to the noise, too many false
  /// alarms for the slow test; the fast stage has its own (`fast_lead`).
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
