// A simulated ship's sensors as a monitor hears them: each sample the detection of a
// simulation takes (the measured pose with its dropouts and faults, the cells, the thrust
// issued) written as the sentences and rows a vessel's receivers send (GGA from the GNSS
// antenna, HDT from the gyro, one XDR per load cell, the thrust as the configuration's feed
// reads it), and played to the feeds of a monitor's configuration: to its UDP ports and
// multicast groups, as a TCP server it connects to, into a pipe, or into a tagged log.
//
// Every line carries the instant it stands for (its TAG block, when the feed is timed by
// tags) 1 ms after the sample's, as a receiver's output follows its measurement; played in
// real time or `speed` times faster.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/sample_clock.h"
#include "detectors/detector.h"
#include "monitor/geodesy.h"
#include "scenarios/monitor_config.h"

namespace moorsim::monitor {

/// One line for one of the configuration's feeds.
struct PlayedLine {
  int feed = 0;
  std::string text;  ///< without its line end
};

/// Which feed each kind of sentence goes to (indices into the configuration's feeds).
struct Routing {
  int position = 0, heading = 0, cells = 0, thrust = -1;
};

/// The default routing: position, heading and cells to the feed of each name given (empty:
/// the first NMEA feed), thrust to the configuration's thrust feed. Throws InputError
/// naming an unknown or unsuitable feed.
Routing RouteFeeds(const scenarios::MonitorConfig& config, const std::string& position,
                   const std::string& heading, const std::string& cells);

class SentenceWriter {
 public:
  /// `cells_rate`: the load cells' sample rate [Hz] (their XDR are sent at its instants
  /// only; 0: with every sample).
  SentenceWriter(const scenarios::MonitorConfig& config, Routing routing, double cells_rate = 0.0);
  /// The lines of one sample, stamped `unix_time` (the sample's instant + 1 ms).
  std::vector<PlayedLine> Lines(const detectors::Observation& o, double unix_time);

 private:
  scenarios::MonitorConfig config_;
  Routing routing_;
  GeodeticFrame frame_;
  double heading_ = 0.0;  // the last measured heading [rad], for the antenna's place
  std::optional<SampleClock> cells_clock_;
};

/// Sends lines to the configuration's feeds (UDP datagrams, TCP clients, a pipe or a log).
class Player {
 public:
  /// Opens every feed's end: throws InputError naming a feed it cannot serve (a serial
  /// line; a port it cannot listen on).
  explicit Player(const scenarios::MonitorConfig& config);
  ~Player();
  Player(const Player&) = delete;
  Player& operator=(const Player&) = delete;
  /// Whether every feed is a tagged log (written at once, never paced).
  bool OnlyLogs() const;
  /// Sends a line (a TAG block in front when its feed is timed by tags).
  void Send(const PlayedLine& line, double unix_time);
  /// Accepts TCP clients waiting; waits at most `ms` for them.
  void Serve(int ms);
  /// TCP clients connected, per feed (-1 for feeds that are not TCP).
  std::vector<int> Clients() const;

 private:
  struct End;
  std::vector<std::unique_ptr<End>> ends_;
};

}  // namespace moorsim::monitor
