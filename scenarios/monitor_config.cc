#include "scenarios/monitor_config.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "scenarios/strict_yaml.h"

// The tables name only the members a key sets (designated initializers), as schema.cc's.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace moorsim::scenarios {
namespace schema {
namespace {

constexpr Bound kPortLow{1.0, false, ""};
constexpr Bound kPortHigh{65535.0, false, ""};
constexpr Bound kPositive{0.0, true, ""};

constexpr Key kOriginKeys[] = {
    {.name = "grid_north_deg",
     .unit = "deg",
     .description = "The scenario's north axis from true north, clockwise (0: the scenario's "
                    "north is true north).",
     .minimum = Bound{-360.0, false, ""},
     .maximum = Bound{360.0, false, ""}},
    {.name = "latitude_deg",
     .unit = "deg",
     .description = "Latitude of the scenario's origin, north positive (WGS84).",
     .required = true,
     .minimum = Bound{-90.0, false, ""},
     .maximum = Bound{90.0, false, ""},
     .interval = true},
    {.name = "longitude_deg",
     .unit = "deg",
     .description = "Longitude of the scenario's origin, east positive (WGS84).",
     .required = true,
     .minimum = Bound{-180.0, false, ""},
     .maximum = Bound{360.0, true, ""}},
};
constexpr Block kOrigin{"Where the scenario's frame sits on the Earth.", kOriginKeys};

constexpr Key kUdpKeys[] = {
    {.name = "address",
     .kind = Kind::kString,
     .description = "The local address to bind (default 0.0.0.0: every interface)."},
    {.name = "group",
     .kind = Kind::kString,
     .description = "A multicast group to join (IPv4, 224.0.0.0/4)."},
    {.name = "interface",
     .kind = Kind::kString,
     .description = "The local interface address on which the group is joined (default: the "
                    "system's choice)."},
    {.name = "port",
     .kind = Kind::kInteger,
     .description = "The UDP port the sentences are sent to.",
     .required = true,
     .minimum = kPortLow,
     .maximum = kPortHigh,
     .interval = true},
};
constexpr Block kUdp{"Datagrams on a UDP port: unicast, broadcast or multicast.", kUdpKeys};

constexpr Key kTcpKeys[] = {
    {.name = "host",
     .kind = Kind::kString,
     .description = "The server's address (a name or an IPv4 address).",
     .required = true},
    {.name = "port",
     .kind = Kind::kInteger,
     .description = "The server's port.",
     .required = true,
     .minimum = kPortLow,
     .maximum = kPortHigh,
     .interval = true},
};
constexpr Block kTcp{"A TCP server the monitor connects to, again after every loss.", kTcpKeys};

constexpr Key kSerialKeys[] = {
    {.name = "baud",
     .kind = Kind::kInteger,
     .description = "Speed: 4800, 9600, 19200, 38400, 57600, 115200 or 230400.",
     .default_json = +[]() -> std::string { return "4800"; }},
    {.name = "device",
     .kind = Kind::kString,
     .description = "The serial device (/dev/ttyS0, /dev/ttyUSB0, ...).",
     .required = true},
    {.name = "parity",
     .kind = Kind::kString,
     .description = "none, even or odd (8 data bits, 1 stop bit).",
     .choices = ChoiceNames<SerialParity>(),
     .choice_noun = ChoiceNoun<SerialParity>()},
};
constexpr Block kSerial{"A serial line.", kSerialKeys};

constexpr Key kFileKeys[] = {
    {.name = "path",
     .kind = Kind::kString,
     .description = "A log file or a named pipe, relative to the configuration's folder.",
     .required = true},
};
constexpr Block kFile{"A recorded log, or a named pipe.", kFileKeys};

constexpr Key kFeedKeys[] = {
    {.name = "file", .kind = Kind::kMap, .description = "Read from a file.", .block = &kFile},
    {.name = "format",
     .kind = Kind::kString,
     .description = "nmea (default): NMEA 0183 sentences; json or csv: the thrust feed's lines.",
     .choices = ChoiceNames<FeedFormat>(),
     .choice_noun = ChoiceNoun<FeedFormat>()},
    {.name = "name",
     .kind = Kind::kString,
     .description = "Unique feed name: letters, digits, _ and -.",
     .required = true},
    {.name = "serial", .kind = Kind::kMap, .description = "Read a serial line.", .block = &kSerial},
    {.name = "tcp", .kind = Kind::kMap, .description = "Connect to a TCP server.", .block = &kTcp},
    {.name = "timing",
     .kind = Kind::kString,
     .description = "When a line was measured: arrival (default; a file: tags), the time it is "
                    "read; tags, its NMEA TAG block's c: (UNIX time), for a recorded log "
                    "(replayed as fast as it reads) or a sender that stamps its sentences (a "
                    "simulated ship played faster than real time).",
     .choices = ChoiceNames<FeedTiming>(),
     .choice_noun = ChoiceNoun<FeedTiming>()},
    {.name = "udp", .kind = Kind::kMap, .description = "Receive UDP datagrams.", .block = &kUdp},
};
constexpr Block kFeed{"One input: exactly one of udp, tcp, serial and file.", kFeedKeys};

constexpr Key kCellKeys[] = {
    {.name = "line",
     .kind = Kind::kInteger,
     .description = "The mooring line whose fairlead tension it reads (from 1).",
     .required = true,
     .minimum = Bound{1.0, false, ""}},
    {.name = "scale",
     .description = "The reading times this is the tension in newtons (1000 for kN).",
     .minimum = kPositive,
     .default_json = +[]() -> std::string { return "1"; }},
    {.name = "transducer",
     .kind = Kind::kString,
     .description = "The XDR transducer name the cell's readings carry.",
     .required = true},
    {.name = "units",
     .kind = Kind::kString,
     .description = "The XDR units field its readings carry (default N).",
     .default_json = +[]() -> std::string { return "\"N\""; }},
};
constexpr Block kCell{"A fairlead load cell read from XDR sentences (type N, force).", kCellKeys};

constexpr Key kThrustKeys[] = {
    {.name = "feed",
     .kind = Kind::kString,
     .description = "The feed that brings it: a json or csv feed, or an nmea feed's XDR.",
     .required = true},
    {.name = "transducers",
     .kind = Kind::kList,
     .description = "For XDR: the transducer names of surge [N], sway [N] and yaw [N m].",
     .item = Kind::kString,
     .min_items = 3,
     .max_items = 3},
};
constexpr Block kThrust{
    "The thrust the position-mooring system's allocation sends, body frame: JSON objects "
    "{\"surge\": N, \"sway\": N, \"yaw\": N m}, CSV rows surge,sway,yaw, or XDR.",
    kThrustKeys};

constexpr Key kBridgeKeys[] = {
    {.name = "listen",
     .kind = Kind::kInteger,
     .description = "The UDP port on which ACK sentences from the bridge are received.",
     .minimum = kPortLow,
     .maximum = kPortHigh,
     .interval = true},
    {.name = "listen_address",
     .kind = Kind::kString,
     .description = "The local address the ACK port is bound to (default 0.0.0.0)."},
    {.name = "repeat",
     .unit = "s",
     .description = "Active alarms' ALR sentences are sent again this often (default 30).",
     .minimum = kPositive,
     .maximum = Bound{3600.0, false, ""}},
    {.name = "send",
     .kind = Kind::kString,
     .description = "host:port the ALR sentences go to (UDP; a broadcast address allowed).",
     .required = true},
    {.name = "talker",
     .kind = Kind::kString,
     .description = "The two-letter talker of the ALR sentences (default MM)."},
};
constexpr Block kBridge{"The bridge alarm system: NMEA 0183 ALR out, ACK in.", kBridgeKeys};

constexpr Key kDisplayKeys[] = {
    {.name = "address",
     .kind = Kind::kString,
     .description = "The address the display is served on (default 127.0.0.1)."},
    {.name = "port",
     .kind = Kind::kInteger,
     .description = "Its port (default 8080; 0: any free one, which the log names).",
     .minimum = Bound{0.0, false, ""},
     .maximum = kPortHigh,
     .interval = true},
    {.name = "watch_circle",
     .unit = "m",
     .description = "The radius of the watch circle drawn around the origin (default none).",
     .minimum = Bound{0.0, false, ""},
     .maximum = Bound{1e5, false, ""}},
};
constexpr Block kDisplay{"The crew's display, a web page the monitor serves.", kDisplayKeys};

constexpr Key kMonitorKeys[] = {
    {.name = "alarms",
     .kind = Kind::kString,
     .description = "Where alarm events go as JSON lines: - (default) for standard output, or a "
                    "file (appended)."},
    {.name = "antenna",
     .kind = Kind::kVector,
     .unit = "m",
     .description = "The GNSS antenna's position on the vessel, body frame (x forward, y "
                    "starboard, z down) from the point the scenario's pose is of.",
     .minimum = Bound{-kMaxBodyCoordinate, false, ""},
     .maximum = Bound{kMaxBodyCoordinate, false, ""}},
    {.name = "bridge",
     .kind = Kind::kMap,
     .description = "Alarms to the bridge.",
     .block = &kBridge},
    {.name = "cells", .kind = Kind::kList, .description = "The load cells.", .block = &kCell},
    {.name = "display", .kind = Kind::kMap, .description = "The display.", .block = &kDisplay},
    {.name = "feeds",
     .kind = Kind::kList,
     .description = "The inputs.",
     .required = true,
     .block = &kFeed,
     .min_items = 1},
    {.name = "max_gap",
     .unit = "s",
     .description = "After this long without position or heading the detection is suspended, "
                    "and starts afresh when they are back (default 60).",
     .minimum = kPositive,
     .maximum = Bound{86400.0, false, ""}},
    {.name = "origin",
     .kind = Kind::kMap,
     .description = "The scenario's frame on the Earth.",
     .required = true,
     .block = &kOrigin},
    {.name = "scenario",
     .kind = Kind::kString,
     .description = "The vessel's scenario, relative to this file's folder.",
     .required = true},
    {.name = "stale_after",
     .unit = "s",
     .description = "A channel without a reading this long is stale (default 3).",
     .minimum = kPositive,
     .maximum = Bound{86400.0, false, ""}},
    {.name = "store",
     .kind = Kind::kString,
     .description = "The folder of the record, relative to this file's folder.",
     .required = true},
    {.name = "thrust", .kind = Kind::kMap, .description = "The thrust feed.", .block = &kThrust},
    {.name = "keep_days",
     .kind = Kind::kInteger,
     .description = "The daily records (lines and samples) older than this many days are "
                    "deleted (default 0: kept); alarms and events are always kept.",
     .minimum = Bound{0.0, false, ""},
     .maximum = Bound{100000.0, false, ""}},
};
constexpr Block kMonitor{"A moorsim monitor configuration.", kMonitorKeys};

}  // namespace

const Block& Monitor() { return kMonitor; }

}  // namespace schema

namespace {

using strict_yaml::ParseContext;
using strict_yaml::Reader;

bool IsName(const std::string& name) {
  if (name.empty()) return false;
  for (const char c : name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
  }
  return true;
}

std::string Resolved(const std::string& config_path, const std::string& given) {
  std::filesystem::path path(given);
  if (path.is_relative()) path = std::filesystem::path(config_path).parent_path() / path;
  return path.lexically_normal().string();
}

std::string NonEmpty(const Reader& reader) {
  std::string text = reader.As<std::string>();
  if (text.empty()) reader.Fail("an empty value");
  return text;
}

FeedConfig ParseFeed(const Reader& item, const std::string& config_path) {
  item.CheckKeys();
  FeedConfig f;
  const Reader name = item.Child("name");
  f.name = name.As<std::string>();
  if (!IsName(f.name)) name.Fail("'" + f.name + "' must be letters, digits, '_' or '-'");
  item.Optional("format", f.format);
  int kinds = 0;
  if (const std::optional<Reader> udp = item.Find("udp")) {
    ++kinds;
    udp->CheckKeys();
    f.kind = FeedConfig::Kind::kUdp;
    f.host = "0.0.0.0";
    if (const std::optional<Reader> address = udp->Find("address")) f.host = NonEmpty(*address);
    f.port = udp->Required<int>("port");
    if (const std::optional<Reader> group = udp->Find("group")) f.group = NonEmpty(*group);
    if (const std::optional<Reader> iface = udp->Find("interface")) {
      f.interface_address = NonEmpty(*iface);
    }
  }
  if (const std::optional<Reader> tcp = item.Find("tcp")) {
    ++kinds;
    tcp->CheckKeys();
    f.kind = FeedConfig::Kind::kTcp;
    f.host = NonEmpty(tcp->Child("host"));
    f.port = tcp->Required<int>("port");
  }
  if (const std::optional<Reader> serial = item.Find("serial")) {
    ++kinds;
    serial->CheckKeys();
    f.kind = FeedConfig::Kind::kSerial;
    f.device = NonEmpty(serial->Child("device"));
    if (const std::optional<Reader> baud = serial->Find("baud")) {
      f.baud = baud->As<int>();
      constexpr int kSpeeds[] = {4800, 9600, 19200, 38400, 57600, 115200, 230400};
      if (std::find(std::begin(kSpeeds), std::end(kSpeeds), f.baud) == std::end(kSpeeds)) {
        baud->Fail(std::to_string(f.baud) +
                   " is not a serial speed (4800, 9600, 19200, 38400, 57600, 115200, 230400)");
      }
    }
    serial->Optional("parity", f.parity);
  }
  if (const std::optional<Reader> file = item.Find("file")) {
    ++kinds;
    file->CheckKeys();
    f.kind = FeedConfig::Kind::kFile;
    f.path = Resolved(config_path, NonEmpty(file->Child("path")));
  }
  if (kinds != 1) {
    item.Fail(kinds == 0 ? "a feed needs one of udp, tcp, serial and file"
                         : "a feed is one of udp, tcp, serial and file, not several");
  }
  f.timing = f.kind == FeedConfig::Kind::kFile ? FeedTiming::kTags : FeedTiming::kArrival;
  item.Optional("timing", f.timing);
  return f;
}

void ParseRoot(const Reader& root, MonitorConfig& c) {
  root.CheckKeys();
  c.scenario_path = Resolved(c.source_path, NonEmpty(root.Child("scenario")));
  {
    const Reader origin = root.Child("origin");
    origin.CheckKeys();
    c.latitude = origin.Required<double>("latitude_deg");
    c.longitude = origin.Required<double>("longitude_deg");
    origin.Optional("grid_north_deg", c.grid_north);
  }
  if (const std::optional<Vec3> antenna = root.Maybe<Vec3>("antenna")) {
    for (int i = 0; i < 3; ++i) c.antenna[i] = (*antenna)(i);
  }
  std::set<std::string> names;
  const std::vector<Reader> feeds = root.Child("feeds").Items();
  if (feeds.empty()) root.Child("feeds").Fail("an empty list (the monitor needs a feed)");
  for (std::size_t i = 0; i < feeds.size(); ++i) {
    FeedConfig f = ParseFeed(feeds[i], c.source_path);
    f.where = strict_yaml::ItemPath("feeds", i);
    if (!names.insert(f.name).second) {
      feeds[i].Child("name").Fail("feed '" + f.name + "' is named twice");
    }
    c.feeds.push_back(std::move(f));
  }
  int replay = 0, tagged = 0;
  for (const FeedConfig& f : c.feeds) {
    replay += f.kind == FeedConfig::Kind::kFile && f.timing == FeedTiming::kTags ? 1 : 0;
    tagged += f.timing == FeedTiming::kTags ? 1 : 0;
  }
  if (replay > 0 && (replay > 1 || c.feeds.size() > 1)) {
    root.Child("feeds").Fail(
        "a file timed by its tags replays a recorded log on the log's own clock: it must be "
        "the only feed");
  }
  if (tagged > 0 && tagged < static_cast<int>(c.feeds.size())) {
    root.Child("feeds").Fail(
        "the feeds are timed on one clock: every feed by its tags, or every feed on arrival");
  }
  if (const std::optional<Reader> cells = root.Find("cells")) {
    std::set<std::string> transducers;
    std::set<int> lines;
    for (const Reader& item : cells->Items()) {
      item.CheckKeys();
      CellConfig cell;
      const Reader transducer = item.Child("transducer");
      cell.transducer = NonEmpty(transducer);
      cell.line = item.Required<int>("line");
      item.Optional("scale", cell.scale);
      if (const std::optional<Reader> units = item.Find("units")) cell.units = NonEmpty(*units);
      if (!transducers.insert(cell.transducer).second) {
        transducer.Fail("transducer '" + cell.transducer + "' is listed twice");
      }
      if (!lines.insert(cell.line).second) {
        item.Child("line").Fail("line " + std::to_string(cell.line) + " has a cell already");
      }
      c.cells.push_back(cell);
    }
  }
  if (const std::optional<Reader> thrust = root.Find("thrust")) {
    thrust->CheckKeys();
    ThrustConfig t;
    const Reader feed = thrust->Child("feed");
    t.feed = NonEmpty(feed);
    const auto found = std::find_if(c.feeds.begin(), c.feeds.end(),
                                    [&](const FeedConfig& f) { return f.name == t.feed; });
    if (found == c.feeds.end()) feed.Fail("no feed is named '" + t.feed + "'");
    if (const std::optional<Reader> names = thrust->Find("transducers")) {
      for (const Reader& name : names->Items()) t.transducers.push_back(NonEmpty(name));
      if (t.transducers.size() != 3) names->Fail("three names: surge, sway and yaw");
    }
    if (found->format == FeedFormat::kNmea && t.transducers.empty()) {
      feed.Fail("feed '" + t.feed +
                "' sends NMEA: name the XDR transducers of surge, sway and yaw (transducers: "
                "[..., ..., ...])");
    }
    if (found->format != FeedFormat::kNmea && !t.transducers.empty()) {
      thrust->Child("transducers")
          .Fail("feed '" + t.feed + "' sends " + std::string(ChoiceName(found->format)) +
                " rows, not XDR");
    }
    c.thrust = t;
  }
  for (std::size_t i = 0; i < c.feeds.size(); ++i) {
    const FeedConfig& f = c.feeds[i];
    if (f.format != FeedFormat::kNmea && !(c.thrust && c.thrust->feed == f.name)) {
      feeds[i].Child("format").Fail("a " + std::string(ChoiceName(f.format)) +
                                    " feed brings thrust: name it in thrust.feed");
    }
  }
  root.Optional("stale_after", c.stale_after);
  root.Optional("keep_days", c.keep_days);
  root.Optional("max_gap", c.max_gap);
  c.store = Resolved(c.source_path, NonEmpty(root.Child("store")));
  if (const std::optional<Reader> alarms = root.Find("alarms")) {
    const std::string given = NonEmpty(*alarms);
    c.alarms = given == "-" ? given : Resolved(c.source_path, given);
  }
  if (const std::optional<Reader> bridge = root.Find("bridge")) {
    bridge->CheckKeys();
    BridgeConfig b;
    const Reader send = bridge->Child("send");
    const std::string text = NonEmpty(send);
    const std::size_t colon = text.rfind(':');
    int port = 0;
    if (colon != std::string::npos && colon > 0 && colon + 1 < text.size() &&
        text.find_first_not_of("0123456789", colon + 1) == std::string::npos &&
        text.size() - colon - 1 <= 5) {
      port = std::stoi(text.substr(colon + 1));
    }
    if (port < 1 || port > 65535) send.Fail("'" + text + "' must be host:port (port 1..65535)");
    b.send_host = text.substr(0, colon);
    b.send_port = port;
    bridge->Optional("listen", b.listen_port);
    if (const std::optional<Reader> address = bridge->Find("listen_address")) {
      b.listen_address = NonEmpty(*address);
    }
    if (const std::optional<Reader> talker = bridge->Find("talker")) {
      b.talker = talker->As<std::string>();
      if (b.talker.size() != 2 || !std::isupper(static_cast<unsigned char>(b.talker[0])) ||
          !std::isupper(static_cast<unsigned char>(b.talker[1]))) {
        talker->Fail("'" + b.talker + "' must be two capital letters");
      }
    }
    bridge->Optional("repeat", b.repeat);
    c.bridge = b;
  }
  if (const std::optional<Reader> display = root.Find("display")) {
    display->CheckKeys();
    DisplayConfig d;
    if (const std::optional<Reader> address = display->Find("address")) {
      d.address = NonEmpty(*address);
    }
    display->Optional("port", d.port);
    display->Optional("watch_circle", d.watch_circle);
    c.display = d;
  }
}

}  // namespace

bool MonitorConfig::Replay() const {
  return feeds.size() == 1 && feeds[0].kind == FeedConfig::Kind::kFile &&
         feeds[0].timing == FeedTiming::kTags;
}

MonitorConfig ParseMonitorConfig(const std::string& yaml_text, const std::string& source_name) {
  MonitorConfig c;
  c.source_path = source_name;
  std::map<std::string, SourceMark> marks;
  ParseContext context;
  context.file = source_name;
  context.marks = &marks;
  context.text = &yaml_text;
  try {
    const YAML::Node document =
        strict_yaml::LoadDocument(yaml_text, source_name, "monitor configuration", "scenario");
    const Reader root(context, document, "", strict_yaml::ToSourceMark(document.Mark()),
                      &schema::Monitor());
    ParseRoot(root, c);
  } catch (const YAML::Exception& error) {
    strict_yaml::ThrowAt(source_name, strict_yaml::ToSourceMark(error.mark), "", error.msg);
  }
  return c;
}

MonitorConfig LoadMonitorConfig(const std::string& path) {
  constexpr std::size_t kMaxConfigBytes = 1 << 20;
  return ParseMonitorConfig(
      strict_yaml::ReadInputFile(path, kMaxConfigBytes, "monitor configuration"), path);
}

}  // namespace moorsim::scenarios
