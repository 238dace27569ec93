// The monitor's configuration (scenarios/monitor_config.h): a whole one reads as written,
// paths resolved from its folder; every mistake is one located line naming the key.
#include "scenarios/monitor_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.h"

namespace moorsim::scenarios {
namespace {

using ::testing::HasSubstr;

constexpr const char* kWhole = R"(scenario: fpso.yaml
origin: {latitude_deg: 61.25, longitude_deg: 1.75, grid_north_deg: 12}
antenna: [12, -3, -30]
feeds:
  - {name: gnss, udp: {port: 10110}}
  - {name: gyro, udp: {port: 10111, group: 239.192.0.1}}
  - {name: cells, tcp: {host: 10.0.0.5, port: 4001}}
  - {name: dp, serial: {device: /dev/ttyS1, baud: 38400, parity: even}, format: json}
cells:
  - {transducer: LC1, line: 1}
  - {transducer: LC2, line: 2, scale: 1000, units: kN}
thrust: {feed: dp}
stale_after: 5
store: store
alarms: alarms.jsonl
bridge: {send: 127.0.0.1:10120, listen: 10121, talker: MS, repeat: 10}
display: {port: 8081}
)";

std::string ErrorOf(const std::string& text) {
  try {
    ParseMonitorConfig(text, "/ship/monitor.yaml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(MonitorConfig, AWholeConfigurationReadsAsWritten) {
  const MonitorConfig c = ParseMonitorConfig(kWhole, "/ship/monitor.yaml");
  EXPECT_EQ(c.scenario_path, "/ship/fpso.yaml");
  EXPECT_EQ(c.store, "/ship/store");
  EXPECT_EQ(c.alarms, "/ship/alarms.jsonl");
  EXPECT_DOUBLE_EQ(c.latitude, 61.25);
  EXPECT_DOUBLE_EQ(c.grid_north, 12.0);
  EXPECT_DOUBLE_EQ(c.antenna[2], -30.0);
  ASSERT_EQ(c.feeds.size(), 4u);
  EXPECT_EQ(c.feeds[0].kind, FeedConfig::Kind::kUdp);
  EXPECT_EQ(c.feeds[0].host, "0.0.0.0");
  EXPECT_EQ(c.feeds[1].group, "239.192.0.1");
  EXPECT_EQ(c.feeds[2].kind, FeedConfig::Kind::kTcp);
  EXPECT_EQ(c.feeds[3].baud, 38400);
  EXPECT_EQ(c.feeds[3].parity, SerialParity::kEven);
  EXPECT_EQ(c.feeds[3].format, FeedFormat::kJson);
  EXPECT_EQ(c.feeds[3].timing, FeedTiming::kArrival);
  ASSERT_EQ(c.cells.size(), 2u);
  EXPECT_DOUBLE_EQ(c.cells[1].scale, 1000.0);
  EXPECT_EQ(c.cells[1].units, "kN");
  ASSERT_TRUE(c.thrust && c.bridge && c.display);
  EXPECT_EQ(c.bridge->send_host, "127.0.0.1");
  EXPECT_EQ(c.bridge->send_port, 10120);
  EXPECT_EQ(c.bridge->talker, "MS");
  EXPECT_EQ(c.display->address, "127.0.0.1");
  EXPECT_FALSE(c.Replay());
  EXPECT_FALSE(c.Tagged());
}

TEST(MonitorConfig, AFileAloneIsAReplayOnItsTags) {
  const MonitorConfig c = ParseMonitorConfig(
      "scenario: s.yaml\norigin: {latitude_deg: 0, longitude_deg: 0}\n"
      "feeds: [{name: log, file: {path: trial.nmea}}]\nstore: s\n",
      "m.yaml");
  EXPECT_TRUE(c.Replay());
  EXPECT_TRUE(c.Tagged());
}

TEST(MonitorConfig, EveryMistakeIsOneLocatedLine) {
  const std::string head =
      "scenario: s.yaml\norigin: {latitude_deg: 61, longitude_deg: 2}\nstore: s\n";
  const struct {
    std::string text, expected;
  } cases[] = {
      {head + "feeds: []\n", "monitor.yaml:4:8: feeds: an empty list"},
      {head + "feeds: [{name: a}]\n", "feeds[1]: a feed needs one of udp, tcp, serial and file"},
      {head + "feeds: [{name: a, udp: {port: 1}, tcp: {host: h, port: 2}}]\n",
       "a feed is one of udp, tcp, serial and file, not several"},
      {head + "feeds: [{name: a, udp: {port: 70000}}]\n",
       "feeds[1].udp.port: 70000 must be in 1..65535"},
      {head + "feeds: [{name: a, udp: {port: 1}}, {name: a, udp: {port: 2}}]\n",
       "feeds[2].name: feed 'a' is named twice"},
      {head + "feeds: [{name: a, udp: {port: 1}, timing: tags}, {name: b, udp: {port: 2}}]\n",
       "feeds: the feeds are timed on one clock"},
      {head + "feeds: [{name: a, file: {path: x}}, {name: b, udp: {port: 2}}]\n",
       "must be the only feed"},
      {head + "feeds: [{name: a, serial: {device: /dev/ttyS0, baud: 1200}}]\n",
       "feeds[1].serial.baud: 1200 is not a serial speed"},
      {head + "feeds: [{name: a, udp: {port: 1}}]\nthrust: {feed: b}\n",
       "thrust.feed: no feed is named 'b'"},
      {head + "feeds: [{name: a, udp: {port: 1}}]\nthrust: {feed: a}\n",
       "name the XDR transducers of surge, sway and yaw"},
      {head + "feeds: [{name: a, udp: {port: 1}, format: json}]\n",
       "feeds[1].format: a json feed brings thrust: name it in thrust.feed"},
      {head + "feeds: [{name: a, udp: {port: 1}}]\ncells: [{transducer: L, line: 1}, "
              "{transducer: L, line: 2}]\n",
       "transducer 'L' is listed twice"},
      {head + "feeds: [{name: a, udp: {port: 1}}]\nbridge: {send: localhost}\n",
       "bridge.send: 'localhost' must be host:port"},
      {head + "feeds: [{name: a, udp: {port: 1}}]\nbridge: {send: h:1, talker: mm}\n",
       "bridge.talker: 'mm' must be two capital letters"},
      {head + "feeds: [{name: a, udp: {port: 1}}]\nstale_afte: 3\n", "stale_afte"},
      {"scenario: s.yaml\norigin: {latitude_deg: 91, longitude_deg: 2}\nstore: s\nfeeds: "
       "[{name: a, udp: {port: 1}}]\n",
       "origin.latitude_deg: 91 deg must be in [-90, 90]"},
  };
  for (const auto& c : cases) {
    const std::string error = ErrorOf(c.text);
    EXPECT_THAT(error, HasSubstr(c.expected)) << c.text;
    EXPECT_THAT(error, HasSubstr("/ship/monitor.yaml:")) << c.text;
    EXPECT_EQ(error.find('\n'), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace moorsim::scenarios
