// How a detector's verdict evolves over a run: every alarm onset, every revision of the
// hypothesis it names while the alarm stands, every end. A single "first alarm after the
// failure" misjudges two cases that matter on a real vessel: a line that parts while an
// earlier (false) alarm stands, which raises no new onset, and an alarm that ends while
// the line is still gone. The history answers both: when the verdict first named the
// failed line after the break (by an onset, a revision, or an alarm already standing on
// it), what it says at the end, and for how long an alarm stood.
#pragma once

#include <limits>
#include <optional>
#include <string_view>
#include <vector>

#include "core/types.h"
#include "detectors/detector.h"

namespace moorsim::detectors {

struct AlarmEvent {
  enum class Kind { kOnset, kRevision, kEnd };
  double time = 0.0;  ///< [s]
  Kind kind = Kind::kOnset;
  /// The hypothesis the verdict names from this event on (0 = intact after an end).
  int hypothesis = 0;
};

/// "onset", "revision", "end".
std::string_view AlarmEventName(AlarmEvent::Kind kind);

class AlarmHistory {
 public:
  /// Takes the verdict at time `t` [s] (non-decreasing; moorsim::ContractError otherwise):
  /// an onset when the alarm rises, a revision when the hypothesis it names changes while it
  /// stands, an end when it falls. While no alarm stands the hypothesis is not recorded.
  void Update(double t, bool alarm, int hypothesis);

  const std::vector<AlarmEvent>& events() const { return events_; }
  /// The verdict after the latest update.
  bool alarm() const { return alarm_; }
  int hypothesis() const { return alarm_ ? hypothesis_ : 0; }
  /// Time of the latest update (NaN before the first).
  double time() const { return time_; }

  /// Alarm onsets strictly before `t`.
  int OnsetsBefore(double t) const;
  /// The first alarm onset at or after `t`, if any.
  std::optional<AlarmEvent> FirstOnset(double t) const;
  /// The first time at or after `t` at which the verdict is an alarm naming `hypothesis`:
  /// `t` itself if such an alarm already stands at `t`, else the onset or revision that
  /// names it. Empty if it never does (up to the latest update).
  std::optional<double> FirstNamed(int hypothesis, double t) const;
  /// Time the alarm stood within [t0, t1] [s], the last verdict held up to t1.
  double AlarmSeconds(double t0, double t1) const;

 private:
  std::vector<AlarmEvent> events_;
  bool alarm_ = false;
  int hypothesis_ = 0;
  double time_ = kNaN;
};

/// A spell during which a detector judged a sensor faulty: from `since` [s] to `until`
/// (unset while it lasts).
struct SensorFaultSpell {
  SensorId sensor;
  SensorSymptom symptom = SensorSymptom::kDisagrees;
  double since = 0.0;
  std::optional<double> until;
};

/// Every spell of every sensor a detector judged faulty over a run, in the order they began.
class SensorFaultHistory {
 public:
  /// Takes the verdict's faulty sensors at time `t` [s].
  void Update(double t, const std::vector<SensorFinding>& faulty);
  const std::vector<SensorFaultSpell>& spells() const { return spells_; }

 private:
  std::vector<SensorFaultSpell> spells_;
  std::vector<SensorFinding> current_;
};

}  // namespace moorsim::detectors
