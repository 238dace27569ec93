// The whole chain on this machine: `moorsim stream` plays the thesis case in which line 6
// parts at 400 s to a monitor, which must name line 6 when the detectors of `moorsim
// detect` do on the samples the monitor recorded (bit for bit: every event, time and
// score); over UDP at 20 times real time its ALR reaches a bridge listening on loopback and
// the bridge's ACK acknowledges it; killed with SIGKILL and started again, the monitor
// lists the alarm with its acknowledgement and goes on.
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "monitor/nmea.h"
#include "monitor/store.h"
#include "tests/monitor/monitor_test_support.h"

namespace moorsim::monitor {
namespace {

using moorsim::testing::ReadWholeFile;
using moorsim::testing::RunCli;
using moorsim::testing::StartCli;
using moorsim::testing::TempDirectory;
using moorsim::testing::WriteWholeFile;
using testing::ConfigText;
using testing::FreePort;
using testing::kLine6;

// The detector events of JSON alarm lines (the alarm changes left out), without the wall
// time each took.
std::vector<nlohmann::json> DetectorEvents(const std::string& lines) {
  std::vector<nlohmann::json> events;
  std::istringstream in(lines);
  std::string line;
  while (std::getline(in, line)) {
    nlohmann::json j = nlohmann::json::parse(line);
    if (j.contains("alarm")) continue;
    j.erase("latency_ms");
    events.push_back(j);
  }
  return events;
}

bool NamesLine6(const std::vector<nlohmann::json>& events, const std::string& detector) {
  for (const nlohmann::json& e : events) {
    if (e["detector"] == detector && e["event"] == "onset" && e["line"] == 6) return true;
  }
  return false;
}

TEST(MonitorSlow, AReplayedSeaTrialGivesTheAlarmsDetectGivesOnTheRecordedSamples) {
  const TempDirectory dir(::testing::TempDir());
  const auto config = dir.path() / "replay.yaml";
  WriteWholeFile(config, ConfigText(kLine6, "  - {name: log, file: {path: trial.nmea}}\n",
                                    "thrust: {feed: log, transducers: [TX, TY, TN]}\n"));
  const auto stream =
      RunCli({"stream", kLine6, "--to", config.string(), "--set", "simulation.duration=600"},
             dir.path(), std::chrono::seconds(120));
  ASSERT_EQ(stream.exit_code, 0) << stream.Describe();
  const auto monitor = RunCli({"monitor", config.string()}, dir.path(), std::chrono::seconds(120));
  ASSERT_EQ(monitor.exit_code, 0) << monitor.Describe();
  const std::vector<nlohmann::json> live =
      DetectorEvents(ReadWholeFile(dir.path() / "alarms.jsonl"));
  EXPECT_TRUE(NamesLine6(live, "glr"));
  EXPECT_TRUE(NamesLine6(live, "deficit"));
  const auto detect =
      RunCli({"detect", (dir.path() / "store").string()}, dir.path(), std::chrono::seconds(120));
  ASSERT_EQ(detect.exit_code, 0) << detect.Describe();
  EXPECT_EQ(DetectorEvents(detect.out), live);
  EXPECT_EQ(ReadStoredSamples((dir.path() / "store").string(), 0.0, 1e12).size(), 601u);
}

// A bridge on loopback: receives ALR sentences, sends ACK.
class Bridge {
 public:
  Bridge() : port_(FreePort(SOCK_DGRAM)) {
    fd_ = ::socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(static_cast<std::uint16_t>(port_));
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
      throw std::runtime_error("bridge: bind");
    }
  }
  ~Bridge() { ::close(fd_); }
  int port() const { return port_; }

  /// Waits at most `seconds` for an ALR of `number` whose condition and acknowledgement
  /// fields are `active` and `acknowledged`.
  bool AwaitAlr(const std::string& number, const std::string& active,
                const std::string& acknowledged, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      pollfd ready = {fd_, POLLIN, 0};
      if (::poll(&ready, 1, 100) <= 0) continue;
      char datagram[512];
      const ssize_t n = ::recv(fd_, datagram, sizeof datagram, 0);
      if (n <= 0) continue;
      std::string text(datagram, static_cast<std::size_t>(n));
      while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
      const NmeaParse parse = ParseNmea(text);
      if (!parse.sentence || parse.sentence->type != "ALR") {
        ADD_FAILURE() << "not an ALR sentence: " << text << " (" << parse.detail << ")";
        continue;
      }
      const std::vector<std::string>& f = parse.sentence->fields;
      if (f.size() == 5 && f[1] == number && f[2] == active && f[3] == acknowledged) return true;
    }
    return false;
  }

  void Ack(int to_port, const std::string& number) {
    const std::string sentence = NmeaText('$', "BRACK", {number}) + "\r\n";
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(static_cast<std::uint16_t>(to_port));
    to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::sendto(fd_, sentence.data(), sentence.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
  }

 private:
  int port_;
  int fd_ = -1;
};

// Waits at most `seconds` for `text` in the file.
bool AwaitText(const std::filesystem::path& file, const std::string& text, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (ReadWholeFile(file).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

int Reap(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    if (::waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &status, 0);
  ADD_FAILURE() << "process " << pid << " did not end in " << seconds << " s";
  return status;
}

TEST(MonitorSlow, AShipAt20TimesOverUdpReachesTheBridgeAndSurvivesAKill) {
  const TempDirectory dir(::testing::TempDir());
  Bridge bridge;
  const int feed_port = FreePort(SOCK_DGRAM), ack_port = FreePort(SOCK_DGRAM);
  const auto config = dir.path() / "ship.yaml";
  WriteWholeFile(config, ConfigText(kLine6,
                                    "  - {name: ship, udp: {address: 127.0.0.1, port: " +
                                        std::to_string(feed_port) + "}, timing: tags}\n",
                                    "thrust: {feed: ship, transducers: [TX, TY, TN]}\n"
                                    "bridge: {send: 127.0.0.1:" +
                                        std::to_string(bridge.port()) +
                                        ", listen: " + std::to_string(ack_port) +
                                        ", listen_address: 127.0.0.1, repeat: 0.5}\n"));
  const auto log1 = dir.path() / "monitor1.log", log2 = dir.path() / "monitor2.log";
  pid_t monitor = StartCli({"monitor", config.string()}, {dir.path() / "out1"}, {log1});
  ASSERT_TRUE(AwaitText(log1, "feed ship", 60.0)) << ReadWholeFile(log1);
  const pid_t stream = StartCli({"stream", kLine6, "--to", config.string(), "--speed", "20",
                                 "--set", "simulation.duration=520"},
                                {dir.path() / "stream.out"}, {dir.path() / "stream.err"});
  // Line 6 parts at 400 s: the GLR names it 28 s later, 21 s of wall time in.
  ASSERT_TRUE(bridge.AwaitAlr("006", "A", "V", 60.0)) << ReadWholeFile(log1);
  bridge.Ack(ack_port, "006");
  ASSERT_TRUE(bridge.AwaitAlr("006", "A", "A", 10.0)) << ReadWholeFile(log1);

  // Killed at once, started again on its store while the ship plays on.
  ::kill(monitor, SIGKILL);
  Reap(monitor, 10.0);
  monitor = StartCli({"monitor", config.string()}, {dir.path() / "out2"}, {log2});
  ASSERT_TRUE(AwaitText(log2, "1 alarms listed as they were", 60.0)) << ReadWholeFile(log2);
  EXPECT_TRUE(AwaitText(log2, "observers warmed on", 1.0)) << ReadWholeFile(log2);
  // Still acknowledged: repeated as it holds (A, A), or cleared and so gone (V, A).
  const bool acknowledged = bridge.AwaitAlr("006", "A", "A", 10.0);
  EXPECT_TRUE(acknowledged) << ReadWholeFile(log2);

  const int stream_status = Reap(stream, 120.0);
  EXPECT_TRUE(WIFEXITED(stream_status) && WEXITSTATUS(stream_status) == 0)
      << ReadWholeFile(dir.path() / "stream.err");
  ::kill(monitor, SIGTERM);
  const int status = Reap(monitor, 30.0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM) << ReadWholeFile(log2);

  // Every announcement was recorded before it was made: one acknowledgement, by the bridge.
  const std::string alarms = ReadWholeFile(dir.path() / "alarms.jsonl");
  std::size_t acks = 0;
  for (std::size_t at = 0;
       (at = alarms.find("\"state\":\"acknowledged\"", at)) != std::string::npos; ++at) {
    ++acks;
  }
  EXPECT_EQ(acks, 1u) << alarms;
  EXPECT_THAT(alarms, ::testing::HasSubstr("\"by\":\"bridge\""));
  EXPECT_TRUE(NamesLine6(DetectorEvents(alarms), "glr")) << alarms;
  const std::vector<StoredSample> samples =
      ReadStoredSamples((dir.path() / "store").string(), 0.0, 1e12);
  ASSERT_FALSE(samples.empty());
  EXPECT_GT(samples.size(), 450u);
  EXPECT_EQ(samples.front().segment, 1);
  EXPECT_EQ(samples.back().segment, 2);
}

}  // namespace
}  // namespace moorsim::monitor

namespace moorsim::monitor {
namespace {

// GET `path` from the display on 127.0.0.1:`port`: the response's body.
std::string HttpGet(int port, const std::string& path) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    ::close(fd);
    return "";
  }
  const std::string request = "GET " + path + " HTTP/1.1\r\nHost: localhost\r\n\r\n";
  ::send(fd, request.data(), request.size(), 0);
  std::string response;
  char buffer[65536];
  for (ssize_t n; (n = ::recv(fd, buffer, sizeof buffer, 0)) > 0;) response.append(buffer, n);
  ::close(fd);
  const std::size_t body = response.find("\r\n\r\n");
  return body == std::string::npos ? "" : response.substr(body + 4);
}

TEST(MonitorSlow, RandomBytesAtAMegabyteASecondAreCountedAndStopNothing) {
  const TempDirectory dir(::testing::TempDir());
  const int feed_port = FreePort(SOCK_DGRAM), tcp_port = FreePort(SOCK_STREAM),
            display_port = FreePort(SOCK_STREAM);
  // The second feed is a TCP server of this test's that sends nothing but noise.
  const int server = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in local{};
  local.sin_family = AF_INET;
  local.sin_port = htons(static_cast<std::uint16_t>(tcp_port));
  local.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const int one = 1;
  ::setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  ASSERT_EQ(::bind(server, reinterpret_cast<sockaddr*>(&local), sizeof local), 0);
  ::listen(server, 1);
  const auto config = dir.path() / "noise.yaml";
  WriteWholeFile(config, ConfigText(kLine6,
                                    "  - {name: udp, udp: {address: 127.0.0.1, port: " +
                                        std::to_string(feed_port) +
                                        "}}\n  - {name: tcp, tcp: {host: 127.0.0.1, port: " +
                                        std::to_string(tcp_port) + "}}\n",
                                    "display: {port: " + std::to_string(display_port) + "}\n"));
  const auto log = dir.path() / "monitor.log";
  const pid_t monitor = StartCli({"monitor", config.string()}, {dir.path() / "out"}, {log});
  ASSERT_TRUE(AwaitText(log, "display: http", 60.0)) << ReadWholeFile(log);
  pollfd waiting = {server, POLLIN, 0};
  ASSERT_EQ(::poll(&waiting, 1, 10000), 1) << "the monitor did not connect";
  const int client = ::accept(server, nullptr, nullptr);

  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to = local;
  to.sin_port = htons(static_cast<std::uint16_t>(feed_port));
  std::mt19937_64 random(20261207);
  const auto start = std::chrono::steady_clock::now();
  std::size_t sent = 0;
  // 5 s at 1 MB/s on each feed: random bytes (with their CR and LF), and now and then a
  // sentence with one character changed.
  const std::string gga = NmeaText('$', "GPGGA",
                                   {"120000.00", "6115.0000000", "N", "00145.0000000", "E", "1",
                                    "12", "0.8", "0.0", "M", "0.0", "M", "", ""});
  while (std::chrono::steady_clock::now() - start < std::chrono::seconds(5)) {
    std::string chunk(1024, '\0');
    for (char& c : chunk) c = static_cast<char>(random() & 0xff);
    std::string mutated = gga;
    mutated[random() % mutated.size()] = static_cast<char>(random() & 0x7f);
    chunk += "\r\n" + mutated + "\r\n";
    ::sendto(sender, chunk.data(), chunk.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to);
    ::send(client, chunk.data(), chunk.size(), MSG_NOSIGNAL);
    sent += 2 * chunk.size();
    const double due = static_cast<double>(sent) / 2e6;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (due > elapsed) std::this_thread::sleep_for(std::chrono::duration<double>(due - elapsed));
  }
  ::close(sender);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));

  // Alive, answering, and every line it read is accounted for: used, ignored or a fault.
  const std::string body = HttpGet(display_port, "/api/state");
  ASSERT_FALSE(body.empty()) << ReadWholeFile(log);
  const nlohmann::json state = nlohmann::json::parse(body);
  std::int64_t faults = 0;
  for (const nlohmann::json& feed : state["feeds"]) {
    std::int64_t kinds = 0;
    for (const auto& [kind, count] : feed["fault_kinds"].items())
      kinds += count.get<std::int64_t>();
    EXPECT_EQ(feed["lines"].get<std::int64_t>(),
              feed["sentences"].get<std::int64_t>() + feed["ignored"].get<std::int64_t>() + kinds)
        << feed.dump();
    EXPECT_GT(feed["lines"].get<std::int64_t>(), 1000) << feed.dump();
    faults += kinds;
  }
  EXPECT_GT(faults, 2000);
  ::close(client);
  ::close(server);
  ::kill(monitor, SIGTERM);
  const int status = Reap(monitor, 30.0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGTERM) << ReadWholeFile(log);
}

}  // namespace
}  // namespace moorsim::monitor

namespace moorsim::monitor {
namespace {

// Every alarm change the monitor printed (its JSON alarm lines): number, state, raise time.
std::vector<nlohmann::json> AlarmChanges(const std::string& lines) {
  std::vector<nlohmann::json> changes;
  std::istringstream in(lines);
  std::string line;
  while (std::getline(in, line)) {
    // A kill may cut the last line short: it was never whole, so never announced.
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded() && j.contains("alarm")) changes.push_back(j);
  }
  return changes;
}

TEST(MonitorSlow, KilledAtRandomMomentsItLosesNoAlarmItAnnounced) {
  const TempDirectory dir(::testing::TempDir());
  Bridge bridge;
  const int feed_port = FreePort(SOCK_DGRAM);
  const auto config = dir.path() / "ship.yaml";
  WriteWholeFile(config, ConfigText(kLine6,
                                    "  - {name: ship, udp: {address: 127.0.0.1, port: " +
                                        std::to_string(feed_port) + "}, timing: tags}\n",
                                    "thrust: {feed: ship, transducers: [TX, TY, TN]}\n"
                                    "stale_after: 1\n"
                                    "bridge: {send: 127.0.0.1:" +
                                        std::to_string(bridge.port()) + "}\n"));
  const auto log = dir.path() / "monitor.log";
  pid_t monitor = StartCli({"monitor", config.string()}, {dir.path() / "out0"}, {log});
  ASSERT_TRUE(AwaitText(log, "feed ship", 60.0)) << ReadWholeFile(log);
  const pid_t stream = StartCli({"stream", kLine6, "--to", config.string(), "--speed", "40",
                                 "--set", "simulation.duration=520"},
                                {dir.path() / "stream.out"}, {dir.path() / "stream.err"});
  // Killed six times at random moments over the 13 s of the trial (the line 6 alarm comes
  // 11 s in), started again each time at once.
  std::mt19937 random(7);
  for (int kill = 1; kill <= 6; ++kill) {
    std::this_thread::sleep_for(
        std::chrono::milliseconds(std::uniform_int_distribution<int>(300, 2500)(random)));
    ::kill(monitor, SIGKILL);
    Reap(monitor, 10.0);
    monitor = StartCli({"monitor", config.string()}, {dir.path() / ("out" + std::to_string(kill))},
                       {log});
  }
  Reap(stream, 120.0);
  std::this_thread::sleep_for(std::chrono::seconds(2));
  ::kill(monitor, SIGTERM);
  Reap(monitor, 30.0);

  // Every change printed is in the store; the store has every occurrence raised.
  const std::vector<nlohmann::json> printed =
      AlarmChanges(ReadWholeFile(dir.path() / "alarms.jsonl"));
  const std::vector<Alarm> stored = ReadStoredAlarms((dir.path() / "store").string());
  ASSERT_FALSE(printed.empty());
  for (const nlohmann::json& change : printed) {
    const int number = change["alarm"];
    const double at = change["unix"];
    const std::string state = change["state"];
    const bool found = std::any_of(stored.begin(), stored.end(), [&](const Alarm& a) {
      if (a.number != number) return false;
      if (state == "raised") return a.raised == at;
      if (state == "cleared") return a.cleared == at;
      return a.acknowledged == at;
    });
    EXPECT_TRUE(found) << change.dump();
  }
  EXPECT_TRUE(std::any_of(printed.begin(), printed.end(), [](const nlohmann::json& c) {
    return c["alarm"] == 6 && c["state"] == "raised";
  })) << ReadWholeFile(dir.path() / "alarms.jsonl");
  // Readable after all of it, with the samples of the whole trial.
  EXPECT_GT(ReadStoredSamples((dir.path() / "store").string(), 0.0, 1e12).size(), 300u);
}

}  // namespace
}  // namespace moorsim::monitor
