#include "detectors/deficit.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "core/error.h"
#include "detectors/registry.h"

namespace moorsim::detectors {

namespace {

constexpr double kMaxSamplesPerValue = 1000.0;

}  // namespace

Deficit::Deficit(const DeficitOptions& options) : options_(options) {
  internal::Require(options.window >= 1, "deficit", "window >= 1");
  internal::Require(options.baseline_time > 0.0, "deficit", "baseline_time > 0");
  internal::Require(options.floor > 0.0, "deficit", "floor > 0");
  internal::Require(options.threshold > 0.0, "deficit", "threshold > 0");
  internal::Require(options.revision > 0.0, "deficit", "revision > 0");
  internal::Require(options.release > 0.0, "deficit", "release > 0");
  internal::Require(options.warmup >= 0.0, "deficit", "warmup >= 0");
  internal::Require(options.learn_delay >= 0, "deficit", "learn_delay >= 0");
  internal::Require(options.small_sample >= 0.0, "deficit", "small_sample >= 0");
  internal::Require(options.direction_prior >= 0.0, "deficit", "direction_prior >= 0");
  internal::Require(options.lead >= 0.0, "deficit", "lead >= 0");
  internal::Require(options.min_fraction > 0.0 && options.min_fraction <= 1.0, "deficit",
                    "0 < min_fraction <= 1");
  internal::Require(options.confirm >= 0.0, "deficit", "confirm >= 0");
  internal::Require(options.fast_window >= 1, "deficit", "fast_window >= 1");
  internal::Require(options.fast_lead >= 0.0, "deficit", "fast_lead >= 0");
  internal::Require(options.confirm_time > 0.0, "deficit", "confirm_time > 0");
  if (options.confirm > 0.0) {
    DeficitOptions fast = options;
    fast.confirm = 0.0;
    fast.window = options.fast_window;
    fast.lead = options.fast_lead;
    fast_ = std::make_unique<Deficit>(fast);
  }
}

void Deficit::Reset(int hypotheses) {
  internal::Require(hypotheses >= 1, "deficit", "at least one hypothesis");
  hypotheses_ = hypotheses;
  ring_.assign(static_cast<std::size_t>(options_.window), Vec2::Zero());
  energies_.assign(static_cast<std::size_t>(options_.window), Regressors::Zero());
  previous_bias_.setZero();
  newest_ = -1;
  filled_ = 0;
  first_time_ = last_time_ = 0.0;
  samples_ = 0;
  learned_ = 0.0;
  learned_samples_ = 0;
  baseline_.setZero();
  energy_mean_.setZero();
  energy_covariance_.setZero();
  cross_.setZero();
  gain_.setZero();
  disturbance_.setZero();
  raw_covariance_.setZero();
  lag_covariance_ = 0.0;
  previous_raw_.setZero();
  delay_.assign(static_cast<std::size_t>(options_.learn_delay) + 1, Pending{});
  delay_oldest_ = delay_count_ = 0;
  held_.clear();
  held_.reserve(HeldLimit());
  z_.assign(static_cast<std::size_t>(hypotheses), 0.0);
  rival_.assign(static_cast<std::size_t>(hypotheses), 0.0);
  verdict_.score.assign(static_cast<std::size_t>(hypotheses), 0.0);
  Restart();
  if (fast_) fast_->Reset(hypotheses);
  fast_taken_ = fast_pending_ = 0;
}

void Deficit::Restart() {
  alarm_ = false;
  named_ = 0;
  std::fill(rival_.begin(), rival_.end(), 0.0);
  reversal_ = 0.0;
  std::fill(verdict_.score.begin(), verdict_.score.end(), 0.0);
  verdict_.hypothesis = 0;
  verdict_.alarm = false;
}

double Deficit::samples_per_value() const {
  const double raw = raw_covariance_.trace();
  const double mean = disturbance_.trace();
  if (!(raw > 0.0) || !(mean > 0.0)) return 1.0;
  const double rho = std::clamp(lag_covariance_ / raw, 0.0, 1.0);
  const double inflation = rho >= 1.0 ? kMaxSamplesPerValue : (1.0 + rho) / (1.0 - rho);
  return std::clamp(inflation * raw / mean, 1.0, kMaxSamplesPerValue);
}

double Deficit::IndependentValues(double samples_per_value) const {
  // The learned samples, counted up to the baseline time (the weights' memory), per
  // independent value.
  const double dt =
      learned_samples_ > 1 ? learned_ / static_cast<double>(learned_samples_ - 1) : 1.0;
  const double span =
      std::min(static_cast<double>(learned_samples_), options_.baseline_time / std::max(dt, 1e-9));
  return std::max(span / samples_per_value, 1e-3);
}

double Deficit::DisturbanceInflation(double samples_per_value) const {
  return 1.0 + options_.small_sample / IndependentValues(samples_per_value);
}

Verdict Deficit::Update(const Evidence& evidence) { return Step(evidence); }

const Verdict& Deficit::Step(const Evidence& evidence) {
  if (!fast_) return StepSlow(evidence);
  const bool was_alarmed = alarm_;
  const Verdict& fast = fast_->StepSlow(evidence);
  StepSlow(evidence);
  if (was_alarmed && !alarm_) {  // the evidence reversed: both tests start over
    fast_->EndFalseAlarm();
    fast_taken_ = fast_pending_ = 0;
    return verdict_;
  }
  const int line = fast.alarm ? fast.hypothesis : 0;
  if (line == 0) {
    fast_taken_ = fast_pending_ = 0;
  } else if (line != fast_taken_) {
    if (line != fast_pending_) {
      fast_pending_ = line;
      fast_onset_ = evidence.t;
    }
    // Raised once this test's sum for the line has reached `confirm`; revised once its
    // evidence for the line over the named one has.
    const std::size_t i = static_cast<std::size_t>(line);
    if (alarm_ && named_ == line) {
      fast_taken_ = line;
      fast_pending_ = 0;
    } else if ((alarm_ ? rival_[i] : verdict_.score[i]) >= options_.confirm) {
      Raise(line);
      fast_taken_ = line;
      fast_pending_ = 0;
    } else if (!alarm_ && evidence.t - fast_onset_ > options_.confirm_time) {
      fast_->EndFalseAlarm();
      fast_pending_ = 0;
    }
  }
  return verdict_;
}

void Deficit::Hold(const Pending& sample) {
  if (options_.relearn && held_.size() < HeldLimit()) held_.push_back(sample);
}

std::size_t Deficit::HeldLimit() const {
  // The delay line at the onset and one baseline time of samples after it.
  return static_cast<std::size_t>(options_.learn_delay) + 1 +
         static_cast<std::size_t>(std::ceil(options_.baseline_time));
}

void Deficit::EndFalseAlarm() {
  // The newest learn_delay samples go back to the delay line rather than into the
  // baseline: a break among them is still tested before it could be learned.
  const std::size_t waiting =
      std::min(held_.size(), static_cast<std::size_t>(options_.learn_delay));
  for (std::size_t i = 0; i + waiting < held_.size(); ++i) Learn(held_[i]);
  const int capacity = static_cast<int>(delay_.size());
  delay_oldest_ = 0;
  delay_count_ = 0;
  for (std::size_t i = held_.size() - waiting; i < held_.size(); ++i) {
    delay_[static_cast<std::size_t>(delay_count_++ % capacity)] = held_[i];
  }
  held_.clear();
  Restart();
}

void Deficit::Raise(int hypothesis) {
  alarm_ = true;
  named_ = hypothesis;
  std::fill(rival_.begin(), rival_.end(), 0.0);
  reversal_ = 0.0;
  verdict_.alarm = true;
  verdict_.hypothesis = hypothesis;
}

Deficit::Vec2 Deficit::Predict(const Regressors& energy) const {
  return baseline_ + gain_ * (energy - energy_mean_);
}

Deficit::Regressors Deficit::WaveRegressors(const Vec3& wave_motion) const {
  const double x = wave_motion.x();
  const double y = wave_motion.y();
  return options_.drift_direction ? Regressors(x * x, y * y, x * y)
                                  : Regressors(x * x + y * y, 0.0, 0.0);
}

// Exponentially weighted moments (West's update for the variance and covariance of s and
// e), the residual covariance C, and the raw bias's covariance and lag-1 covariance: the
// first learned sample sets the means, then a running mean until baseline_time has been
// learned, then weight dt / baseline_time per sample.
void Deficit::Learn(const Pending& sample) {
  const double alpha =
      learned_samples_ == 0
          ? 1.0
          : std::min(1.0, sample.dt / std::min(learned_ + sample.dt, options_.baseline_time));
  const Vec2 ds = sample.mean - baseline_;
  const Regressors de = sample.energy - energy_mean_;
  baseline_ += alpha * ds;
  energy_mean_ += alpha * de;
  energy_covariance_ = (1.0 - alpha) * (energy_covariance_ + alpha * de * de.transpose());
  cross_ = (1.0 - alpha) * (cross_ + alpha * ds * de.transpose());
  // The gain once e has varied measurably (1e-12 m^4: a millimetre of wave motion). With
  // the direction, a ridge of 1e-3 of the regressors' mean variance keeps a regressor that
  // hardly varies (no sway motion in head seas) from taking a gain from noise, and the
  // regression is shrunk toward the energy-only gain (g_e, g_e, 0) (the energy x^2 + y^2
  // is the sum of the first two regressors) with weight n / (n + direction_prior).
  const double variance = energy_covariance_.trace();
  gain_.setZero();
  if (options_.drift && variance > 1e-12) {
    if (options_.drift_direction) {
      const Eigen::Matrix3d ridged =
          energy_covariance_ + 1e-3 * variance / 3.0 * Eigen::Matrix3d::Identity();
      gain_ = ridged.ldlt().solve(cross_.transpose()).transpose();
      const Eigen::Vector3d sum(1.0, 1.0, 0.0);
      const double energy_variance = sum.dot(energy_covariance_ * sum);
      if (options_.direction_prior > 0.0 && energy_variance > 1e-12) {
        const Gain prior = (cross_ * sum / energy_variance) * sum.transpose();
        const double n = IndependentValues(samples_per_value());
        const double weight = n / (n + options_.direction_prior);
        gain_ = weight * gain_ + (1.0 - weight) * prior;
      }
    } else {
      gain_.col(0) = cross_.col(0) / energy_covariance_(0, 0);
    }
  }
  const Vec2 e = sample.mean - Predict(sample.energy);
  disturbance_ += alpha * (e * e.transpose() - disturbance_);
  const Vec2 r = sample.raw - Predict(sample.energy);
  raw_covariance_ += alpha * (r * r.transpose() - raw_covariance_);
  if (learned_samples_ > 0) {
    lag_covariance_ += alpha * (r.dot(previous_raw_) - lag_covariance_);
    learned_ += sample.dt;
  }
  previous_raw_ = r;
  ++learned_samples_;
}

const Verdict& Deficit::StepSlow(const Evidence& evidence) {
  internal::CheckEvidence("deficit", evidence, hypotheses_);
  if (!evidence.load) return verdict_;
  const LoadEvidence& load = *evidence.load;
  internal::Require(static_cast<int>(load.line_load.size()) == hypotheses_, "deficit",
                    "one line load per hypothesis");
  const double t = evidence.t;
  if (!load.bias.allFinite() || !load.wave_motion.allFinite()) {
    std::ostringstream message;
    message << "deficit: non-finite bias or wave-motion estimate at t = " << t << " s";
    throw SolverError(message.str());
  }

  // The short mean s of the horizontal bias, lead-compensated.
  const double dt = samples_ == 0 ? 0.0 : t - last_time_;
  const Vec2 bias = load.bias.head<2>();
  const Vec2 compensated =
      dt > 0.0 ? Vec2(bias + options_.lead / dt * (bias - previous_bias_)) : bias;
  previous_bias_ = bias;
  newest_ = (newest_ + 1) % options_.window;
  filled_ = std::min(filled_ + 1, options_.window);
  ring_[static_cast<std::size_t>(newest_)] = compensated;
  energies_[static_cast<std::size_t>(newest_)] = WaveRegressors(load.wave_motion);
  Vec2 mean = Vec2::Zero();
  Regressors energy = Regressors::Zero();
  for (int i = 0; i < filled_; ++i) {
    mean += ring_[static_cast<std::size_t>(i)];
    energy += energies_[static_cast<std::size_t>(i)];
  }
  mean /= filled_;
  energy /= filled_;
  if (samples_ == 0) first_time_ = t;
  ++samples_;
  last_time_ = t;
  if (filled_ < options_.window) return verdict_;

  // The delay line: learn the oldest sample once it is learn_delay samples old; an alarm
  // drops everything still waiting.
  std::vector<double>& sums = verdict_.score;
  if (alarm_) {
    // Held while the alarm stands: learned if the evidence reverses (EndFalseAlarm()).
    const int capacity = static_cast<int>(delay_.size());
    for (; delay_count_ > 0; --delay_count_) {
      Hold(delay_[static_cast<std::size_t>(delay_oldest_)]);
      delay_oldest_ = (delay_oldest_ + 1) % capacity;
    }
    Hold(Pending{mean, compensated, energy, dt});
  } else {
    const int capacity = static_cast<int>(delay_.size());
    delay_[static_cast<std::size_t>((delay_oldest_ + delay_count_) % capacity)] =
        Pending{mean, compensated, energy, dt};
    // During the warm-up (with warmup_learning) nothing waits: no alarm can be raised
    // yet, so there is nothing to protect the baseline from.
    const bool warming_up = options_.warmup_learning && t - first_time_ < options_.warmup;
    if (++delay_count_ > options_.learn_delay || warming_up) {
      Learn(delay_[static_cast<std::size_t>(delay_oldest_)]);
      delay_oldest_ = (delay_oldest_ + 1) % capacity;
      --delay_count_;
    }
  }
  if (t - first_time_ < options_.warmup || learned_samples_ == 0) return verdict_;

  // z_h against the learned disturbance, per independent value; C inflated while it rests
  // on few independent values.
  const double m = samples_per_value();
  const Eigen::Matrix2d information =
      (DisturbanceInflation(m) * disturbance_ +
       options_.floor * options_.floor * Eigen::Matrix2d::Identity())
          .inverse();
  const Vec2 shift = mean - Predict(energy);
  for (int h = 1; h < hypotheses_; ++h) {
    const Vec2 d = -load.line_load[static_cast<std::size_t>(h)].head<2>();
    const Vec2 weighted = information * d;
    const double along = weighted.dot(shift);  // d' C^-1 D
    const double power = weighted.dot(d);      // d' C^-1 d
    // The share a of the line's load that is missing: 1, or its maximum-likelihood value
    // within [min_fraction, 1].
    const double a = options_.min_fraction < 1.0 && power > 0.0
                         ? std::clamp(along / power, options_.min_fraction, 1.0)
                         : 1.0;
    z_[static_cast<std::size_t>(h)] = (a * along - 0.5 * a * a * power) / m;
  }

  if (!alarm_) {
    int best = 0;
    for (int h = 1; h < hypotheses_; ++h) {
      double& sum = sums[static_cast<std::size_t>(h)];
      sum = std::max(0.0, sum + z_[static_cast<std::size_t>(h)]);
      if (sum > options_.threshold && (best == 0 || sum > sums[static_cast<std::size_t>(best)])) {
        best = h;
      }
    }
    if (best != 0) Raise(best);
  } else {
    for (int h = 1; h < hypotheses_; ++h) {
      double& sum = sums[static_cast<std::size_t>(h)];
      sum = std::max(0.0, sum + z_[static_cast<std::size_t>(h)]);
    }
    const double named_z = z_[static_cast<std::size_t>(named_)];
    int rival = 0;
    for (int j = 1; j < hypotheses_; ++j) {
      double& r = rival_[static_cast<std::size_t>(j)];
      r = j == named_ ? 0.0 : std::max(0.0, r + z_[static_cast<std::size_t>(j)] - named_z);
      if (r > options_.revision && (rival == 0 || r > rival_[static_cast<std::size_t>(rival)])) {
        rival = j;
      }
    }
    if (rival != 0) Raise(rival);
    reversal_ = std::max(0.0, reversal_ - z_[static_cast<std::size_t>(named_)]);
    if (reversal_ > options_.release) EndFalseAlarm();
  }
  verdict_.alarm = alarm_;
  verdict_.hypothesis = alarm_ ? named_ : 0;
  return verdict_;
}

}  // namespace moorsim::detectors
