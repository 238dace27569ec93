// The detection of a plant model on its own: the hypothesis bank, the observer bank and the
// model's detectors, fed one sensor sample at a time. The coupled simulation feeds it the
// samples its sensors take; `moorsim detect` and the monitor feed it a recorded or live
// stream without the plant. All build it from the same model the same way, so a replay of a
// run's recorded detection input gives the run's verdicts bit for bit.
//
// The models depend on the set-up and the vessel's moored static start only (not on the
// seed): the bank, the GLR signatures and the passive observers' training are shared by
// every Detection of the same set-up in the process (shared_parts.h).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/types.h"
#include "detectors/alarm_history.h"
#include "detectors/detector.h"
#include "detectors/plugin_detector.h"
#include "simulation/plant_model.h"
#include "vessel/vessel_model.h"

namespace moorsim::simulation {

/// What a detector did over a run (summary.json). Alarm onsets are the samples where its
/// alarm turns on. `alarm_time` is the first onset at or after the true failure time (with
/// no failure: the first onset at all), `isolated` the hypothesis it named there; onsets
/// before the failure (all onsets without one) count as false alarms.
struct DetectorRecord {
  std::string label;
  std::string type;
  /// The threshold the detector's alarm rule compares its score with (GLR: h on g; DHT:
  /// the posterior), for plots; unset for detectors without one (MLE: a margin on gaps).
  std::optional<double> threshold;
  /// The scenario's failure time; unset without a failure.
  std::optional<double> failure_time;
  /// Every onset, revision of the named hypothesis and end of its alarm.
  detectors::AlarmHistory history;
  /// Every spell of a sensor the detector judged faulty.
  detectors::SensorFaultHistory sensor_faults;

  /// The first alarm onset at or after the failure (without a failure, the first onset):
  /// its time is the alarm time, its hypothesis the isolated one.
  std::optional<detectors::AlarmEvent> FirstAlarm() const {
    return history.FirstOnset(failure_time.value_or(-std::numeric_limits<double>::infinity()));
  }
  /// Alarm onsets before the failure (all of them without a failure).
  int FalseAlarms() const {
    return history.OnsetsBefore(failure_time.value_or(std::numeric_limits<double>::infinity()));
  }
};

/// Wall time spent on detection (steady clock).
struct DetectionTiming {
  double setup_seconds = 0.0;   ///< hypothesis bank, observers, signatures, training
  double update_seconds = 0.0;  ///< observer bank and detectors, all samples
  long samples = 0;             ///< observations processed
};

/// Builds every detector of `setup` once to check its type and parameters and that its
/// observers give what it reads. Throws InputError "detectors[<i>].<key>: ..." (1-based
/// i) for a bad one.
void CheckDetectors(const DetectionSetup& setup);

class Detection {
 public:
  /// The detection of `plant` (its `detection` must be set) for the plant's vessel model
  /// `vessel` at its moored static start `moored_pose` (Simulation::initial_pose()). Throws
  /// moorsim::InputError for a detector the model cannot have (as CheckDetectors()).
  Detection(const PlantModel& plant, const vessel::VesselModel& vessel, const Vec6& moored_pose);
  ~Detection();
  Detection(const Detection&) = delete;
  Detection& operator=(const Detection&) = delete;

  /// One sensor sample: the observers, then every detector in the setup's order, whose alarm
  /// histories record what changed. Times must not decrease (ContractError otherwise).
  void Update(const detectors::Observation& observation);

  /// Keeps every observation given to Update until TakeInput, for the run's record of its
  /// detection input (run.h5 /detection/input).
  void KeepInput(bool keep) { keep_input_ = keep; }
  /// The observations since the last call, in order.
  std::vector<detectors::Observation> TakeInput();

  int num_hypotheses() const;
  /// "intact", "line 6", "lines 2+5", by hypothesis.
  std::vector<std::string> HypothesisLabels() const;
  /// Per hypothesis, the 1-based lines it says have failed (0 where there is none).
  std::vector<std::array<int, 2>> FailedLines() const;
  /// Whether the observers are the EKF bank, whose load picture bias()/wave_motion() give.
  bool estimates_load() const;
  /// Every detector's latest verdict (the setup's order).
  const std::vector<detectors::Verdict>& verdicts() const;
  const std::vector<DetectorRecord>& records() const { return records_; }
  /// The plugin libraries the detectors came from, in the setup's order without repeats.
  std::vector<std::shared_ptr<const detectors::PluginLibrary>> PluginLibraries() const;
  const DetectionTiming& timing() const { return timing_; }
  /// The intact observer's latest bias b [N, N, N m] and wave-frequency motion [m, m, rad]
  /// (Earth frame); unset before the first sample or without the EKF bank.
  const std::optional<Vec3>& bias() const;
  const std::optional<Vec3>& wave_motion() const;
  /// What each fairlead's cell should read at the intact filter's pose [N] (NaN where the
  /// model holds no expectation), as of the latest sample that carried cell readings; unset
  /// before one or without cells.
  const std::optional<VecX>& expected_tensions() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
  std::vector<DetectorRecord> records_;
  DetectionTiming timing_;
  bool keep_input_ = false;
  std::vector<detectors::Observation> input_;
};

/// The plugin libraries `used` (detectors/plugin_detector.h), and every library registered
/// with --plugin: [{path, sha256}] in that order without repeats, so that a result names
/// exactly the code that produced it. Empty without plugins.
nlohmann::json PluginsSummary(
    const std::vector<std::shared_ptr<const detectors::PluginLibrary>>& used);

/// One alarm event as `moorsim detect` prints it (one JSON object a line): time, detector
/// label and type, event, the hypothesis it names (its label; the line number, null for a
/// pair), the detector's score for it, and `latency_ms`, the wall time of that sample in
/// the observers and detectors.
nlohmann::ordered_json AlarmEventJson(const DetectorRecord& record, const detectors::AlarmEvent& e,
                                      const detectors::Verdict& verdict,
                                      const std::vector<std::string>& labels, int lines,
                                      double latency_ms);

}  // namespace moorsim::simulation
