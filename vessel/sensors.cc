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
    throw std::logic_error(std::string(instrument) + ": instant t = " + internal::FormatValue(t) +
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

double ChannelError::Next() {
  // Every stream gives its fixed share whatever the configuration (file comment).
  const double white = noise_.std_dev * noise_stream_.Normal();
  const double outlier_draw = outlier_stream_.Uniform();
  const double outlier_size = noise_.outlier_std_dev * outlier_stream_.Normal();
  double error = bias_ + white;
  if (outlier_draw < noise_.outlier_probability) error += outlier_size;
  bias_ = bias_decay_ * bias_ + bias_step_std_ * bias_stream_.Normal();
  return error;
}

}  // namespace internal

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
  draw.north = north_.Next();
  draw.east = east_.Next();
  const double onset_draw = gnss_dropout_stream_.Uniform();
  const double t_k = gnss_clock_.Instant(k);
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

PoseSensors::GyroDraw PoseSensors::DrawGyro() {
  GyroDraw draw;
  draw.heading = heading_.Next();
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
      measurement.value.x() = true_pose.x() + draw.north;
      measurement.value.y() = true_pose.y() + draw.east;
      measurement.valid[0] = measurement.valid[1] = true;
    }
  }
  if (gyro_k) {
    while (gyro_next_index_ < *gyro_k) {
      DrawGyro();
      ++gyro_next_index_;
    }
    const GyroDraw draw = DrawGyro();
    ++gyro_next_index_;
    if (!draw.lost) {
      measurement.value.z() = WrapAngle(true_pose.z() + draw.heading);
      measurement.valid[2] = true;
    }
  }
  return measurement;
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
    measured[i] = true_tensions[i] + cells_[i].Next();
    Fault& fault = faults_[i];
    if (fault.kind == Fault::Kind::kStuck) {
      if (t < fault.from || std::isnan(fault.held)) fault.held = measured[i];
      if (t >= fault.from) measured[i] = fault.held;
    } else if (fault.kind == Fault::Kind::kDrift && t >= fault.from) {
      measured[i] += fault.rate * (t - fault.from);
    } else if (fault.kind == Fault::Kind::kDead && t >= fault.from) {
      measured[i] -= true_tensions[i];
    }
  }
  ++next_index_;
  return measured;
}

void TensionCells::SetStuck(int line, double from) {
  faults_.at(static_cast<std::size_t>(line)) = {Fault::Kind::kStuck, from, 0.0,
                                                std::numeric_limits<double>::quiet_NaN()};
}

void TensionCells::SetDead(int line, double from) {
  faults_.at(static_cast<std::size_t>(line)) = {Fault::Kind::kDead, from, 0.0,
                                                std::numeric_limits<double>::quiet_NaN()};
}

void TensionCells::SetDrift(int line, double from, double rate) {
  faults_.at(static_cast<std::size_t>(line)) = {Fault::Kind::kDrift, from, rate,
                                                std::numeric_limits<double>::quiet_NaN()};
}

void TensionCells::SetFault(const CellFault& fault) {
  switch (fault.mode) {
    case CellFault::Mode::kStuck:
      SetStuck(fault.line, fault.from);
      break;
    case CellFault::Mode::kDrift:
      SetDrift(fault.line, fault.from, fault.rate);
      break;
    case CellFault::Mode::kDead:
      SetDead(fault.line, fault.from);
      break;
  }
}

}  // namespace moorsim::vessel
