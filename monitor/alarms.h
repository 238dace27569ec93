// The monitor's alarms as the bridge and the crew see them: a fixed list of conditions,
// each with its alarm number (the number the bridge's ALR and ACK sentences carry),
// raised while its condition holds and acknowledged by the crew:
//   1..99     line k parted: a detector's alarm names a hypothesis in which line k failed
//   100..199  a channel stale: position (100), heading (101), the cells (102 on), thrust
//   200..299  a sensor judged faulty by the detectors: GNSS 200, gyro 201, pose 202,
//             cell k 210 + k
//   300       the detection suspended (position or heading missing longer than max_gap)
// An alarm that clears unacknowledged stays in the list (rectified, unacknowledged) until
// acknowledged, as bridge alert management has it; one acknowledged and cleared leaves it.
// Every raise, clear and acknowledgement is an AlarmChange, which the store records before
// it is announced.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "monitor/nmea.h"

namespace moorsim::monitor {

/// One occurrence of an alarm: raised, possibly cleared and acknowledged.
struct Alarm {
  std::int64_t id = 0;  ///< the occurrence's number in the store (0 until stored)
  int number = 0;       ///< the condition's alarm number
  std::string text;     ///< "Mooring line 6 parted"
  double raised = 0.0;  ///< UNIX time [s]
  std::optional<double> cleared, acknowledged;
  std::string acknowledged_by;  ///< "bridge", "display", ...
  bool Active() const { return !cleared.has_value(); }
  /// Shown until it is both cleared and acknowledged.
  bool Listed() const { return Active() || !acknowledged.has_value(); }
};

struct AlarmChange {
  enum class Kind { kRaised, kCleared, kAcknowledged };
  Kind kind = Kind::kRaised;
  Alarm alarm;  ///< its state after the change
};

class AlarmBoard {
 public:
  /// Restores the listed alarms (from the store) as they were.
  void Restore(std::vector<Alarm> listed);

  /// The conditions that hold now, by number with their text: raises the new ones, clears
  /// the ones gone. Returns the changes in number order.
  std::vector<AlarmChange> Update(const std::map<int, std::string>& holding, double now);
  /// Acknowledges the listed alarm of `number` (nothing if none, or already acknowledged).
  std::optional<AlarmChange> Acknowledge(int number, double now, const std::string& by);

  /// The listed alarms, by number.
  const std::map<int, Alarm>& listed() const { return listed_; }
  /// Sets the stored id of the occurrence of `number`.
  void SetId(int number, std::int64_t id);

 private:
  std::map<int, Alarm> listed_;
};

/// An ALR sentence for an alarm: its time of change, number, condition (A: holds, V: not),
/// acknowledgement (A/V) and text (cut to fit 82 characters; NMEA's reserved characters
/// replaced by spaces).
std::string AlrSentence(const std::string& talker, const Alarm& alarm);
/// The alarm number an ACK sentence acknowledges, or nothing with `why`.
std::optional<int> AckNumber(const NmeaSentence& sentence, std::string* why);

}  // namespace moorsim::monitor
