// From the feeds' lines to the detection's samples: sentences checked and decoded into the
// vessel's channels (position, heading, each load cell, thrust), each channel's health
// counted, and one detectors::Observation per instant of the detection's sample clock, as
// `moorsim detect` reads them from a CSV row.
//
// The sample clock: instants t_k = k / rate seconds after the monitor's epoch (a whole UNIX
// second fixed when its store was made), the rate being the scenario's sensors' (the rate
// the detectors were built for). Sample k takes the first position fix and the first
// heading read in [t_k, t_k+1). It closes as soon as it has them and, where the vessel
// sends them at the detection's rate or faster (Waits), a thrust reading and the reading of
// every cell that is not stale (no waiting beyond: the alarm follows the line that completes
// it), or when a line read at or after t_k+1 (or the clock, live) says the interval is
// over, a position or heading missing then being a dropout the observers predict through.
// The thrust and the cells are held: the sample takes each one's latest reading, a cell's
// only while it has read within `stale_after` of t_k (a stale cell's is withheld, NaN, and
// the other cells still count; no tensions at all while every cell is stale).
// Everything depends only on the lines and their times, in order, so a recorded log
// replayed gives the same samples as the live feeds gave.
//
// Positions: latitude and longitude of the GNSS antenna to metres in the scenario's frame
// (GeodeticFrame, rotated by the grid's north), less the antenna's offset turned by the
// sample's heading (the last heading when this sample has none). Headings: degrees true to
// radians in the scenario's frame, unwrapped against the previous one.
//
// The detection runs in segments: it starts at the first sample with a position and a
// heading, and is suspended when either has been missing longer than `max_gap` (the
// observers' prediction is then worth no verdict); the next sample with both starts a new
// segment, with observers built afresh.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "detectors/detector.h"
#include "monitor/feeds.h"
#include "monitor/geodesy.h"
#include "scenarios/monitor_config.h"

namespace moorsim::monitor {

/// One of the vessel's measured quantities.
struct ChannelHealth {
  std::string name;  ///< "position", "heading", "cell LC3 (line 3)", "thrust"
  std::string feed;  ///< the feed it is read from ("" before its first reading)
  std::int64_t readings = 0;
  std::int64_t rejected = 0;  ///< decoded but not usable (no fix, not valid, out of range)
  double last = 0.0;          ///< UNIX time of its last good reading, 0 before one
  std::string problem;        ///< why the last one was rejected
  /// What the last good reading said of itself: a fix's sentence, quality, satellites and
  /// HDOP ("GGA quality 4, 12 satellites, HDOP 0.8"), a THS's mode.
  std::string detail;
  bool Stale(double now, double stale_after) const {
    return !(last > 0.0) || now - last > stale_after;
  }
};

/// What came in on one feed, sentence by sentence.
struct FeedCounts {
  std::int64_t sentences = 0;  ///< read and used
  std::int64_t ignored = 0;    ///< good sentences of a type the monitor does not read
  std::map<std::string, std::int64_t> faults;  ///< by kind: "bad checksum", "bad field", ...
  std::string last_fault;                      ///< the last bad line's fault, for the log
  std::int64_t Faults() const {
    std::int64_t n = 0;
    for (const auto& [kind, count] : faults) n += count;
    return n;
  }
};

/// A sample for the detection.
struct Sample {
  std::int64_t index = 0;  ///< k
  detectors::Observation observation;
  bool starts_segment = false;  ///< the detection (re)starts with it
  /// UNIX time the line that completed it was read (live: the clock's time when it closed
  /// an interval that ended without one), for the monitor's latencies.
  double arrival = 0.0;
};

/// Which held channels a sample waits for (besides position and heading): those the vessel
/// delivers at least as often as the detection samples (a 1 Hz cell is not waited for by a
/// 10 Hz detection: the sample takes its latest reading).
struct Waits {
  bool cells = true;
  bool thrust = true;
};

class Ingest {
 public:
  /// `lines`: the scenario's mooring lines; `rate`: the detection's sample rate [Hz];
  /// `epoch`: UNIX time of instant 0.
  Ingest(const scenarios::MonitorConfig& config, int lines, double rate, double epoch,
         Waits waits = {});

  /// One line read; the samples it closes are queued (TakeSamples).
  void Take(const FeedLine& line);
  /// Live: the clock says `now` [UNIX s]; closes the intervals that ended by then (their
  /// samples' arrival: `wall`, the system's clock).
  void Advance(double now, double wall);
  std::vector<Sample> TakeSamples();
  /// After a restart: the detection goes on from the recorded sample `last` (index k): the
  /// next interval is the one the clock is in, the heading unwrapped from the recorded one,
  /// the thrust held; the next sample starts a new segment on the warmed detection.
  void Resume(std::int64_t k, const detectors::Observation& last);
  /// When the open interval ends [UNIX s] (live: wake up then).
  double NextDeadline() const;

  double epoch() const { return epoch_; }
  double rate() const { return rate_; }
  bool active() const { return active_; }
  /// Position, heading, cells in line order, thrust.
  const std::vector<ChannelHealth>& channels() const { return channels_; }
  const std::vector<FeedCounts>& feeds() const { return counts_; }
  /// The latest readings, for the display: the reference point's north, east [m] and
  /// heading [rad] in the scenario's frame, each cell's tension [N] (NaN before one), the
  /// thrust [N, N, N m].
  const Vec3& latest_pose() const { return latest_pose_; }
  const VecX& latest_tensions() const { return latest_tensions_; }
  const Vec3& latest_thrust() const { return latest_thrust_; }

 private:
  struct Window {
    std::optional<Vec3> fix;  // antenna north, east, down
    std::optional<double> heading;
    bool thrust = false;  // a thrust reading in this interval
  };
  // Whether the open interval has every channel it waits for.
  bool Complete() const;
  // Whether `tau` lies in the open interval.
  bool InOpen(double tau) const { return open_ >= 0 && tau >= static_cast<double>(open_) / rate_; }
  void CloseBefore(double tau);
  // From `t` on the cells are waited for (as if they had read at t) until they are stale:
  // from the first interval, and from a resumed one.
  void ExpectCellsFrom(double t);
  // Opens the first interval at the first reading; whether `tau` lies in the open one.
  bool Start(double tau);
  void Close();
  void Reject(int channel, int feed, const std::string& why);
  // Whether `feed` brings `channel`: the first feed that brings a channel keeps it, so that
  // two receivers are never mixed (the other's sentences are counted as ignored).
  bool Claim(int channel, int feed);

  scenarios::MonitorConfig config_;
  Waits waits_;
  double arrival_ = 0.0;  // of the line being taken, or the clock's
  int lines_;
  double rate_;
  double epoch_;
  GeodeticFrame frame_;
  double cos_grid_, sin_grid_;
  std::vector<ChannelHealth> channels_;
  std::vector<FeedCounts> counts_;
  std::map<std::string, int> cell_of_transducer_;  // -> channel index
  std::int64_t open_ = -1;                         // the open interval's k (-1: none yet)
  Window window_;
  bool active_ = false;
  bool segment_start_ = true;
  double last_position_ = 0.0, last_heading_ = 0.0;  // t of the last valid ones
  std::optional<double> heading_;                    // the last heading [rad], unwrapped
  std::vector<double> cell_value_, cell_time_;       // latest reading, its tau
  std::vector<std::int64_t> cell_interval_;          // the interval it last read in
  Vec3 thrust_ = Vec3::Zero();
  Vec3 latest_pose_ = Vec3::Constant(kNaN);
  VecX latest_tensions_;
  Vec3 latest_thrust_ = Vec3::Zero();
  std::vector<Sample> samples_;
};

/// Channel indices.
inline constexpr int kPositionChannel = 0;
inline constexpr int kHeadingChannel = 1;

}  // namespace moorsim::monitor
