#include "vessel/sensors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "vessel/checks.h"

namespace moorsim::vessel {
namespace {

[[noreturn]] void ThrowBadValue(std::string_view key, double value, std::string_view constraint) {
  internal::ThrowBadValue(key, value, "", constraint);
}

std::string Key(std::string_view path, std::string_view field) {
  return std::string(path) + "." + std::string(field);
}

void RequireFinite(std::string_view key, double value) {
  if (!std::isfinite(value)) ThrowBadValue(key, value, "must be finite");
}

void RequirePositive(std::string_view key, double value) {
  RequireFinite(key, value);
  if (value <= 0.0) ThrowBadValue(key, value, "must be > 0");
}

void RequireNonNegative(std::string_view key, double value) {
  RequireFinite(key, value);
  if (value < 0.0) ThrowBadValue(key, value, "must be >= 0");
}

void RequireProbability(std::string_view key, double value) {
  // Written so NaN fails too.
  if (!(value >= 0.0 && value <= 1.0)) ThrowBadValue(key, value, "must be in [0, 1]");
}

const PoseSensorSpec& Validated(const PoseSensorSpec& spec) {
  ValidatePoseSensorSpec(spec);
  return spec;
}

const ChannelNoise& ValidatedTensionNoise(int lines, const ChannelNoise& noise) {
  if (lines < 1) {
    throw InputError("sensors.tension_cells.lines: " + std::to_string(lines) + " must be >= 1");
  }
  ValidateChannelNoise(noise, "sensors.tension_cells.noise");
  return noise;
}

void RequireNotSampled(std::int64_t k, std::int64_t next_index, std::string_view instrument,
                       double t) {
  if (k < next_index) {
    throw std::logic_error(std::string(instrument) + ": instant t = " + FormatNumber(t) +
                           " s was already sampled or lies before the last sample");
  }
}

}  // namespace

PoseSensorSpec SeedPoseSensors() { return PoseSensorSpec{}; }

void ValidateChannelNoise(const ChannelNoise& noise, std::string_view key_path) {
  RequireNonNegative(Key(key_path, "std_dev"), noise.std_dev);
  RequireNonNegative(Key(key_path, "bias_walk"), noise.bias_walk);
  RequireNonNegative(Key(key_path, "bias_time_constant_s"), noise.bias_time_constant);
  RequireFinite(Key(key_path, "initial_bias"), noise.initial_bias);
  RequireProbability(Key(key_path, "outlier_probability"), noise.outlier_probability);
  RequireNonNegative(Key(key_path, "outlier_std_dev"), noise.outlier_std_dev);
}

void ValidatePoseSensorSpec(const PoseSensorSpec& spec, std::string_view key_path) {
  const std::string gnss = Key(key_path, "gnss");
  const std::string gyro = Key(key_path, "gyro");
  RequirePositive(Key(gnss, "rate_hz"), spec.gnss_rate);
  RequirePositive(Key(gyro, "rate_hz"), spec.gyro_rate);
  ValidateChannelNoise(spec.north, Key(gnss, "north"));
  ValidateChannelNoise(spec.east, Key(gnss, "east"));
  ValidateChannelNoise(spec.heading, Key(gyro, "heading"));
  RequireProbability(Key(gnss, "dropout_probability"), spec.gnss_dropout_probability);
  RequireProbability(Key(gyro, "dropout_probability"), spec.gyro_dropout_probability);
  RequireNonNegative(Key(gnss, "dropout_mean_duration_s"), spec.gnss_dropout_mean_duration);
}

// --- internal::ChannelError ----------------------------------------------------------

namespace internal {

ChannelError::ChannelError(const ChannelNoise& noise, double sample_interval,
                           std::uint64_t run_seed, std::string_view prefix)
    : noise_(noise),
      bias_(noise.initial_bias),
      noise_stream_(RandomStream::Derive(run_seed, std::string(prefix) + ".noise")),
      bias_stream_(RandomStream::Derive(run_seed, std::string(prefix) + ".bias")),
      outlier_stream_(RandomStream::Derive(run_seed, std::string(prefix) + ".outlier")) {
  const double q = noise.bias_walk;
  const double tau = noise.bias_time_constant;
  if (tau > 0.0) {
    // Exact discretisation of db = -b / tau dt + q dW over dt: the innovation's variance
    // is the integral of q^2 exp(-2 s / tau) over [0, dt] = q^2 tau / 2 (1 - phi^2).
    // expm1 keeps it accurate when dt << tau.
    bias_decay_ = std::exp(-sample_interval / tau);
    bias_step_std_ = q * std::sqrt(0.5 * tau * -std::expm1(-2.0 * sample_interval / tau));
  } else {
    bias_decay_ = 1.0;
    bias_step_std_ = q * std::sqrt(sample_interval);
  }
}

double ChannelError::Next(double white_factor) {
  // Every stream gives its fixed share whatever the configuration (file comment).
  const double white = white_factor * noise_.std_dev * noise_stream_.Normal();
  const double outlier_draw = outlier_stream_.Uniform();
  const double outlier_size = noise_.outlier_std_dev * outlier_stream_.Normal();
  double error = bias_ + white;
  if (outlier_draw < noise_.outlier_probability) error += outlier_size;
  bias_ = bias_decay_ * bias_ + bias_step_std_ * bias_stream_.Normal();
  return error;
}

namespace {

bool Active(const SensorFault& fault, double t) { return t >= fault.from && t < fault.until; }

}  // namespace

double ChannelFaults::NoiseFactor(double t) const {
  double factor = 1.0;
  for (const Held& h : faults_) {
    if (h.fault.mode == SensorFault::Mode::kDegraded && Active(h.fault, t)) factor *= h.fault.size;
  }
  return factor;
}

std::optional<double> ChannelFaults::Reading(double t, double truth, double error,
                                             bool dead_reads_noise) {
  using Mode = SensorFault::Mode;
  double gain = 1.0;
  for (const Held& h : faults_) {
    if (h.fault.mode == Mode::kGain && Active(h.fault, t)) gain *= h.fault.size;
  }
  double reading = gain * truth + error;
  for (Held& h : faults_) {
    const SensorFault& f = h.fault;
    const bool active = Active(f, t);
    switch (f.mode) {
      case Mode::kStep:
        if (active) reading += f.size;
        break;
      case Mode::kDrift:
        if (active) reading += f.size * (t - f.from);
        break;
      case Mode::kDead:
        if (active) {
          if (!dead_reads_noise) return std::nullopt;
          reading -= gain * truth;
        }
        break;
      case Mode::kStuck:
        // The last reading before the fault (the first one if there was none before).
        if (t < f.from || std::isnan(h.value)) h.value = reading;
        if (active) reading = h.value;
        break;
      case Mode::kDegraded:
      case Mode::kGain:
        break;  // in the error's draw and the gain above
    }
  }
  return reading;
}

}  // namespace internal

std::string_view SensorFaultSizeKey(SensorFault::Mode mode) {
  switch (mode) {
    case SensorFault::Mode::kStep:
      return "offset";
    case SensorFault::Mode::kDrift:
      return "rate";
    case SensorFault::Mode::kDegraded:
      return "factor";
    case SensorFault::Mode::kGain:
      return "gain";
    case SensorFault::Mode::kStuck:
    case SensorFault::Mode::kDead:
      break;
  }
  return "size";
}

void ValidateSensorFault(const SensorFault& fault, std::string_view key_path) {
  RequireNonNegative(Key(key_path, "time"), fault.from);
  if (!(fault.until > fault.from)) {
    ThrowBadValue(Key(key_path, "end"), fault.until, "must be after the fault's time");
  }
  const std::string size = Key(key_path, SensorFaultSizeKey(fault.mode));
  RequireFinite(size, fault.size);
  if (fault.mode == SensorFault::Mode::kDegraded || fault.mode == SensorFault::Mode::kGain) {
    RequirePositive(size, fault.size);
  }
}

// --- PoseSensors ---------------------------------------------------------------------

PoseSensors::PoseSensors(const PoseSensorSpec& spec, std::uint64_t run_seed,
                         std::string_view gnss_name, std::string_view gyro_name)
    : spec_(Validated(spec)),
      gnss_clock_(spec.gnss_rate, "sensors.gnss.rate_hz"),
      gyro_clock_(spec.gyro_rate, "sensors.gyro.rate_hz"),
      north_(spec.north, 1.0 / spec.gnss_rate, run_seed, std::string(gnss_name) + ".north"),
      east_(spec.east, 1.0 / spec.gnss_rate, run_seed, std::string(gnss_name) + ".east"),
      heading_(spec.heading, 1.0 / spec.gyro_rate, run_seed, std::string(gyro_name) + ".heading"),
      gnss_dropout_stream_(RandomStream::Derive(run_seed, std::string(gnss_name) + ".dropout")),
      gnss_dropout_duration_stream_(
          RandomStream::Derive(run_seed, std::string(gnss_name) + ".dropout.duration")),
      gyro_dropout_stream_(RandomStream::Derive(run_seed, std::string(gyro_name) + ".dropout")) {}

double PoseSensors::NextSampleTime(double t) const {
  return std::min(gnss_clock_.NextSampleTime(t), gyro_clock_.NextSampleTime(t));
}

PoseSensors::GnssDraw PoseSensors::DrawGnss(std::int64_t k) {
  GnssDraw draw;
  const double t_k = gnss_clock_.Instant(k);
  draw.north = north_.Next(faults_[0].NoiseFactor(t_k));
  draw.east = east_.Next(faults_[1].NoiseFactor(t_k));
  const double onset_draw = gnss_dropout_stream_.Uniform();
  if (t_k < gnss_dropout_end_) {
    draw.lost = true;  // inside a dropout that started earlier
  } else if (onset_draw < spec_.gnss_dropout_probability) {
    draw.lost = true;
    if (spec_.gnss_dropout_mean_duration > 0.0) {
      // Exponential by inversion; 1 - U is in (0, 1], so the log is finite.
      const double duration =
          -spec_.gnss_dropout_mean_duration * std::log1p(-gnss_dropout_duration_stream_.Uniform());
      gnss_dropout_end_ = t_k + duration;
    }
  }
  return draw;
}

PoseSensors::GyroDraw PoseSensors::DrawGyro(std::int64_t k) {
  GyroDraw draw;
  draw.heading = heading_.Next(faults_[2].NoiseFactor(gyro_clock_.Instant(k)));
  draw.lost = gyro_dropout_stream_.Uniform() < spec_.gyro_dropout_probability;
  return draw;
}

PoseMeasurement PoseSensors::Sample(double t, const Vec3& true_pose) {
  PoseMeasurement measurement;
  measurement.time = t;
  measurement.value.setConstant(kNaN);
  measurement.valid = {false, false, false};

  const std::optional<std::int64_t> gnss_k = gnss_clock_.Index(t);
  const std::optional<std::int64_t> gyro_k = gyro_clock_.Index(t);
  // Check both before drawing, so a refused call leaves the sensors as they were.
  if (gnss_k) RequireNotSampled(*gnss_k, gnss_next_index_, "GNSS", t);
  if (gyro_k) RequireNotSampled(*gyro_k, gyro_next_index_, "gyro", t);

  if (gnss_k) {
    while (gnss_next_index_ < *gnss_k) DrawGnss(gnss_next_index_++);
    const GnssDraw draw = DrawGnss(gnss_next_index_++);
    if (!draw.lost) {
      const double errors[2] = {draw.north, draw.east};
      for (int i = 0; i < 2; ++i) {
        if (const std::optional<double> reading = faults_[i].Reading(t, true_pose(i), errors[i],
                                                                     /*dead_reads_noise=*/false)) {
          measurement.value(i) = *reading;
          measurement.valid[i] = true;
        }
      }
    }
  }
  if (gyro_k) {
    while (gyro_next_index_ < *gyro_k) {
      DrawGyro(gyro_next_index_);
      ++gyro_next_index_;
    }
    const GyroDraw draw = DrawGyro(gyro_next_index_);
    ++gyro_next_index_;
    if (!draw.lost) {
      if (const std::optional<double> reading =
              faults_[2].Reading(t, true_pose.z(), draw.heading, /*dead_reads_noise=*/false)) {
        measurement.value.z() = WrapAngle(*reading);
        measurement.valid[2] = true;
      }
    }
  }
  return measurement;
}

void PoseSensors::AddFault(PoseChannel channel, const SensorFault& fault,
                           std::string_view key_path) {
  ValidateSensorFault(fault, key_path);
  faults_[static_cast<std::size_t>(channel)].Add(fault);
}

// --- TensionCells --------------------------------------------------------------------

TensionCells::TensionCells(int lines, const ChannelNoise& noise, double rate,
                           std::uint64_t run_seed)
    : clock_(rate, "sensors.tension_cells.rate_hz") {
  const ChannelNoise& checked = ValidatedTensionNoise(lines, noise);
  cells_.reserve(static_cast<std::size_t>(lines));
  for (int k = 1; k <= lines; ++k) {
    cells_.emplace_back(checked, 1.0 / rate, run_seed, "tension_cell." + std::to_string(k));
  }
  faults_.resize(cells_.size());
}

std::vector<double> TensionCells::Sample(double t, std::span<const double> true_tensions) {
  if (true_tensions.size() != cells_.size()) {
    throw std::invalid_argument("TensionCells::Sample: " + std::to_string(true_tensions.size()) +
                                " tensions for " + std::to_string(cells_.size()) + " lines");
  }
  std::vector<double> measured(cells_.size(), kNaN);
  const std::optional<std::int64_t> k = clock_.Index(t);
  if (!k) return measured;
  RequireNotSampled(*k, next_index_, "tension cells", t);
  for (; next_index_ < *k; ++next_index_) {
    for (internal::ChannelError& cell : cells_) cell.Next();
  }
  for (std::size_t i = 0; i < cells_.size(); ++i) {
    const double error = cells_[i].Next(faults_[i].NoiseFactor(t));
    measured[i] = *faults_[i].Reading(t, true_tensions[i], error, /*dead_reads_noise=*/true);
  }
  ++next_index_;
  return measured;
}

void TensionCells::AddFault(const CellFault& fault, std::string_view key_path) {
  if (fault.line < 0 || fault.line >= lines()) {
    throw InputError(Key(key_path, "line") + ": " + std::to_string(fault.line + 1) +
                     " is not a line of the mooring (1.." + std::to_string(lines()) + ")");
  }
  ValidateSensorFault(fault.fault, key_path);
  faults_[static_cast<std::size_t>(fault.line)].Add(fault.fault);
}

}  // namespace moorsim::vessel
