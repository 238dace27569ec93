// Periodic clocks of a hybrid simulation (sensors, controller, detectors, output rows) and
// the loop that integrates through their instants.
//
// Instants are t_k = k / rate (k = 0, 1, 2, ...), computed from the integer k each time,
// never by adding up 1 / rate, so a 3-hour run at 10 Hz ends on 10800 s exactly. A time t
// is at instant k if |t - k / rate| <= 1e-9 / rate + 4 eps |t| (a billionth of a sample
// interval, or a few units in the last place of t). That absorbs the last-bit difference
// between k1 / rate1 and k2 / rate2 of two clocks whose instants coincide, so such an
// instant is one event for both.
//
// Why integer indices: a loop that stops the integrator at k / rate but then asks whether
// t >= k * (1 / rate) can disagree in the last bit (3 / 10 < 3 * 0.1), never fire, and
// never advance. Every clock here is asked the same question the same way.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

namespace moorsim {

class Integrator;

/// The instants k / rate, k = 0, 1, 2, ..., of a sampled process.
class SampleClock {
 public:
  /// Throws moorsim::InputError "<key_path>: <rate> must be > 0" (or "must be finite") for
  /// a rate that is not a positive finite number.
  explicit SampleClock(double rate, std::string_view key_path = "rate_hz");

  /// The index k >= 0 of the instant at t, if t is one (within the file comment's
  /// tolerance).
  std::optional<std::int64_t> Index(double t) const;
  bool Due(double t) const { return Index(t).has_value(); }
  /// The first instant strictly after t (an instant within the tolerance of t counts as
  /// t itself, so this is the one after it); 0 for t before instant 0; +inf beyond 2^53
  /// samples.
  double NextSampleTime(double t) const;
  /// Index of the last instant at or before t (within the tolerance); -1 before instant 0.
  std::int64_t LastIndex(double t) const;
  /// t_k = k / rate [s], rounded once.
  double Instant(std::int64_t k) const { return static_cast<double>(k) / rate_; }
  double rate() const { return rate_; }

 private:
  double rate_ = 1.0;
};

/// Integrates through discrete events up to `t`. At each pass it asks `next_event(now)` for
/// the next event time (strictly after now, +inf if none), lets `integrator()` stop exactly
/// there (or at `t` if that comes first), and calls `on_events(now)` after every stop; that
/// handler acts on everything due and may replace the integrator (a topology change), which
/// is why the integrator is fetched anew each pass. `on_events` is also called once at the
/// start, so events due at the current time are handled first.
///
/// A pass that does not advance time is an error, never a spin: throws moorsim::SolverError
/// naming the time and the event that did not move.
void AdvanceThroughEvents(double t, const std::function<Integrator&()>& integrator,
                          const std::function<double(double now)>& next_event,
                          const std::function<void(double now)>& on_events);

}  // namespace moorsim
