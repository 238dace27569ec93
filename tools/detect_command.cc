// `moorsim detect`: the observer bank and a scenario's detectors on a recorded or live pose
// stream, without the plant (tools/simulation/pose_stream.h has the input formats). Every
// alarm event is printed as one JSON line on standard output the moment the sample that
// raised it has been processed; --out DIR also keeps alarms.csv, detect.h5 (the figures of
// tools/plot_run.py) and summary.json.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/version.h"
#include "detectors/registry.h"
#include "scenarios/load.h"
#include "tools/commands.h"
#include "tools/output/hdf5_file.h"
#include "tools/output/hdf5_reader.h"
#include "tools/simulation/detection_tables.h"
#include "tools/simulation/pose_stream.h"
#include "tools/simulation/run.h"
#include "tools/simulation/simulation.h"

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
  bool follow = false;
  bool quiet = false;
};

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Lines of a stream; with `follow`, waits at its end for more (a file being appended)
/// until a stop signal. A last line without its newline is kept until the newline comes.
class LineSource {
 public:
  LineSource(std::istream& in, bool follow) : in_(in), follow_(follow) {}
  bool Next(std::string* line) {
    for (;;) {
      std::string chunk;
      if (std::getline(in_, chunk)) {
        if (!in_.eof()) {
          *line = pending_ + chunk;
          pending_.clear();
          return true;
        }
        pending_ += chunk;  // the writer has not finished this line yet
      }
      if (!follow_ || simulation::StopSignal() != 0) {
        if (pending_.empty()) return false;
        line->swap(pending_);
        pending_.clear();
        return true;
      }
      in_.clear();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

 private:
  std::istream& in_;
  bool follow_;
  std::string pending_;
};

/// detect.h5: what tools/plot_run.py draws of a run that detection alone can give (the
/// measured pose, the thrust given, the observers' load picture and every detector's
/// verdict per sample), with the identity of the input and the scenario.
class DetectWriter {
 public:
  DetectWriter(const std::string& path, const scenarios::Scenario& scenario,
               const std::string& input, const Detection& detection)
      : file_(path) {
    file_.SetAttribute("/", "scenario", scenario.text);
    file_.SetAttribute("/", "scenario_name", scenario.name);
    file_.SetAttribute("/", "scenario_path", scenario.source_path);
    file_.SetAttribute("/", "input", input);
    file_.SetAttribute("/", "version", std::string(moorsim::kVersion));
    file_.SetAttribute("/", "failure_line", static_cast<std::int64_t>(scenario.failure.line));
    file_.SetAttribute("/", "failure_time",
                       scenario.failure.line > 0 ? scenario.failure.time : kNaN);
    time_ = file_.CreateTable("/time", 0, "s");
    pose_ = file_.CreateTable("/vessel/pose_measured", 3, "m,m,rad", {"x", "y", "psi"});
    thrust_ = file_.CreateTable("/thrust/delivered", 3, "N,N,N m", {"X", "Y", "N"});
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
  void Close() { file_.Close(); }

 private:
  void Row(output::TableId table, const Vec3& v) {
    file_.Append(table, std::span<const double>(v.data(), 3));
  }
  output::Hdf5File file_;
  output::TableId time_, pose_, thrust_;
  std::optional<simulation::DetectionTables> tables_;
};

/// One alarm event as a JSON object: time, detector label and type, event, the hypothesis
/// it names (its label; the line number, null for a pair), and the detector's score for it.
nlohmann::ordered_json EventJson(const simulation::DetectorRecord& record,
                                 const detectors::AlarmEvent& e, const detectors::Verdict& verdict,
                                 const std::vector<std::string>& labels, int lines,
                                 double latency_ms) {
  const bool end = e.kind == detectors::AlarmEvent::Kind::kEnd;
  nlohmann::ordered_json j;
  j["time"] = e.time;
  j["detector"] = record.label;
  j["type"] = record.type;
  j["event"] = detectors::AlarmEventName(e.kind);
  j["hypothesis"] = end ? nlohmann::json(nullptr) : nlohmann::json(labels.at(e.hypothesis));
  j["line"] = !end && e.hypothesis >= 1 && e.hypothesis <= lines ? nlohmann::json(e.hypothesis)
                                                                 : nlohmann::json(nullptr);
  j["score"] = end ? nlohmann::json(nullptr) : nlohmann::json(verdict.score.at(e.hypothesis));
  j["latency_ms"] = latency_ms;
  return j;
}

std::string CsvCell(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number_integer()) return std::to_string(value.get<long long>());
  return FormatNumber(value.get<double>());
}

/// Per-sample wall time of the observers and detectors [ms]: mean and max over every sample,
/// the 99th percentile over the last kRecent (a day at 1 Hz), so that a live monitor that
/// runs for months keeps bounded memory.
class Latency {
 public:
  static constexpr std::size_t kRecent = 86400;
  void Add(double ms) {
    if (recent_.size() < kRecent) {
      recent_.push_back(ms);
    } else {
      recent_[count_ % kRecent] = ms;
    }
    ++count_;
    sum_ += ms;
    max_ = std::max(max_, ms);
    last_ = ms;
  }
  double last() const { return last_; }
  double mean() const { return count_ > 0 ? sum_ / static_cast<double>(count_) : 0.0; }
  nlohmann::json Summary() const {
    if (count_ == 0) return {{"samples", 0}};
    std::vector<double> sorted = recent_;
    const std::size_t p99 =
        std::min(sorted.size() - 1, static_cast<std::size_t>(0.99 * sorted.size()));
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(p99),
                     sorted.end());
    return {{"samples", count_},
            {"mean_ms", mean()},
            {"p99_ms", sorted[p99]},
            {"p99_over_samples", sorted.size()},
            {"max_ms", max_}};
  }

 private:
  std::vector<double> recent_;
  std::size_t count_ = 0;
  double sum_ = 0.0, max_ = 0.0, last_ = 0.0;
};

int Detect(const DetectOptions& o) {
  const bool from_stdin = o.input == "-";
  if (!from_stdin && !fs::exists(o.input)) throw InputError(o.input + ": no such file");
  const bool hdf5 = !from_stdin && output::LooksLikeHdf5(o.input);
  if (o.follow && hdf5) throw InputError("--follow: " + o.input + " is a run.h5, not a CSV stream");
  const double max_gap =
      o.max_gap ? ParseNumber("--max-gap", *o.max_gap) : simulation::kDefaultMaxGap;
  if (!(max_gap > 0.0)) throw InputError("--max-gap: '" + *o.max_gap + "' must be positive [s]");
  scenarios::Scenario scenario;
  if (o.scenario) {
    scenario = scenarios::LoadScenario(RequireText("--scenario", *o.scenario), o.sets);
  } else if (hdf5) {
    scenario = simulation::ReadRunScenario(o.input);
    if (!o.sets.empty()) {
      throw InputError("--set: needs --scenario (the run's own scenario is replayed as it ran)");
    }
  } else {
    throw InputError(
        "--scenario: required for a CSV stream (the mooring and vessel of the "
        "detectors' models come from it)");
  }
  const std::unique_ptr<Detection> detection = simulation::MakeDetection(scenario);
  const std::vector<std::string> labels = detection->HypothesisLabels();
  const int lines = static_cast<int>(scenario.mooring.lines.size());

  std::optional<DetectWriter> writer;
  std::ofstream alarms_csv;
  fs::path out;
  if (o.out) {
    out = RequireText("--out", *o.out);
    fs::create_directories(out);
    writer.emplace((out / "detect.h5").string(), scenario, o.input, *detection);
    alarms_csv.open(out / "alarms.csv");
    if (!alarms_csv) throw Error((out / "alarms.csv").string() + ": cannot be written");
    alarms_csv << "time,detector,type,event,hypothesis,line,score\n";
  }

  std::vector<std::size_t> seen(detection->records().size(), 0);
  Latency latency;
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
    for (std::size_t i = 0; i < seen.size(); ++i) {
      const simulation::DetectorRecord& record = detection->records()[i];
      for (; seen[i] < record.history.events().size(); ++seen[i]) {
        const nlohmann::ordered_json event =
            EventJson(record, record.history.events()[seen[i]], detection->verdicts()[i], labels,
                      lines, latency.last());
        std::cout << event.dump() << std::endl;  // flushed: a live reader sees it now
        if (alarms_csv.is_open()) {
          alarms_csv << CsvCell(event["time"]);
          for (const char* key : {"detector", "type", "event", "hypothesis", "line", "score"}) {
            alarms_csv << ',' << CsvCell(event[key]);
          }
          alarms_csv << '\n' << std::flush;
        }
      }
    }
    if (writer) writer->Append(observation, *detection);
  };

  if (hdf5) {
    for (const detectors::Observation& observation :
         simulation::ReadRunDetectionInput(o.input, lines, max_gap)) {
      take(observation);
    }
  } else {
    std::ifstream file;
    if (!from_stdin) {
      file.open(o.input);
      if (!file) throw InputError(o.input + ": cannot be read");
    }
    if (o.follow && !from_stdin) simulation::InstallStopSignalHandlers();
    LineSource source(from_stdin ? std::cin : file, o.follow && !from_stdin);
    simulation::CsvPoseStream stream(from_stdin ? "<stdin>" : o.input, lines, max_gap);
    std::string line;
    detectors::Observation observation;
    while (source.Next(&line)) {
      if (stream.Take(line, &observation)) take(observation);
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
  summary["failure"] = simulation::FailureSummary(scenario);
  if (const nlohmann::json plugins = simulation::PluginsSummary(detection->PluginLibraries());
      !plugins.empty()) {
    summary["plugins"] = plugins;
  }
  summary["detectors"] =
      simulation::DetectorsSummary(scenario, *detection, samples > 0 ? last_time : 0.0);
  summary["detection"] = {{"setup_seconds", detection->timing().setup_seconds},
                          {"latency", latency.Summary()}};
  if (writer) {
    writer->Close();
    alarms_csv.close();
    simulation::WriteFileAtomically(out / "summary.json", summary.dump(2) + "\n");
  }
  if (!o.quiet) {
    std::fprintf(stderr, "moorsim detect: %ld samples (%.6g s to %.6g s), %.3f ms per sample\n",
                 samples, samples > 0 ? first_time : 0.0, samples > 0 ? last_time : 0.0,
                 latency.mean());
  }
  const int signal = simulation::StopSignal();
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace

Command AddDetectCommand(CLI::App& app) {
  auto o = std::make_shared<DetectOptions>();
  CLI::App* sub = app.add_subcommand(
      "detect", "run the observers and detectors on a recorded or live pose stream (no plant)");
  sub->add_option("input", o->input,
                  "a CSV log (header required), a moorsim run.h5 to replay, or - for rows on "
                  "standard input")
      ->required();
  sub->add_option("--scenario", o->scenario,
                  "scenario YAML: mooring, vessel, sensors and detectors (default for a "
                  "run.h5: the scenario it ran)");
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_option("--out", o->out, "also write DIR/alarms.csv, DIR/detect.h5, DIR/summary.json");
  sub->add_option("--max-gap", o->max_gap,
                  "longest time step or channel dropout accepted [s] (default 60)");
  sub->add_flag("--follow", o->follow,
                "at the end of a CSV file, wait for more rows (a log being appended) until "
                "SIGINT/SIGTERM");
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
      "naming file, row and column), 128 + signal when --follow was stopped.\n\n" +
      detectors::DetectorHelp());
  return [o] { return Detect(*o); };
}

}  // namespace moorsim::cli
