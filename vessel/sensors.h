// Position-reference sensors (GNSS north/east, gyro heading) and fairlead tension cells:
// the noisy, sampled, sometimes missing view of the plant that the controller and the
// detectors get.
//
// Error model of one channel (the usual navigation-sensor model: white noise plus a
// Gauss-Markov or random-walk bias, Farrell, "Aided Navigation", 2008, sections 4.9 and
// 4.10; Gelb, "Applied Optimal Estimation", 1974, table 3.1-1), at sample k (time t_k):
//
//   y_k = truth(t_k) + b_k + sigma w_k + o_k
//   b_0 = initial_bias
//   b_{k+1} = b_k + q sqrt(dt) v_k                                 (tau = 0: random walk)
//   b_{k+1} = phi b_k + q sqrt(tau / 2 (1 - phi^2)) v_k,  phi = exp(-dt / tau)   (tau > 0)
//   o_k = s z_k with probability p_outlier, else 0
//
// w_k, v_k, z_k standard normal, dt = 1 / rate. The tau > 0 line is the exact
// discretisation of the first-order Gauss-Markov process db = -b / tau dt + q dW, so the
// bias statistics do not depend on the sample rate: its variance tends to q^2 tau / 2 and
// its correlation between samples is exp(-|t_i - t_j| / tau). With tau = 0 the variance
// grows as q^2 t.
//
// Independence by construction. The TAPM thesis drew every DOF's noise from one seed, so
// x, y and psi carried the same numbers and its detection results were void. Here every
// noise source has its own stream, RandomStream::Derive(run_seed, name) with the names
//
//   <gnss>.north.noise  <gnss>.north.bias  <gnss>.north.outlier   (and .east.)
//   <gnss>.dropout  <gnss>.dropout.duration
//   <gyro>.heading.noise  <gyro>.heading.bias  <gyro>.heading.outlier  <gyro>.dropout
//   tension_cell.<k>.noise  tension_cell.<k>.bias  tension_cell.<k>.outlier  (k 1-based)
//
// (<gnss> and <gyro> are the instrument names, "gnss" and "gyro" by default), and every
// sample instant takes a fixed set of draws from each stream whatever the configuration
// and whether the sample is delivered: one normal from .noise and one from .bias, one
// uniform then one normal from .outlier, one uniform from .dropout (.dropout.duration
// gives one uniform per GNSS dropout that starts). Hence turning outliers, biases or
// dropouts on or off, or changing their sizes, never changes the white noise of a
// delivered sample, and a lost sample is simply not delivered.
//
// Sample instants are t_k = k / rate (k = 0, 1, 2, ...), computed from k each time, never
// by adding up 1 / rate, so a 3-hour run at 10 Hz ends on 10800 s exactly. A time t is at
// instant k if |t - k / rate| <= 1e-9 / rate + 4 eps |t| (a billionth of a sample
// interval, or a few units in the last place of t). That absorbs the last-bit difference
// between k1 / rate1 and k2 / rate2 of two instruments whose instants coincide, so such
// an instant gives one measurement with both.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/choice.h"
#include "core/random.h"
#include "core/sample_clock.h"
#include "core/types.h"

namespace moorsim::vessel {

/// Error model of one measured quantity, in that quantity's unit (m for GNSS, rad for the
/// gyro, N for a tension cell; written "u" below). See the file comment for the equations.
struct ChannelNoise {
  double std_dev = 0.0;              ///< sigma, white-noise standard deviation [u], >= 0
  double bias_walk = 0.0;            ///< q, bias driving intensity [u/sqrt(s)], >= 0
  double bias_time_constant = 0.0;   ///< tau [s], >= 0; 0 = random walk, > 0 = Gauss-Markov
  double initial_bias = 0.0;         ///< b_0 at t = 0 [u]
  double outlier_probability = 0.0;  ///< p_outlier, per sample, in [0, 1]
  double outlier_std_dev = 0.0;      ///< s, standard deviation of an outlier [u], >= 0
};

/// The seed case's measurement variance (docs/design.md section 9), 0.005 m^2 (GNSS) and
/// 0.005 rad^2 (gyro) per DOF (TAPM thesis appendix A, the R of its observers):
/// sigma = sqrt(0.005) = 0.0707 m and 0.0707 rad (4.05 deg, large for a real gyrocompass; it is
/// the thesis's number).
inline constexpr double kSeedPoseStdDev = 0.070710678118654752;

/// GNSS (north, east) and gyro (heading) as two instruments with their own rates and
/// dropouts. The defaults are the seed case's sensors (see SeedPoseSensors()).
struct PoseSensorSpec {
  double gnss_rate = 1.0;                            ///< GNSS sample rate [Hz], > 0
  double gyro_rate = 1.0;                            ///< gyro sample rate [Hz], > 0
  ChannelNoise north{.std_dev = kSeedPoseStdDev};    ///< GNSS x (north) [m]
  ChannelNoise east{.std_dev = kSeedPoseStdDev};     ///< GNSS y (east) [m]
  ChannelNoise heading{.std_dev = kSeedPoseStdDev};  ///< gyro psi [rad]
  /// Probability that a GNSS dropout starts at a sample, in [0, 1]. A dropout loses north
  /// and east together: the receiver is one instrument.
  double gnss_dropout_probability = 0.0;
  /// Probability that a gyro sample is lost, in [0, 1]; gyro dropouts last one sample.
  double gyro_dropout_probability = 0.0;
  /// Mean duration of a GNSS dropout [s], >= 0. 0: a dropout loses the one sample where
  /// it starts. > 0: a dropout starting at t_k lasts an exponentially distributed time D
  /// with this mean and loses every GNSS sample in [t_k, t_k + D) (always t_k itself); no
  /// new dropout can start inside one. Being memoryless, the number of samples lost is
  /// geometric: each further sample is still lost with probability
  /// r = exp(-1 / (rate mean)), so a dropout loses L = 1 / (1 - r) samples on average
  /// and the long-run lost fraction is L / (L + (1 - p) / p), p the start probability. (A
  /// new dropout may start at the first sample after one ends; the two then look like one
  /// run of lost samples, whose length is geometric with continuation r + (1 - r) p.)
  /// This is the two-state (Gilbert) model of a receiver that loses its fix behind an
  /// obstruction and takes a while to regain it. The onset is drawn from "<gnss>.dropout"
  /// at every GNSS instant, the duration from "<gnss>.dropout.duration" once per dropout.
  double gnss_dropout_mean_duration = 0.0;
};

/// The seed case's sensors: GNSS and gyro at 1 Hz (the thesis samples at 1 Hz), white noise of
/// sigma = sqrt(0.005) on each DOF, no bias, outliers or dropouts. Equal to
/// PoseSensorSpec{}; the name says where the numbers come from.
PoseSensorSpec SeedPoseSensors();

/// Throws moorsim::InputError naming the key and value if a field is out of range or not
/// finite, e.g. "sensors.gnss.north.std_dev: -1 must be >= 0". `key_path` is the key of
/// this struct ("sensors.gnss.north").
void ValidateChannelNoise(const ChannelNoise& noise, std::string_view key_path);

/// ValidateChannelNoise for each channel, plus the rates and dropout fields, with keys
/// under `key_path`: "<key_path>.gnss.rate_hz", "<key_path>.gyro.heading.std_dev",
/// "<key_path>.gnss.dropout_probability", "<key_path>.gnss.dropout_mean_duration_s", ...
void ValidatePoseSensorSpec(const PoseSensorSpec& spec, std::string_view key_path = "sensors");

/// The instants k / rate of a sampled instrument (core/sample_clock.h).
using SensorClock = SampleClock;

/// A fault of one sensor channel from `from` [s] until `until` [s] (infinity: to the end
/// of the run). In the channel's unit u (m, rad or N):
struct SensorFault {
  enum class Mode {
    kStep,      ///< the reading jumps by `size` [u] and stays off by it
    kStuck,     ///< a frozen output: the reading repeats its last value before `from`
    kDegraded,  ///< the white noise is `size` (> 0) times larger
    kDrift,     ///< the reading runs off by `size` [u/s] x (t - from)
    kDead,      ///< GNSS, gyro: no reading at all; a load cell reads its noise about zero
    kGain,      ///< the reading is `size` x the true value, plus the error
  };
  Mode mode = Mode::kStep;
  double from = 0.0;
  double until = std::numeric_limits<double>::infinity();
  double size = 0.0;
};

inline constexpr std::string_view kSensorFaultModeNames[] = {"step",  "stuck", "degraded",
                                                             "drift", "dead",  "gain"};
constexpr ChoiceInfo ChoicesOf(SensorFault::Mode) {
  return {"sensor fault", kSensorFaultModeNames};
}

/// The scenario's name of a mode's size: "offset" (step), "rate" (drift), "factor"
/// (degraded), "gain" (gain); "size" for the modes without one.
std::string_view SensorFaultSizeKey(SensorFault::Mode mode);

/// Throws moorsim::InputError naming the key under `key_path` ("time", "end" or the size's
/// key) for a fault whose times or size are out of range: from finite and >= 0, until >
/// from, a finite size, > 0 for kDegraded and kGain.
void ValidateSensorFault(const SensorFault& fault, std::string_view key_path);

namespace internal {

/// One channel's error b_k + sigma w_k + o_k at successive samples (file comment), with
/// its three streams "<prefix>.noise", "<prefix>.bias" and "<prefix>.outlier".
class ChannelError {
 public:
  /// `noise` must have passed ValidateChannelNoise; sample_interval dt [s] > 0.
  ChannelError(const ChannelNoise& noise, double sample_interval, std::uint64_t run_seed,
               std::string_view prefix);
  /// The error at the next sample, its white noise `white_factor` times its size, after
  /// which the bias moves on one interval.
  double Next(double white_factor = 1.0);

 private:
  ChannelNoise noise_;
  double bias_ = 0.0;
  double bias_decay_ = 1.0;     // phi (1 for a random walk)
  double bias_step_std_ = 0.0;  // standard deviation of the bias's innovation per interval
  RandomStream noise_stream_;
  RandomStream bias_stream_;
  RandomStream outlier_stream_;
};

/// A channel's faults, acting in the order they were added.
class ChannelFaults {
 public:
  void Add(const SensorFault& fault) { faults_.push_back({fault}); }
  /// The white noise's factor at t: the product of the degraded periods' sizes (1 outside).
  double NoiseFactor(double t) const;
  /// The reading at t of a channel whose true value is `truth` and whose error (drawn with
  /// NoiseFactor(t)) is `error`; nullopt for a dead channel that gives no reading
  /// (`dead_reads_noise` false), else one that reads its error about zero.
  std::optional<double> Reading(double t, double truth, double error, bool dead_reads_noise);

 private:
  struct Held {
    SensorFault fault;
    double value = kNaN;  // a stuck channel's reading
  };
  std::vector<Held> faults_;
};

}  // namespace internal

/// A channel of the pose sensors.
enum class PoseChannel { kNorth, kEast, kHeading };

/// One sample of the pose sensors. A channel that was not sampled at `time` (its
/// instrument is not due then) or whose sample was lost to a dropout has valid = false and
/// value NaN: a consumer that ignores `valid` gets NaNs, not a stale or invented number.
struct PoseMeasurement {
  double time = 0.0;  ///< [s], the t passed to Sample
  /// x north [m], y east [m], psi [rad] wrapped to (-pi, pi] (NED).
  Vec3 value = Vec3::Zero();
  std::array<bool, 3> valid{};  ///< x, y, psi
};

/// GNSS position and gyro heading with the errors of PoseSensorSpec.
///
/// Usage: from t = 0, call Sample at every instant NextSampleTime gives (and at 0). Each
/// instrument keeps its own sample index; an instrument's instant that the caller skips
/// is drawn and discarded, so the value at an instant does not depend on which earlier
/// instants were sampled (catching up costs one set of draws per skipped instant).
class PoseSensors {
 public:
  /// Validates `spec` (throws moorsim::InputError, keys under "sensors"); the instrument
  /// names prefix the stream names (file comment).
  PoseSensors(const PoseSensorSpec& spec, std::uint64_t run_seed,
              std::string_view gnss_name = "gnss", std::string_view gyro_name = "gyro");

  /// True if the GNSS or the gyro samples at t.
  bool Due(double t) const { return gnss_clock_.Due(t) || gyro_clock_.Due(t); }
  /// The first instant of either instrument strictly after t.
  double NextSampleTime(double t) const;

  /// The measurement at t of the true pose (x [m], y [m], psi [rad], NED; psi need not be
  /// wrapped). Channels whose instrument is not due at t are invalid; if neither is due
  /// the result is all invalid and no random numbers are drawn. Throws std::logic_error
  /// if an instrument due at t has already sampled at or after t (each instant is
  /// measured once: measuring it again would need the same numbers twice).
  PoseMeasurement Sample(double t, const Vec3& true_pose);

  /// A fault of one channel (ValidateSensorFault; keys under `key_path`). A GNSS fault of
  /// both channels is one fault of each.
  void AddFault(PoseChannel channel, const SensorFault& fault,
                std::string_view key_path = "sensors.faults");

  const PoseSensorSpec& spec() const { return spec_; }
  const SensorClock& gnss_clock() const { return gnss_clock_; }
  const SensorClock& gyro_clock() const { return gyro_clock_; }

 private:
  struct GnssDraw {
    double north = 0.0;
    double east = 0.0;
    bool lost = false;
  };
  struct GyroDraw {
    double heading = 0.0;
    bool lost = false;
  };
  GnssDraw DrawGnss(std::int64_t k);
  GyroDraw DrawGyro(std::int64_t k);

  PoseSensorSpec spec_;
  SensorClock gnss_clock_;
  SensorClock gyro_clock_;
  internal::ChannelError north_;
  internal::ChannelError east_;
  internal::ChannelError heading_;
  std::array<internal::ChannelFaults, 3> faults_;  // north, east, heading
  RandomStream gnss_dropout_stream_;
  RandomStream gnss_dropout_duration_stream_;
  RandomStream gyro_dropout_stream_;
  std::int64_t gnss_next_index_ = 0;  // first GNSS instant not yet drawn
  std::int64_t gyro_next_index_ = 0;
  // GNSS samples before this time [s] are lost (-inf: none yet).
  double gnss_dropout_end_ = -std::numeric_limits<double>::infinity();
};

/// A load cell that goes wrong during a run: cell `line` (0-based) with `fault`.
struct CellFault {
  int line = 0;
  SensorFault fault;
};

/// Fairlead tension cells: one per line, all with the same error model and rate, each
/// with its own streams "tension_cell.<k>.noise" / ".bias" / ".outlier" (k = 1 .. lines).
/// Readings are not clipped at zero: a load cell on a slack line reads noise around zero.
class TensionCells {
 public:
  /// Throws moorsim::InputError for lines < 1 or a bad rate or noise, with keys
  /// "sensors.tension_cells.lines", ".rate_hz" and ".noise.<field>".
  TensionCells(int lines, const ChannelNoise& noise, double rate, std::uint64_t run_seed);

  bool Due(double t) const { return clock_.Due(t); }
  double NextSampleTime(double t) const { return clock_.NextSampleTime(t); }

  /// Measured tensions [N] of the true fairlead tensions [N] (one per line, in line
  /// order) at t; all NaN if t is not an instant. Skipped instants are drawn and
  /// discarded as in PoseSensors. Throws std::invalid_argument if the span's size is not
  /// the number of lines, std::logic_error if t was already sampled.
  std::vector<double> Sample(double t, std::span<const double> true_tensions);

  int lines() const { return static_cast<int>(cells_.size()); }
  const SensorClock& clock() const { return clock_; }

  /// Adds a fault of one cell (ValidateSensorFault and the line's range; keys under
  /// `key_path`).
  void AddFault(const CellFault& fault, std::string_view key_path = "sensors.tension_cells.faults");

 private:
  SensorClock clock_;
  std::vector<internal::ChannelError> cells_;
  std::vector<internal::ChannelFaults> faults_;
  std::int64_t next_index_ = 0;
};

}  // namespace moorsim::vessel
