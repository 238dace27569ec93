// The monitor's inputs: lines of text from UDP datagrams (unicast, broadcast, multicast), a
// TCP server the monitor connects to (again after every loss), a serial line or a named
// pipe, each line stamped with the time it was read; and a recorded log replayed on the
// times its TAG blocks carry. One thread waits on all of them (Poller), so that a feed that
// floods, stalls or dies never holds up another.
//
// A line ends at LF or CR (either, or both), and a datagram's end ends a line too. A line
// longer than kMaxLineBytes is cut off and counted, never kept growing: a feed of random
// bytes costs bounded memory. An IEC 61162-450 datagram's "UdPbC" header is skipped.
#pragma once

#include <netinet/in.h>
#include <poll.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "scenarios/monitor_config.h"

namespace moorsim::monitor {

/// The longest line kept [bytes]; an NMEA sentence with a TAG block is far shorter.
inline constexpr std::size_t kMaxLineBytes = 256;

/// The system clock as UNIX time, to the microsecond (so that a log written with
/// NmeaTagBlock replays on exactly the times read).
double UnixNow();
/// Microseconds as the seconds they stand for (one rounding).
inline double FromMicroseconds(std::int64_t us) { return static_cast<double>(us) / 1e6; }

/// The IPv4 address of `host` (a name or dotted quad) and `port`; throws InputError
/// "<what>: '<host>' cannot be resolved: ..." otherwise.
sockaddr_in ResolveIpv4(const std::string& host, int port, const std::string& what);

/// Waits on file descriptors and calls each one's handler with what poll() reported.
class Poller {
 public:
  using Handler = std::function<void(short revents)>;
  void Add(int fd, short events, Handler handler);
  void Remove(int fd);
  /// Waits at most `timeout_ms` (-1: no limit) and calls the handlers of the ready ones.
  /// Returns false if interrupted by a signal.
  bool Wait(int timeout_ms);

 private:
  std::map<int, std::pair<short, Handler>> handlers_;
};

/// One line read, and when.
struct FeedLine {
  int feed = 0;          ///< index in the configuration's feeds
  std::string text;      ///< without its line end (a TAG block, if any, still in front)
  double stamp = 0.0;    ///< UNIX time [s] it was read (or its tag's, when replayed)
  double arrival = 0.0;  ///< UNIX time [s] it was read, whatever its stamp (for latencies)
};

/// What a feed has done since it started.
struct FeedHealth {
  std::string name;
  std::string kind;        ///< "udp", "tcp", "serial", "file"
  std::string endpoint;    ///< "0.0.0.0:10110", "10.0.0.5:4001", "/dev/ttyS1", a path
  bool connected = false;  ///< the socket bound, the connection up, the device or pipe open
  std::int64_t bytes = 0;
  std::int64_t lines = 0;
  std::int64_t overlong = 0;    ///< lines cut at kMaxLineBytes
  std::int64_t reconnects = 0;  ///< TCP connections made again, devices reopened
  std::int64_t untimed = 0;     ///< lines without a TAG block time on a feed timed by tags
  double last_line = 0.0;       ///< UNIX time of the last line, 0 before one
  std::string problem;          ///< the last failure to open or read ("" when fine)
};

class Feed;

/// Every feed of a configuration, on one Poller.
class Feeds {
 public:
  /// Opens every feed (a feed that cannot open yet, a TCP server down or a device absent,
  /// is retried; a configuration that cannot work, a bad address, throws InputError naming
  /// the feed). `sink` receives each line as it is read.
  Feeds(const std::vector<scenarios::FeedConfig>& feeds, Poller* poller,
        std::function<void(FeedLine)> sink);
  ~Feeds();
  Feeds(const Feeds&) = delete;
  Feeds& operator=(const Feeds&) = delete;

  /// Retries what is down whose wait is over; returns the next time [UNIX s] it wants to.
  double Maintain(double now);
  std::vector<FeedHealth> Health() const;

 private:
  std::unique_ptr<std::function<void(FeedLine)>> sink_;
  std::vector<std::unique_ptr<Feed>> feeds_;
};

/// A recorded log read line by line, each with its TAG block's time (a replay).
class TaggedLog {
 public:
  TaggedLog(const std::string& path, int feed);
  ~TaggedLog();
  /// The next line, false at the end. A line without a usable TAG block is skipped and
  /// counted (`untimed`).
  bool Next(FeedLine* line);
  std::int64_t untimed() const { return untimed_; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  int feed_;
  double last_ = 0.0;
  std::int64_t untimed_ = 0;
};

/// Splits a byte stream into lines (LF, CR or both end one), at most kMaxLineBytes each.
class LineSplitter {
 public:
  /// Takes bytes; calls `line` for each complete line (empty lines skipped). Returns the
  /// number of lines cut at kMaxLineBytes.
  int Take(const char* data, std::size_t size, const std::function<void(std::string)>& line);
  /// Ends the line in progress (a datagram's end, a closed stream).
  int End(const std::function<void(std::string)>& line);

 private:
  std::string buffer_;
  bool skipping_ = false;  // the rest of an overlong line
};

}  // namespace moorsim::monitor
