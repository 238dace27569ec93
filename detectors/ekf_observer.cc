#include "detectors/ekf_observer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <sstream>
#include <string_view>
#include <utility>

#include <Eigen/Cholesky>

#include "core/error.h"
#include "core/types.h"
#include "detectors/observer_support.h"
#include "detectors/sensor_monitor.h"

namespace moorsim::detectors {
namespace {

using internal::CheckScalar;
using internal::CheckVector;
using internal::kLogTwoPi;
using internal::WrapAngle;
using internal::YawRotation;

/// exp(A) by scaling and squaring with a truncated Taylor series: A is scaled by 2^-k so
/// its 1-norm is below 1/2, where 20 terms are exact to rounding. Construction-time and
/// rare (when the sample interval changes), on fixed-size matrices: no allocation.
template <int N>
Eigen::Matrix<double, N, N> MatrixExponential(const Eigen::Matrix<double, N, N>& a) {
  using Matrix = Eigen::Matrix<double, N, N>;
  const double norm = a.cwiseAbs().colwise().sum().maxCoeff();
  int squarings = 0;
  if (norm > 0.5) squarings = static_cast<int>(std::ceil(std::log2(norm / 0.5)));
  const Matrix scaled = a / std::ldexp(1.0, squarings);
  Matrix result = Matrix::Identity();
  Matrix term = Matrix::Identity();
  for (int k = 1; k <= 20; ++k) {
    term = (term * scaled / k).eval();
    result += term;
  }
  for (int i = 0; i < squarings; ++i) result = (result * result).eval();
  return result;
}

}  // namespace

void Validate(const EkfOptions& options) {
  constexpr std::string_view kPrefix = "ekf.";
  CheckVector(kPrefix, "wave_frequency", options.wave_frequency, false);
  CheckVector(kPrefix, "wave_damping", options.wave_damping, false);
  CheckVector(kPrefix, "wave_motion_std", options.wave_motion_std, true);
  CheckVector(kPrefix, "bias_time_constant", options.bias_time_constant, false);
  CheckVector(kPrefix, "bias_std", options.bias_std, true);
  CheckVector(kPrefix, "force_noise", options.force_noise, true);
  CheckVector(kPrefix, "measurement_variance", options.measurement_variance, false);
  CheckVector(kPrefix, "mooring_damping_ratio", options.mooring_damping_ratio, true);
  CheckVector(kPrefix, "initial_velocity_std", options.initial_velocity_std, true);
  CheckScalar(kPrefix, "max_substep", options.max_substep);
  CheckScalar(kPrefix, "max_interval", options.max_interval);
}

// ---------------------------------------------------------------------------------------
// HypothesisEkf

HypothesisEkf::HypothesisEkf(QuasiStaticMooring mooring, const LowFrequencyModel& model,
                             const Mat3& mooring_damping, const EkfOptions& options)
    : mooring_(std::move(mooring)), options_(options) {
  Validate(options);
  mass_inverse_ = internal::CheckedMass("ekf", model, mooring_damping).inverse;
  damping_ = model.damping + mooring_damping;
  bias_rate_ = options.bias_time_constant.cwiseInverse();
  // Var(xi2) = s^2 / (4 lambda w0) for xi2'' + 2 lambda w0 xi2' + w0^2 xi2 = s w'.
  wave_sigma_ = options.wave_motion_std.cwiseProduct(
      (4.0 * options.wave_damping.cwiseProduct(options.wave_frequency)).cwiseSqrt());
  // Bias: Var(b) = q^2 T / 2 for b' = -b / T + w_b.
  const Vec3 bias_density = options.bias_std.cwiseProduct((2.0 * bias_rate_).cwiseSqrt());
  lf_noise_.setZero();
  lf_noise_.block<3, 3>(3, 3) = bias_density.cwiseAbs2().asDiagonal();
  lf_noise_.block<3, 3>(6, 6) =
      mass_inverse_ * options.force_noise.cwiseAbs2().asDiagonal() * mass_inverse_.transpose();
  Reset();
}

void HypothesisEkf::SetEstimate(const State& x, const Covariance& P) {
  if (!initialised_) {
    throw InputError("ekf: SetEstimate on a filter that has not been initialised");
  }
  x_ = x;
  x_(kPose + 2) = WrapAngle(x_(kPose + 2));
  P_ = 0.5 * (P + P.transpose());
}

void HypothesisEkf::Reset() {
  initialised_ = false;
  t_ = 0.0;
  tau_.setZero();
  x_.setZero();
  P_.setZero();
  nis_ = 0.0;
}

HypothesisEkf::LfState HypothesisEkf::LowFrequencyDerivative(const LfState& x, const Vec3& tau,
                                                             LfMatrix* A) const {
  const Vec3 eta = x.segment<3>(0);
  const Vec3 b = x.segment<3>(3);
  const Vec3 nu = x.segment<3>(6);
  const double c = std::cos(eta.z());
  const double s = std::sin(eta.z());
  const Mat3 R = YawRotation(c, s);
  Mat3 J_load_eta;
  const Vec3 load_earth = mooring_.Load(eta, A != nullptr ? &J_load_eta : nullptr) + b;
  LfState xdot;
  xdot.segment<3>(0) = R * nu;
  xdot.segment<3>(3) = -bias_rate_.cwiseProduct(b);
  xdot.segment<3>(6) = mass_inverse_ * (-damping_ * nu + R.transpose() * load_earth + tau);
  if (A != nullptr) {
    Mat3 dR_dpsi;
    dR_dpsi << -s, -c, 0.0, c, -s, 0.0, 0.0, 0.0, 0.0;
    A->setZero();
    A->block<3, 1>(0, 2) = dR_dpsi * nu;
    A->block<3, 3>(0, 6) = R;
    A->block<3, 3>(3, 3) = (-bias_rate_).asDiagonal();
    Mat3 J_force_eta = R.transpose() * J_load_eta;
    J_force_eta.col(2) += dR_dpsi.transpose() * load_earth;
    A->block<3, 3>(6, 0) = mass_inverse_ * J_force_eta;
    A->block<3, 3>(6, 3) = mass_inverse_ * R.transpose();
    A->block<3, 3>(6, 6) = -mass_inverse_ * damping_;
  }
  return xdot;
}

HypothesisEkf::LfState HypothesisEkf::LowFrequencyStep(const LfState& x, const Vec3& tau, double h,
                                                       LfMatrix* Phi) const {
  // Classic RK4 and, stage by stage, its tangent-linear model:
  //   K1 = A(x), K2 = A(x2)(I + h/2 K1), K3 = A(x3)(I + h/2 K2), K4 = A(x4)(I + h K3),
  //   Phi = I + h/6 (K1 + 2 K2 + 2 K3 + K4).
  const bool tangent = Phi != nullptr;
  LfMatrix A1, A2, A3, A4;
  const LfState k1 = LowFrequencyDerivative(x, tau, tangent ? &A1 : nullptr);
  const LfState k2 = LowFrequencyDerivative(x + 0.5 * h * k1, tau, tangent ? &A2 : nullptr);
  const LfState k3 = LowFrequencyDerivative(x + 0.5 * h * k2, tau, tangent ? &A3 : nullptr);
  const LfState k4 = LowFrequencyDerivative(x + h * k3, tau, tangent ? &A4 : nullptr);
  if (tangent) {
    const LfMatrix I = LfMatrix::Identity();
    const LfMatrix K1 = A1;
    const LfMatrix K2 = A2 * (I + 0.5 * h * K1);
    const LfMatrix K3 = A3 * (I + 0.5 * h * K2);
    const LfMatrix K4 = A4 * (I + h * K3);
    *Phi = I + (h / 6.0) * (K1 + 2.0 * K2 + 2.0 * K3 + K4);
  }
  return x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

void HypothesisEkf::CacheWaveDiscretisation(double dt) {
  if (dt == wave_dt_) return;
  wave_transition_.setZero();
  wave_noise_.setZero();
  for (int i = 0; i < 3; ++i) {
    const double w0 = options_.wave_frequency(i);
    Eigen::Matrix2d a;
    a << 0.0, 1.0, -w0 * w0, -2.0 * options_.wave_damping(i) * w0;
    Eigen::Matrix2d qc = Eigen::Matrix2d::Zero();
    qc(1, 1) = wave_sigma_(i) * wave_sigma_(i);
    // Van Loan (1978): exp([-A Qc; 0 A^T] dt) = [. E12; 0 E22], Phi = E22^T, Q = Phi E12.
    Eigen::Matrix4d m = Eigen::Matrix4d::Zero();
    m.topLeftCorner<2, 2>() = -a * dt;
    m.topRightCorner<2, 2>() = qc * dt;
    m.bottomRightCorner<2, 2>() = a.transpose() * dt;
    const Eigen::Matrix4d e = MatrixExponential<4>(m);
    const Eigen::Matrix2d phi = e.bottomRightCorner<2, 2>().transpose();
    Eigen::Matrix2d q = phi * e.topRightCorner<2, 2>();
    q = 0.5 * (q + q.transpose()).eval();
    const int index[2] = {i, 3 + i};  // xi1_i, xi2_i
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) {
        wave_transition_(index[r], index[c]) = phi(r, c);
        wave_noise_(index[r], index[c]) = q(r, c);
      }
    }
  }
  wave_dt_ = dt;
}

void HypothesisEkf::Initialise(const Observation& observation) {
  x_.setZero();
  P_.setZero();
  x_.segment<3>(kPose) = observation.pose;
  x_(kPose + 2) = WrapAngle(observation.pose.z());
  for (int i = 0; i < 3; ++i) {
    const double w0 = options_.wave_frequency(i);
    const double var_xi2 = options_.wave_motion_std(i) * options_.wave_motion_std(i);
    P_(kWave + i, kWave + i) = var_xi2 / (w0 * w0);  // s^2 / (4 lambda w0^3)
    P_(kWave + 3 + i, kWave + 3 + i) = var_xi2;
    P_(kPose + i, kPose + i) = var_xi2 + options_.measurement_variance(i);
    P_(kPose + i, kWave + 3 + i) = -var_xi2;
    P_(kWave + 3 + i, kPose + i) = -var_xi2;
    P_(kBias + i, kBias + i) = options_.bias_std(i) * options_.bias_std(i);
    P_(kVelocity + i, kVelocity + i) =
        options_.initial_velocity_std(i) * options_.initial_velocity_std(i);
  }
  t_ = observation.t;
  initialised_ = true;
}

void HypothesisEkf::Predict(double dt) {
  CacheWaveDiscretisation(dt);
  const int substeps = static_cast<int>(std::ceil(dt / options_.max_substep - 1e-9));
  const double h = dt / substeps;

  LfState x = x_.segment<9>(kPose);
  LfMatrix P_lf = P_.block<9, 9>(kPose, kPose);
  LfMatrix Phi_total = LfMatrix::Identity();
  LfMatrix Phi;
  for (int k = 0; k < substeps; ++k) {
    x = LowFrequencyStep(x, tau_, h, &Phi);
    const LfMatrix Q = (0.5 * h) * (Phi * lf_noise_ * Phi.transpose() + lf_noise_);
    P_lf = (Phi * P_lf * Phi.transpose()).eval() + Q;
    Phi_total = (Phi * Phi_total).eval();
  }
  x_.segment<9>(kPose) = x;
  x_(kPose + 2) = WrapAngle(x_(kPose + 2));
  x_.segment<6>(kWave) = wave_transition_ * x_.segment<6>(kWave);

  const Eigen::Matrix<double, 6, 6> P_ww = P_.block<6, 6>(kWave, kWave);
  const Eigen::Matrix<double, 6, 9> P_wl = P_.block<6, 9>(kWave, kPose);
  P_.block<6, 6>(kWave, kWave) =
      wave_transition_ * P_ww * wave_transition_.transpose() + wave_noise_;
  const Eigen::Matrix<double, 6, 9> P_wl_new = wave_transition_ * P_wl * Phi_total.transpose();
  P_.block<6, 9>(kWave, kPose) = P_wl_new;
  P_.block<9, 6>(kPose, kWave) = P_wl_new.transpose();
  P_.block<9, 9>(kPose, kPose) = 0.5 * (P_lf + P_lf.transpose());
}

HypothesisEvidence HypothesisEkf::MeasurementUpdate(const Observation& observation) {
  // Max-size matrices: at most 3 valid channels, no heap.
  using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, kStates, Eigen::RowMajor, 3, kStates>;
  using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;
  using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
  using Gain = Eigen::Matrix<double, kStates, Eigen::Dynamic, 0, kStates, 3>;

  HypothesisEvidence evidence;
  // Prediction of y and the full innovation covariance S = H P H^T + R, H = [0 I | I | 0 0].
  Eigen::Matrix<double, 3, kStates> HP;
  for (int i = 0; i < 3; ++i) HP.row(i) = P_.row(kWave + 3 + i) + P_.row(kPose + i);
  Mat3 S;
  for (int j = 0; j < 3; ++j) S.col(j) = HP.col(kWave + 3 + j) + HP.col(kPose + j);
  S = 0.5 * (S + S.transpose()).eval();
  S.diagonal() += options_.measurement_variance.cwiseProduct(noise_scale_);
  evidence.covariance = S;

  int channel[3];
  int m = 0;
  for (int i = 0; i < 3; ++i) {
    if (observation.valid[i]) channel[m++] = i;
  }
  evidence.dimension = m;
  nis_ = 0.0;
  if (m == 0) {
    evidence.innovation.setZero();
    evidence.log_likelihood = 0.0;
    return evidence;
  }
  Vec3 innovation = Vec3::Zero();
  for (int a = 0; a < m; ++a) {
    const int i = channel[a];
    const double predicted = x_(kPose + i) + x_(kWave + 3 + i);
    innovation(i) = observation.pose(i) - predicted;
  }
  if (observation.valid[2]) innovation(2) = WrapAngle(innovation(2));
  evidence.innovation = innovation;

  RowBlock HP_v(m, kStates);
  Small S_v(m, m);
  SmallVector e_v(m);
  Small R_v = Small::Zero(m, m);
  for (int a = 0; a < m; ++a) {
    HP_v.row(a) = HP.row(channel[a]);
    e_v(a) = innovation(channel[a]);
    R_v(a, a) = options_.measurement_variance(channel[a]) * noise_scale_(channel[a]);
    for (int b = 0; b < m; ++b) S_v(a, b) = S(channel[a], channel[b]);
  }
  const Eigen::LLT<Small> llt(S_v);
  if (llt.info() != Eigen::Success || !S_v.allFinite()) {
    std::ostringstream out;
    out << "ekf: innovation covariance not positive definite at t = " << observation.t << " s";
    throw SolverError(out.str());
  }
  const SmallVector whitened = llt.matrixL().solve(e_v);
  nis_ = whitened.squaredNorm();
  double log_det = 0.0;
  for (int a = 0; a < m; ++a) log_det += 2.0 * std::log(llt.matrixL()(a, a));
  evidence.log_likelihood = -0.5 * (nis_ + log_det + m * kLogTwoPi);

  // K = P H^T S^-1; Joseph form P = (I - K H) P (I - K H)^T + K R K^T, written as
  // A = P - K H P, P = A - (A H^T) K^T + K R K^T.
  const Gain K = llt.solve(HP_v).transpose();
  x_ += K * e_v;
  x_(kPose + 2) = WrapAngle(x_(kPose + 2));
  const Covariance A = P_ - K * HP_v;
  Gain AHt(kStates, m);
  for (int b = 0; b < m; ++b)
    AHt.col(b) = A.col(kWave + 3 + channel[b]) + A.col(kPose + channel[b]);
  P_ = A - AHt * K.transpose() + K * R_v * K.transpose();
  P_ = 0.5 * (P_ + P_.transpose()).eval();
  if (!std::isfinite(evidence.log_likelihood) || !x_.allFinite() || !P_.allFinite()) {
    std::ostringstream out;
    out << "ekf: non-finite estimate at t = " << observation.t << " s";
    throw SolverError(out.str());
  }
  return evidence;
}

HypothesisEvidence HypothesisEkf::Update(const Observation& observation) {
  internal::CheckObservation(observation);
  HypothesisEvidence evidence;
  evidence.covariance = options_.measurement_variance.asDiagonal();
  evidence.dimension = 0;
  if (!initialised_) {
    if (observation.valid[0] && observation.valid[1] && observation.valid[2]) {
      Initialise(observation);
      tau_ = options_.use_thrust_command ? observation.tau_command : Vec3::Zero();
    }
    nis_ = 0.0;
    return evidence;
  }
  const double dt = internal::CheckInterval(observation.t, t_, options_.max_interval);
  Predict(dt);
  t_ = observation.t;
  evidence = MeasurementUpdate(observation);
  tau_ = options_.use_thrust_command ? observation.tau_command : Vec3::Zero();
  return evidence;
}

// ---------------------------------------------------------------------------------------
// ObserverBank

void Validate(const ObserverBankOptions& options) {
  if (!(std::isfinite(options.switch_rate) && options.switch_rate >= 0.0)) {
    internal::ThrowField("detection.switch_rate", options.switch_rate, "must be finite and >= 0");
  }
  if (options.sensor_checks) Validate(*options.sensor_checks);
}

ObserverBank::~ObserverBank() = default;
ObserverBank::ObserverBank(ObserverBank&&) noexcept = default;
ObserverBank& ObserverBank::operator=(ObserverBank&&) noexcept = default;

ObserverBank::ObserverBank(const HypothesisBank& bank, const LowFrequencyModel& model,
                           const EkfOptions& options, const ObserverBankOptions& bank_options)
    : options_(bank_options) {
  Validate(options);
  Validate(bank_options);
  filters_.reserve(bank.size());
  for (int h = 0; h < bank.size(); ++h) {
    filters_.emplace_back(
        bank.mooring(h), model,
        internal::MooringDampingFor(bank, h, model.mass, options.mooring_damping_ratio), options);
  }
  if (bank_options.switch_rate > 0.0 && bank.size() > 0) {
    nominal_.emplace(
        bank.mooring(0), model,
        internal::MooringDampingFor(bank, 0, model.mass, options.mooring_damping_ratio), options);
  }
  const std::size_t n = filters_.size();
  if (bank.size() > 0) {
    intact_mooring_ = bank.mooring(0);
    failed_.resize(n);
    for (int h = 0; h < bank.size(); ++h) {
      for (int id : bank.failed_lines(h)) failed_[h].push_back(id - 1);
    }
    line_load_.resize(static_cast<std::size_t>(bank.num_lines()));
    for (int i = 0; i < bank.num_lines(); ++i)
      line_index_.push_back(intact_mooring_.IndexOf(i + 1));
    if (bank.has_networks()) {
      for (int h = 0; h < bank.size(); ++h) hypothesis_moorings_.push_back(bank.mooring(h));
      network_line_hypothesis_.assign(line_index_.size(), -1);
      for (std::size_t i = 0; i < line_index_.size(); ++i) {
        const int id = static_cast<int>(i) + 1;
        if (line_index_[i] < 0) network_line_hypothesis_[i] = bank.Find(std::span(&id, 1));
      }
    }
  }
  if (bank_options.sensor_checks) {
    monitor_ =
        std::make_unique<SensorMonitor>(*bank_options.sensor_checks, options.measurement_variance);
  }
  evidence_.hypotheses.resize(n);
  log_probability_.resize(n);
  probability_.resize(n);
  predicted_.resize(n);
  mixed_state_.resize(n);
  mixed_covariance_.resize(n);
  difference_.resize(n);
  weight_.resize(n);
  Reset();
}

void ObserverBank::Reset() {
  for (HypothesisEkf& filter : filters_) filter.Reset();
  if (nominal_) nominal_->Reset();
  if (monitor_) monitor_->Reset();
  evidence_.t = 0.0;
  evidence_.sensor_faults.clear();
  for (HypothesisEvidence& e : evidence_.hypotheses) e = HypothesisEvidence();
  evidence_.nominal.reset();
  evidence_.load.reset();
  const double uniform = 1.0 / static_cast<double>(filters_.size());
  std::fill(probability_.begin(), probability_.end(), uniform);
  std::fill(log_probability_.begin(), log_probability_.end(), std::log(uniform));
  std::fill(predicted_.begin(), predicted_.end(), uniform);
}

void ObserverBank::Mix(double dt) {
  const int n = size();
  const double stay = std::exp(-options_.switch_rate * dt);
  const double move = n > 1 ? (1.0 - stay) / (n - 1) : 0.0;
  constexpr double kSmallestWeight = 1e-12;
  for (int j = 0; j < n; ++j) {
    predicted_[j] = stay * probability_[j] + move * (1.0 - probability_[j]);
    const HypothesisEkf::State& own = filters_[j].state();
    HypothesisEkf::State& x0 = mixed_state_[j];
    x0.setZero();
    double total = 0.0;
    for (int i = 0; i < n; ++i) {
      const double w = (i == j ? stay : move) * probability_[i] / predicted_[j];
      weight_[i] = w >= kSmallestWeight ? w : 0.0;
      total += weight_[i];
    }
    // Headings as wrapped differences from filter j's own, so +-pi does not average to 0.
    for (int i = 0; i < n; ++i) {
      if (weight_[i] == 0.0) continue;
      weight_[i] /= total;
      HypothesisEkf::State& d = difference_[i];
      d = filters_[i].state() - own;
      d(HypothesisEkf::kPose + 2) = WrapAngle(d(HypothesisEkf::kPose + 2));
      x0 += weight_[i] * d;
    }
    HypothesisEkf::Covariance& P0 = mixed_covariance_[j];
    P0.setZero();
    for (int i = 0; i < n; ++i) {
      if (weight_[i] == 0.0) continue;
      const HypothesisEkf::State d = difference_[i] - x0;
      P0.noalias() += weight_[i] * (filters_[i].covariance() + d * d.transpose());
    }
    x0 += own;
  }
  for (int j = 0; j < n; ++j) filters_[j].SetEstimate(mixed_state_[j], mixed_covariance_[j]);
}

const Evidence& ObserverBank::Update(const Observation& raw) {
  evidence_.t = raw.t;
  const int n = size();
  bool initialised = true;
  for (const HypothesisEkf& filter : filters_) initialised = initialised && filter.initialised();
  // Mix only on a valid step; a bad time is left to the filters to report.
  const double dt = initialised ? raw.t - filters_[0].time() : 0.0;
  const bool mixing = options_.switch_rate > 0.0 && initialised && dt > 0.0 && std::isfinite(raw.t);
  if (mixing) {
    Mix(dt);
  } else {
    std::copy(probability_.begin(), probability_.end(), predicted_.begin());
  }
  // The sensor checks screen the sample against the intact filter's prediction; every
  // filter then takes the screened sample, with the noise weights they set.
  const Observation& observation =
      monitor_ ? monitor_->Screen(raw, nominal_ ? *nominal_ : filters_[0]) : raw;
  if (monitor_) {
    for (HypothesisEkf& filter : filters_) filter.SetMeasurementNoiseScale(monitor_->noise_scale());
    if (nominal_) nominal_->SetMeasurementNoiseScale(monitor_->noise_scale());
    evidence_.sensor_faults = monitor_->findings();
  }
  if (nominal_) evidence_.nominal = nominal_->Update(observation);
  double best = -std::numeric_limits<double>::infinity();
  bool informative = false;
  for (int h = 0; h < n; ++h) {
    const HypothesisEvidence& e = evidence_.hypotheses[h] = filters_[h].Update(observation);
    informative = informative || e.dimension > 0;
    log_probability_[h] = std::log(predicted_[h]) + e.log_likelihood;
    best = std::max(best, log_probability_[h]);
  }
  UpdateLoadEvidence(nominal_ ? *nominal_ : filters_[0]);
  UpdateTensionEvidence(nominal_ ? *nominal_ : filters_[0], observation);
  if (!informative) {
    std::copy(predicted_.begin(), predicted_.end(), probability_.begin());
    for (int h = 0; h < n; ++h) log_probability_[h] = std::log(probability_[h]);
    return evidence_;
  }
  double sum = 0.0;
  for (int h = 0; h < n; ++h) sum += std::exp(log_probability_[h] - best);
  const double log_sum = best + std::log(sum);
  for (int h = 0; h < n; ++h) {
    log_probability_[h] -= log_sum;
    probability_[h] = std::exp(log_probability_[h]);
  }
  return evidence_;
}

void ObserverBank::UpdateTensionEvidence(const HypothesisEkf& intact,
                                         const Observation& observation) {
  const auto lines = static_cast<Eigen::Index>(line_index_.size());
  if (!observation.tensions || !intact.initialised() || observation.tensions->size() != lines) {
    evidence_.tensions.reset();
    return;
  }
  if (!evidence_.tensions) evidence_.tensions.emplace();
  TensionEvidence& cells = *evidence_.tensions;
  cells.measured = *observation.tensions;
  // A line the intact model does not hold (its points reach no anchor or no fairlead) has
  // no expectation: NaN, which the detectors skip.
  constexpr double kNone = kNaN;
  cells.expected.setConstant(lines, kNone);
  const Vec3 pose = intact.pose();
  intact_mooring_.UpperTensions(pose, cells.expected);
  if (network_line_hypothesis_.empty()) return;
  cells.expected_if_parted.setConstant(lines, lines, kNone);
  for (Eigen::Index k = 0; k < lines; ++k) {
    const int h = network_line_hypothesis_[static_cast<std::size_t>(k)];
    if (h > 0) {
      hypothesis_moorings_[static_cast<std::size_t>(h)].UpperTensions(
          pose, cells.expected_if_parted.col(k));
      cells.expected_if_parted(k, k) = 0.0;  // the parted line's own cell
    }
  }
}

void ObserverBank::UpdateLoadEvidence(const HypothesisEkf& intact) {
  if (!intact.initialised() || failed_.empty()) {
    evidence_.load.reset();
    return;
  }
  if (!evidence_.load) {
    evidence_.load.emplace();
    evidence_.load->line_load.resize(failed_.size());
  }
  LoadEvidence& load = *evidence_.load;
  load.bias = intact.bias();
  load.wave_motion = intact.wave_motion();
  load.bias_covariance =
      intact.covariance().block<3, 3>(HypothesisEkf::kBias, HypothesisEkf::kBias);
  const Vec3 pose = intact.pose();
  for (std::size_t i = 0; i < line_load_.size(); ++i) {
    line_load_[i] =
        line_index_[i] >= 0 ? intact_mooring_.LineLoad(line_index_[i], pose) : Vec3::Zero();
  }
  const Vec3 network_load =
      hypothesis_moorings_.empty() ? Vec3::Zero() : intact_mooring_.NetworkLoad(pose);
  for (std::size_t h = 0; h < failed_.size(); ++h) {
    Vec3 sum = Vec3::Zero();
    for (int index : failed_[h]) sum += line_load_[static_cast<std::size_t>(index)];
    if (!hypothesis_moorings_.empty()) {
      sum += network_load - hypothesis_moorings_[h].NetworkLoad(pose);
    }
    load.line_load[h] = sum;
  }
}

}  // namespace moorsim::detectors
