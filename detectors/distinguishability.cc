#include "detectors/distinguishability.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <unsupported/Eigen/MatrixFunctions>

#include "core/error.h"
#include "detectors/observer_support.h"

namespace moorsim::detectors {
namespace {

using internal::kLogTwoPi;
constexpr int kStates = HypothesisEkf::kStates;
constexpr int kWave = HypothesisEkf::kWave;
constexpr int kPose = HypothesisEkf::kPose;
constexpr int kBias = HypothesisEkf::kBias;
constexpr int kVelocity = HypothesisEkf::kVelocity;

Mat3 Rotation(double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  Mat3 r;
  r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

/// The controller closed around the truth, linearised about its setpoint (file comment,
/// "Closed loop"), on its own state c (low-passed pose and integral, deviations, SI):
///   c_t = A c_{t-1} + B y_t,   du_t = K c_{t-1} + D y_t   (y_t the measured deviation).
/// Without feedback it has no state and du = 0: the thrust is held.
struct Loop {
  MatX A = MatX::Zero(0, 0);
  MatX B = MatX::Zero(0, 3);
  MatX K = MatX::Zero(3, 0);
  MatX D = MatX::Zero(3, 3);
};

/// dR(psi)^T / dpsi.
Mat3 RotationTransposeDerivative(double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  Mat3 d;
  d << -s, c, 0.0, -c, -s, 0.0, 0.0, 0.0, 0.0;
  return d;
}

/// The pi controller of vessel/controller.h at sample time dt, linearised about eta_ref =
/// (.., psi) where the integral holds the rest thrust `tau_rest` (body):
///   f_t = f_{t-1} + a (y_t - f_{t-1}),  a = 1 - exp(-dt / T_f) (1 without the filter),
///   e_t = f_t where the error is filtered, y_t otherwise,   z_t = z_{t-1} + dt e_t,
///   F_t = Kp e_t + Ki z_t + Kd a (y_t - f_{t-1}) / dt   (NED),   u_t = -R(psi_m)^T F_t,
/// so du_t = -R^T dF_t + dR^T/dpsi R tau_rest dpsi_m: the measured heading also turns the
/// standing force.
Loop MakeLoop(const std::optional<PoseFeedback>& feedback, double dt, double psi,
              const Vec3& tau_rest) {
  Loop loop;
  if (!feedback) return loop;
  const PoseFeedback& fb = *feedback;
  const double a =
      fb.derivative_filter_time > 0.0 ? -std::expm1(-dt / fb.derivative_filter_time) : 1.0;
  Mat3 S = Mat3::Zero();
  for (int i = 0; i < 3; ++i) S(i, i) = fb.filtered_error[static_cast<std::size_t>(i)] ? 1.0 : 0.0;
  const Mat3 I = Mat3::Identity();
  const Mat3 error_of_f = (1.0 - a) * S;  // e_t = error_of_f f_{t-1} + error_of_y y_t
  const Mat3 error_of_y = a * S + (I - S);
  const Mat3 P = (fb.kp + dt * fb.ki).asDiagonal();  // Kp e_t + Ki (z_{t-1} + dt e_t)
  const Mat3 Kd = (fb.kd * (a / dt)).asDiagonal();
  const Mat3 Rt = Rotation(psi).transpose();
  loop.A = MatX::Zero(6, 6);
  loop.A.topLeftCorner(3, 3) = (1.0 - a) * I;
  loop.A.bottomLeftCorner(3, 3) = dt * error_of_f;
  loop.A.bottomRightCorner(3, 3) = I;
  loop.B = MatX::Zero(6, 3);
  loop.B.topRows(3) = a * I;
  loop.B.bottomRows(3) = dt * error_of_y;
  loop.K = MatX::Zero(3, 6);
  loop.K.leftCols(3) = -Rt * (P * error_of_f - Kd);
  loop.K.rightCols(3) = -Rt * Mat3(fb.ki.asDiagonal());
  Mat3 D = -Rt * (P * error_of_y + Kd);
  D.col(2) += RotationTransposeDerivative(psi) * Rotation(psi) * tau_rest;
  loop.D = D;
  return loop;
}

MatX InputMatrixOrZero(const LinearGaussianModel& m) {
  return m.input_matrix.size() > 0 ? m.input_matrix : MatX::Zero(m.transition.rows(), 3);
}

/// The augmented system of the file comment on z = [x; c; eps]: z_{t+1} = F z_t + c + noise
/// of covariance W, innovation e_t = H z_t + v_t, with x the truth, c the controller (none
/// without feedback) and eps = x - x^- the filter's prediction error. With observation
/// matrices C_i of the truth and C_j of the filter (equal for the hypotheses, not in
/// general), input matrices G_i, G_j and the loop's du_t = K c + D (C_i x_t + v_t):
///   x_{t+1}   = Phi_i x_t + G_i du_t + c_i + w_t,
///   c_{t+1}   = A c_t + B (C_i x_t + v_t),
///   eps_{t+1} = (Phi_i - Phi_j - Phi_j K_f (C_i - C_j)) x_t + Phi_j (I - K_f C_j) eps_t
///               + (G_i - G_j) du_t + w_t - Phi_j K_f v_t + c_i - c_j,
///   e_t       = (C_i - C_j) x_t + C_j eps_t + v_t,
/// where v_t enters the next state through the controller too (correlated noise terms).
struct Augmented {
  MatX F;
  VecX c;
  MatX W;
  MatX H;
};

/// `truth_transition` and `filter_transition` stand in for the models' own transitions (the
/// transient takes them along its trajectories).
Augmented Augment(const LinearGaussianModel& truth, const MatX& truth_transition,
                  const LinearGaussianModel& filter_model, const MatX& filter_transition,
                  const SteadyStateFilter& filter, const Loop& loop) {
  const int n = static_cast<int>(truth_transition.rows());
  const int nc = static_cast<int>(loop.A.rows());
  const int N = 2 * n + nc;
  const MatX& Cj = filter_model.observation;
  const MatX& Ci = truth.observation;
  const MatX C_difference = Ci - Cj;
  const MatX identity = MatX::Identity(n, n);
  const MatX PK = filter_transition * filter.gain;
  Augmented a;
  a.F = MatX::Zero(N, N);
  a.F.block(0, 0, n, n) = truth_transition;
  a.F.block(n + nc, 0, n, n) = truth_transition - filter_transition - PK * C_difference;
  a.F.block(n + nc, n + nc, n, n) = filter_transition * (identity - filter.gain * Cj);
  a.H = MatX::Zero(Cj.rows(), N);
  a.H.leftCols(n) = C_difference;
  a.H.rightCols(n) = Cj;
  a.c = VecX::Zero(N);
  a.c.head(n) = truth.input;
  a.c.tail(n) = truth.input - filter_model.input;
  MatX process = MatX::Zero(N, n);  // how w_t enters
  process.topRows(n) = identity;
  process.bottomRows(n) = identity;
  MatX measurement = MatX::Zero(N, Cj.rows());  // how v_t enters
  measurement.bottomRows(n) = -PK;
  if (nc > 0) {  // the controller, on the measured pose
    if (Ci.rows() != loop.B.cols()) {
      throw ContractError("distinguishability: the controller needs the 3 pose outputs");
    }
    const MatX Gi = InputMatrixOrZero(truth);
    const MatX G_difference = Gi - InputMatrixOrZero(filter_model);
    a.F.block(0, 0, n, n) += Gi * loop.D * Ci;
    a.F.block(0, n, n, nc) = Gi * loop.K;
    a.F.block(n, 0, nc, n) = loop.B * Ci;
    a.F.block(n, n, nc, nc) = loop.A;
    a.F.block(n + nc, 0, n, n) += G_difference * loop.D * Ci;
    a.F.block(n + nc, n, n, nc) = G_difference * loop.K;
    measurement.topRows(n) = Gi * loop.D;
    measurement.middleRows(n, nc) = loop.B;
    measurement.bottomRows(n) += G_difference * loop.D;
  }
  a.W = process * truth.process_noise * process.transpose() +
        measurement * truth.measurement_noise * measurement.transpose();
  a.W = 0.5 * (a.W + a.W.transpose()).eval();
  return a;
}

Augmented Augment(const LinearGaussianModel& truth, const LinearGaussianModel& filter_model,
                  const SteadyStateFilter& filter, const Loop& loop = Loop()) {
  return Augment(truth, truth.transition, filter_model, filter_model.transition, filter, loop);
}

/// Sigma = F Sigma F^T + W by doubling (Smith's method): after k steps Sigma holds the sum
/// of F^t W F^tT over t < 2^k. Empty if F^(2^k) does not vanish (F not stable).
std::optional<MatX> SolveLyapunov(const MatX& F, const MatX& W) {
  MatX sigma = W;
  MatX power = F;
  for (int k = 0; k < 64; ++k) {
    sigma += power * sigma * power.transpose();
    power = (power * power).eval();
    if (!sigma.allFinite() || !power.allFinite()) return std::nullopt;
    if (power.cwiseAbs().maxCoeff() < 1e-15) return MatX(0.5 * (sigma + sigma.transpose()));
  }
  return std::nullopt;
}

/// Stationary mean and covariance of the augmented state; empty if the truth is unstable.
std::optional<std::pair<VecX, MatX>> AugmentedStationary(const Augmented& a) {
  std::optional<MatX> sigma = SolveLyapunov(a.F, a.W);
  if (!sigma) return std::nullopt;
  const int n = static_cast<int>(a.F.rows());
  const VecX mean = (MatX::Identity(n, n) - a.F).partialPivLu().solve(a.c);
  if (!mean.allFinite()) return std::nullopt;
  return std::make_pair(mean, *sigma);
}

/// Moments of e = H z + v from those of z = [x; eps].
InnovationMoments InnovationOf(const VecX& mean, const MatX& covariance, const MatX& H,
                               const MatX& R) {
  InnovationMoments m;
  m.mean = H * mean;
  m.covariance = H * covariance * H.transpose() + R;
  m.covariance = 0.5 * (m.covariance + m.covariance.transpose()).eval();
  return m;
}

/// The bank's hypotheses as linear models about eta_ref (file comment). Everything is in
/// scaled coordinates x = T x~, T diagonal with the states' natural sizes (wave motion, bias
/// and velocity spreads, measurement std), so that the matrix exponentials, the DARE and the
/// Lyapunov doubling work on entries of comparable size: the raw state mixes metres with
/// meganewtons and Q spans 16 orders of magnitude. Likelihoods do not depend on T.
class LinearisedBank {
 public:
  LinearisedBank(const HypothesisBank& bank, const LowFrequencyModel& model, const EkfOptions& ekf,
                 const Vec3& pose, double dt)
      : ekf_(ekf), pose_(pose), dt_(dt), rotation_(Rotation(pose.z())) {
    const bool damped = (ekf.mooring_damping_ratio.array() > 0.0).any();
    for (int h = 0; h < bank.size(); ++h) {
      const Mat3 mooring_damping =
          damped ? bank.MooringDamping(h, model.mass, ekf.mooring_damping_ratio) : Mat3::Zero();
      filters_.emplace_back(bank.mooring(h), model, mooring_damping, ekf);
      load_.push_back(bank.mooring(h).Load(pose));
    }
    const Eigen::LLT<Mat3> mass(0.5 * (model.mass + model.mass.transpose()));
    const Mat3 mass_inverse = mass.solve(Mat3::Identity());
    thrust_input_ = MatX::Zero(kStates, 3);
    thrust_input_.block<3, 3>(kVelocity, 0) = mass_inverse;
    scale_.resize(kStates);
    auto or_one = [](double v) { return v > 0.0 ? v : 1.0; };
    for (int i = 0; i < 3; ++i) {
      scale_(kWave + i) = or_one(ekf.wave_motion_std(i) / ekf.wave_frequency(i));
      scale_(kWave + 3 + i) = or_one(ekf.wave_motion_std(i));
      scale_(kPose + i) = std::sqrt(ekf.measurement_variance(i));
      scale_(kBias + i) = or_one(ekf.bias_std(i));
      scale_(kVelocity + i) = or_one(ekf.initial_velocity_std(i));
    }
    // Q_c and C as the EKF has them (ekf_observer.h), then scaled.
    MatX qc = MatX::Zero(kStates, kStates);
    for (int i = 0; i < 3; ++i) {
      const double s =
          ekf.wave_motion_std(i) * std::sqrt(4.0 * ekf.wave_damping(i) * ekf.wave_frequency(i));
      qc(kWave + 3 + i, kWave + 3 + i) = s * s;
      qc(kBias + i, kBias + i) =
          2.0 * ekf.bias_std(i) * ekf.bias_std(i) / ekf.bias_time_constant(i);
    }
    qc.block<3, 3>(kVelocity, kVelocity) =
        mass_inverse * ekf.force_noise.cwiseAbs2().asDiagonal() * mass_inverse.transpose();
    const VecX inverse = scale_.cwiseInverse();
    scaled_noise_ = inverse.asDiagonal() * qc * inverse.asDiagonal();
    observation_ = MatX::Zero(3, kStates);
    for (int i = 0; i < 3; ++i) {
      observation_(i, kWave + 3 + i) = scale_(kWave + 3 + i);
      observation_(i, kPose + i) = scale_(kPose + i);
    }
    measurement_noise_ = ekf.measurement_variance.asDiagonal();
    // The wave-frequency block is the same in every model and decoupled from the rest.
    wave_transition_ = Linearise(0, Vec3::Zero(), Vec3::Zero()).transition.topLeftCorner(6, 6);
  }

  int size() const { return static_cast<int>(filters_.size()); }
  const HypothesisEkf& ekf(int h) const { return filters_[h]; }
  /// The station-keeping thrust of model i: -R^T g_i(eta_ref), body axes.
  Vec3 StationKeepingThrust(int i) const { return -rotation_.transpose() * load_[i]; }
  /// Model h as data source at (eta_ref, b = 0, nu = 0) under thrust `tau` (its input is
  /// its drift there: zero when tau is its own station-keeping thrust).
  LinearGaussianModel Data(int h, const Vec3& tau) const { return Linearise(h, Vec3::Zero(), tau); }
  /// Filter h on data whose source is held at rest by `tau`: fed tau (or 0 without the
  /// thrust command), linearised at its own rest state b_h* (file comment).
  LinearGaussianModel Filter(int h, const Vec3& tau) const {
    const Vec3 tau_filter = ekf_.use_thrust_command ? tau : Vec3::Zero();
    const Vec3 rest_bias = -load_[h] - rotation_ * tau_filter;
    LinearGaussianModel m = Linearise(h, rest_bias, tau_filter);
    if (!ekf_.use_thrust_command) m.input_matrix.setZero();  // it does not see the thrust
    return m;
  }

  /// The scaled 15-state transition over dt of `model` from the low-frequency state `*x`
  /// (advanced to the end of the step): the RK4 substeps and their tangent-linear map as the
  /// EKF takes them, and the exact wave-frequency block.
  MatX Transition(const HypothesisEkf& model, HypothesisEkf::LfState* x, const Vec3& tau) const {
    const int substeps = static_cast<int>(std::ceil(dt_ / ekf_.max_substep - 1e-9));
    HypothesisEkf::LfMatrix total = HypothesisEkf::LfMatrix::Identity();
    HypothesisEkf::LfMatrix step;
    for (int q = 0; q < substeps; ++q) {
      *x = model.LowFrequencyStep(*x, tau, dt_ / substeps, &step);
      total = (step * total).eval();
    }
    MatX phi = MatX::Zero(kStates, kStates);
    phi.topLeftCorner<6, 6>() = wave_transition_;
    const VecX lf_scale = scale_.segment<9>(kPose);
    phi.block<9, 9>(kPose, kPose) =
        lf_scale.cwiseInverse().asDiagonal() * total * lf_scale.asDiagonal();
    return phi;
  }

 private:
  LinearGaussianModel Linearise(int h, const Vec3& bias, const Vec3& tau) const {
    HypothesisEkf::LfState x;
    x << pose_, bias, Vec3::Zero();
    HypothesisEkf::LfMatrix lf_jacobian;
    const HypothesisEkf::LfState drift = filters_[h].LowFrequencyDerivative(x, tau, &lf_jacobian);
    MatX A = MatX::Zero(kStates, kStates);
    for (int i = 0; i < 3; ++i) {
      const double w0 = ekf_.wave_frequency(i);
      A(kWave + i, kWave + 3 + i) = 1.0;
      A(kWave + 3 + i, kWave + i) = -w0 * w0;
      A(kWave + 3 + i, kWave + 3 + i) = -2.0 * ekf_.wave_damping(i) * w0;
    }
    A.block<9, 9>(kPose, kPose) = lf_jacobian;
    // In deviations from the truth's rest state, which has b = 0.
    HypothesisEkf::LfState offset = HypothesisEkf::LfState::Zero();
    offset.segment<3>(3) = bias;
    VecX u = VecX::Zero(kStates);
    u.segment<9>(kPose) = drift - lf_jacobian * offset;
    const VecX inverse = scale_.cwiseInverse();
    const MatX A_scaled = inverse.asDiagonal() * A * scale_.asDiagonal();
    return Discretise(A_scaled, inverse.cwiseProduct(u));
  }

  /// Exact discretisation over dt: Van Loan (1978), exp([-A Qc; 0 A^T] dt) = [. E12; 0 E22]
  /// with Phi = E22^T, Q = Phi E12; the constant input through exp([A u; 0 0] dt).
  LinearGaussianModel Discretise(const MatX& A, const VecX& u) const {
    const int n = kStates;
    MatX van_loan = MatX::Zero(2 * n, 2 * n);
    van_loan.topLeftCorner(n, n) = -A * dt_;
    van_loan.topRightCorner(n, n) = scaled_noise_ * dt_;
    van_loan.bottomRightCorner(n, n) = A.transpose() * dt_;
    const MatX e = van_loan.exp();
    LinearGaussianModel m;
    m.transition = e.bottomRightCorner(n, n).transpose();
    const MatX q = m.transition * e.topRightCorner(n, n);
    m.process_noise = 0.5 * (q + q.transpose());
    MatX hold = MatX::Zero(n + 4, n + 4);
    hold.topLeftCorner(n, n) = A * dt_;
    hold.block(0, n, n, 1) = u * dt_;
    hold.block(0, n + 1, n, 3) = scale_.cwiseInverse().asDiagonal() * thrust_input_ * dt_;
    const MatX held = hold.exp();
    m.input = held.block(0, n, n, 1);
    m.input_matrix = held.block(0, n + 1, n, 3);
    m.observation = observation_;
    m.measurement_noise = measurement_noise_;
    return m;
  }

  EkfOptions ekf_;
  Vec3 pose_;
  double dt_;
  Mat3 rotation_;
  std::vector<HypothesisEkf> filters_;
  std::vector<Vec3> load_;
  VecX scale_;
  MatX scaled_noise_;
  MatX observation_;
  MatX measurement_noise_;
  MatX wave_transition_;
  MatX thrust_input_;  // d(x')/d(tau), unscaled
};

/// Filter h's view of the intact truth before the break: its model, steady state and the
/// stationary augmented moments.
struct PreBreak {
  LinearGaussianModel model;
  SteadyStateFilter filter;
  double log_det_s = 0.0;
  // Computed before use (after the stationary pass). Constructed from an empty matrix so
  // that moving a PreBreak never copies Eigen's uninitialised ComputationInfo (UBSan flags
  // the load of an invalid enum value).
  Eigen::LLT<MatX> s_llt{MatX()};
  VecX mean;
  MatX covariance;
};

double LogDet(const Eigen::LLT<MatX>& llt) {
  const MatX L = llt.matrixL();
  return 2.0 * L.diagonal().array().log().sum();
}

void CheckOption(const char* name, double value, bool allow_zero) {
  const bool ok = std::isfinite(value) && (allow_zero ? value >= 0.0 : value > 0.0);
  if (!ok) {
    std::ostringstream out;
    out.precision(10);
    out << "distinguishability." << name << " = " << value << ": must be finite and "
        << (allow_zero ? ">= 0" : "> 0");
    throw InputError(out.str());
  }
}

/// Spectral radius of a square matrix.
double SpectralRadius(const MatX& a) {
  const Eigen::EigenSolver<MatX> solver(a, false);
  return solver.eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace

SteadyStateFilter SolveSteadyStateFilter(const LinearGaussianModel& model) {
  // The filtering DARE P = Phi P (I + C^T R^-1 C P)^-1 Phi^T + Q is the control DARE
  // X = A^T X (I + G X)^-1 A + H with A = Phi^T, G = C^T R^-1 C, H = Q. SDA:
  //   A' = A W^-1 A,  G' = G + A W^-1 G A^T,  H' = H + A^T H W^-1 A,  W = I + G H,
  // and H -> X quadratically.
  const int n = static_cast<int>(model.transition.rows());
  const MatX& C = model.observation;
  const Eigen::LLT<MatX> r_llt(model.measurement_noise);
  if (r_llt.info() != Eigen::Success) {
    throw SolverError("steady-state filter: the measurement noise is not positive definite");
  }
  MatX a = model.transition.transpose();
  MatX g = C.transpose() * r_llt.solve(C);
  MatX h = model.process_noise;
  const MatX identity = MatX::Identity(n, n);
  bool converged = false;
  for (int k = 0; k < 100 && !converged; ++k) {
    const Eigen::PartialPivLU<MatX> w(identity + g * h);
    const MatX wa = w.solve(a);
    const MatX wg = w.solve(g);
    MatX h_next = h + a.transpose() * h * wa;
    h_next = 0.5 * (h_next + h_next.transpose()).eval();
    g = g + a * wg * a.transpose();
    g = 0.5 * (g + g.transpose()).eval();
    a = (a * wa).eval();
    if (!h_next.allFinite()) break;
    converged = (h_next - h).norm() <= 1e-14 * h_next.norm();
    h = h_next;
  }
  if (!converged) {
    throw SolverError(
        "steady-state filter: the Riccati equation did not converge (a mode that is unstable "
        "and not observable)");
  }
  SteadyStateFilter f;
  f.predicted_covariance = h;
  f.innovation_covariance = C * h * C.transpose() + model.measurement_noise;
  f.innovation_covariance = 0.5 * (f.innovation_covariance + f.innovation_covariance.transpose());
  const Eigen::LLT<MatX> s_llt(f.innovation_covariance);
  f.gain = s_llt.solve(C * h).transpose();
  return f;
}

std::optional<InnovationMoments> StationaryInnovation(const LinearGaussianModel& truth,
                                                      const LinearGaussianModel& filter_model,
                                                      const SteadyStateFilter& filter) {
  const Augmented a = Augment(truth, filter_model, filter);
  const std::optional<std::pair<VecX, MatX>> z = AugmentedStationary(a);
  if (!z) return std::nullopt;
  return InnovationOf(z->first, z->second, a.H, truth.measurement_noise);
}

double ExpectedLogLikelihood(const MatX& innovation_covariance, const InnovationMoments& moments) {
  const Eigen::LLT<MatX> llt(innovation_covariance);
  if (llt.info() != Eigen::Success) {
    throw SolverError("expected log-likelihood: S is not positive definite");
  }
  const MatX second = moments.covariance + moments.mean * moments.mean.transpose();
  const double trace = llt.solve(second).trace();
  const double m = static_cast<double>(innovation_covariance.rows());
  return -0.5 * (m * kLogTwoPi + LogDet(llt) + trace);
}

Distinguishability AnalyzeDistinguishability(const HypothesisBank& bank,
                                             const LowFrequencyModel& model, const EkfOptions& ekf,
                                             const Vec3& pose,
                                             const DistinguishabilityOptions& options) {
  CheckOption("sample_interval", options.sample_interval, false);
  CheckOption("transient_duration", options.transient_duration, false);
  CheckOption("min_rate", options.min_rate, true);
  if (!pose.allFinite()) throw InputError("distinguishability: the reference pose must be finite");
  Validate(ekf);
  if (options.sample_interval > ekf.max_interval) {
    std::ostringstream out;
    out << "distinguishability.sample_interval = " << options.sample_interval
        << " s: must not exceed ekf.max_interval = " << ekf.max_interval << " s";
    throw InputError(out.str());
  }
  const double dt = options.sample_interval;
  const LinearisedBank models(bank, model, ekf, pose, dt);
  const int n = models.size();
  if (options.feedback) {
    const PoseFeedback& fb = *options.feedback;
    for (int i = 0; i < 3; ++i) {
      CheckOption("feedback.kp", fb.kp(i), true);
      CheckOption("feedback.ki", fb.ki(i), true);
      CheckOption("feedback.kd", fb.kd(i), true);
    }
    CheckOption("feedback.derivative_filter_time", fb.derivative_filter_time, true);
  }

  Distinguishability result;
  result.sample_interval = dt;
  result.rate = MatX::Constant(n, n, kNaN);
  std::vector<PreBreak> pre(n);
  std::vector<double> log_likelihood(n);
  for (int i = 0; i < n; ++i) {
    const Vec3 tau = models.StationKeepingThrust(i);
    const LinearGaussianModel truth = models.Data(i, tau);
    const Loop loop = MakeLoop(options.feedback, dt, pose.z(), tau);
    bool stationary = true;
    for (int j = 0; j < n && stationary; ++j) {
      PreBreak p;
      p.model = models.Filter(j, tau);
      p.filter = SolveSteadyStateFilter(p.model);
      const Augmented a = Augment(truth, p.model, p.filter, loop);
      const std::optional<std::pair<VecX, MatX>> z = AugmentedStationary(a);
      if (!z) {
        stationary = false;
        break;
      }
      p.mean = z->first;
      p.covariance = z->second;
      log_likelihood[j] =
          ExpectedLogLikelihood(p.filter.innovation_covariance,
                                InnovationOf(p.mean, p.covariance, a.H, truth.measurement_noise));
      if (i == 0) pre[j] = std::move(p);
    }
    if (!stationary) {
      if (i == 0) {
        throw SolverError(options.feedback
                              ? "distinguishability: the intact model under the controller is "
                                "not stable about the reference pose"
                              : "distinguishability: the intact model is not stable about the "
                                "reference pose (without the controller)");
      }
      continue;
    }
    for (int j = 0; j < n; ++j) result.rate(i, j) = log_likelihood[i] - log_likelihood[j];
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (result.rate(i, j) < options.min_rate && result.rate(j, i) < options.min_rate) {
        result.hard_pairs.emplace_back(i, j);
      }
    }
  }

  // Transient after a break. Mean: the EKFs on noise-free data of the nonlinear models
  // (under the linearised controller, if closed). Covariance: the augmented system from its
  // stationary state under the intact truth, linearised along those noise-free trajectories
  // (the truth's, and each filter's estimate where the EKF takes its Jacobian), with each
  // filter's steady-state gain. A frozen Jacobian would not do: the drifting vessel's
  // velocity turns the rotated-load coupling of the rest state into a spurious growth of the
  // cross-drift innovation variance.
  const int samples = std::max(1, static_cast<int>(std::lround(options.transient_duration / dt)));
  result.transient_samples = samples;
  const Vec3 tau0 = models.StationKeepingThrust(0);
  const Loop loop = MakeLoop(options.feedback, dt, pose.z(), tau0);
  const int nc = static_cast<int>(loop.A.rows());
  std::vector<Eigen::LLT<MatX>> position_llt;  // S restricted to x, y, per filter
  std::vector<double> position_log_det;
  for (PreBreak& p : pre) {
    p.s_llt.compute(p.filter.innovation_covariance);
    p.log_det_s = LogDet(p.s_llt);
    position_llt.emplace_back(MatX(p.filter.innovation_covariance.topLeftCorner(2, 2)));
    position_log_det.push_back(LogDet(position_llt.back()));
  }
  // Settle the filters on the intact truth at rest until their slowest closed-loop mode has
  // decayed to 1e-6, then copy them for every break.
  double radius = 0.0;
  for (const PreBreak& p : pre) {
    radius = std::max(radius,
                      SpectralRadius(p.model.transition * (MatX::Identity(kStates, kStates) -
                                                           p.filter.gain * p.model.observation)));
  }
  const int settle = std::clamp(
      static_cast<int>(std::ceil(std::log(1e-6) / std::log(std::min(radius, 1.0 - 1e-9)))) + 50,
      100, 200000);
  std::vector<HypothesisEkf> settled;
  for (int h = 0; h < n; ++h) settled.push_back(models.ekf(h));
  Observation observation;
  observation.pose = pose;
  observation.tau_command = tau0;
  double t = 0.0;
  for (int s = 0; s <= settle; ++s, t += dt) {
    observation.t = t;
    for (HypothesisEkf& f : settled) f.Update(observation);
  }
  const double t_break = t - dt;
  const Vec3 tau_filter = ekf.use_thrust_command ? tau0 : Vec3::Zero();
  for (int k = 1; k <= bank.num_lines(); ++k) {
    const LinearGaussianModel truth = models.Data(k, tau0);
    const HypothesisEkf& truth_model = models.ekf(k);
    std::vector<HypothesisEkf> filters = settled;
    std::vector<MatX> covariance(n);
    for (int h = 0; h < n; ++h) covariance[h] = pre[h].covariance;
    std::vector<double> total(n, 0.0);     // sum_t E[log p_h(y_t | Y_{t-1})]
    std::vector<double> position(n, 0.0);  // the same for the x, y channels alone
    HypothesisEkf::LfState x;
    x << pose, Vec3::Zero(), Vec3::Zero();
    VecX controller = VecX::Zero(nc);  // noise-free controller state (deviations)
    Vec3 du = Vec3::Zero();            // the thrust deviation held over the coming step
    double time = t_break;
    for (int s = 1; s <= samples; ++s) {
      const MatX truth_transition = models.Transition(truth_model, &x, tau0 + du);
      time += dt;
      observation.t = time;
      observation.pose = x.segment<3>(0);
      // The controller on the noise-free measurement; the filters predict the coming
      // interval with the thrust it issues (Observation::tau_command).
      Vec3 y = x.segment<3>(0) - pose;
      y.z() = std::remainder(y.z(), 2.0 * std::numbers::pi);
      const Vec3 du_previous = du;
      du = loop.K * controller + loop.D * y;
      controller = (loop.A * controller + loop.B * y).eval();
      observation.tau_command = tau0 + du;
      for (int h = 0; h < n; ++h) {
        // The filter's prediction to this sample, linearised where the EKF linearises it:
        // at its estimate after the previous sample.
        HypothesisEkf::LfState estimate = filters[h].state().segment<9>(kPose);
        const Vec3 tau_known = ekf.use_thrust_command ? Vec3(tau_filter + du_previous) : tau_filter;
        const MatX filter_transition = models.Transition(filters[h], &estimate, tau_known);
        const VecX innovation = filters[h].Update(observation).innovation;
        const PreBreak& p = pre[h];
        const Augmented a =
            Augment(truth, truth_transition, p.model, filter_transition, p.filter, loop);
        covariance[h] = a.F * covariance[h] * a.F.transpose() + a.W;
        const MatX second = a.H * covariance[h] * a.H.transpose() + p.model.measurement_noise +
                            innovation * innovation.transpose();
        total[h] += -0.5 * (3.0 * kLogTwoPi + p.log_det_s + p.s_llt.solve(second).trace());
        position[h] += -0.5 * (2.0 * kLogTwoPi + position_log_det[h] +
                               position_llt[h].solve(second.topLeftCorner(2, 2)).trace());
      }
    }
    TransientEvidence evidence;
    evidence.hypothesis = k;
    evidence.against_intact = total[k] - total[0];
    evidence.against_intact_heading = evidence.against_intact - (position[k] - position[0]);
    for (int h = 1; h < n; ++h) {
      if (h == k) continue;
      const double against = total[k] - total[h];
      if (evidence.rival < 0 || against < evidence.against_rival) {
        evidence.rival = h;
        evidence.against_rival = against;
      }
    }
    result.transient.push_back(evidence);
  }
  return result;
}

}  // namespace moorsim::detectors
