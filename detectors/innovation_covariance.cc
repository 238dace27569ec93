#include "detectors/innovation_covariance.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include <Eigen/Eigenvalues>

#include "core/error.h"
#include "detectors/observer_support.h"

namespace moorsim::detectors {
namespace {

using internal::MooringDampingFor;
using internal::ThrowField;
using internal::YawRotation;

/// exp(A t) of the wave filter A = [0 1; -w0^2 -2 lambda w0] in closed form: with
/// a = -lambda w0 and B = A - a I, B^2 = delta I, delta = w0^2 (lambda^2 - 1), so
/// exp(A t) = e^(a t) (C I + S B) with C, S = cos, sin(w t) / w (delta < 0, w^2 = -delta),
/// cosh, sinh(w t) / w (delta > 0) or 1, t (delta = 0).
Eigen::Matrix2d WaveTransition(double w0, double lambda, double t) {
  const double a = -lambda * w0;
  const double delta = w0 * w0 * (lambda * lambda - 1.0);
  double c = 1.0, s = t;
  if (delta < 0.0) {
    const double w = std::sqrt(-delta);
    c = std::cos(w * t);
    s = std::sin(w * t) / w;
  } else if (delta > 0.0) {
    const double w = std::sqrt(delta);
    c = std::cosh(w * t);
    s = std::sinh(w * t) / w;
  }
  Eigen::Matrix2d b;
  b << -a, 1.0, -w0 * w0, a;
  return std::exp(a * t) * (c * Eigen::Matrix2d::Identity() + s * b);
}

/// Lower Cholesky factor of a 2x2 covariance that may be semi-definite (zero noise).
Eigen::Matrix2d CholeskyFactor(const Eigen::Matrix2d& q) {
  Eigen::Matrix2d l = Eigen::Matrix2d::Zero();
  l(0, 0) = std::sqrt(std::max(q(0, 0), 0.0));
  if (l(0, 0) > 0.0) l(1, 0) = q(1, 0) / l(0, 0);
  l(1, 1) = std::sqrt(std::max(q(1, 1) - l(1, 0) * l(1, 0), 0.0));
  return l;
}

std::string StreamName(std::string_view streams, const char* source) {
  std::string name(streams);
  name += '.';
  name += source;
  return name;
}

void CheckHypothesis(const HypothesisBank& bank, int h) {
  if (h < 0 || h >= bank.size()) {
    std::ostringstream out;
    out << "training hypothesis = " << h << ": must be in [0, " << bank.size() - 1 << "]";
    throw InputError(out.str());
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------
// InnovationCovarianceEstimator

InnovationCovarianceEstimator::InnovationCovarianceEstimator(int min_samples)
    : min_samples_(min_samples) {
  if (min_samples < 4) {
    ThrowField("innovation_covariance.min_samples", min_samples,
               "must be >= 4 (a 3x3 covariance needs at least 4 samples)");
  }
}

void InnovationCovarianceEstimator::Reset() {
  count_ = 0;
  mean_.setZero();
  m2_.setZero();
}

bool InnovationCovarianceEstimator::Add(const Vec3& innovation, const std::array<bool, 3>& valid) {
  if (!(valid[0] && valid[1] && valid[2])) return false;
  if (!innovation.allFinite()) {
    std::ostringstream out;
    out << "innovation_covariance: sample " << count_ + 1 << " is not finite ("
        << innovation.transpose() << ")";
    throw InputError(out.str());
  }
  ++count_;
  const Vec3 delta = innovation - mean_;
  mean_ += delta / static_cast<double>(count_);
  m2_ += delta * (innovation - mean_).transpose();
  return true;
}

bool InnovationCovarianceEstimator::Add(const HypothesisEvidence& evidence) {
  if (evidence.dimension != 3) return false;
  return Add(evidence.innovation);
}

Mat3 InnovationCovarianceEstimator::Covariance() const {
  if (count_ < min_samples_) {
    std::ostringstream out;
    out << "innovation_covariance: " << count_ << " samples with all channels valid, need at least "
        << min_samples_;
    throw InputError(out.str());
  }
  Mat3 covariance = m2_ / static_cast<double>(count_ - 1);
  covariance = 0.5 * (covariance + covariance.transpose()).eval();
  const Eigen::SelfAdjointEigenSolver<Mat3> eigen(covariance, Eigen::EigenvaluesOnly);
  const Vec3 values = eigen.eigenvalues();  // ascending
  if (!covariance.allFinite() || !(values(0) > 1e-12 * values(2))) {
    std::ostringstream out;
    out.precision(6);
    out << "innovation_covariance: the covariance of " << count_
        << " samples is not positive definite (eigenvalues " << values.transpose()
        << "): a channel that never varies, or channels that move together exactly";
    throw InputError(out.str());
  }
  return covariance;
}

// ---------------------------------------------------------------------------------------
// HypothesisModelSimulator

Vec3 HoldingThrust(const QuasiStaticMooring& mooring, const Vec3& pose) {
  const Mat3 R = YawRotation(std::cos(pose.z()), std::sin(pose.z()));
  return -(R.transpose() * mooring.Load(pose));
}

HypothesisModelSimulator::HypothesisModelSimulator(QuasiStaticMooring mooring,
                                                   const LowFrequencyModel& model,
                                                   const Mat3& mooring_damping,
                                                   const EkfOptions& noise, const Vec3& pose,
                                                   std::uint64_t seed, std::string_view streams,
                                                   double max_substep)
    : mooring_(std::move(mooring)),
      noise_(noise),
      max_substep_(max_substep),
      wave_(RandomStream::Derive(seed, StreamName(streams, "wave"))),
      bias_(RandomStream::Derive(seed, StreamName(streams, "bias"))),
      force_(RandomStream::Derive(seed, StreamName(streams, "force"))),
      measure_x_(RandomStream::Derive(seed, StreamName(streams, "measurement.x"))),
      measure_y_(RandomStream::Derive(seed, StreamName(streams, "measurement.y"))),
      measure_psi_(RandomStream::Derive(seed, StreamName(streams, "measurement.psi"))) {
  Validate(noise);
  if (!(std::isfinite(max_substep) && max_substep > 0.0)) {
    ThrowField("simulation.max_substep", max_substep, "must be finite and > 0");
  }
  if (!pose.allFinite()) throw InputError("simulation.pose must be finite");
  mass_inverse_ = internal::CheckedMass("simulation", model, mooring_damping).inverse;
  damping_ = model.damping + mooring_damping;
  force_noise_ = mass_inverse_ * noise.force_noise.asDiagonal();

  RandomStream initial = RandomStream::Derive(seed, StreamName(streams, "initial"));
  x_.setZero();
  for (int i = 0; i < 3; ++i) {
    const double wave_std = noise.wave_motion_std(i);
    x_(HypothesisPassiveObserver::kWave + i) =
        wave_std / noise.wave_frequency(i) * initial.Normal();
    x_(HypothesisPassiveObserver::kWave + 3 + i) = wave_std * initial.Normal();
    x_(HypothesisPassiveObserver::kBias + i) = noise.bias_std(i) * initial.Normal();
  }
  x_.segment<3>(HypothesisPassiveObserver::kPose) = pose;
}

void HypothesisModelSimulator::CacheWaveStep(double dt) {
  if (dt == wave_dt_) return;
  for (int i = 0; i < 3; ++i) {
    const double w0 = noise_.wave_frequency(i);
    const double variance = noise_.wave_motion_std(i) * noise_.wave_motion_std(i);
    const Eigen::Matrix2d phi = WaveTransition(w0, noise_.wave_damping(i), dt);
    const Eigen::Matrix2d stationary = Eigen::Vector2d(variance / (w0 * w0), variance).asDiagonal();
    Eigen::Matrix2d q = stationary - phi * stationary * phi.transpose();
    q = 0.5 * (q + q.transpose()).eval();
    wave_transition_[i] = phi;
    wave_noise_factor_[i] = CholeskyFactor(q);
  }
  wave_dt_ = dt;
}

void HypothesisModelSimulator::Advance(double dt, const Vec3& tau) {
  using Hpo = HypothesisPassiveObserver;
  CacheWaveStep(dt);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d xi(x_(Hpo::kWave + i), x_(Hpo::kWave + 3 + i));
    const Eigen::Vector2d n(wave_.Normal(), wave_.Normal());
    const Eigen::Vector2d next = wave_transition_[i] * xi + wave_noise_factor_[i] * n;
    x_(Hpo::kWave + i) = next(0);
    x_(Hpo::kWave + 3 + i) = next(1);
  }

  using Lf = Eigen::Matrix<double, 6, 1>;  // [eta, nu]
  const int substeps = static_cast<int>(std::ceil(dt / max_substep_ - 1e-9));
  const double h = dt / substeps;
  const Vec3 decay = (-h * noise_.bias_time_constant.cwiseInverse()).array().exp();
  const Vec3 bias_kick =
      noise_.bias_std.cwiseProduct((Vec3::Ones() - decay.cwiseAbs2()).cwiseSqrt());
  const double half_root = std::sqrt(0.5 * h);
  auto derivative = [&](const Lf& x, const Vec3& b) {
    const Vec3 eta = x.head<3>();
    const Vec3 nu = x.tail<3>();
    const Mat3 R = YawRotation(std::cos(eta.z()), std::sin(eta.z()));
    Lf d;
    d.head<3>() = R * nu;
    d.tail<3>() = mass_inverse_ * (-damping_ * nu + R.transpose() * (mooring_.Load(eta) + b) + tau);
    return d;
  };
  auto force_kick = [&]() {
    const Vec3 n(force_.Normal(), force_.Normal(), force_.Normal());
    return Vec3(force_noise_ * n * half_root);
  };
  Lf x;
  x << x_.segment<3>(Hpo::kPose), x_.segment<3>(Hpo::kVelocity);
  Vec3 b = x_.segment<3>(Hpo::kBias);
  for (int k = 0; k < substeps; ++k) {
    const Vec3 b_next =
        decay.cwiseProduct(b) +
        bias_kick.cwiseProduct(Vec3(bias_.Normal(), bias_.Normal(), bias_.Normal()));
    x.tail<3>() += force_kick();
    const Vec3 b_mid = 0.5 * (b + b_next);
    const Lf k1 = derivative(x, b);
    const Lf k2 = derivative(x + 0.5 * h * k1, b_mid);
    const Lf k3 = derivative(x + 0.5 * h * k2, b_mid);
    const Lf k4 = derivative(x + h * k3, b_next);
    x += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    x.tail<3>() += force_kick();
    b = b_next;
  }
  x_.segment<3>(Hpo::kPose) = x.head<3>();
  x_.segment<3>(Hpo::kVelocity) = x.tail<3>();
  x_.segment<3>(Hpo::kBias) = b;
  if (!x_.allFinite()) {
    throw SolverError("simulation: non-finite state of the hypothesis model");
  }
}

Observation HypothesisModelSimulator::Measure(double t, const Vec3& tau) {
  using Hpo = HypothesisPassiveObserver;
  const Vec3 r = noise_.measurement_variance.cwiseSqrt();
  Observation observation;
  observation.t = t;
  observation.pose =
      x_.segment<3>(Hpo::kPose) + x_.segment<3>(Hpo::kWave + 3) +
      Vec3(r(0) * measure_x_.Normal(), r(1) * measure_y_.Normal(), r(2) * measure_psi_.Normal());
  observation.pose.z() = internal::WrapAngle(observation.pose.z());
  observation.tau_command = tau;
  return observation;
}

// ---------------------------------------------------------------------------------------
// Training

void Validate(const CovarianceTrainingOptions& options) {
  if (!options.pose.allFinite()) throw InputError("training.pose must be finite");
  if (!(std::isfinite(options.duration) && options.duration > 0.0)) {
    ThrowField("training.duration", options.duration, "must be finite and > 0");
  }
  if (!(std::isfinite(options.settle_time) && options.settle_time >= 0.0)) {
    ThrowField("training.settle_time", options.settle_time, "must be finite and >= 0");
  }
  if (!(std::isfinite(options.sample_interval) && options.sample_interval > 0.0)) {
    ThrowField("training.sample_interval", options.sample_interval, "must be finite and > 0");
  }
  if (!(std::isfinite(options.max_substep) && options.max_substep > 0.0)) {
    ThrowField("training.max_substep", options.max_substep, "must be finite and > 0");
  }
  if (options.min_samples < 4) {
    ThrowField("training.min_samples", options.min_samples, "must be >= 4");
  }
}

Mat3 TrainPassiveCovariance(const HypothesisBank& bank, int h, const LowFrequencyModel& model,
                            const PassiveObserverOptions& options, std::span<const Observation> run,
                            double settle_time, int min_samples) {
  CheckHypothesis(bank, h);
  if (!(std::isfinite(settle_time) && settle_time >= 0.0)) {
    ThrowField("training.settle_time", settle_time, "must be finite and >= 0");
  }
  HypothesisPassiveObserver observer(
      bank.mooring(h), model, MooringDampingFor(bank, h, model.mass, options.mooring_damping_ratio),
      Mat3::Identity(), options);
  InnovationCovarianceEstimator estimator(min_samples);
  if (run.empty()) return estimator.Covariance();  // throws: no samples
  const double start = run.front().t + settle_time;
  for (const Observation& observation : run) {
    const HypothesisEvidence evidence = observer.Update(observation);
    if (observation.t >= start) estimator.Add(evidence);
  }
  return estimator.Covariance();
}

Mat3 TrainPassiveCovariance(const HypothesisBank& bank, int h, const LowFrequencyModel& model,
                            const PassiveObserverOptions& options, const EkfOptions& noise,
                            const CovarianceTrainingOptions& training) {
  CheckHypothesis(bank, h);
  Validate(training);
  const QuasiStaticMooring& mooring = bank.mooring(h);
  HypothesisModelSimulator plant(
      mooring, model, MooringDampingFor(bank, h, model.mass, noise.mooring_damping_ratio), noise,
      training.pose, training.seed, "training", training.max_substep);
  HypothesisPassiveObserver observer(
      mooring, model, MooringDampingFor(bank, h, model.mass, options.mooring_damping_ratio),
      Mat3::Identity(), options);
  InnovationCovarianceEstimator estimator(training.min_samples);
  const Vec3 tau = HoldingThrust(mooring, training.pose);
  const double dt = training.sample_interval;
  const auto samples =
      static_cast<std::int64_t>(std::ceil((training.settle_time + training.duration) / dt - 1e-9));
  for (std::int64_t k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) * dt;
    if (k > 0) plant.Advance(dt, tau);
    const HypothesisEvidence evidence = observer.Update(plant.Measure(t, tau));
    if (t >= training.settle_time) estimator.Add(evidence);
  }
  return estimator.Covariance();
}

std::vector<Mat3> TrainPassiveCovariances(const HypothesisBank& bank,
                                          const LowFrequencyModel& model,
                                          const PassiveObserverOptions& options,
                                          const EkfOptions& noise,
                                          const CovarianceTrainingOptions& training) {
  std::vector<Mat3> covariances;
  covariances.reserve(bank.size());
  for (int h = 0; h < bank.size(); ++h) {
    covariances.push_back(TrainPassiveCovariance(bank, h, model, options, noise, training));
  }
  return covariances;
}

}  // namespace moorsim::detectors
