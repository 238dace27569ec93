// Distinguishability of the hypotheses (Hassani et al. 2018, section 4, Theorem 2): how fast, in
// expectation, the log-likelihood ratio between two hypotheses' filters grows, computed
// off-line from the models alone, so a user knows before a campaign which failures can be
// told apart.
//
// Rate. Theorem 2 (eq. 52-56) makes the DHT pick the true hypothesis i when, for every
// other j, filter i's averaged log-likelihood exceeds filter j's by some eps > 0; the
// odds ratio L_i^j of eq. 53 then shrinks like exp(-n eps). For linear Gaussian models
// and steady-state filters that average converges to
//   D(i||j) = E_i[log p_i(y_t | Y_{t-1}) - log p_j(y_t | Y_{t-1})]   [nats/sample],
// the expectation under data from model i: a Kullback-Leibler rate, 0 for j = i and >= 0
// when filter i is the optimal predictor of its own data. At 0.01 nats/sample, 10 nats
// (odds e^10 ~ 2e4) take 1000 samples. With innovations e_j of filter j,
//   E_i[log p_j] = -1/2 (m log 2 pi + log det S_j + tr(S_j^-1 (C_ij + m_ij m_ij^T))),
// S_j its steady-state innovation covariance, m_ij and C_ij the stationary mean and
// covariance of its innovation on model-i data, m = 3 channels; for a matched filter i
// (C_ii = S_i, m_ii = 0)
//   D(i||j) = 1/2 (log det S_j - log det S_i + tr(S_j^-1 (C_ij + m_ij m_ij^T)) - m).
//
// Models. Hypothesis h is its EKF's model (ekf_observer.h, state [xi, eta, b, nu]),
// linearised about the station-keeping pose eta_ref (the bank's reference pose, i.e. the
// controller's setpoint) with the filter's own Jacobian (HypothesisEkf::
// LowFrequencyDerivative) and discretised exactly at the sample interval dt (Van Loan's
// method for Phi and Q, the zero-order-hold integral for the constant input), with the
// noise the EkfOptions state: wave_motion_std, bias_std / bias_time_constant, force_noise,
// measurement_variance, and the same mooring damping rule as ObserverBank. The EKF itself
// steps RK4 (Phi equal to ~1e-10) with a trapezoidal Q (~1e-3 of Q per substep).
//
// Constant terms. The model's bias is zero-mean (b' = -b/T + w_b), so the only load that
// can hold model i at rest at eta_ref is the thrust: the station-keeping thrust is taken as
//   tau_i = -R(psi_ref)^T g_i(eta_ref)   (body axes),
// the thrusters carrying the whole mean load (the environment's mean would add to tau_i
// and to every filter's bias alike; it is left out). Every filter gets tau_i as its known
// input (or 0 with EkfOptions::use_thrust_command off), so the thrust cancels between the
// truth and the filters and leaves, for filter j, the mooring-load difference: at rest at
// eta_ref filter j needs the bias
//   b_j* = -g_j(eta_ref) - R tau_f = g_i(eta_ref) - g_j(eta_ref)   (tau_f = tau_i).
// In deviations dx from the truth's rest state x_i* = (xi 0, eta_ref, b 0, nu 0), filter
// j's model, linearised at its own rest state x_j* = x_i* + (0, 0, b_j*, 0), is
//   dx' = A_j dx + u_j,  u_j = f_j(x_j*) - A_j (x_j* - x_i*) = (0, 0, 0, -M^-1 R^T b_j*):
// in the b rows f_j's mean reversion -b_j*/T and A_j's cancel, so u_j acts on nu, and the
// filter can hold b_j* only by a standing correction through its gain. That is where a
// constant load difference leaves a stationary mean innovation m_ij, kept exact here
// (with T -> infinity it would vanish). The truth's own model has no constant term, and
// A_i, A_j share the rotated-load term d(R^T)/dpsi (g + b) = d(R^T)/dpsi g_i, since both
// hold the same total load at rest.
//
// Closed loop. Where the mooring alone does not hold the pose (a hull on a turret bearing
// has no mooring yaw stiffness about the turret, so the heading is a free integrator) the
// truth only has a stationary law under its controller. With DistinguishabilityOptions::
// feedback the analysis closes the pi controller of vessel/controller.h around the truth,
// sampled with the observations and linearised about the setpoint, its integral holding
// tau_i: on its state c (low-passed pose, integral) c_t = A c_{t-1} + B y_t and the thrust
// deviation du_t = K c_{t-1} + D y_t, D including the measured heading's rotation of the
// standing force. The thrust is known to every filter (it predicts the coming interval with
// it, Observation::tau_command), so du enters the truth and the filter alike and leaves,
// for filter j, only (G_i - G_j) du_t, G the models' discretised input matrices (they
// differ through the mooring's stiffness within the step); but the measurement noise now
// also moves the truth, through the controller. The transient's mean runs the same
// linearised controller on the noise-free measurement.
//
// Stationary moments. Filter j runs its steady-state Kalman filter (Hassani et al. 2018, eq. 48-50;
// DARE eq. 49 by structured doubling). On z = [x; eps], x the truth and eps = x - x^-_j
// filter j's prediction error,
//   x_{t+1}   = Phi_i x_t + c_i + w_t,
//   eps_{t+1} = (Phi_i - Phi_j) x_t + Phi_j (I - K_j C) eps_t + w_t - Phi_j K_j v_t
//               + c_i - c_j,
//   e_t       = C eps_t + v_t,
// (with the controller, z = [x; c; eps] as distinguishability.cc writes out), whose
// stationary mean solves (I - F) mu = c and covariance the discrete Lyapunov equation
// Sigma = F Sigma F^T + W (by doubling); m_ij = C mu_eps, C_ij = C Sigma_eps C^T + R.
// Model i must be stable (a moored vessel is); if it is not, its rates are NaN.
//
// Transient. What matters more for the detection delay is the evidence gathered right
// after a line parts. Before t = 0 the truth is the intact model at rest under tau_0 and
// every filter has converged on it (its stationary mean and covariance); at t = 0 line k
// parts: the truth follows model k under the same thrust tau_0 (plus, with feedback, the
// controller's reaction), so it drifts away from line k's anchor. The expected evidence for k over
// h in the first n = round(T / dt) samples is
//   Lambda_kh = sum_{t=1..n} (E[log p_k(y_t | Y_{t-1})] - E[log p_h(y_t | Y_{t-1})]),
// each term the expression above with the time-varying innovation moments of filter h.
// Their mean comes from the real HypothesisEkf on noise-free data of the nonlinear model
// (GlrSignatures' construction; the filters first settle on the truth at rest until their
// slowest closed-loop mode has decayed to 1e-6); their covariance from the augmented
// system, started at its stationary value and linearised along those noise-free
// trajectories (the truth's, and each filter's estimate, where the EKF takes its Jacobian),
// with each filter's steady-state gain. Reported: k against intact, and against its most
// confusable rival (the other failure hypothesis with the least evidence).
//
// Limits. Everything is about the rest pose: the model's own bias moves the vessel about it
// (metres at the default 1 MN), and on the hardening catenary the average break is then a
// little stronger than the break at the rest pose. Against Monte-Carlo with the real EKFs
// the transient evidence is low by about 7 % at the default bias, 2 % at 0.5 MN, 0.5 % at
// 0.25 MN (in proportion to the bias variance); the stationary rates agreed to 0.5 %
// (tests/detectors/distinguishability_test.cc). At the default bias (1 MN, 1000 s) the
// stationary rates are small, ~0.004 nats/sample between intact and a failure on the
// thesis mooring, and five sixths of that is the cost of a wrong filter holding its bias at
// the load difference against the mean reversion (with T = 1e5 s it drops to ~0.0007): a
// parted line is, to a wrong filter, mostly a constant force its bias absorbs, and the
// evidence comes from the transient. The filters are independent, as in Hassani et al. 2018:
// an IMM bank (ObserverBankOptions::switch_rate > 0) pulls its failure filters back to the
// intact estimate while intact holds, which is not modelled here.
#pragma once

#include <array>
#include <optional>
#include <utility>
#include <vector>

#include "core/types.h"
#include "detectors/ekf_observer.h"
#include "detectors/hypothesis_bank.h"

namespace moorsim::detectors {

/// A discrete-time linear Gaussian model x_{t+1} = Phi x_t + c + w_t, y_t = C x_t + v_t,
/// with w ~ N(0, Q) and v ~ N(0, R) white and independent.
struct LinearGaussianModel {
  MatX transition;  ///< Phi
  VecX input;       ///< c, added at every step
  /// Gamma: what a thrust deviation du [N, N, N m] (body), held over the step, adds to
  /// x_{t+1}; empty where the model has no thrust input.
  MatX input_matrix;
  MatX process_noise;      ///< Q
  MatX observation;        ///< C
  MatX measurement_noise;  ///< R (positive definite)
};

/// The steady-state Kalman filter of a model (Hassani et al. 2018, eq. 48-50): the predicted state
/// covariance P (the DARE, eq. 49), the innovation covariance S = C P C^T + R (eq. 50) and
/// the update gain K = P C^T S^-1, so x+ = x- + K (y - C x-) and x-_{t+1} = Phi x+ + c.
struct SteadyStateFilter {
  MatX predicted_covariance;
  MatX innovation_covariance;
  MatX gain;
};

/// Solves the DARE by the structured doubling algorithm (Chu, Fan and Lin 2005; quadratic
/// convergence). Throws moorsim::SolverError if it does not converge or the result is not
/// finite (a mode that is unstable and unobservable).
SteadyStateFilter SolveSteadyStateFilter(const LinearGaussianModel& model);

/// First and second moments of an innovation [units of y].
struct InnovationMoments {
  VecX mean;
  MatX covariance;
};

/// Stationary moments of the innovation of `filter` (the steady-state filter of
/// `filter_model`) on data from `truth` (file comment): same state size and outputs, the
/// observation matrices may differ. Empty if `truth` is not stable.
std::optional<InnovationMoments> StationaryInnovation(const LinearGaussianModel& truth,
                                                      const LinearGaussianModel& filter_model,
                                                      const SteadyStateFilter& filter);

/// E[log N(e; 0, S)] [nats] for an innovation e with the given moments.
double ExpectedLogLikelihood(const MatX& innovation_covariance, const InnovationMoments& moments);

/// The position controller the analysis closes around the truth (file comment, "Closed
/// loop"): the pi controller of vessel/controller.h (PiControllerOptions, same meanings and
/// units), sampled with the observations, linearised about its setpoint eta_ref.
struct PoseFeedback {
  Vec3 kp = Vec3::Zero();                                      ///< [N/m, N/m, N m/rad], NED axes
  Vec3 ki = Vec3::Zero();                                      ///< [N/(m s), N/(m s), N m/(rad s)]
  Vec3 kd = Vec3::Zero();                                      ///< [N s/m, N s/m, N m s/rad]
  double derivative_filter_time = 0.0;                         ///< low-pass time constant [s]
  std::array<bool, 3> filtered_error = {false, false, false};  ///< P and I on the low-pass
};

struct DistinguishabilityOptions {
  double sample_interval = 1.0;      ///< dt between observations [s]
  double transient_duration = 60.0;  ///< window T after a break [s]
  /// A pair is hard to tell apart when D is below this both ways [nats/sample].
  double min_rate = 0.01;
  /// The controller, if the analysis is to close it (needed where the mooring alone does
  /// not hold the pose, e.g. the heading of a hull on a turret bearing); without it the
  /// thrust is held at each model's station-keeping value.
  std::optional<PoseFeedback> feedback;
};

/// The expected evidence in the first `transient_duration` after line `hypothesis` parts.
struct TransientEvidence {
  int hypothesis = 0;           ///< k: the single-line hypothesis that became true
  double against_intact = 0.0;  ///< Lambda_k0 [nats]
  /// The part of Lambda_k0 the heading channel adds to what the position channels give
  /// (chain rule: log p(y) = log p(x, y) + log p(psi | x, y) for each filter) [nats].
  double against_intact_heading = 0.0;
  int rival = -1;              ///< the other failure hypothesis with the least evidence
  double against_rival = 0.0;  ///< Lambda_k,rival [nats]
};

struct Distinguishability {
  double sample_interval = 0.0;  ///< [s]
  int transient_samples = 0;     ///< n
  /// rate(i, j) = D(i||j) [nats/sample]; a row is NaN when model i is not stable.
  MatX rate;
  /// Pairs (i, j), i < j, with D(i||j) and D(j||i) both below min_rate.
  std::vector<std::pair<int, int>> hard_pairs;
  /// One entry per single-line hypothesis k = 1..bank.num_lines().
  std::vector<TransientEvidence> transient;
};

/// The rates and the transient evidence of every hypothesis of `bank` (file comment).
/// `pose` is eta_ref (x, y [m], psi [rad]), the pose the bank was linearised about.
/// Throws moorsim::InputError on bad options, moorsim::SolverError if a filter has no
/// steady state. About 0.3 s for the 9 hypotheses of the thesis mooring, 2 s with its 28
/// pairs.
Distinguishability AnalyzeDistinguishability(const HypothesisBank& bank,
                                             const LowFrequencyModel& model, const EkfOptions& ekf,
                                             const Vec3& pose,
                                             const DistinguishabilityOptions& options = {});

}  // namespace moorsim::detectors
