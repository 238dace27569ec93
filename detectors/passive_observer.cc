#include "detectors/passive_observer.h"

#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include <Eigen/Cholesky>

#include "core/error.h"
#include "detectors/observer_support.h"

namespace moorsim::detectors {
namespace {

using internal::kLogTwoPi;
using internal::Rotation;
using internal::WrapAngle;

constexpr std::string_view kPrefix = "passive.";

/// ThrowField for the element "passive.<name>[i + 1]".
[[noreturn]] void ThrowElement(std::string_view name, int i, double value, std::string_view rule) {
  internal::ThrowField(std::string(kPrefix) + internal::Element(name, i), value, rule);
}

}  // namespace

void Validate(const PassiveObserverOptions& options) {
  using internal::CheckScalar;
  using internal::CheckVector;
  CheckVector(kPrefix, "wave_frequency", options.wave_frequency, false);
  CheckVector(kPrefix, "wave_damping", options.wave_damping, false);
  CheckVector(kPrefix, "notch_damping", options.notch_damping, false);
  CheckVector(kPrefix, "cutoff_ratio", options.cutoff_ratio, false);
  CheckVector(kPrefix, "bias_time_constant", options.bias_time_constant, false);
  CheckVector(kPrefix, "velocity_gain", options.velocity_gain, false);
  CheckVector(kPrefix, "bias_gain", options.bias_gain, false);
  CheckVector(kPrefix, "mooring_damping_ratio", options.mooring_damping_ratio, true);
  CheckScalar(kPrefix, "max_substep", options.max_substep);
  CheckScalar(kPrefix, "max_interval", options.max_interval);
  for (int i = 0; i < 3; ++i) {
    // The notch needs zeta_n > lambda (K1 changes sign otherwise; Fossen 2011 11.4.1).
    if (!(options.notch_damping(i) > options.wave_damping(i))) {
      ThrowElement("notch_damping", i, options.notch_damping(i),
                   "must be > wave_damping (the notch is deeper than the wave peak)");
    }
    // Fossen's tuning rule 1/T << K3/K4 < w0 < w_c (the loop transfer is then SPR).
    if (!(options.cutoff_ratio(i) > 1.0)) {
      ThrowElement("cutoff_ratio", i, options.cutoff_ratio(i), "must be > 1 (w_c > w0)");
    }
    const double ratio = options.bias_gain(i) / options.velocity_gain(i);
    if (!(ratio > 1.0 / options.bias_time_constant(i) && ratio < options.wave_frequency(i))) {
      std::ostringstream rule;
      rule.precision(10);
      rule << "bias_gain / velocity_gain = " << ratio << " 1/s must lie in (1 / T, w0) = ("
           << 1.0 / options.bias_time_constant(i) << ", " << options.wave_frequency(i)
           << ") (Fossen's rule 1/T << K3/K4 < w0)";
      ThrowElement("bias_gain", i, options.bias_gain(i), rule.str());
    }
  }
}

PassiveObserverGains ComputePassiveObserverGains(const PassiveObserverOptions& options) {
  Validate(options);
  PassiveObserverGains gains;
  for (int i = 0; i < 3; ++i) {
    const double w0 = options.wave_frequency(i);
    const double wc = options.cutoff_ratio(i) * w0;
    const double notch = options.notch_damping(i) - options.wave_damping(i);
    gains.k1_integral(i) = -2.0 * notch * wc / w0;
    gains.k1_wave(i) = 2.0 * w0 * notch;
    gains.k2(i) = wc;
  }
  gains.k3 = options.bias_gain;
  gains.k4 = options.velocity_gain;
  return gains;
}

// ---------------------------------------------------------------------------------------
// HypothesisPassiveObserver

HypothesisPassiveObserver::HypothesisPassiveObserver(QuasiStaticMooring mooring,
                                                     const LowFrequencyModel& model,
                                                     const Mat3& mooring_damping,
                                                     const Mat3& innovation_covariance,
                                                     const PassiveObserverOptions& options)
    : mooring_(std::move(mooring)),
      options_(options),
      gains_(ComputePassiveObserverGains(options)) {
  const internal::MassMatrices mass = internal::CheckedMass("passive", model, mooring_damping);
  mass_ = mass.mass;
  mass_inverse_ = mass.inverse;
  damping_ = model.damping + mooring_damping;
  bias_rate_ = options.bias_time_constant.cwiseInverse();
  wave_stiffness_ = options.wave_frequency.cwiseAbs2();
  wave_resistance_ = 2.0 * options.wave_damping.cwiseProduct(options.wave_frequency);

  const Mat3& S = innovation_covariance;
  const double scale = S.cwiseAbs().maxCoeff();
  if (!S.allFinite() || !((S - S.transpose()).cwiseAbs().maxCoeff() <= 1e-9 * scale)) {
    std::ostringstream out;
    out.precision(10);
    out << "passive: innovation covariance must be finite and symmetric, got [" << S.row(0) << "; "
        << S.row(1) << "; " << S.row(2) << "]";
    throw InputError(out.str());
  }
  covariance_ = 0.5 * (S + S.transpose());
  information_[0].setZero();
  log_determinant_[0] = 0.0;
  for (int mask = 1; mask < 8; ++mask) {
    int channel[3];
    int m = 0;
    for (int i = 0; i < 3; ++i) {
      if (mask & (1 << i)) channel[m++] = i;
    }
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> block(m, m);
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) block(a, b) = covariance_(channel[a], channel[b]);
    }
    const Eigen::LLT<decltype(block)> llt(block);
    if (llt.info() != Eigen::Success) {
      std::ostringstream out;
      out.precision(10);
      out << "passive: innovation covariance must be positive definite, got [" << covariance_.row(0)
          << "; " << covariance_.row(1) << "; " << covariance_.row(2) << "]";
      throw InputError(out.str());
    }
    const decltype(block) inverse = llt.solve(decltype(block)::Identity(m, m));
    information_[mask].setZero();
    double log_det = 0.0;
    for (int a = 0; a < m; ++a) {
      log_det += 2.0 * std::log(llt.matrixL()(a, a));
      for (int b = 0; b < m; ++b) information_[mask](channel[a], channel[b]) = inverse(a, b);
    }
    log_determinant_[mask] = log_det;
  }
  Reset();
}

void HypothesisPassiveObserver::Reset() {
  initialised_ = false;
  t_ = 0.0;
  y_.setZero();
  valid_ = {false, false, false};
  tau_.setZero();
  x_.setZero();
  nis_ = 0.0;
}

HypothesisPassiveObserver::State HypothesisPassiveObserver::Derivative(
    const State& x, const Vec3& y, const std::array<bool, 3>& valid, const Vec3& tau) const {
  const Vec3 xi1 = x.segment<3>(kWave);
  const Vec3 xi2 = x.segment<3>(kWave + 3);
  const Vec3 eta = x.segment<3>(kPose);
  const Vec3 b = x.segment<3>(kBias);
  const Vec3 nu = x.segment<3>(kVelocity);
  Vec3 e = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (valid[i]) e(i) = y(i) - eta(i) - xi2(i);
  }
  if (valid[2]) e(2) = WrapAngle(e(2));

  const Mat3 R = Rotation(std::cos(eta.z()), std::sin(eta.z()));
  const Vec3 k3e = gains_.k3.cwiseProduct(e);
  const Vec3 k4e = gains_.k4.cwiseProduct(e);
  Vec3 bias_correction, acceleration_correction;
  if (options_.mass_scaled_gains) {
    bias_correction = R * (mass_ * (R.transpose() * k3e));  // M_e K3 e
    acceleration_correction = R.transpose() * k4e;          // M^-1 R^T M_e K4 e
  } else {
    bias_correction = k3e;
    acceleration_correction = mass_inverse_ * (R.transpose() * k4e);
  }
  const Vec3 load_earth = mooring_.Load(eta) + b;

  State d;
  d.segment<3>(kWave) = xi2 + gains_.k1_integral.cwiseProduct(e);
  d.segment<3>(kWave + 3) = -wave_stiffness_.cwiseProduct(xi1) -
                            wave_resistance_.cwiseProduct(xi2) + gains_.k1_wave.cwiseProduct(e);
  d.segment<3>(kPose) = R * nu + gains_.k2.cwiseProduct(e);
  d.segment<3>(kBias) = -bias_rate_.cwiseProduct(b) + bias_correction;
  d.segment<3>(kVelocity) =
      mass_inverse_ * (-damping_ * nu + R.transpose() * load_earth + tau) + acceleration_correction;
  return d;
}

void HypothesisPassiveObserver::Propagate(double dt) {
  const int substeps = static_cast<int>(std::ceil(dt / options_.max_substep - 1e-9));
  const double h = dt / substeps;
  for (int k = 0; k < substeps; ++k) {
    const State k1 = Derivative(x_, y_, valid_, tau_);
    const State k2 = Derivative(x_ + 0.5 * h * k1, y_, valid_, tau_);
    const State k3 = Derivative(x_ + 0.5 * h * k2, y_, valid_, tau_);
    const State k4 = Derivative(x_ + h * k3, y_, valid_, tau_);
    x_ += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    x_(kPose + 2) = WrapAngle(x_(kPose + 2));
  }
}

HypothesisEvidence HypothesisPassiveObserver::Update(const Observation& observation) {
  internal::CheckObservation(observation);
  HypothesisEvidence evidence;
  evidence.covariance = covariance_;
  evidence.dimension = 0;
  nis_ = 0.0;
  const Vec3 tau = options_.use_thrust_command ? observation.tau_command : Vec3::Zero();
  if (!initialised_) {
    if (observation.valid[0] && observation.valid[1] && observation.valid[2]) {
      x_.setZero();
      x_.segment<3>(kPose) = observation.pose;
      x_(kPose + 2) = WrapAngle(observation.pose.z());
      y_ = observation.pose;
      valid_ = observation.valid;
      tau_ = tau;
      t_ = observation.t;
      initialised_ = true;
    }
    return evidence;
  }
  const double dt = internal::CheckInterval(observation.t, t_, options_.max_interval);
  Propagate(dt);
  t_ = observation.t;

  int mask = 0;
  Vec3 innovation = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (!observation.valid[i]) continue;
    mask |= 1 << i;
    innovation(i) = observation.pose(i) - x_(kPose + i) - x_(kWave + 3 + i);
  }
  if (observation.valid[2]) innovation(2) = WrapAngle(innovation(2));
  const int m = (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1);
  evidence.innovation = innovation;
  evidence.dimension = m;
  if (m > 0) {
    nis_ = innovation.dot(information_[mask] * innovation);
    evidence.log_likelihood = -0.5 * (nis_ + log_determinant_[mask] + m * kLogTwoPi);
  }
  if (!x_.allFinite() || !std::isfinite(evidence.log_likelihood)) {
    std::ostringstream out;
    out << "passive observer: non-finite estimate at t = " << observation.t << " s";
    throw SolverError(out.str());
  }
  for (int i = 0; i < 3; ++i) y_(i) = observation.valid[i] ? observation.pose(i) : 0.0;
  valid_ = observation.valid;
  tau_ = tau;
  return evidence;
}

// ---------------------------------------------------------------------------------------
// PassiveObserverBank

PassiveObserverBank::PassiveObserverBank(const HypothesisBank& bank, const LowFrequencyModel& model,
                                         const PassiveObserverOptions& options,
                                         const std::vector<Mat3>& covariances) {
  Validate(options);
  if (static_cast<int>(covariances.size()) != bank.size()) {
    std::ostringstream out;
    out << "passive: " << covariances.size() << " innovation covariances for " << bank.size()
        << " hypotheses: need one per hypothesis";
    throw InputError(out.str());
  }
  observers_.reserve(bank.size());
  for (int h = 0; h < bank.size(); ++h) {
    const Mat3 mooring_damping =
        internal::MooringDampingFor(bank, h, model.mass, options.mooring_damping_ratio);
    try {
      observers_.emplace_back(bank.mooring(h), model, mooring_damping, covariances[h], options);
    } catch (const InputError& e) {
      throw InputError("hypothesis " + std::to_string(h) + " (" + bank.Label(h) + "): " + e.what());
    }
  }
  evidence_.hypotheses.resize(bank.size());
}

void PassiveObserverBank::Reset() {
  for (HypothesisPassiveObserver& observer : observers_) observer.Reset();
  evidence_.t = 0.0;
  for (HypothesisEvidence& e : evidence_.hypotheses) e = HypothesisEvidence();
}

const Evidence& PassiveObserverBank::Update(const Observation& observation) {
  evidence_.t = observation.t;
  for (int h = 0; h < size(); ++h) evidence_.hypotheses[h] = observers_[h].Update(observation);
  return evidence_;
}

}  // namespace moorsim::detectors
