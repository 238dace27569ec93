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

constexpr std::string_view kPrefix = "passive.";
constexpr PassiveObserverKeys kPassiveKeys{.prefix = kPrefix};

/// The observer's options: `options`' tuning, zero-order hold, all channels at the start.
PassiveNonlinearObserverOptions CoreOptions(const PassiveObserverOptions& options) {
  PassiveNonlinearObserverOptions observer;
  static_cast<PassiveObserverTuning&>(observer) = options;
  observer.max_substep = options.max_substep;
  return observer;
}

}  // namespace

void Validate(const PassiveObserverOptions& options) {
  ValidatePassiveObserver(CoreOptions(options), kPassiveKeys);
  internal::CheckVector(kPrefix, "mooring_damping_ratio", options.mooring_damping_ratio, true);
  internal::CheckScalar(kPrefix, "max_interval", options.max_interval);
}

namespace {

const PassiveObserverOptions& ValidatedPassiveOptions(const PassiveObserverOptions& options) {
  Validate(options);
  return options;
}

}  // namespace

PassiveObserverGains ComputePassiveObserverGains(const PassiveObserverOptions& options) {
  return ::moorsim::ComputePassiveObserverGains(CoreOptions(ValidatedPassiveOptions(options)),
                                                kPassiveKeys);
}

// ---------------------------------------------------------------------------------------
// HypothesisPassiveObserver

HypothesisPassiveObserver::HypothesisPassiveObserver(QuasiStaticMooring mooring,
                                                     const LowFrequencyModel& model,
                                                     const Mat3& mooring_damping,
                                                     const Mat3& innovation_covariance,
                                                     const PassiveObserverOptions& options)
    : options_(ValidatedPassiveOptions(options)),
      observer_(
          CoreOptions(options), internal::CheckedMass("passive", model, mooring_damping).mass,
          model.damping + mooring_damping,
          [mooring = std::move(mooring)](const Vec3& eta) { return mooring.Load(eta); },
          kPassiveKeys) {
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
  observer_.Reset();
  t_ = 0.0;
  tau_.setZero();
  nis_ = 0.0;
}

HypothesisEvidence HypothesisPassiveObserver::Update(const Observation& observation) {
  internal::CheckObservation(observation);
  HypothesisEvidence evidence;
  evidence.covariance = covariance_;
  evidence.dimension = 0;
  nis_ = 0.0;
  const Vec3 tau = options_.use_thrust_command ? observation.tau_command : Vec3::Zero();
  if (!observer_.started()) {
    observer_.Update(0.0, tau, observation.pose, observation.valid);
    if (observer_.started()) {
      tau_ = tau;
      t_ = observation.t;
    }
    return evidence;
  }
  const double dt = internal::CheckInterval(observation.t, t_, options_.max_interval);
  // Integrates with the held sample and thrust, then holds the observation's sample.
  observer_.Update(dt, tau_, observation.pose, observation.valid);
  t_ = observation.t;
  tau_ = tau;

  int mask = 0;
  for (int i = 0; i < 3; ++i) {
    if (observation.valid[i]) mask |= 1 << i;
  }
  const Vec3 innovation = observer_.OutputError(observation.pose, observation.valid);
  const int m = (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1);
  evidence.innovation = innovation;
  evidence.dimension = m;
  if (m > 0) {
    nis_ = innovation.dot(information_[mask] * innovation);
    evidence.log_likelihood = -0.5 * (nis_ + log_determinant_[mask] + m * kLogTwoPi);
  }
  if (!observer_.state().allFinite() || !std::isfinite(evidence.log_likelihood)) {
    std::ostringstream out;
    out << "passive observer: non-finite estimate at t = " << observation.t << " s";
    throw SolverError(out.str());
  }
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
