#include "monitor/service.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <deque>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/version.h"
#include "monitor/alarms.h"
#include "monitor/display.h"
#include "monitor/feeds.h"
#include "monitor/ingest.h"
#include "monitor/nmea.h"
#include "monitor/store.h"
#include "simulation/detection.h"
#include "simulation/latency.h"
#include "simulation/simulation.h"

namespace moorsim::monitor {
namespace {

/// The samples whose positions the display draws as the vessel's track (at 1 Hz, 15 min).
constexpr std::size_t kTrack = 900;

std::string ReadWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// "2026-12-07T16:40:00.123Z".
std::string UtcText(double unix_time) {
  const auto seconds = static_cast<std::time_t>(std::floor(unix_time));
  const int ms = static_cast<int>(std::floor((unix_time - std::floor(unix_time)) * 1000.0));
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[96];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, ms);
  return text;
}

const char* ChangeName(AlarmChange::Kind kind) {
  switch (kind) {
    case AlarmChange::Kind::kRaised:
      return "raised";
    case AlarmChange::Kind::kCleared:
      return "cleared";
    case AlarmChange::Kind::kAcknowledged:
      return "acknowledged";
  }
  return "";
}

int SensorAlarm(const detectors::SensorId& sensor) {
  switch (sensor.kind) {
    case detectors::SensorId::Kind::kGnss:
      return 200;
    case detectors::SensorId::Kind::kGyro:
      return 201;
    case detectors::SensorId::Kind::kPose:
      return 202;
    case detectors::SensorId::Kind::kCell:
      return 210 + sensor.line;
  }
  return 299;
}

}  // namespace

nlohmann::json MonitorSummary::Json() const {
  return {{"lines", lines},
          {"samples", samples},
          {"events", events},
          {"alarm_changes", alarm_changes},
          {"segments", segments},
          {"warmed_seconds", warmed_seconds},
          {"sample_latency", sample_latency},
          {"alarm_latency", alarm_latency}};
}

struct Monitor::Parts {
  scenarios::MonitorConfig config;
  MonitoredVessel vessel;  // its model is what the detection is built from
  MonitorOptions options;
  int lines = 0;
  std::unique_ptr<simulation::Detection> detection;
  std::vector<std::string> labels;
  std::vector<std::array<int, 2>> failed_lines;
  std::vector<std::size_t> seen;  // per detector, the events announced
  std::unique_ptr<Store> store;
  std::unique_ptr<Ingest> ingest;
  Poller poller;
  std::unique_ptr<Feeds> feeds;
  std::unique_ptr<TaggedLog> log;
  AlarmBoard board;
  std::int64_t segment = 0;
  bool warmed = false;  // the detection continues the recorded past
  bool ever_active = false;
  double started = 0.0;  // UNIX time the monitor started (or the replay's first line)
  double now = 0.0;      // the monitor's clock: the system's, or the replayed line's
  double last_commit = 0.0;
  double last_tag_wall = 0.0;  // when the latest tag was read (feeds timed by tags)
  double next_repeat = 0.0;
  int send_fd = -1, ack_fd = -1;
  sockaddr_in send_to{};
  std::FILE* alarms = stdout;
  bool alarms_owned = false;
  MonitorSummary summary;
  // From the arrival of the line that completed a sample to its events recorded and
  // printed, and, for samples that changed an alarm, to its ALR sent [ms].
  simulation::Latency sample_latency, alarm_latency;
  std::vector<FeedHealth> feed_health;      // as last logged
  std::vector<bool> stale;                  // per channel, as last logged
  std::deque<std::array<double, 2>> track;  // the latest samples' positions
  std::unique_ptr<DisplayServer> display;
  bool alarms_changed = false;  // since the display was last sent the state

  ~Parts() {
    if (send_fd >= 0) ::close(send_fd);
    if (ack_fd >= 0) ::close(ack_fd);
    if (alarms_owned) std::fclose(alarms);
  }

  void Log(const std::string& line) const {
    if (options.log) options.log(line);
  }

  void Emit(const nlohmann::ordered_json& line) {
    const std::string text = line.dump();
    std::fprintf(alarms, "%s\n", text.c_str());
    std::fflush(alarms);
  }

  void NewDetection() {
    detection = simulation::MakeDetection(vessel.model, vessel.seed);
    seen.assign(detection->records().size(), 0);
  }

  /// One sample through the detection; its events recorded, then printed.
  void TakeSample(const Sample& sample, bool announce) {
    if (sample.starts_segment) {
      ++segment;
      ++summary.segments;
      store->SegmentStarted(segment);
      if (!warmed) NewDetection();
      warmed = false;
      ever_active = true;
      Log("detection: segment " + std::to_string(segment) +
          " starts at t = " + FormatNumber(sample.observation.t) + " s");
    }
    store->SampleTaken(sample, segment);
    if (sample.observation.valid[0]) {
      track.push_back({sample.observation.pose(0), sample.observation.pose(1)});
      if (track.size() > kTrack) track.pop_front();
    }
    const auto start = std::chrono::steady_clock::now();
    detection->Update(sample.observation);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ++summary.samples;
    for (std::size_t i = 0; i < seen.size(); ++i) {
      const simulation::DetectorRecord& record = detection->records()[i];
      for (; seen[i] < record.history.events().size(); ++seen[i]) {
        if (!announce) continue;
        const nlohmann::ordered_json event = simulation::AlarmEventJson(
            record, record.history.events()[seen[i]], detection->verdicts()[i], labels, lines, ms);
        store->Event(now, event.dump());
        Emit(event);
        ++summary.events;
      }
    }
  }

  /// The samples the ingest closed, each through the detection and the alarms.
  void TakeSamples() {
    for (const Sample& sample : ingest->TakeSamples()) {
      TakeSample(sample, true);
      const long changes = summary.alarm_changes;
      UpdateAlarms();
      const double ms = 1e3 * (UnixNow() - sample.arrival);
      sample_latency.Add(ms);
      if (summary.alarm_changes > changes) alarm_latency.Add(ms);
    }
  }

  /// The conditions that hold now, and the alarm changes they make.
  void UpdateAlarms() {
    std::map<int, std::string> holding;
    if (detection && ingest->active()) {
      const std::vector<detectors::Verdict>& verdicts = detection->verdicts();
      for (const detectors::Verdict& v : verdicts) {
        if (v.alarm && v.hypothesis > 0) {
          for (const int line : failed_lines.at(static_cast<std::size_t>(v.hypothesis))) {
            if (line > 0) holding[line] = "Mooring line " + std::to_string(line) + " parted";
          }
        }
        for (const detectors::SensorFinding& f : v.faulty_sensors) {
          holding[SensorAlarm(f.sensor)] = f.sensor.Name() + " judged faulty (" +
                                           std::string(detectors::SensorSymptomName(f.symptom)) +
                                           ")";
        }
      }
    }
    const std::vector<ChannelHealth>& channels = ingest->channels();
    stale.resize(channels.size(), false);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      const double since = std::max(channels[c].last, started);
      const bool is_stale = now - since > config.stale_after;
      if (is_stale) {
        std::string name = channels[c].name;
        name[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(name[0])));
        holding[100 + static_cast<int>(c)] =
            name + " stale: nothing for " + FormatNumber(config.stale_after) + " s";
      }
      if (is_stale != stale[c]) {
        stale[c] = is_stale;
        Log("channel " + channels[c].name + ": " + (is_stale ? "stale" : "reading again"));
        store->Health(now, "channel " + channels[c].name + (is_stale ? ": stale" : ": fresh"));
      }
    }
    if (ever_active && !ingest->active()) {
      holding[300] =
          "Detection suspended: no position or heading for " + FormatNumber(config.max_gap) + " s";
    }
    for (const AlarmChange& change : board.Update(holding, now)) Announce(change);
  }

  void Announce(AlarmChange change) {
    alarms_changed = true;
    const std::int64_t id = store->Change(change);
    if (change.kind == AlarmChange::Kind::kRaised) {
      change.alarm.id = id;
      board.SetId(change.alarm.number, id);
    }
    ++summary.alarm_changes;
    nlohmann::ordered_json line;
    line["unix"] = now;
    line["utc"] = UtcText(now);
    line["alarm"] = change.alarm.number;
    line["state"] = ChangeName(change.kind);
    line["text"] = change.alarm.text;
    if (change.kind == AlarmChange::Kind::kAcknowledged) line["by"] = change.alarm.acknowledged_by;
    Emit(line);
    SendAlr(change.alarm);
  }

  void SendAlr(const Alarm& alarm) {
    if (send_fd < 0) return;
    const std::string sentence = AlrSentence(config.bridge->talker, alarm) + "\r\n";
    if (::sendto(send_fd, sentence.data(), sentence.size(), 0,
                 reinterpret_cast<const sockaddr*>(&send_to), sizeof send_to) < 0) {
      Log("bridge: cannot send ALR: " + std::string(std::strerror(errno)));
    }
  }

  /// The listed alarms again every `repeat` seconds of the system's clock (a replay sends
  /// none again).
  void RepeatAlr() {
    const double wall = UnixNow();
    if (send_fd < 0 || log || wall < next_repeat) return;
    for (const auto& [number, alarm] : board.listed()) SendAlr(alarm);
    next_repeat = wall + config.bridge->repeat;
  }

  void ReadAcks() {
    char datagram[1024];
    for (int i = 0; i < 16; ++i) {
      const ssize_t n = ::recv(ack_fd, datagram, sizeof datagram, 0);
      if (n <= 0) return;
      std::istringstream lines(std::string(datagram, static_cast<std::size_t>(n)));
      std::string line;
      while (std::getline(lines, line)) {
        const NmeaParse parse = ParseNmea(line);
        std::string why;
        const std::optional<int> number =
            parse.sentence ? AckNumber(*parse.sentence, &why) : std::nullopt;
        if (!number) {
          if (!line.empty() && line != "\r") {
            Log("bridge: not an ACK: " + (parse.sentence ? why : parse.detail));
          }
          continue;
        }
        Acknowledge(*number, "bridge");
      }
    }
  }

  bool Acknowledge(int number, const std::string& by) {
    const std::optional<AlarmChange> change = board.Acknowledge(number, now, by);
    if (!change) return false;
    Announce(*change);
    return true;
  }

  void LogFeeds() {
    if (!feeds) return;
    const std::vector<FeedHealth> health = feeds->Health();
    feed_health.resize(health.size());
    for (std::size_t i = 0; i < health.size(); ++i) {
      const FeedHealth& h = health[i];
      FeedHealth& was = feed_health[i];
      if (h.connected != was.connected || h.problem != was.problem) {
        const std::string what = "feed " + h.name + " (" + h.kind + " " + h.endpoint +
                                 "): " + (h.connected ? std::string("up") : "down") +
                                 (h.problem.empty() ? "" : ", " + h.problem);
        Log(what);
        store->Health(now, what);
      }
      was = h;
    }
  }

  void Line(const FeedLine& line) {
    ++summary.lines;
    if (config.Tagged() && line.stamp >= now) {
      now = line.stamp;
      last_tag_wall = UnixNow();
    }
    store->Line(line);
    ingest->Take(line);
    TakeSamples();
  }

  void Publish() {
    if (!display) return;
    display->Publish(alarms_changed);
    alarms_changed = false;
  }

  void Tick() {
    ingest->Advance(now, UnixNow());
    TakeSamples();
    UpdateAlarms();
    RepeatAlr();
    Publish();
    if (now - last_commit >= 1.0) {
      store->Commit();
      last_commit = now;
    }
  }

  void Warm() {
    const double tau = now - store->epoch();
    const std::vector<StoredSample> past = store->RecentSamples(tau - config.max_gap - kWarmUp);
    segment = store->LastSegment();
    if (past.empty() || past.back().observation.t < tau - config.max_gap) {
      Log("store: resumed; the last samples are older than max_gap, the detection starts afresh");
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    NewDetection();
    for (const StoredSample& s : past) detection->Update(s.observation);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    for (std::size_t i = 0; i < seen.size(); ++i) {
      seen[i] = detection->records()[i].history.events().size();
    }
    ingest->Resume(past.back().index, past.back().observation);
    warmed = true;
    summary.warmed_seconds = past.back().observation.t - past.front().observation.t;
    Log("store: resumed; observers warmed on " + FormatNumber(summary.warmed_seconds) +
        " s of recorded samples (" + std::to_string(past.size()) + " samples, " +
        FormatNumber(std::round(took * 1000.0)) + " ms)");
  }
};

Monitor::Monitor(const scenarios::MonitorConfig& config, const MonitoredVessel& vessel,
                 MonitorOptions options)
    : parts_(std::make_unique<Parts>()) {
  Parts& p = *parts_;
  p.config = config;
  p.vessel = vessel;
  p.options = std::move(options);
  const simulation::PlantModel& model = vessel.model;
  p.lines = static_cast<int>(model.mooring.lines.size());
  if (!model.detection || model.detection->detectors.empty()) {
    throw InputError(config.scenario_path + ": the scenario has no detectors to run");
  }
  const double rate = model.pose_sensors.gnss_rate;
  if (rate != model.pose_sensors.gyro_rate) {
    throw InputError(config.scenario_path +
                     ": sensors.gnss.rate_hz and sensors.gyro.rate_hz differ; the monitor "
                     "samples both on one clock");
  }
  p.NewDetection();
  p.labels = p.detection->HypothesisLabels();
  p.failed_lines = p.detection->FailedLines();

  StoreIdentity identity;
  identity.config_path = config.source_path;
  identity.config_text = ReadWhole(config.source_path);
  identity.scenario_path = vessel.source_path;
  identity.scenario_text = vessel.source_text;
  identity.version = kVersion;

  FeedLine first;
  const bool replay = config.Replay();
  if (replay) {
    p.log = std::make_unique<TaggedLog>(config.feeds[0].path, 0);
    if (!p.log->Next(&first)) {
      throw InputError(config.feeds[0].path + ": no line with a TAG block time (\\c:...*hh\\)");
    }
    p.now = first.stamp;
  } else {
    p.now = UnixNow();
  }
  p.started = p.now;
  p.store = std::make_unique<Store>(config.store, identity, p.now, config.keep_days);
  if (replay && p.store->resumed()) {
    throw InputError(config.store +
                     ": a replay records into a store of its own: give an empty "
                     "folder");
  }
  Waits waits;
  waits.cells = model.tension_cells && model.tension_cells->rate >= rate;
  waits.thrust = model.controller.rate >= rate;
  p.ingest = std::make_unique<Ingest>(config, p.lines, rate, p.store->epoch(), waits);
  if (p.store->resumed()) {
    p.board.Restore(p.store->ListedAlarms());
    p.Log("store: " + std::to_string(p.board.listed().size()) + " alarms listed as they were");
    p.Warm();
  }
  if (config.alarms != "-") {
    p.alarms = std::fopen(config.alarms.c_str(), "a");
    if (p.alarms == nullptr) {
      p.alarms = stdout;
      throw InputError(config.alarms + ": cannot append alarm lines: " + std::strerror(errno));
    }
    p.alarms_owned = true;
  }
  if (config.bridge) {
    const scenarios::BridgeConfig& b = *config.bridge;
    p.send_to = ResolveIpv4(b.send_host, b.send_port, "bridge.send");
    p.send_fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    const int one = 1;
    ::setsockopt(p.send_fd, SOL_SOCKET, SO_BROADCAST, &one, sizeof one);
    if (b.listen_port > 0) {
      p.ack_fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
      ::setsockopt(p.ack_fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
      sockaddr_in local = ResolveIpv4(b.listen_address, b.listen_port, "bridge.listen_address");
      if (::bind(p.ack_fd, reinterpret_cast<const sockaddr*>(&local), sizeof local) != 0) {
        throw InputError("bridge.listen: cannot listen on " + b.listen_address + ":" +
                         std::to_string(b.listen_port) + ": " + std::strerror(errno));
      }
      p.poller.Add(p.ack_fd, POLLIN, [&p](short) { p.ReadAcks(); });
    }
  }
  if (replay) {
    p.Line(first);
  } else {
    p.feeds =
        std::make_unique<Feeds>(config.feeds, &p.poller, [&p](FeedLine line) { p.Line(line); });
    if (config.display) {
      p.display = std::make_unique<DisplayServer>(
          *config.display, &p.poller, [this] { return State().dump(); },
          [&p](int number) { return p.Acknowledge(number, "display"); });
      p.Log("display: http://" + config.display->address + ":" + std::to_string(p.display->port()) +
            "/");
    }
  }
}

Monitor::~Monitor() = default;

MonitorSummary Monitor::Run() {
  Parts& p = *parts_;
  const auto stop = [&] { return p.options.stop && p.options.stop(); };
  if (p.log) {
    FeedLine line;
    while (!stop() && p.log->Next(&line)) {
      p.now = line.stamp;
      p.Line(line);
      p.UpdateAlarms();
      if (p.now - p.last_commit >= 1.0) {
        p.store->Commit();
        p.last_commit = p.now;
      }
    }
    p.store->Commit();
    p.summary.sample_latency = p.sample_latency.Summary();
    p.summary.alarm_latency = p.alarm_latency.Summary();
    return p.summary;
  }
  // The clock: the system's, or with feeds timed by their tags the latest tag read (the
  // sender's time, which may run faster than the system's).
  const bool tagged = p.config.Tagged();
  while (!stop()) {
    const double wall = UnixNow();
    double wanted = std::min(p.feeds->Maintain(wall), wall + 0.2);
    if (!tagged) wanted = std::min(wanted, p.ingest->NextDeadline());
    p.LogFeeds();
    const int wait_ms = static_cast<int>(std::clamp((wanted - wall) * 1000.0, 0.0, 200.0));
    p.poller.Wait(wait_ms);
    if (!tagged) {
      p.now = UnixNow();
    } else if (p.last_tag_wall > 0.0) {
      // Nothing for a second: the clock runs on with the system's, so that silent feeds
      // go stale and a stopped sender is seen.
      const double quiet = UnixNow() - p.last_tag_wall - 1.0;
      if (quiet > 0.0) {
        p.now += quiet;
        p.last_tag_wall += quiet;
      }
    }
    p.Tick();
  }
  p.store->Commit();
  p.summary.sample_latency = p.sample_latency.Summary();
  p.summary.alarm_latency = p.alarm_latency.Summary();
  return p.summary;
}

nlohmann::json Monitor::State() const {
  const Parts& p = *parts_;
  const auto number = [](double x) {
    return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
  };
  nlohmann::json state;
  state["scenario"] = p.vessel.name;
  state["now"] = p.now;
  state["wall"] = UnixNow();  // the system's clock, which the feeds' times are on
  state["epoch"] = p.store->epoch();
  state["detecting"] = p.ingest->active();
  state["segment"] = p.segment;
  const Vec3& pose = p.ingest->latest_pose();
  state["vessel"] = {
      {"north", number(pose(0))}, {"east", number(pose(1))}, {"heading", number(pose(2))}};
  const simulation::PlantModel& model = p.vessel.model;
  state["hull"] = {{"length", p.vessel.hull_length}, {"beam", p.vessel.hull_beam}};
  state["turret"] = {model.turret.x, model.turret.y};
  nlohmann::json track = nlohmann::json::array();
  for (const auto& point : p.track) track.push_back({point[0], point[1]});
  state["track"] = track;
  state["watch_circle"] = p.config.display && p.config.display->watch_circle > 0.0
                              ? nlohmann::json(p.config.display->watch_circle)
                              : nlohmann::json(nullptr);

  // A line is parted while an active alarm names it; unknown while nothing is detected.
  const VecX& measured = p.ingest->latest_tensions();
  const std::optional<VecX> expected =
      p.detection ? p.detection->expected_tensions() : std::nullopt;
  const double noise = model.tension_cells ? model.tension_cells->noise.std_dev : 0.0;
  nlohmann::json lines = nlohmann::json::array();
  for (int k = 1; k <= p.lines; ++k) {
    const mooring_fem::LineParameters& spec = model.mooring.lines[static_cast<std::size_t>(k - 1)];
    const auto alarm = p.board.listed().find(k);
    const bool parted = alarm != p.board.listed().end() && alarm->second.Active();
    const double e = expected ? (*expected)(k - 1) : kNaN;
    lines.push_back({{"line", k},
                     {"anchor", {spec.anchor(0), spec.anchor(1)}},
                     {"fairlead_body", {spec.fairlead_body(0), spec.fairlead_body(1)}},
                     {"state", parted ? "parted" : (p.ingest->active() ? "intact" : "unknown")},
                     {"measured", number(measured(k - 1))},
                     {"expected", number(e)},
                     // The band: three times the cells' noise, or a tenth of what is
                     // expected, whichever is wider.
                     {"band", number(std::max(3.0 * noise, 0.1 * std::abs(e)))}});
  }
  state["lines"] = lines;

  nlohmann::json detectors = nlohmann::json::array();
  for (std::size_t i = 0; p.detection && i < p.detection->records().size(); ++i) {
    const simulation::DetectorRecord& r = p.detection->records()[i];
    const detectors::Verdict& v = p.detection->verdicts()[i];
    const std::size_t h = static_cast<std::size_t>(v.hypothesis);
    detectors.push_back(
        {{"label", r.label},
         {"type", r.type},
         {"alarm", v.alarm},
         {"hypothesis", h < p.labels.size() ? p.labels[h] : std::string("?")},
         {"score", h < v.score.size() ? number(v.score[h]) : nlohmann::json(nullptr)},
         {"threshold", r.threshold ? nlohmann::json(*r.threshold) : nlohmann::json(nullptr)}});
  }
  state["detectors"] = detectors;

  nlohmann::json alarms = nlohmann::json::array();
  for (const auto& [n, a] : p.board.listed()) {
    alarms.push_back({{"number", n},
                      {"text", a.text},
                      {"raised", a.raised},
                      {"active", a.Active()},
                      {"acknowledged", a.acknowledged.has_value()}});
  }
  state["alarms"] = alarms;

  nlohmann::json feeds = nlohmann::json::array();
  if (p.feeds) {
    const std::vector<FeedHealth> health = p.feeds->Health();
    for (std::size_t i = 0; i < health.size(); ++i) {
      const FeedHealth& h = health[i];
      const FeedCounts& counts = p.ingest->feeds()[i];
      feeds.push_back({{"name", h.name},
                       {"kind", h.kind},
                       {"endpoint", h.endpoint},
                       {"connected", h.connected},
                       {"lines", h.lines},
                       {"sentences", counts.sentences},
                       {"faults", counts.Faults() + h.overlong + h.untimed},
                       {"fault_kinds", counts.faults},
                       {"overlong", h.overlong},
                       {"ignored", counts.ignored},
                       {"last_fault", counts.last_fault},
                       {"problem", h.problem},
                       {"last_line", h.last_line}});
    }
  }
  state["feeds"] = feeds;
  nlohmann::json channels = nlohmann::json::array();
  for (const ChannelHealth& c : p.ingest->channels()) {
    channels.push_back({{"name", c.name},
                        {"feed", c.feed},
                        {"readings", c.readings},
                        {"rejected", c.rejected},
                        {"last", c.last},
                        {"stale", c.Stale(p.now, p.config.stale_after)},
                        {"problem", c.problem},
                        {"detail", c.detail}});
  }
  state["channels"] = channels;
  return state;
}

}  // namespace moorsim::monitor
