// `moorsim detect`: the observer bank and a scenario's detectors on a recorded or live pose
// stream, without the plant (simulation/pose_stream.h has the input formats). Every
// alarm event is printed as one JSON line on standard output the moment the sample that
// raised it has been processed; --out DIR also keeps alarms.csv, detect.h5 (the figures of
// tools/plot_run.py) and summary.json (DetectOutputs says how they survive a kill).
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <thread>
#include <utility>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/format.h"
#include "core/types.h"
#include "core/version.h"
#include "detectors/registry.h"
#include "io/csv_table.h"
#include "io/directory_lock.h"
#include "io/hdf5_file.h"
#include "io/hdf5_reader.h"
#include "io/text_file.h"
#include "monitor/store.h"
#include "runner/run.h"
#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "simulation/detection_tables.h"
#include "simulation/followed_file.h"
#include "simulation/latency.h"
#include "simulation/output_layout.h"
#include "simulation/pose_stream.h"
#include "simulation/simulation.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

namespace fs = std::filesystem;
using simulation::Detection;

struct DetectOptions {
  std::string input;
  std::optional<std::string> scenario;
  std::vector<std::string> sets;
  std::optional<std::string> out;
  std::optional<std::string> max_gap;
  std::optional<std::string> flush_interval;
  std::optional<std::string> from, to;
  bool follow = false;
  bool quiet = false;
};

/// How much of a live monitor's detect.h5 and alarms.csv a kill may lose at most [s].
constexpr double kDefaultFlushInterval = 10.0;

/// Lines of a stream read to its end (a file, or standard input until it closes); a last
/// line without its newline counts. `waiting` is called about every 50 ms while the
/// descriptor `poll_fd` (standard input, or -1) is quiet. A followed file is read by
/// simulation::FollowedFile.
class LineSource {
 public:
  LineSource(std::istream& in, int poll_fd, std::function<void()> waiting)
      : in_(in), poll_fd_(poll_fd), waiting_(std::move(waiting)) {}
  bool Next(std::string* line) {
    if (poll_fd_ >= 0) AwaitInput();
    return static_cast<bool>(std::getline(in_, *line));
  }

 private:
  /// Returns once the stream has something buffered, or poll_fd_ is readable (or at its
  /// end, or a signal came).
  void AwaitInput() {
    while (in_.rdbuf()->in_avail() == 0) {
      pollfd ready = {poll_fd_, POLLIN, 0};
      if (::poll(&ready, 1, 50) != 0) return;
      waiting_();
    }
  }

  std::istream& in_;
  int poll_fd_;
  std::function<void()> waiting_;
};

/// One line on stderr when a followed log rotates: what happened and what is read next.
void ReportRotation(const std::string& path, simulation::Rotation rotation,
                    std::size_t dropped_bytes) {
  std::string what;
  switch (rotation) {
    case simulation::Rotation::kTruncated:
    case simulation::Rotation::kRewritten:
      what = std::string(simulation::RotationName(rotation)) + "; following it from its start";
      break;
    case simulation::Rotation::kReplaced:
      what = "replaced by a new file; following the new file from its start";
      break;
    case simulation::Rotation::kMissing:
      what = "moved or removed; reading on what was open and waiting for a file at this path";
      break;
  }
  if (dropped_bytes > 0) {
    what += " (an unfinished last line of " + std::to_string(dropped_bytes) + " bytes dropped)";
  }
  std::cerr << "moorsim detect: " << path << ": " << what << std::endl;
}

/// detect.h5: what tools/plot_run.py draws of a run that detection alone can give (the
/// measured pose, the thrust given, the observers' load picture and every detector's
/// verdict per sample), with the identity of the input and the scenario.
class DetectWriter {
 public:
  DetectWriter(output::Hdf5File file, const scenarios::Scenario& scenario, const std::string& input,
               const Detection& detection)
      : file_(std::move(file)) {
    file_.SetAttribute("/", "scenario", scenario.text);
    file_.SetAttribute("/", "scenario_name", scenario.name);
    file_.SetAttribute("/", "scenario_path", scenario.source_path);
    file_.SetAttribute("/", "input", input);
    file_.SetAttribute("/", "version", std::string(moorsim::kVersion));
    file_.SetAttribute("/", "failure_line", static_cast<std::int64_t>(scenario.failure.line));
    file_.SetAttribute("/", "failure_time",
                       scenario.failure.line > 0 ? scenario.failure.time : kNaN);
    time_ = simulation::layout::Create(file_, simulation::layout::kTime);
    pose_ = simulation::layout::Create(file_, simulation::layout::kPoseMeasured);
    thrust_ = simulation::layout::Create(file_, simulation::layout::kThrustDelivered);
    tables_.emplace(file_, &detection);
  }

  void Append(const detectors::Observation& o, const Detection& detection) {
    file_.Append(time_, o.t);
    Vec3 pose = o.pose;
    for (int i = 0; i < 3; ++i) {
      if (!o.valid[i]) pose(i) = kNaN;
    }
    Row(pose_, pose);
    Row(thrust_, o.tau_command);
    tables_->Append(file_, detection.bias(), detection.wave_motion(), detection.verdicts());
  }
  void Flush() { file_.Flush(); }
  void Close() { file_.Close(); }

 private:
  void Row(output::TableId table, const Vec3& v) {
    file_.Append(table, std::span<const double>(v.data(), 3));
  }
  output::Hdf5File file_;
  output::TableId time_, pose_, thrust_;
  std::optional<simulation::DetectionTables> tables_;
};

std::string CsvCell(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return output::CsvField(value.get<std::string>());
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  return FormatNumber(value.get<double>());
}

/// DIR of `detect --out`: detect.h5, alarms.csv and summary.json, written by this process
/// alone (output::DirectoryLock). The previous run's outputs go first, summary.json first,
/// so DIR never mixes two runs.
///
/// A finite input (a file without --follow) writes detect.h5 and alarms.csv under ".partial"
/// names and renames them into place when complete, then writes summary.json: a kill or a
/// full disk leaves no partial file under a final name, and a failure removes the partial
/// files. A live input (--follow, or standard input) writes them under their final names:
/// detect.h5 appears once its tables exist and it opens, and both files are made durable
/// (HDF5's metadata written only then, fsync) every flush interval and at every alarm
/// before the alarm is printed, so a kill or a power loss loses at most the rows of the
/// last flush interval.
class DetectOutputs {
 public:
  DetectOutputs(const fs::path& dir, bool live, double flush_interval,
                const scenarios::Scenario& scenario, const std::string& input,
                const Detection& detection)
      : dir_(dir), live_(live), flush_interval_(flush_interval), lock_(dir) {
    for (const char* name :
         {"summary.json", "detect.h5", "alarms.csv", "detect.h5.partial", "alarms.csv.partial"}) {
      std::error_code error;
      fs::remove(dir_ / name, error);
      if (error) {
        throw Error((dir_ / name).string() +
                    ": cannot remove the previous run's file: " + error.message());
      }
    }
    try {
      output::Hdf5FileOptions options;
      options.durable_flushes = live_;
      output::Hdf5File file(Partial("detect.h5").string(), options);
      created_ = true;
      writer_.emplace(std::move(file), scenario, input, detection);
      alarms_.emplace(live_ ? dir_ / "alarms.csv" : Partial("alarms.csv"));
      alarms_->Write("time,detector,type,event,hypothesis,line,score\n");
      if (live_) {
        Flush();
        Publish("detect.h5");
      }
    } catch (...) {
      Abandon();
      throw;
    }
  }
  ~DetectOutputs() {
    if (!finished_) Abandon();
  }
  DetectOutputs(const DetectOutputs&) = delete;
  DetectOutputs& operator=(const DetectOutputs&) = delete;

  /// One sample's rows and its new alarm events; live, durable at once if there are events
  /// (the caller prints them after this returns) or the flush interval has passed.
  void Take(const detectors::Observation& observation, const Detection& detection,
            const std::vector<nlohmann::ordered_json>& events) {
    writer_->Append(observation, detection);
    for (const nlohmann::ordered_json& event : events) {
      std::string line = CsvCell(event["time"]);
      for (const char* key : {"detector", "type", "event", "hypothesis", "line", "score"}) {
        line += ',' + CsvCell(event[key]);
      }
      alarms_->Write(line + '\n');
    }
    unflushed_ = true;
    if (live_ && (!events.empty() || IntervalPassed())) Flush();
  }
  /// The input has nothing new: live, rows still only in memory become durable once the
  /// flush interval has passed.
  void Idle() {
    if (live_ && unflushed_ && IntervalPassed()) Flush();
  }
  /// Closes both files, puts them in place and writes summary.json.
  void Finish(const nlohmann::json& summary) {
    writer_->Close();
    alarms_->Close();
    if (!live_) {
      Publish("detect.h5");
      Publish("alarms.csv");
    }
    finished_ = true;
    runner::WriteFileAtomically(dir_ / "summary.json", summary.dump(2) + "\n");
  }

 private:
  fs::path Partial(const std::string& name) const { return output::PartialPath(dir_ / name); }
  bool IntervalPassed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - last_flush_).count() >=
           flush_interval_;
  }
  void Flush() {
    writer_->Flush();
    alarms_->Sync();
    unflushed_ = false;
    last_flush_ = std::chrono::steady_clock::now();
  }
  void Publish(const std::string& name) { output::PublishPartial(dir_ / name); }
  /// After a failure: closes what is open (its own failures are not news) and removes the
  /// partial files this run created. A live file stays: it holds the last flush.
  void Abandon() noexcept {
    try {
      if (writer_) writer_->Close();
    } catch (const std::exception&) {
    }
    const bool alarms_created = alarms_.has_value();
    alarms_.reset();
    std::error_code ignored;
    if (!live_ && created_) fs::remove(Partial("detect.h5"), ignored);
    if (!live_ && alarms_created) fs::remove(Partial("alarms.csv"), ignored);
  }

  fs::path dir_;
  bool live_;
  double flush_interval_;
  output::DirectoryLock lock_;  // before the files: held until they are closed
  bool created_ = false;        // detect.h5's file
  bool finished_ = false;
  bool unflushed_ = false;
  std::chrono::steady_clock::time_point last_flush_ = std::chrono::steady_clock::now();
  std::optional<DetectWriter> writer_;
  std::optional<output::TextFile> alarms_;
};

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// A time as UNIX seconds: a number, or UTC as YYYY-MM-DDTHH:MM:SS with an optional Z.
double ParseUtc(const std::string& flag, const std::string& text) {
  std::tm utc{};
  int year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
  char z = 'Z';
  const int read = std::sscanf(text.c_str(), "%4d-%2d-%2dT%2d:%2d:%2d%c", &year, &month, &day,
                               &hour, &minute, &second, &z);
  if ((read == 6 || (read == 7 && z == 'Z')) &&
      text.size() == static_cast<std::size_t>(read == 7 ? 20 : 19)) {
    utc.tm_year = year - 1900;
    utc.tm_mon = month - 1;
    utc.tm_mday = day;
    utc.tm_hour = hour;
    utc.tm_min = minute;
    utc.tm_sec = second;
    return static_cast<double>(timegm(&utc));
  }
  try {
    return ParseNumber(flag, text);
  } catch (const InputError&) {
    throw InputError(flag + ": '" + text +
                     "' is neither UTC (2026-12-07T16:00:00Z) nor UNIX seconds");
  }
}

int Detect(const DetectOptions& o) {
  // std::cin then reads through a buffer of its own, whose fill in_avail() tells (stdio's
  // is invisible): LineSource::AwaitInput relies on it.
  std::ios::sync_with_stdio(false);
  const bool from_stdin = o.input == "-";
  if (!from_stdin && !fs::exists(o.input)) throw InputError(o.input + ": no such file");
  const bool store = !from_stdin && fs::is_directory(o.input);
  const bool hdf5 = !from_stdin && !store && output::LooksLikeHdf5(o.input);
  if (o.follow && hdf5) throw InputError("--follow: " + o.input + " is a run.h5, not a CSV stream");
  if (o.follow && store) {
    throw InputError("--follow: " + o.input + " is a monitor's store, not a CSV stream");
  }
  if ((o.from || o.to) && !store) {
    throw InputError(std::string(o.from ? "--from" : "--to") +
                     ": chooses the samples of a monitor's store (a folder), not of a file");
  }
  const double max_gap =
      o.max_gap ? ParseNumber("--max-gap", *o.max_gap) : simulation::kDefaultMaxGap;
  if (!(max_gap > 0.0)) throw InputError("--max-gap: '" + *o.max_gap + "' must be positive [s]");
  const bool live = o.follow || from_stdin;
  double flush_interval = kDefaultFlushInterval;
  if (o.flush_interval) {
    flush_interval = ParseNumber("--flush-interval", *o.flush_interval);
    if (!(flush_interval > 0.0 && flush_interval < 1e9)) {
      throw InputError("--flush-interval: '" + *o.flush_interval + "' must be positive [s]");
    }
    if (!o.out || !live) {
      throw InputError(
          "--flush-interval: paces the writes of --out DIR for a live input (--follow, or - "
          "for standard input); a finite input's files are written whole at the end");
    }
  }
  scenarios::Scenario scenario;
  if (o.scenario) {
    scenario = scenarios::LoadScenario(RequireText("--scenario", *o.scenario), o.sets);
  } else if (store) {
    const monitor::StoreIdentity identity = monitor::ReadStoreIdentity(o.input);
    scenario = scenarios::ParseScenario(identity.scenario_text, identity.scenario_path);
    if (!o.sets.empty()) {
      throw InputError("--set: needs --scenario (the monitor's own scenario is replayed)");
    }
  } else if (hdf5) {
    scenario = runner::ReadRunScenario(o.input);
    if (!o.sets.empty()) {
      throw InputError("--set: needs --scenario (the run's own scenario is replayed as it ran)");
    }
  } else {
    throw InputError(
        "--scenario: required for a CSV stream (the mooring and vessel of the "
        "detectors' models come from it)");
  }
  const std::unique_ptr<Detection> detection = runner::MakeDetection(scenario);
  const std::vector<std::string> labels = detection->HypothesisLabels();
  const int lines = static_cast<int>(scenario.mooring.lines.size());

  std::optional<DetectOutputs> outputs;
  if (o.out) {
    outputs.emplace(RequireText("--out", *o.out), live, flush_interval, scenario, o.input,
                    *detection);
  }
  // `moorsim detect ... | head -1`: a closed standard output stops the run like a signal,
  // with every file finished, instead of killing it half-way through a write.
  std::signal(SIGPIPE, SIG_IGN);
  bool stdout_closed = false;

  std::vector<std::size_t> seen(detection->records().size(), 0);
  simulation::Latency latency;
  long samples = 0;
  double first_time = kNaN, last_time = kNaN;
  // One sample through the bank; every new alarm event printed (and kept) at once.
  const auto take = [&](const detectors::Observation& observation) {
    const auto start = std::chrono::steady_clock::now();
    detection->Update(observation);
    latency.Add(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count());
    if (samples++ == 0) first_time = observation.t;
    last_time = observation.t;
    std::vector<nlohmann::ordered_json> events;
    for (std::size_t i = 0; i < seen.size(); ++i) {
      const simulation::DetectorRecord& record = detection->records()[i];
      for (; seen[i] < record.history.events().size(); ++seen[i]) {
        events.push_back(simulation::AlarmEventJson(record, record.history.events()[seen[i]],
                                                    detection->verdicts()[i], labels, lines,
                                                    latency.last()));
      }
    }
    if (outputs) outputs->Take(observation, *detection, events);
    for (const nlohmann::ordered_json& event : events) {
      std::cout << event.dump() << std::endl;  // flushed: a live reader sees it now
    }
    if (!std::cout) stdout_closed = true;
  };

  if (store) {
    const double from = o.from ? ParseUtc("--from", *o.from) : -kInfinity;
    const double to = o.to ? ParseUtc("--to", *o.to) : kInfinity;
    const std::vector<monitor::StoredSample> samples =
        monitor::ReadStoredSamples(o.input, from, to);
    if (samples.empty()) throw InputError(o.input + ": no samples between --from and --to");
    if (samples.front().segment != samples.back().segment) {
      throw InputError(
          o.input + ": the samples span the monitor's detection segments " +
          std::to_string(samples.front().segment) + " to " +
          std::to_string(samples.back().segment) +
          " (its detection started afresh in between); choose one with --from and --to");
    }
    simulation::StreamChecks checks(max_gap);
    for (const monitor::StoredSample& sample : samples) {
      checks.Check(sample.observation, o.input + " sample " + std::to_string(sample.index));
      take(sample.observation);
      if (stdout_closed) break;
    }
  } else if (hdf5) {
    for (const detectors::Observation& observation :
         simulation::ReadRunDetectionInput(o.input, lines, max_gap)) {
      take(observation);
      if (stdout_closed) break;
    }
  } else {
    simulation::CsvPoseStream stream(from_stdin ? "<stdin>" : o.input, lines, max_gap);
    std::string line;
    detectors::Observation observation;
    const auto idle = [&] {
      if (outputs) outputs->Idle();
    };
    if (o.follow && !from_stdin) {
      runner::InstallStopSignalHandlers();
      simulation::FollowedFile followed(o.input);
      // Asked at the end of the file before each wait: the outputs' flush happens there.
      const auto stop = [&] {
        idle();
        return runner::StopSignal() != 0;
      };
      const auto rotated = [&](simulation::Rotation rotation, std::size_t dropped_bytes) {
        ReportRotation(o.input, rotation, dropped_bytes);
        if (rotation != simulation::Rotation::kMissing) stream.Restart();
      };
      while (!stdout_closed && followed.Next(&line, stop, rotated)) {
        if (stream.Take(line, &observation)) take(observation);
      }
    } else {
      std::ifstream file;
      if (!from_stdin) {
        file.open(o.input);
        if (!file) throw InputError(o.input + ": cannot be read");
      }
      LineSource source(from_stdin ? std::cin : file, from_stdin ? STDIN_FILENO : -1, idle);
      while (!stdout_closed && source.Next(&line)) {
        if (stream.Take(line, &observation)) take(observation);
      }
    }
    if (!stream.has_header()) {
      throw InputError((from_stdin ? std::string("<stdin>") : o.input) +
                       ": no header line (time, north, east, heading, thrust_surge, "
                       "thrust_sway, thrust_yaw)");
    }
  }

  nlohmann::json summary;
  summary["input"] = o.input;
  summary["scenario"] = scenario.name;
  summary["scenario_path"] = scenario.source_path;
  summary["overrides"] = scenario.overrides;
  summary["version"] = moorsim::kVersion;
  summary["max_gap"] = max_gap;
  summary["samples"] = samples;
  summary["first_time"] = samples > 0 ? nlohmann::json(first_time) : nlohmann::json(nullptr);
  summary["last_time"] = samples > 0 ? nlohmann::json(last_time) : nlohmann::json(nullptr);
  summary["failure"] = runner::FailureSummary(scenario);
  if (const nlohmann::json plugins = simulation::PluginsSummary(detection->PluginLibraries());
      !plugins.empty()) {
    summary["plugins"] = plugins;
  }
  summary["detectors"] =
      runner::DetectorsSummary(scenario, *detection, samples > 0 ? last_time : 0.0);
  summary["detection"] = {{"setup_seconds", detection->timing().setup_seconds},
                          {"latency", latency.Summary()}};
  const int signal = stdout_closed ? SIGPIPE : runner::StopSignal();
  if (signal != 0) {
    summary["stopped"] =
        stdout_closed ? std::string("standard output closed") : "signal " + std::to_string(signal);
  }
  if (outputs) outputs->Finish(summary);
  if (!o.quiet) {
    std::fprintf(stderr, "moorsim detect: %ld samples (%.6g s to %.6g s), %.3f ms per sample\n",
                 samples, samples > 0 ? first_time : 0.0, samples > 0 ? last_time : 0.0,
                 latency.mean());
  }
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace

Command AddDetectCommand(CLI::App& app) {
  auto o = std::make_shared<DetectOptions>();
  CLI::App* sub = app.add_subcommand(
      "detect", "run the observers and detectors on a recorded or live pose stream (no plant)");
  sub->add_option("input", o->input,
                  "a CSV log (header required), a moorsim run.h5 to replay, a monitor's store (its "
                  "folder), or - for rows on standard input")
      ->required();
  sub->add_option("--scenario", o->scenario,
                  "scenario YAML: mooring, vessel, sensors and detectors (default for a "
                  "run.h5: the scenario it ran)");
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_option("--out", o->out, "also write DIR/alarms.csv, DIR/detect.h5, DIR/summary.json");
  sub->add_option("--max-gap", o->max_gap,
                  "longest time step or channel dropout accepted [s] (default 60)");
  sub->add_option("--flush-interval", o->flush_interval,
                  "live input with --out: DIR/detect.h5 and DIR/alarms.csv are made durable at "
                  "least this often and at every alarm; a kill loses at most this much [s] "
                  "(default 10)");
  sub->add_option("--from", o->from,
                  "a monitor's store: the first sample's time, UTC (2026-12-07T16:00:00Z) or "
                  "UNIX seconds (default: the first recorded)");
  sub->add_option("--to", o->to, "a monitor's store: samples before this time (default: all)");
  sub->add_flag("--follow", o->follow,
                "at the end of a CSV file, wait for more rows (a log being appended) until "
                "SIGINT/SIGTERM; follows rotation as tail -F does (truncated, replaced or "
                "rewritten: read again from its start, said on stderr)");
  sub->add_flag("--quiet", o->quiet, "no summary line on stderr");
  AddPluginOption(sub);
  sub->footer(
      "\nCSV columns (SI units, any order, matched by name): time [s], north [m], east [m],\n"
      "heading [rad] (an empty cell: the sensor gave nothing), thrust_surge [N],\n"
      "thrust_sway [N], thrust_yaw [N m] (body frame, as the allocation sent it), optional\n"
      "tension_1 .. tension_N [N]. Each alarm event is printed on stdout as one JSON line\n"
      "{time, detector, type, event (onset, revision, end), hypothesis, line, score,\n"
      "latency_ms: the wall time of that sample in the observers and detectors} as soon\n"
      "as its sample is processed. The scenario's failure, if it has one, is the truth the\n"
      "summary scores the verdicts against. Exit codes: 0 ok, 1 failed, 2 bad input (one line\n"
      "naming file, row and column), 128 + signal when --follow was stopped, 141 when\n"
      "standard output was closed (`| head`: the files are finished with what was read).\n\n"
      "--out DIR is held by one moorsim at a time and starts empty of the previous run's\n"
      "files. A file input's detect.h5 and alarms.csv are written as .partial and renamed\n"
      "when complete. A live input's (--follow, -) are written under their final names and\n"
      "made durable every --flush-interval and at each alarm before it is printed: after a\n"
      "kill or a power loss detect.h5 opens and holds every row up to the last flush.\n\n" +
      detectors::DetectorHelp());
  return [o] { return Detect(*o); };
}

}  // namespace moorsim::cli
