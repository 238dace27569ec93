#include "core/sample_clock.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "core/integrator.h"

namespace moorsim {
namespace {

// See the file comment of sample_clock.h: a billionth of an interval, or a few ulps of t
// (two clocks' k1 / rate1 and k2 / rate2 for the same instant differ by at most one
// rounding each, eps |t| / 2).
constexpr double kInstantToleranceIntervals = 1e-9;
constexpr double kInstantToleranceUlps = 4.0 * std::numeric_limits<double>::epsilon();

// Beyond 2^53 samples k / rate no longer has distinct instants; no run gets near it.
constexpr double kMaxIndex = 0x1.0p53;

double InstantTolerance(double t, double rate) {
  return kInstantToleranceIntervals / rate + kInstantToleranceUlps * std::abs(t);
}

}  // namespace

SampleClock::SampleClock(double rate, std::string_view key_path) : rate_(rate) {
  if (!std::isfinite(rate)) {
    throw InputError(std::string(key_path) + ": " + FormatNumber(rate) + " must be finite");
  }
  if (rate <= 0.0) {
    throw InputError(std::string(key_path) + ": " + FormatNumber(rate) + " must be > 0");
  }
}

std::optional<std::int64_t> SampleClock::Index(double t) const {
  const double scaled = t * rate_;
  if (!(scaled > -0.5 && scaled < kMaxIndex)) return std::nullopt;  // also rejects NaN
  const auto k = static_cast<std::int64_t>(std::nearbyint(scaled));
  if (std::abs(t - Instant(k)) > InstantTolerance(t, rate_)) return std::nullopt;
  return k;
}

std::int64_t SampleClock::LastIndex(double t) const {
  const double limit = t + InstantTolerance(t, rate_);
  if (!(limit >= 0.0)) return -1;  // also NaN
  const double scaled = t * rate_;
  if (!(scaled < kMaxIndex)) return static_cast<std::int64_t>(kMaxIndex);
  // The rounding of t * rate can leave the guess one off either way.
  auto k = static_cast<std::int64_t>(std::max(0.0, std::floor(scaled)));
  while (k > 0 && Instant(k) > limit) --k;
  while (Instant(k + 1) <= limit) ++k;
  return k;
}

double SampleClock::NextSampleTime(double t) const {
  if (std::isnan(t)) return t;
  const std::int64_t k = LastIndex(t);
  if (k >= static_cast<std::int64_t>(kMaxIndex)) return std::numeric_limits<double>::infinity();
  return Instant(k + 1);
}

void AdvanceThroughEvents(double t, const std::function<Integrator&()>& integrator,
                          const std::function<double(double now)>& next_event,
                          const std::function<void(double now)>& on_events) {
  double now = integrator().time();
  on_events(now);
  while (now < t) {
    const double event = next_event(now);
    if (!(event > now)) {
      std::ostringstream message;
      message.precision(17);
      message << "t = " << now << " s: the event loop made no progress (next event at " << event
              << " s is not after the current time)";
      throw SolverError(message.str());
    }
    Integrator& solver = integrator();
    // CVODE stops exactly at discrete events (inputs change there); other output times are
    // interpolated from its steps, which then carry on past them.
    if (std::isfinite(event)) solver.SetStopTime(event);
    solver.AdvanceTo(std::min(t, event));
    const double reached = solver.time();
    if (!(reached > now)) {
      std::ostringstream message;
      message.precision(17);
      message << "t = " << now << " s: the integrator did not advance toward " << std::min(t, event)
              << " s";
      throw SolverError(message.str());
    }
    now = reached;
    on_events(now);
  }
}

}  // namespace moorsim
