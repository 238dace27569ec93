// The offline innovation covariance of the passive observers (TAPM thesis section 4.4 and
// appendix A.5): the passive observer computes no covariance, so each hypothesis's
// Sigma_h is the sample covariance (MATLAB's cov(): about the sample mean, divided by
// n - 1) of that observer's innovations on a long run in which the hypothesis is true.
// The seed ran its coupled simulator for 10000 s per failure scenario with the controller
// active; here that is
//  - InnovationCovarianceEstimator: the streaming (Welford) mean and covariance;
//  - TrainPassiveCovariance(bank, h, ..., run): observer h on a recorded run (e.g. a
//    coupled moorsim run with hypothesis h true);
//  - TrainPassiveCovariance(bank, h, ..., noise, training): when no such run exists,
//    observer h on a run simulated from hypothesis h's own model, the stochastic model
//    HypothesisEkf assumes (HypothesisModelSimulator), with the noise levels of EkfOptions.
// The covariance is that of the innovations of the PREDICTED output (the evidence's
// innovation, detectors/passive_observer.h: y_k against the output integrated over the
// interval with y_{k-1} held), the very quantity whose likelihood the detectors evaluate,
// so training and use see the same statistic. On the seed FPSO with the EKF's default
// noise levels it is about diag(0.031 m^2, 0.031 m^2, 0.010 rad^2): more than the
// measurement noise plus wave motion (0.0275 m^2, 0.0051 rad^2), because the observer's
// 1.1 rad/s position loop follows the noise of the previous sample into the prediction.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/random.h"
#include "core/types.h"
#include "detectors/detector.h"
#include "detectors/ekf_observer.h"
#include "detectors/hypothesis_bank.h"
#include "detectors/passive_observer.h"

namespace moorsim::detectors {

/// Streaming mean and covariance of 3-vectors (Welford 1962, per component pair:
/// mean += d / n, M2 += d (x - mean)^T with d = x - mean_old), numerically stable for long
/// runs. Samples with an invalid channel are skipped: the offline covariance is that of
/// complete innovations.
class InnovationCovarianceEstimator {
 public:
  /// `min_samples` (>= 4, default 100): Covariance() refuses fewer. Throws
  /// moorsim::InputError otherwise.
  explicit InnovationCovarianceEstimator(int min_samples = 100);

  void Reset();
  /// Adds `innovation` if all three channels are valid; returns whether it was used.
  /// A non-finite valid sample throws moorsim::InputError.
  bool Add(const Vec3& innovation, const std::array<bool, 3>& valid = {true, true, true});
  /// Adds the evidence's innovation if its dimension is 3.
  bool Add(const HypothesisEvidence& evidence);

  std::int64_t count() const { return count_; }
  int min_samples() const { return min_samples_; }
  const Vec3& mean() const { return mean_; }
  /// Sample covariance M2 / (n - 1), symmetric. Throws moorsim::InputError if fewer than
  /// min_samples samples were added, or if it is not positive definite (smallest
  /// eigenvalue <= 1e-12 of the largest: a channel that never varies, or channels that
  /// move together exactly).
  Mat3 Covariance() const;

 private:
  int min_samples_ = 100;
  std::int64_t count_ = 0;
  Vec3 mean_ = Vec3::Zero();
  Mat3 m2_ = Mat3::Zero();
};

/// Body thrust [X, Y, N] that makes `pose` an equilibrium of `mooring` for a still vessel
/// without bias: -R(psi)^T g(pose) (zero at the mooring's own equilibrium).
Vec3 HoldingThrust(const QuasiStaticMooring& mooring, const Vec3& pose);

/// A stochastic simulation of one hypothesis's own model, the model HypothesisEkf assumes
/// (detectors/ekf_observer.h, with the noise levels of EkfOptions): state
/// [xi (6), eta (3), b (3), nu (3)] in HypothesisEkf's layout,
///   xi1' = xi2, xi2' = -w0^2 xi1 - 2 lambda w0 xi2 + s w_w,  s = wave_std sqrt(4 lambda w0)
///   eta' = R(psi) nu,  b' = -b / T + w_b,  M nu' = -(D + D_mo) nu + R^T (g(eta) + b) + tau + w_F
///   y = eta + xi2 + v,  v ~ N(0, measurement_variance), heading wrapped to (-pi, pi].
/// Discretisation: the wave filter and the bias are linear and are sampled exactly (the
/// transition exp(A dt) in closed form; the noise covariance P - Phi P Phi^T from the
/// stationary covariance P; the bias as an exact Ornstein-Uhlenbeck step per substep).
/// [eta, nu] is integrated by RK4 in equal substeps of at most `max_substep` (0.25 s by
/// default; the fastest low-frequency time constant of the seed model is 20 s) with the
/// bias interpolated linearly across the substep and the force noise injected
/// Euler-Maruyama, half before and half after each substep (variance q^2 h / 2 each).
/// Each noise source draws from its own RandomStream, RandomStream::Derive(seed,
/// "<streams>.wave" / ".bias" / ".force" / ".initial" / ".measurement.x" / ".y" / ".psi").
/// The start is stationary in xi and b (drawn from ".initial"), nu = 0, eta = pose.
class HypothesisModelSimulator {
 public:
  using State = HypothesisPassiveObserver::State;

  /// Throws moorsim::InputError on bad noise options, a mass that is not positive
  /// definite or a max_substep that is not > 0.
  HypothesisModelSimulator(QuasiStaticMooring mooring, const LowFrequencyModel& model,
                           const Mat3& mooring_damping, const EkfOptions& noise, const Vec3& pose,
                           std::uint64_t seed, std::string_view streams = "own_model",
                           double max_substep = 0.25);

  const State& state() const { return x_; }
  /// Replaces the truth state (tests start from a chosen state).
  void set_state(const State& x) { x_ = x; }
  /// Advances by dt [s] with the body thrust tau [N, N, N m] held.
  void Advance(double dt, const Vec3& tau);
  /// The measured pose at time t with all channels valid, and tau as the command.
  Observation Measure(double t, const Vec3& tau);

 private:
  void CacheWaveStep(double dt);

  QuasiStaticMooring mooring_;
  EkfOptions noise_;
  Mat3 mass_inverse_ = Mat3::Zero();
  Mat3 damping_ = Mat3::Zero();
  Mat3 force_noise_ = Mat3::Zero();  // M^-1 diag(force_noise): nu kick per unit normal
  double max_substep_ = 0.25;
  // Exact wave step for wave_dt_, per DOF: transition and Cholesky factor of its noise.
  double wave_dt_ = -1.0;
  std::array<Eigen::Matrix2d, 3> wave_transition_{};
  std::array<Eigen::Matrix2d, 3> wave_noise_factor_{};
  RandomStream wave_, bias_, force_, measure_x_, measure_y_, measure_psi_;
  State x_ = State::Zero();
};

struct CovarianceTrainingOptions {
  Vec3 pose = Vec3::Zero();      ///< pose the vessel is held about [m, m, rad] (HoldingThrust)
  double duration = 10000.0;     ///< recorded span [s] (TAPM thesis section 4.4: 10000 s)
  double settle_time = 500.0;    ///< simulated and discarded first: the observer's start [s]
  double sample_interval = 1.0;  ///< [s], the TAPM thesis's sensor rate
  double max_substep = 0.25;     ///< plant RK4 substep bound [s]
  std::uint64_t seed = 1;        ///< streams "training.*", the same for every hypothesis
  int min_samples = 100;         ///< InnovationCovarianceEstimator's minimum
};

/// Throws moorsim::InputError naming the field ("training.duration = -1: ...").
void Validate(const CovarianceTrainingOptions& options);

/// Sigma_h from a recorded run: observer h (with options.mooring_damping_ratio's D_mo) on
/// `run`, innovations with all channels valid from t >= run.front().t + settle_time.
/// Throws moorsim::InputError if fewer than min_samples remain or the covariance is
/// singular.
Mat3 TrainPassiveCovariance(const HypothesisBank& bank, int h, const LowFrequencyModel& model,
                            const PassiveObserverOptions& options, std::span<const Observation> run,
                            double settle_time = 500.0, int min_samples = 100);

/// Sigma_h from hypothesis h's own model: HypothesisModelSimulator (plant D_mo from
/// noise.mooring_damping_ratio) held at training.pose by HoldingThrust, which is also the
/// observer's thrust command, for settle_time + duration seconds; observer h as above.
/// The noise levels are those of `noise` (wave_motion_std, bias_std, bias_time_constant,
/// force_noise, measurement_variance, wave_frequency, wave_damping). Every hypothesis is
/// trained on the same noise realisation (streams "training.*" from training.seed: common
/// random numbers), so the differences between the Sigma_h come from the models and not
/// from Monte-Carlo noise: log det Sigma_h enters every sample's likelihood, and the
/// sampling error of a 10000 s run (a few % of each variance, the innovations being
/// correlated over ~10 s) would otherwise be a bias of ~0.01-0.05 nats per sample between
/// hypotheses, tens of nats over a 2000 s detection window.
Mat3 TrainPassiveCovariance(const HypothesisBank& bank, int h, const LowFrequencyModel& model,
                            const PassiveObserverOptions& options, const EkfOptions& noise,
                            const CovarianceTrainingOptions& training = {});

/// TrainPassiveCovariance(bank, h, ...) for every hypothesis, in order.
std::vector<Mat3> TrainPassiveCovariances(const HypothesisBank& bank,
                                          const LowFrequencyModel& model,
                                          const PassiveObserverOptions& options,
                                          const EkfOptions& noise,
                                          const CovarianceTrainingOptions& training = {});

}  // namespace moorsim::detectors
