// `moorsim monitor`: the detection on a vessel's own feeds, as a service. Lines are read
// from the feeds (or a recorded log, replayed), turned into the detection's samples
// (ingest.h), run through the same observers and detectors `moorsim detect` runs, and every
// decision is recorded (store.h) before it is announced: detector events as JSON lines (as
// `detect` prints them), alarm changes as JSON lines and as NMEA ALR sentences to the
// bridge, whose ACK sentences acknowledge them.
//
// Restart: a monitor started on an existing store lists the alarms as they were, with
// their acknowledgements, and warms its observers on the last samples it recorded (up to
// kWarmUp seconds of them, if the last one is no older than max_gap; the events of that
// replay are not announced again). Otherwise its detection starts afresh with the feeds.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "scenarios/monitor_config.h"
#include "simulation/plant_model.h"

namespace moorsim::monitor {

/// How much of the recorded past a restarted monitor's observers are warmed on [s].
inline constexpr double kWarmUp = 1800.0;

struct MonitorOptions {
  /// Asked between waits (at least every 200 ms): stop when it returns true.
  std::function<bool()> stop;
  /// A line for the operator's log (standard error): feeds connecting, channels going
  /// stale, the store resumed.
  std::function<void(const std::string&)> log;
};

/// The vessel the monitor watches: its typed plant model (mooring, sensors, controller and
/// detection: what the detection is built from, as simulation::MakeDetection() builds it)
/// and what the display and the store need besides. `moorsim monitor` fills it from the
/// configuration's scenario file; a program may fill it in code.
struct MonitoredVessel {
  simulation::PlantModel model;
  /// The run seed the detection's static start is made with (a scenario's simulation.seed).
  std::uint64_t seed = 1;
  /// Shown on the display.
  std::string name;
  /// The hull's outline on the display's plan view [m].
  double hull_length = 0.0, hull_beam = 0.0;
  /// What the model was made from, recorded with the store: `moorsim detect STORE` loads
  /// `source_text` as a scenario to replay the record, and a store of another source is
  /// refused.
  std::string source_path, source_text;
};

/// What a run of the monitor did.
struct MonitorSummary {
  long lines = 0;
  long samples = 0;
  long events = 0;
  long alarm_changes = 0;
  long segments = 0;
  double warmed_seconds = 0.0;  ///< the recorded past the observers were warmed on
  /// From the arrival of the line that completed a sample to its events printed (every
  /// sample), and to its ALR sent (the samples that changed an alarm): simulation::Latency's
  /// summaries.
  nlohmann::json sample_latency, alarm_latency;
  nlohmann::json Json() const;
};

class Monitor {
 public:
  /// Builds the detection of `vessel` (the configuration's), opens the store, the feeds,
  /// the bridge's sockets and the alarm output. Throws InputError for what the
  /// configuration asks that cannot be had (a port taken, a store of another scenario).
  Monitor(const scenarios::MonitorConfig& config, const MonitoredVessel& vessel,
          MonitorOptions options);
  ~Monitor();
  Monitor(const Monitor&) = delete;
  Monitor& operator=(const Monitor&) = delete;

  /// Runs until stopped (live) or to the log's end (a replay).
  MonitorSummary Run();
  /// What the display shows, as JSON: the vessel, lines, cells, detectors, alarms, feeds.
  nlohmann::json State() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

}  // namespace moorsim::monitor
