// The configuration of `moorsim monitor`: which vessel (its scenario: mooring, sensors'
// noise, detectors), where the scenario's frame sits on the Earth, which feeds bring the
// vessel's sensors, and where alarms, the record and the display go. Read as strictly as a
// scenario: every problem is one moorsim::InputError line "<file>:<line>:<col>: <key.path>:
// <what>"; paths are relative to the configuration file's folder.
//
//   scenario: fpso.yaml               # required: the vessel, its mooring and detectors
//   origin:                           # required: the scenario's frame on the Earth (WGS84)
//     latitude_deg: 61.25             #   the frame's origin
//     longitude_deg: 1.75
//     grid_north_deg: 0               #   the frame's north axis from true north, clockwise
//   antenna: [12, -3, -30]            # the GNSS antenna on the vessel, body frame [m]
//   feeds:                            # required, >= 1; each one of udp, tcp, serial, file
//     - {name: gnss, udp: {port: 10110}}               # unicast or broadcast on a port
//     - {name: gyro, udp: {port: 10111, group: 239.192.0.1}}   # a multicast group
//     - {name: cells, tcp: {host: 10.0.0.5, port: 4001}}     # a client that reconnects
//     - {name: dp, serial: {device: /dev/ttyS1, baud: 38400, parity: none}, format: json}
//     - {name: log, file: {path: sea-trial.nmea}}            # a recorded, tagged log
//                                     # timing: arrival (default; a file: tags) or tags
//   cells:                            # XDR transducers that are fairlead load cells
//     - {transducer: LC1, line: 1}    #   its name and line; `scale` to newtons (default 1)
//   thrust: {feed: dp}                # optional: the thrust the allocation sends
//   stale_after: 3                    # [s] a channel silent this long is stale
//   store: store                      # the record (alarms, acknowledgements, samples)
//   keep_days: 90                     # daily records older than this are deleted
//   alarms: alarms.jsonl              # JSON alarm lines; "-" (default) for stdout
//   bridge: {send: 127.0.0.1:10120, listen: 10121}   # ALR sentences out, ACK in (UDP)
//   display: {address: 127.0.0.1, port: 8080, watch_circle: 40}
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/choice.h"
#include "scenarios/schema.h"

namespace moorsim::scenarios {

/// What a feed's lines are: NMEA 0183 sentences, or thrust as JSON objects or CSV rows.
enum class FeedFormat { kNmea, kJson, kCsv };
inline constexpr std::string_view kFeedFormatNames[] = {"nmea", "json", "csv"};
constexpr ChoiceInfo ChoicesOf(FeedFormat) { return {"feed format", kFeedFormatNames}; }

enum class SerialParity { kNone, kEven, kOdd };
inline constexpr std::string_view kSerialParityNames[] = {"none", "even", "odd"};
constexpr ChoiceInfo ChoicesOf(SerialParity) { return {"parity", kSerialParityNames}; }

/// When a line of a feed was taken: on arrival (the system clock), or from the NMEA TAG
/// block's `c:` (UNIX time) written before it (a recorded log, replayed on its own clock).
enum class FeedTiming { kArrival, kTags };
inline constexpr std::string_view kFeedTimingNames[] = {"arrival", "tags"};
constexpr ChoiceInfo ChoicesOf(FeedTiming) { return {"feed timing", kFeedTimingNames}; }

struct FeedConfig {
  enum class Kind { kUdp, kTcp, kSerial, kFile };
  std::string name;
  Kind kind = Kind::kUdp;
  FeedFormat format = FeedFormat::kNmea;
  /// udp: the address to bind (default any) and port; `group` a multicast group joined on
  /// `interface_address`. tcp: the server to connect to.
  std::string host;
  int port = 0;
  std::string group;
  std::string interface_address;
  /// serial: the device, its speed and parity (8 data bits, 1 stop bit).
  std::string device;
  int baud = 4800;
  SerialParity parity = SerialParity::kNone;
  /// file: a log (or a named pipe).
  std::string path;
  /// How its lines are timed (default: arrival; a file: tags).
  FeedTiming timing = FeedTiming::kArrival;
  /// Where in the configuration the feed is written ("feeds[2]"), for messages.
  std::string where;
};

struct CellConfig {
  std::string transducer;   ///< the XDR transducer name
  int line = 0;             ///< 1-based
  double scale = 1.0;       ///< reading x scale = newtons
  std::string units = "N";  ///< the XDR units field expected
};

struct ThrustConfig {
  std::string feed;  ///< a json or csv feed, or an nmea feed carrying XDR
  /// For XDR: the transducer names of surge [N], sway [N] and yaw [N m].
  std::vector<std::string> transducers;
};

struct BridgeConfig {
  std::string send_host;  ///< where ALR sentences go (UDP)
  int send_port = 0;
  int listen_port = 0;  ///< ACK sentences received on 127.0.0.1 or `listen_address`
  std::string listen_address = "0.0.0.0";
  std::string talker = "MM";  ///< the ALR sentences' talker
  double repeat = 30.0;       ///< [s] active alarms are sent again this often
};

struct DisplayConfig {
  std::string address = "127.0.0.1";
  int port = 8080;            ///< 0: any free port (the log says which)
  double watch_circle = 0.0;  ///< [m] drawn around the origin; 0: none
};

struct MonitorConfig {
  std::string source_path;
  std::string scenario_path;                                 ///< resolved
  double latitude = 0.0, longitude = 0.0, grid_north = 0.0;  ///< [deg]
  double antenna[3] = {0.0, 0.0, 0.0};                       ///< body frame [m]
  std::vector<FeedConfig> feeds;
  std::vector<CellConfig> cells;
  std::optional<ThrustConfig> thrust;
  double stale_after = 3.0;  ///< [s]
  double max_gap = 60.0;     ///< [s] the detection is suspended after a gap this long
  std::string store;         ///< resolved
  int keep_days = 0;         ///< daily records older than this are deleted; 0: kept
  std::string alarms = "-";  ///< "-" or a resolved path
  std::optional<BridgeConfig> bridge;
  std::optional<DisplayConfig> display;
  /// A file feed timed by tags replays a recorded log as fast as it reads.
  bool Replay() const;
  /// Every feed timed by its tags: the monitor's clock is theirs, not the system's.
  bool Tagged() const { return !feeds.empty() && feeds[0].timing == FeedTiming::kTags; }
};

namespace schema {
/// The monitor configuration's keys.
const Block& Monitor();
}  // namespace schema

/// Reads a monitor configuration (strict: the first problem is a located InputError).
MonitorConfig LoadMonitorConfig(const std::string& path);
MonitorConfig ParseMonitorConfig(const std::string& yaml_text, const std::string& source_name);

}  // namespace moorsim::scenarios
