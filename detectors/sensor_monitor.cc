#include "detectors/sensor_monitor.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/types.h"

namespace moorsim::detectors {

namespace {

// Samples after a gap in a channel (no reading, or a frozen one) whose innovations teach
// nothing of its noise and from which no jump is judged.
constexpr int kAfterGap = 30;

void Refuse(const char* field, double value, const char* rule) {
  std::ostringstream out;
  out << "detection.sensor_checks." << field << ": " << value << " " << rule;
  throw InputError(out.str());
}

}  // namespace

void Validate(const SensorCheckOptions& options) {
  if (options.frozen_samples < 2) {
    Refuse("frozen_samples", options.frozen_samples, "must be >= 2");
  }
  if (!(std::isfinite(options.gate) && options.gate > 0.0)) {
    Refuse("gate", options.gate, "must be finite and > 0");
  }
  if (options.jump_samples < 1) Refuse("jump_samples", options.jump_samples, "must be >= 1");
  if (!(std::isfinite(options.agree) && options.agree > 0.0)) {
    Refuse("agree", options.agree, "must be finite and > 0");
  }
  if (!(std::isfinite(options.noise_time) && options.noise_time > 0.0)) {
    Refuse("noise_time", options.noise_time, "must be finite and > 0");
  }
  if (!(std::isfinite(options.baseline_time) && options.baseline_time > options.noise_time)) {
    Refuse("baseline_time", options.baseline_time, "must be finite and > noise_time");
  }
  if (!(std::isfinite(options.noisy_ratio) && options.noisy_ratio > 1.0)) {
    Refuse("noisy_ratio", options.noisy_ratio, "must be finite and > 1");
  }
  if (!(std::isfinite(options.fast_time) && options.fast_time > 0.0 &&
        options.fast_time < options.noise_time)) {
    Refuse("fast_time", options.fast_time, "must be finite, > 0 and < noise_time");
  }
  if (!(std::isfinite(options.fast_ratio) && options.fast_ratio > 1.0)) {
    Refuse("fast_ratio", options.fast_ratio, "must be finite and > 1");
  }
}

SensorMonitor::SensorMonitor(const SensorCheckOptions& options, const Vec3& rated_variance)
    : options_(options), rated_(rated_variance) {
  Validate(options);
  sensors_ = {{.id = {.kind = SensorId::Kind::kGnss}, .first = 0, .count = 2, .pending = {}},
              {.id = {.kind = SensorId::Kind::kGyro}, .first = 2, .count = 1, .pending = {}}};
  for (PoseSensor& s : sensors_) s.pending.reserve(static_cast<std::size_t>(options.jump_samples));
  Reset();
}

void SensorMonitor::Reset() {
  channels_.assign(3, Channel{});
  for (PoseSensor& s : sensors_) {
    s.pending.clear();
    s.before.setZero();
    s.before_in_gate = false;
    s.noisy = false;
    s.jump.setZero();
    s.jump_time = -std::numeric_limits<double>::infinity();
  }
  cells_.clear();
  noise_scale_ = Vec3::Ones();
  findings_.clear();
  started_ = false;
}

bool SensorMonitor::Repeats::Frozen(double reading, int samples) {
  repeats = seen && reading == last ? repeats + 1 : 0;
  seen = true;
  last = reading;
  return repeats + 1 >= samples;
}

double SensorMonitor::GateVariance(int i, const Mat3& S) const {
  const Channel& c = channels_[static_cast<std::size_t>(i)];
  return c.level.learned > 0.0 ? std::max(S(i, i), c.level.usual) : S(i, i);
}

namespace {
// An exponential mean that starts as a plain mean (its first samples weigh equally).
void Average(double& mean, long& samples, double value, double dt, double time) {
  ++samples;
  const double weight = std::max(1.0 / static_cast<double>(samples), 1.0 - std::exp(-dt / time));
  mean += weight * (value - mean);
}
}  // namespace

void SensorMonitor::NoiseLevel::Learn(double square, double dt, const SensorCheckOptions& options,
                                      bool noisy) {
  Average(recent, samples, square, dt, options.noise_time);
  // The usual level learns over its first quarter, then only while the recent one is near
  // it: a sensor turning noisy must not teach it.
  if (!noisy && (!Warm(options) || recent <= usual * options.noisy_ratio / 2.0)) {
    Average(usual, usual_samples, square, dt, options.baseline_time);
    learned += dt;
  }
}

bool SensorMonitor::NoiseLevel::Warm(const SensorCheckOptions& options) const {
  return learned >= options.baseline_time / 4.0 && usual > 0.0;
}

bool SensorMonitor::NoiseLevel::Judge(double ratio, double limit, bool noisy) {
  return noisy ? ratio > limit / 2.0 : ratio > limit;
}

void SensorMonitor::LearnNoise(int i, double innovation, double gate_variance, double dt) {
  Channel& c = channels_[static_cast<std::size_t>(i)];
  // Just after a gap (a dropout, a frozen spell) the innovations carry the motion the
  // filter could not follow: no evidence of the noise.
  if (c.since_gap < kAfterGap) {
    c.follows = false;
    return;
  }
  const double bound = options_.gate * gate_variance;
  c.level.Learn(std::min(innovation * innovation, bound), dt, options_,
                sensors_[i < 2 ? 0 : 1].noisy);
  if (c.follows) {
    const double step = innovation - c.previous;
    Average(c.fast, c.fast_samples, std::min(step * step / 2.0, bound), dt, options_.fast_time);
  }
  c.previous = innovation;
  c.follows = true;
}

void SensorMonitor::CheckCell(Cell& cell, double reading, double dt) {
  if (!std::isfinite(reading)) {
    cell.follows = false;
    return;
  }
  if (cell.follows && dt > 0.0) {
    // Half the squared difference of successive readings, bounded as an innovation is: a
    // parting line's fall is one large difference, not noise.
    const double step = reading - cell.previous;
    const double square = step * step / 2.0;
    const double bound = cell.level.Warm(options_) ? options_.gate * cell.level.usual : square;
    cell.level.Learn(std::min(square, bound), dt, options_, cell.noisy);
    if (cell.level.Warm(options_)) {
      cell.noisy =
          NoiseLevel::Judge(cell.level.recent / cell.level.usual, options_.noisy_ratio, cell.noisy);
    }
  }
  cell.previous = reading;
  cell.follows = true;
}

void SensorMonitor::CheckPoseSensor(PoseSensor& sensor, const HypothesisEvidence& predicted,
                                    double dt) {
  const int a = sensor.first, n = sensor.count;
  bool any = false;
  for (int i = a; i < a + n; ++i) any = any || screened_.valid[i];
  if (!any || predicted.dimension == 0) return;
  // The sensor's valid channels: their innovations and the variances they are judged by.
  Eigen::Vector2d e = Eigen::Vector2d::Zero();
  Eigen::Vector2d variance = Eigen::Vector2d::Ones();
  for (int r = 0; r < n; ++r) {
    if (!screened_.valid[a + r]) continue;
    e(r) = predicted.innovation(a + r);
    variance(r) = GateVariance(a + r, predicted.covariance);
  }
  const auto nis = [&](const Eigen::Vector2d& v) {
    return v.cwiseAbs2().cwiseQuotient(variance).sum();
  };
  const auto learn = [&](const Eigen::Vector2d& v) {
    for (int r = 0; r < n; ++r) {
      if (screened_.valid[a + r]) {
        LearnNoise(a + r, v(r), variance(r), dt);
      }
    }
  };
  if (nis(e) <= options_.gate) {
    for (const Eigen::Vector2d& outlier : sensor.pending) learn(outlier);
    sensor.pending.clear();
    learn(e);
    sensor.before = e;
    sensor.before_in_gate = true;
    return;
  }
  // Withheld, until a run of them is long enough to judge.
  for (int i = a; i < a + n; ++i) screened_.valid[i] = false;
  sensor.pending.push_back(e);
  if (static_cast<int>(sensor.pending.size()) < options_.jump_samples) return;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : sensor.pending) mean += p;
  mean /= static_cast<double>(sensor.pending.size());
  // A step: from a sample the filter predicted well, by more than the gate, to readings
  // that then stay put (each near their mean, and no trend from the first to the last).
  bool settled = sensor.before_in_gate;  // ... and not just after a gap
  for (int r = 0; r < n; ++r) {
    settled = settled && channels_[static_cast<std::size_t>(a + r)].since_gap >=
                             kAfterGap + static_cast<int>(sensor.pending.size());
  }
  bool agree = settled && nis(sensor.pending.front() - sensor.before) > options_.gate &&
               nis(sensor.pending.back() - sensor.pending.front()) <= options_.agree;
  for (const Eigen::Vector2d& p : sensor.pending) agree = agree && nis(p - mean) <= options_.agree;
  if (agree) {
    for (int r = 0; r < n; ++r) channels_[static_cast<std::size_t>(a + r)].offset += mean(r);
    sensor.jump = mean;
    sensor.jump_time = t_;
    sensor.pending.clear();
    sensor.before = Eigen::Vector2d::Zero();
    sensor.before_in_gate = false;
    return;
  }
  // As many withheld samples as a jump takes, and not a jump: the vessel moves in a way the
  // filter did not predict (a line parting, a gust), or the sensor has turned noisy. The
  // filter must see it. A motion changes little from one sample to the next; if these
  // samples scatter from one to the next by more than half the gate, they are the noise's
  // first samples and are learned at once, so the noise is named before they move the
  // observers. Otherwise their innovations go unlearned.
  const std::size_t m = sensor.pending.size();
  double scatter = 0.0;  // the sum of half the successive differences' normalised squares
  for (std::size_t j = 1; j < m; ++j) {
    scatter += nis(sensor.pending[j] - sensor.pending[j - 1]) / 2.0;
  }
  const bool scatters = m > 1 && scatter > static_cast<double>(m - 1) * options_.gate / 2.0;
  for (int i = a; i < a + n; ++i) {
    screened_.valid[i] = observation_valid_[i];
    if (!scatters) channels_[static_cast<std::size_t>(i)].follows = false;
  }
  if (scatters) {
    for (const Eigen::Vector2d& p : sensor.pending) learn(p);
  }
  sensor.pending.clear();
  sensor.before = e;
  sensor.before_in_gate = false;
}

const Observation& SensorMonitor::Screen(const Observation& observation,
                                         const HypothesisEkf& intact) {
  screened_ = observation;
  const double dt = started_ ? observation.t - t_ : 0.0;
  t_ = observation.t;
  started_ = true;
  findings_.clear();
  // Frozen channels, then the offsets of earlier jumps.
  bool frozen[3] = {false, false, false};
  for (int i = 0; i < 3; ++i) {
    Channel& c = channels_[static_cast<std::size_t>(i)];
    c.missing = observation.valid[i] ? 0 : c.missing + 1;
    c.since_gap = observation.valid[i] ? c.since_gap + 1 : 0;
    if (!observation.valid[i]) continue;
    frozen[i] = c.readings.Frozen(observation.pose(i), options_.frozen_samples);
    if (frozen[i]) {
      screened_.valid[i] = false;
      c.since_gap = 0;
    }
    screened_.pose(i) -= c.offset;
  }
  observation_valid_ = screened_.valid;
  if (observation.tensions) {
    const VecX& readings = *observation.tensions;
    cells_.resize(static_cast<std::size_t>(readings.size()));
    for (Eigen::Index k = 0; k < readings.size(); ++k) {
      Cell& cell = cells_[static_cast<std::size_t>(k)];
      const SensorId id{.kind = SensorId::Kind::kCell, .line = int(k) + 1};
      if (cell.readings.Frozen(readings(k), options_.frozen_samples)) {
        (*screened_.tensions)(k) = kNaN;
        findings_.push_back({.sensor = id, .symptom = SensorSymptom::kFrozen});
      }
      CheckCell(cell, (*screened_.tensions)(k), dt);
      if (cell.noisy) findings_.push_back({.sensor = id, .symptom = SensorSymptom::kNoisy});
    }
  }
  // The intact model's prediction of this sample.
  if (intact.initialised() && dt > 0.0) {
    if (probe_) {
      *probe_ = intact;
    } else {
      probe_.emplace(intact);
    }
    const HypothesisEvidence predicted = probe_->Update(screened_);
    for (PoseSensor& s : sensors_) CheckPoseSensor(s, predicted, dt);
  }
  // The verdict on each pose sensor, and the weight the observers give it.
  for (PoseSensor& s : sensors_) {
    bool is_frozen = false, jumped = false, silent = true;
    double ratio = 1.0, fast_ratio = 1.0;  // the recent and fast levels over usual
    for (int i = s.first; i < s.first + s.count; ++i) {
      const Channel& c = channels_[static_cast<std::size_t>(i)];
      is_frozen = is_frozen || frozen[i];
      silent = silent && c.missing >= options_.frozen_samples;
      if (c.level.Warm(options_)) {
        ratio = std::max(ratio, c.level.recent / c.level.usual);
        fast_ratio = std::max(fast_ratio, c.fast / c.level.usual);
      }
    }
    // Noisy by either level; trusted again once both are below half their ratios.
    const bool was_noisy = s.noisy;
    s.noisy = NoiseLevel::Judge(ratio, options_.noisy_ratio, s.noisy) ||
              NoiseLevel::Judge(fast_ratio, options_.fast_ratio, s.noisy);
    if (s.noisy && !was_noisy && t_ - s.jump_time <= 2.0 * options_.fast_time) {
      // A jump judged in the seconds before the noise was: the jump test assumes the noise
      // the gate was set for, and its agreeing samples were the noise's first ones. Its
      // re-anchoring is taken back.
      for (int r = 0; r < s.count; ++r) {
        channels_[static_cast<std::size_t>(s.first + r)].offset -= s.jump(r);
      }
      s.jump_time = -std::numeric_limits<double>::infinity();
    }
    for (int i = s.first; i < s.first + s.count; ++i) {
      const Channel& c = channels_[static_cast<std::size_t>(i)];
      jumped = jumped || c.offset * c.offset > options_.gate * std::max(rated_(i), c.level.usual);
      const double excess = std::max(c.level.recent, c.fast) - c.level.usual;
      noise_scale_(i) = s.noisy ? 1.0 + std::max(0.0, excess) / rated_(i) : 1.0;
    }
    if (is_frozen) findings_.push_back({.sensor = s.id, .symptom = SensorSymptom::kFrozen});
    if (silent) findings_.push_back({.sensor = s.id, .symptom = SensorSymptom::kSilent});
    if (jumped) findings_.push_back({.sensor = s.id, .symptom = SensorSymptom::kJump});
    if (s.noisy) findings_.push_back({.sensor = s.id, .symptom = SensorSymptom::kNoisy});
  }
  return screened_;
}

}  // namespace moorsim::detectors
