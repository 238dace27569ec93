// An extended Kalman filter per hypothesis (Hassani et al. 2018, sections 2-3, eq. 28-38 and 48-50;
// TAPM thesis eq. 3.6-3.17) and the bank that runs one per hypothesis of a HypothesisBank.
//
// Model (horizontal plane; state x = [xi (6), eta (3), b (3), nu (3)]):
//   xi'  = A_w xi + E_w w_w          wave-frequency motion, per DOF a second-order filter
//                                    xi1' = xi2, xi2' = -w0^2 xi1 - 2 lambda w0 xi2 + s w
//                                    (TAPM thesis eq. 3.7-3.12; Hassani et al. 2018, eq. 28)
//   eta' = R(psi) nu                 (TAPM thesis eq. 3.6b)
//   b'   = -T^-1 b + w_b             Earth-frame slowly varying load, first-order Markov
//                                    (TAPM thesis eq. 3.6c)
//   M nu' = -(D + D_mo) nu + R(psi)^T (g_h(eta) + b) + tau_c + w_F
//                                    g_h: the hypothesis's quasi-static mooring load, Earth
//                                    frame (TAPM thesis eq. 3.13-3.17; Hassani et al. 2018,
//                                    eq. 32 with the nonlinear g_mo instead of G_mo eta)
//   y    = eta + C_w xi + v,  C_w = [0 I],  v ~ N(0, R)
//                                    (TAPM thesis eq. 3.6e; Hassani et al. 2018, eq. 38)
// R(psi) rotates the force part of [Fx, Fy, Mz] and leaves Mz. The wave-frequency motion
// is in the Earth frame, as in the TAPM thesis (Hassani et al. 2018 puts it in body axes; at
// the small yaw of a moored vessel they differ by a rotation of a sub-metre signal).
//
// Discretisation (the filter runs at the sample times of the observations, 1 s for the
// seed case's sensors):
//  - xi is linear and time-invariant and decoupled from the rest: its transition
//    exp(A_w dt) and process covariance int_0^dt exp(A_w s) E Q E^T exp(A_w^T s) ds are
//    exact (Van Loan's method, a matrix exponential by scaling and squaring), cached for
//    the last dt. At w0 dt = 0.9 a first-order approximation would be off by tens of %.
//  - [eta, b, nu] is integrated by RK4 in equal substeps of at most max_substep (0.5 s):
//    the fastest low-frequency time constant of the seed model is 20 s (yaw damping), so
//    |lambda h| <= 0.025 and RK4's relative error per step, ~(lambda h)^5 / 120, is ~1e-10.
//    The transition matrix is the exact Jacobian of that discrete RK4 map (its tangent
//    linear model, stage by stage), so mean and covariance see the same dynamics; the
//    covariance is propagated substep by substep, P <- Phi_h P Phi_h^T + Q_h, with the
//    trapezoidal Q_h = (Phi_h Q_c Phi_h^T + Q_c) h / 2 (error O((lambda h)^2) ~ 1e-3 of
//    Q_h). Thrust is held (zero-order hold) from one observation to the next, as the
//    controller holds it.
//  - Update: Joseph form over the valid channels only; the log-likelihood is that of the
//    valid channels' innovation under their block of S (Hassani et al. 2018, eq. 50-51). The
//    heading innovation is wrapped to (-pi, pi]; the filter's heading is kept in (-pi, pi].
//
// Process noise (Q) and why (values in EkfOptions): each source is given as the
// stationary standard deviation it produces (wave motion, bias) or as a white-noise
// density with a stated meaning (force), not as raw Q entries, so the numbers can be
// checked against the plant. Q_c = diag(s^2 (wave, on xi2), 2 bias_std^2 / T (on b),
// M^-1 diag(force_noise^2) M^-T (on nu)); nothing enters eta directly.
//  - Consistency: on data from its own model the filter is consistent for any Q (tests:
//    the mean normalised innovation squared over 2000 s averaged 3.01 over 13 seeds,
//    with a spread of 0.04 between seeds; chi-square gives 3 +- 0.055).
//  - The defaults fit the plant: `moorsim run thesis_no_failure.yaml` (FEM
//    lines, WAMIT hull, JONSWAP Hs 2.5 m / Tp 7 s, the thesis's PI, 1 Hz sensors),
//    replayed through the intact filter with the delivered thrust as input, skipping
//    the first 100 s. Over a grid (wave std 0.05-0.5 m, bias std 0.1-4 MN, force 2e4-1e5
//    N sqrt(s)) the predictive log-likelihood per sample peaks at about 0.1 m / 2-4 MN
//    (2.57; mean NIS 2.8-3.1); the defaults 0.15 m / 1 MN / 5e4 N sqrt(s) give 2.36 with
//    mean NIS 2.92 (per channel e_i^2 / S_ii = 1.02, 1.00, 0.88; the heading channel is
//    measurement noise, whose realised variance in that run was 0.9 of R). Below the
//    likelihood peak on purpose: a bias that moves faster also takes up a parted line's
//    load faster, and the hypotheses then look alike. With these defaults a plain DHT
//    (floor 1e-9) on the replayed thesis runs, again with the delivered thrust, passes
//    p = 0.9 for the right line 30 s (line 6), 23 s (line 7) and 82 s (line 8) after the
//    break and holds it 98, 96 and 88 % of the remaining time. A 0.5 MN spread isolates
//    lines 7 and 8 sooner (17 s, 29 s) but holds line 6 only 57 % of the time and is
//    inconsistent on the plant (NIS 3.9); 0.1-0.2 MN give NIS 6-9 and hold lines 7 and 8
//    less than half of the time. The force noise barely matters there (the bias and the
//    wave model take up the plant's residual motion).
// A broken line is, to a wrong filter, a constant force that its bias can absorb: the
// evidence between hypotheses comes mostly from the transient after a break (and from
// the 1/8 change of stiffness afterwards), which is what the detectors integrate.
//
// Initialisation: at the first observation with all three channels valid, eta = y (psi
// wrapped), xi = 0, b = 0, nu = 0 with the stationary covariances of xi and b, the given
// velocity spread, and the eta covariance conditioned on that first measurement
// (var eta = var(C_w xi) + R, cov(eta, C_w xi) = -var(C_w xi)). Until then, and at that
// sample, the evidence has dimension 0.
//
// On bad state: a non-finite innovation or covariance throws moorsim::SolverError naming
// the time; a non-finite valid measurement or command, or a time that does not advance
// (or jumps by more than max_interval), throws moorsim::InputError.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "core/observer_state.h"
#include "core/types.h"
#include "detectors/detector.h"
#include "detectors/hypothesis_bank.h"

namespace moorsim::detectors {

class SensorMonitor;

struct EkfOptions {
  /// Wave model (TAPM thesis section 4.4; docs/design.md section 9): peak frequency
  /// w0 = 2 pi / 7 s.
  Vec3 wave_frequency = Vec3::Constant(0.8975979010256552);  ///< w0 [rad/s]
  Vec3 wave_damping = Vec3::Constant(0.1);                   ///< lambda [-]
  /// Stationary standard deviation of the wave-frequency motion C_w xi [m, m, rad]; the
  /// filter's intensity is s = std sqrt(4 lambda w0). 0.15 m, 0.15 m, 0.5 deg: fitted to
  /// the thesis plant (file comment); a 200 m FPSO moves little at 7 s.
  Vec3 wave_motion_std = Vec3(0.15, 0.15, 0.0087);
  Vec3 bias_time_constant = Vec3::Constant(1000.0);  ///< T [s] (TAPM thesis section 4.4)
  /// Stationary standard deviation of the bias b [N, N, N m]: current, wind and wave
  /// drift (about 1 MN mean on the thesis plant in beam seas); the intensity is
  /// std sqrt(2 / T). See the file comment for the trade-off against detection.
  Vec3 bias_std = Vec3(1e6, 1e6, 5e7);
  /// Density of the white force w_F on the low-frequency dynamics [N sqrt(s), N sqrt(s),
  /// N m sqrt(s)]: its average over 1 s has this standard deviation in N (N m). It stands
  /// for what the model lacks at periods shorter than the bias: slowly varying drift,
  /// thruster lag behind the command, line dynamics.
  Vec3 force_noise = Vec3(5e4, 5e4, 1e7);
  Vec3 measurement_variance = Vec3::Constant(0.005);  ///< R diagonal [m^2, m^2, rad^2]
  /// Linear mooring damping as a fraction of critical per DOF (MooringDampingMatrix);
  /// 0 = none. TAPM thesis section 3.3.1 suggests 0.1-0.2; the default leaves it to the
  /// vessel's own low-frequency damping, which is already 37 % of critical in surge.
  Vec3 mooring_damping_ratio = Vec3::Zero();
  /// Whether Observation::tau_command drives the model. Set false when the plant's
  /// delivered thrust is far from the command (saturated thrusters, wound-up integrators):
  /// the thrust is then left to the bias and the force noise. On the thesis scenarios the
  /// PI commands up to 13 MN while the thrusters deliver under 1 MN, and the command
  /// misleads the filter more than no thrust at all (intact NIS 4.1 against 3.2).
  bool use_thrust_command = true;
  /// Initial standard deviation of nu [m/s, m/s, rad/s].
  Vec3 initial_velocity_std = Vec3(0.1, 0.1, 0.002);
  double max_substep = 0.5;    ///< RK4 substep bound [s]
  double max_interval = 60.0;  ///< longest gap between observations the filter bridges [s]
};

/// Throws moorsim::InputError naming the field ("ekf.bias_std[2]") and the value.
void Validate(const EkfOptions& options);

class HypothesisEkf : public ObserverStateLayout {
 public:
  using Covariance = Eigen::Matrix<double, kStates, kStates>;
  /// The low-frequency part [eta, b, nu].
  using LfState = Eigen::Matrix<double, 9, 1>;
  using LfMatrix = Eigen::Matrix<double, 9, 9>;

  /// `mooring_damping` is D_mo [N s/m, ...] in body axes, added to the model's D.
  /// Throws moorsim::InputError on bad options or a mass that is not positive definite.
  HypothesisEkf(QuasiStaticMooring mooring, const LowFrequencyModel& model,
                const Mat3& mooring_damping, const EkfOptions& options = {});

  /// Forgets the estimate; the next complete observation initialises it.
  void Reset();
  /// Replaces the estimate of an initialised filter (the observer bank's mixing). The
  /// heading is wrapped to (-pi, pi]; `P` is symmetrised.
  void SetEstimate(const State& x, const Covariance& P);
  /// Predicts to observation.t and updates with its valid channels. Allocates nothing.
  /// The evidence's innovation is 0 on invalid channels; its covariance is the full
  /// predicted S, of which the valid block is what the log-likelihood used.
  HypothesisEvidence Update(const Observation& observation);

  /// Multiplies R per channel from the next sample on (a sensor judged noisy; the observer
  /// bank's sensor checks set it). Ones by default.
  void SetMeasurementNoiseScale(const Vec3& scale) { noise_scale_ = scale; }

  bool initialised() const { return initialised_; }
  double time() const { return t_; }
  const State& state() const { return x_; }
  const Covariance& covariance() const { return P_; }
  Vec3 pose() const { return x_.segment<3>(kPose); }
  Vec3 bias() const { return x_.segment<3>(kBias); }
  Vec3 velocity() const { return x_.segment<3>(kVelocity); }
  Vec3 wave_motion() const { return x_.segment<3>(kWave + 3); }
  /// e^T S^-1 e over the last sample's valid channels (0 if none).
  double normalised_innovation_squared() const { return nis_; }

  /// d[eta, b, nu]/dt for thrust `tau` (body) and, if `A` is given, its Jacobian.
  LfState LowFrequencyDerivative(const LfState& x, const Vec3& tau, LfMatrix* A) const;
  /// One RK4 step of size h of the low-frequency model and its exact Jacobian Phi.
  LfState LowFrequencyStep(const LfState& x, const Vec3& tau, double h, LfMatrix* Phi) const;

 private:
  void Initialise(const Observation& observation);
  void Predict(double dt);
  void CacheWaveDiscretisation(double dt);
  HypothesisEvidence MeasurementUpdate(const Observation& observation);

  QuasiStaticMooring mooring_;
  EkfOptions options_;
  Mat3 mass_inverse_ = Mat3::Zero();
  Mat3 damping_ = Mat3::Zero();           // D + D_mo
  Vec3 bias_rate_ = Vec3::Zero();         // 1 / T
  Vec3 wave_sigma_ = Vec3::Zero();        // s per DOF
  LfMatrix lf_noise_ = LfMatrix::Zero();  // Q_c of [eta, b, nu]

  // Wave discretisation for wave_dt_.
  double wave_dt_ = -1.0;
  Eigen::Matrix<double, 6, 6> wave_transition_ = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> wave_noise_ = Eigen::Matrix<double, 6, 6>::Zero();

  bool initialised_ = false;
  double t_ = 0.0;
  Vec3 tau_ = Vec3::Zero();  // held thrust, body
  State x_ = State::Zero();
  Covariance P_ = Covariance::Zero();
  double nis_ = 0.0;
  Vec3 noise_scale_ = Vec3::Ones();
};

/// The checks the observer bank makes on the sensors before its filters take a sample
/// (detectors/sensor_monitor.h).
struct SensorCheckOptions {
  /// Samples of a bit-identical reading that make it frozen, and samples without a reading
  /// that make it silent, >= 2.
  int frozen_samples = 4;
  /// Normalised innovation squared beyond which a sample is withheld (per sensor: 2 degrees
  /// of freedom for the GNSS, 1 for the gyro), > 0. 25: about 5 standard deviations.
  double gate = 25.0;
  /// Consecutive withheld samples that agree that make a jump, >= 1.
  int jump_samples = 3;
  /// Normalised squared distance within which each of them must lie from their mean, > 0.
  /// 9: 3 standard deviations.
  double agree = 9.0;
  /// [s] Averaging time of the innovations' recent variance, > 0.
  double noise_time = 90.0;
  /// [s] Averaging time of their usual variance, > noise_time; it is learned while the
  /// sensor is not judged noisy, and the noisy check waits for a quarter of it.
  double baseline_time = 600.0;
  /// Recent over usual variance beyond which a sensor is noisy, > 1.
  double noisy_ratio = 5.0;
  /// [s] Averaging time of the noise's fast estimate from successive differences, which
  /// judges a sensor noisy at the onset of its noise; > 0 and < noise_time.
  double fast_time = 10.0;
  /// That estimate over the usual variance beyond which a sensor is noisy, > 1.
  double fast_ratio = 8.0;
};

/// Throws moorsim::InputError naming the field ("detection.sensor_checks.gate") and value.
void Validate(const SensorCheckOptions& options);

/// How the observer bank couples its filters.
struct ObserverBankOptions {
  /// Rate [1/s] at which the truth may switch from its hypothesis to any other, shared
  /// equally among the others; 0 = independent filters, as in the papers. With a rate > 0
  /// the bank is an interacting-multiple-model (IMM) bank (Blom and Bar-Shalom 1988):
  /// before each sample every filter restarts from the mixture of all filters' estimates,
  /// weighted by the probability that its hypothesis came from each of theirs. See
  /// ObserverBank for why the detectors need it on a moored vessel. Default 0.01/s, a
  /// design value, not a failure rate: it sets how far a failure filter may drift from the
  /// intact estimate while intact holds (the transition probability 0.01 dt / (N - 1) is
  /// roughly the floor of the bank's probabilities). On the coupled thesis plant (each of
  /// the 8 lines parting, waves, current, PI; benchmarks/README.md) 0.003 isolates faster
  /// but lets wave-drift groups raise MLE false alarms, and 0.03 loses the failure filters
  /// to the drift (misisolations and false alarms); 0.01 isolates every line with neither.
  double switch_rate = 0.01;
  /// Checks on the sensors before the filters take a sample; unset: none (the papers'
  /// observers take every delivered sample as it is).
  std::optional<SensorCheckOptions> sensor_checks;
};

/// Throws moorsim::InputError naming the field ("detection.switch_rate") and the value.
void Validate(const ObserverBankOptions& options);

/// One HypothesisEkf per hypothesis of a HypothesisBank, all fed the same observations.
/// With options.mooring_damping_ratio > 0, hypothesis h gets
/// D_mo = bank.MooringDamping(h, model.mass, ratio).
///
/// Mixing (bank.switch_rate > 0). Independent filters cannot tell a parted line from a
/// steady environmental load: each filter's bias state absorbs the pretension its model
/// lacks (the line-6 filter carries -H_6 = 3.5 MN of "current" while all lines hold), so
/// when line 6 parts the line-6 filter's bias must move by H_6 just as the intact one's
/// must, and the evidence between them is only the small change of stiffness. A bank in
/// which the hypotheses may switch models what is asked: "has line k parted since the
/// estimate was last right?". With probabilities mu (the bank's own, from the same
/// likelihoods) and transition probabilities p_ij over the sample interval dt
/// (p_ii = exp(-rate dt), p_ij = (1 - p_ii) / (N - 1)), filter j restarts from
///   c_j = sum_i p_ij mu_i,  w_ij = p_ij mu_i / c_j,
///   x0_j = sum_i w_ij x_i,  P0_j = sum_i w_ij (P_i + (x_i - x0_j)(x_i - x0_j)^T)
/// (headings averaged as wrapped differences from x_j's), then predicts and updates as
/// usual; afterwards mu_j is proportional to c_j times its likelihood (kept in log space).
/// While the intact filter holds nearly all the probability, each failure filter keeps
/// being pulled back to the intact estimate, its bias stays the environment's, and a
/// parted line shows at once as the failure filter predicting the drift the others miss.
/// Weights below 1e-12 are skipped (and the rest renormalised). A mixing bank also runs
/// one more intact filter that is never mixed and reports it as Evidence::nominal: the
/// residuals of the nominal model alone, which is what a GLR tests.
///
/// Evidence::load is that nominal filter's bias estimate (the first filter's where the bank
/// does not mix) with the load of each hypothesis's failed lines at its pose estimate.
class ObserverBank {
 public:
  ObserverBank(const HypothesisBank& bank, const LowFrequencyModel& model,
               const EkfOptions& options = {}, const ObserverBankOptions& bank_options = {});
  ~ObserverBank();
  ObserverBank(ObserverBank&&) noexcept;
  ObserverBank& operator=(ObserverBank&&) noexcept;

  int size() const { return static_cast<int>(filters_.size()); }
  void Reset();
  /// Runs every filter on `observation`; the result stays valid until the next call.
  /// Allocates nothing, except the load evidence's table once after each Reset().
  const Evidence& Update(const Observation& observation);
  const Evidence& evidence() const { return evidence_; }
  const HypothesisEkf& filter(int h) const { return filters_.at(h); }
  /// The bank's own hypothesis probabilities mu (uniform until the first update; with
  /// switch_rate 0 they are the unfloored Bayesian posterior).
  std::span<const double> probabilities() const { return probability_; }

 private:
  void Mix(double dt);
  void UpdateLoadEvidence(const HypothesisEkf& intact);
  void UpdateTensionEvidence(const HypothesisEkf& intact, const Observation& observation);

  ObserverBankOptions options_;
  std::vector<HypothesisEkf> filters_;
  std::optional<HypothesisEkf> nominal_;    // unmixed intact filter (mixing banks only)
  std::unique_ptr<SensorMonitor> monitor_;  // options_.sensor_checks
  Evidence evidence_;
  std::vector<double> log_probability_;  // log mu
  std::vector<double> probability_;      // mu
  std::vector<double> predicted_;        // c_j
  // Mixing work space, sized once.
  std::vector<HypothesisEkf::State> mixed_state_;
  std::vector<HypothesisEkf::Covariance> mixed_covariance_;
  std::vector<HypothesisEkf::State> difference_;  // x_i - x_j, heading wrapped
  std::vector<double> weight_;
  // The load evidence: the intact mooring, each hypothesis's failed lines (0-based) and
  // the per-line load scratch; each line's index among the intact mooring's straight
  // lines (-1: in a network) and, where lines meet at free points, each hypothesis's
  // mooring (the load it loses is the networks' load less theirs).
  QuasiStaticMooring intact_mooring_;
  std::vector<std::vector<int>> failed_;
  std::vector<Vec3> line_load_;
  std::vector<int> line_index_;
  std::vector<QuasiStaticMooring> hypothesis_moorings_;
  // Per line (0-based), the hypothesis "that line alone parted" where the line is in a
  // network (-1 otherwise): the cells' expectations with it parted.
  std::vector<int> network_line_hypothesis_;
};

}  // namespace moorsim::detectors
