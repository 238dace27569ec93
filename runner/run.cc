#include "runner/run.h"

#include "simulation/output_layout.h"

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <new>
#include <optional>
#include <span>
#include <sstream>

#include "core/angles.h"
#include "core/error.h"
#include "core/sample_clock.h"
#include "core/version.h"
#include "io/directory_lock.h"
#include "io/hdf5_file.h"
#include "io/text_file.h"
#include "runner/design_record.h"
#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "simulation/detection_tables.h"

namespace moorsim::runner {

namespace layout = simulation::layout;
using simulation::Detection;
using simulation::DetectionTables;
using simulation::DetectionTiming;
using simulation::DetectorRecord;
using simulation::PluginsSummary;
using simulation::Sample;
using simulation::Simulation;
using simulation::StationKeeping;
namespace {

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : "\n") + s;
  return out;
}

/// The tables of run.h5 (docs/design.md section 7) and how each sample fills them.
class RunWriter {
 public:
  RunWriter(output::Hdf5File file, const scenarios::Scenario& scenario, Simulation& sim)
      : file_(std::move(file)) {
    file_.SetAttribute("/", "scenario", scenario.text);
    file_.SetAttribute("/", "scenario_name", scenario.name);
    // Absolute, so that the run replays from any folder (`moorsim detect RUN.h5`): the
    // scenario's relative paths (WAMIT stem, seabed grid) are relative to its folder.
    file_.SetAttribute(
        "/", "scenario_path",
        scenario.source_path.empty()
            ? scenario.source_path
            : std::filesystem::absolute(scenario.source_path).lexically_normal().string());
    file_.SetAttribute("/", "overrides", Join(scenario.overrides));
    file_.SetAttribute("/", "seed", sim.seed());
    file_.SetAttribute("/", "version", std::string(moorsim::kVersion));
    file_.SetAttribute("/", "failure_line", static_cast<std::int64_t>(scenario.failure.line));
    file_.SetAttribute("/", "failure_time",
                       scenario.failure.line > 0 ? scenario.failure.time : kNaN);
    file_.SetAttribute(
        "/", "failure_mode",
        scenario.failure.line > 0 ? std::string(ChoiceName(scenario.failure.mode)) : std::string());
    time_ = layout::Create(file_, layout::kTime);
    pose_true_ = layout::Create(file_, layout::kPoseTrue);
    pose_lf_ = layout::Create(file_, layout::kPoseLowFrequency);
    velocity_ = layout::Create(file_, layout::kVelocityTrue);
    measured_ = layout::Create(file_, layout::kPoseMeasured);
    if (sim.plant().turret_turns()) turret_ = layout::Create(file_, layout::kTurret);
    const int lines = sim.num_lines();
    lines_ = static_cast<std::size_t>(lines);
    tension_ = layout::Create(file_, layout::kFairleadTension, lines);
    if (scenario.sensors.tension_cells) {
      tension_measured_ = layout::Create(file_, layout::kTensionMeasured, lines);
    }
    const output::TableId anchors = layout::Create(file_, layout::kAnchors);
    for (int i = 0; i < lines; ++i) {
      const Vec3 a = sim.mooring().line(i).anchor;
      file_.Append(anchors, std::vector<double>{a.x(), a.y(), a.z()});
    }
    commanded_ = layout::Create(file_, layout::kThrustCommanded);
    delivered_ = layout::Create(file_, layout::kThrustDelivered);
    mooring_ = layout::Create(file_, layout::kLoadMooring);
    drift_ = layout::Create(file_, layout::kLoadWavesDrift);
    current_ = layout::Create(file_, layout::kLoadCurrent);
    wind_ = layout::Create(file_, layout::kLoadWind);
    thrust_ = layout::Create(file_, layout::kLoadThrust);
    detection_tables_.emplace(file_, sim.detection());
    if (sim.detection()) {
      // Every sample the detection took, as it took it: `moorsim detect` replays these.
      sim.KeepDetectionInput(true);
      input_time_ = layout::Create(file_, layout::kInputTime);
      input_pose_ = layout::Create(file_, layout::kInputPose);
      file_.SetAttribute(std::string(layout::kInputPose.path), "missing",
                         std::string("NaN: the channel delivered nothing at this sample"));
      input_thrust_ = layout::Create(file_, layout::kInputThrust);
      if (scenario.sensors.tension_cells) {
        input_tension_ = layout::Create(file_, layout::kInputTension, lines);
      }
    }
  }

  void Append(const Sample& s) {
    for (const detectors::Observation& o : s.detection_input) {
      file_.Append(*input_time_, o.t);
      Vec3 pose = o.pose;
      for (int i = 0; i < 3; ++i) {
        if (!o.valid[i]) pose(i) = kNaN;
      }
      Row(*input_pose_, pose);
      Row(*input_thrust_, o.tau_command);
      if (input_tension_) {
        if (o.tensions) {
          Row(*input_tension_, *o.tensions);
        } else {
          file_.Append(*input_tension_, std::vector<double>(lines_, kNaN));
        }
      }
    }
    file_.Append(time_, s.time);
    Row(pose_true_, s.pose_true);
    Row(pose_lf_, s.pose_low_frequency);
    Row(velocity_, s.velocity);
    Row(measured_, s.pose_measured);
    if (turret_ && s.turret) Row(*turret_, *s.turret);
    file_.Append(tension_, s.fairlead_tension);
    if (tension_measured_) {
      std::vector<double> row = s.tension_measured;
      row.resize(s.fairlead_tension.size(), kNaN);
      file_.Append(*tension_measured_, row);
    }
    Row(commanded_, s.thrust_commanded);
    Row(delivered_, s.thrust_delivered);
    Row(mooring_, s.load_mooring);
    Row(drift_, s.load_wave_drift);
    Row(current_, s.load_current);
    Row(wind_, s.load_wind);
    Row(thrust_, s.load_thrust);
    detection_tables_->Append(file_, s.observer_bias, s.observer_wave_motion, s.detectors);
  }

  void Flush() { file_.Flush(); }
  void Close() { file_.Close(); }

 private:
  template <class V>
  void Row(output::TableId table, const V& v) {
    file_.Append(table, std::span<const double>(v.data(), static_cast<std::size_t>(v.size())));
  }

  output::Hdf5File file_;
  output::TableId time_, pose_true_, pose_lf_, velocity_, measured_, tension_, commanded_,
      delivered_, mooring_, drift_, current_, wind_, thrust_;
  std::optional<output::TableId> tension_measured_;
  std::optional<output::TableId> turret_;
  std::optional<output::TableId> input_time_, input_pose_, input_thrust_, input_tension_;
  std::size_t lines_ = 0;
  std::optional<DetectionTables> detection_tables_;
};

nlohmann::json Stats(const IntegratorStats& s) {
  return {{"steps", s.steps},
          {"rhs_evaluations", s.rhs_evals},
          {"jacobian_evaluations", s.jacobian_evals},
          {"linear_setups", s.linear_setups},
          {"newton_iterations", s.newton_iterations},
          {"newton_failures", s.newton_failures},
          {"error_test_failures", s.error_test_failures},
          {"rhs_seconds", s.rhs_seconds},
          {"jacobian_seconds", s.jacobian_seconds},
          {"linear_setup_seconds", s.linear_setup_seconds},
          {"linear_solve_seconds", s.linear_solve_seconds}};
}

/// What every summary.json starts with: the run's identity.
nlohmann::json SummaryHead(const scenarios::Scenario& scenario) {
  nlohmann::json summary;
  summary["scenario"] = scenario.name;
  summary["scenario_path"] = scenario.source_path;
  summary["overrides"] = scenario.overrides;
  summary["seed"] = scenario.simulation.seed;
  summary["version"] = moorsim::kVersion;
  summary["duration"] = scenario.simulation.duration;
  summary["failure"] = FailureSummary(scenario);
  return summary;
}

/// The per-detector results and detection timing of a run.
void AddDetection(const scenarios::Scenario& scenario, const Simulation& sim,
                  nlohmann::json& summary) {
  summary["detectors"] = sim.detection() ? DetectorsSummary(scenario, *sim.detection(), sim.time())
                                         : nlohmann::json::object();
  if (sim.detection()) {
    const nlohmann::json plugins = PluginsSummary(sim.detection()->PluginLibraries());
    if (!plugins.empty()) summary["plugins"] = plugins;
  }
  const DetectionTiming& timing = sim.detection_timing();
  summary["detection"] = {{"setup_seconds", timing.setup_seconds},
                          {"update_seconds", timing.update_seconds},
                          {"samples", timing.samples}};
}

/// How well the station keeping held (Simulation::station_keeping), in degrees.
void AddStationKeeping(const Simulation& sim, nlohmann::json& summary) {
  const StationKeeping& kept = sim.station_keeping();
  summary["station_keeping"] = {{"controller_updates", kept.updates},
                                {"thrust_saturated_share", kept.SaturatedShare()},
                                {"heading_error_max_deg", kept.heading_error_max / kDegree},
                                {"heading_error_final_deg", kept.heading_error_last / kDegree}};
}

void RemoveQuietly(const std::filesystem::path& path) {
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
}

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void OnStopSignal(int signal) {
  g_stop_signal = signal;
  std::signal(signal, SIG_DFL);  // a second one ends the process at once
}

}  // namespace

const char* StatusName(RunStatus status) {
  switch (status) {
    case RunStatus::kOk:
      return "ok";
    case RunStatus::kFailed:
      return "failed";
    case RunStatus::kInterrupted:
      return "interrupted";
    case RunStatus::kRejected:
      return "rejected";
    case RunStatus::kTimedOut:
      return "timeout";
  }
  return "failed";
}

void WriteFileAtomically(const std::filesystem::path& path, const std::string& text) {
  WriteFilesAtomically({{path, text}});
}

void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files) {
  std::size_t written = 0;  // partial files this call has created
  try {
    for (const auto& [path, text] : files) {
      // Messages name `path`; a partial file is removed only once this call has created it.
      output::TextFile file(output::PartialPath(path), path);
      ++written;
      file.Write(text);
      file.Sync();
      file.Close();
    }
    for (const auto& [path, text] : files) output::PublishPartial(path);
  } catch (const Error&) {
    for (std::size_t k = 0; k < written; ++k) RemoveQuietly(output::PartialPath(files[k].first));
    throw;
  }
}

void InstallStopSignalHandlers() {
  g_stop_signal = 0;
  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
}

int StopSignal() { return g_stop_signal; }

RunResult RunScenario(const RunRequest& request) noexcept {
  RunResult result;
  // 1. Everything about the input, before anything is simulated or written. The output
  // directory is this process's alone until it returns.
  std::shared_ptr<const scenarios::Scenario> loaded = request.scenario;
  std::optional<output::DirectoryLock> lock;
  try {
    if (!loaded) {
      loaded = std::make_shared<const scenarios::Scenario>(
          scenarios::LoadScenario(request.scenario_path, request.overrides));
    }
    CheckDetectors(*loaded);
    result.directory =
        request.out.empty() ? std::filesystem::path("out") / loaded->name : request.out;
    if (request.write_files) lock.emplace(result.directory);
  } catch (const InputError& e) {
    result.status = RunStatus::kRejected;
    result.message = e.what();
    if (const auto* option = dynamic_cast<const OptionError*>(&e)) {
      result.option_error = std::make_shared<const OptionError>(*option);
    }
    return result;
  } catch (const std::exception& e) {
    result.status = RunStatus::kFailed;
    result.message = e.what();
    return result;
  }
  const scenarios::Scenario& scenario = *loaded;
  const std::filesystem::path run_path = result.directory / "run.h5";
  const std::filesystem::path summary_path = result.directory / "summary.json";
  nlohmann::json summary = SummaryHead(scenario);

  // 2. The run. Any failure from here on is reported in summary.json.
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<RunWriter> writer;
  std::optional<DesignRecord> design;
  bool run_file_broken = false;
  bool partial_created = false;  // only a file this run created is ever removed
  result.status = RunStatus::kOk;
  try {
    try {
      sim = MakeSimulation(scenario, scenario.simulation.seed);
    } catch (const InputError& e) {  // a scenario the loader's rules let through
      result.status = RunStatus::kRejected;
      result.message = e.what();
      return result;
    }
    design.emplace(scenario, *sim);
    try {
      if (request.write_files) {
        output::Hdf5File file(output::PartialPath(run_path).string());
        partial_created = true;
        writer = std::make_unique<RunWriter>(std::move(file), scenario, *sim);
      }
    } catch (const Error&) {
      run_file_broken = true;
      throw;
    }
    // Output rows at k / rate for every k with k / rate <= duration (integer indices).
    const SampleClock rows(scenario.simulation.output_rate, "simulation.output_rate_hz");
    const std::int64_t last_row = rows.LastIndex(scenario.simulation.duration);
    auto last_progress = start;
    for (std::int64_t k = 0; k <= last_row; ++k) {
      sim->AdvanceTo(rows.Instant(k));
      // Recorded whether or not a file is written, so a run is the same either way.
      const Sample sample = sim->Record();
      design->Add(*sim, sample);
      if (request.on_row) request.on_row(sample);
      try {
        if (writer) {
          writer->Append(sample);
          if (request.flush_rows > 0 && (k + 1) % request.flush_rows == 0) writer->Flush();
        }
      } catch (const Error&) {
        run_file_broken = true;
        throw;
      }
      if (request.stop_requested) {
        if (const int signal = request.stop_requested(); signal != 0 && k < last_row) {
          result.status = RunStatus::kInterrupted;
          result.signal = signal;
          std::ostringstream message;
          message << "stopped by signal " << signal << " (" << strsignal(signal)
                  << ") at t = " << sim->time() << " s";
          result.message = message.str();
          break;
        }
      }
      if (request.deadline && k < last_row &&
          std::chrono::steady_clock::now() >= *request.deadline) {
        result.status = RunStatus::kTimedOut;
        std::ostringstream message;
        message << "stopped at its wall-clock limit at t = " << sim->time() << " s";
        result.message = message.str();
        break;
      }
      const auto now = std::chrono::steady_clock::now();
      if (request.progress && std::chrono::duration<double>(now - last_progress).count() > 2.0) {
        const double wall = std::chrono::duration<double>(now - start).count();
        std::fprintf(stderr, "moorsim run: t = %.0f / %.0f s (%.0f %%), %.0fx real time\n",
                     sim->time(), scenario.simulation.duration,
                     100.0 * sim->time() / scenario.simulation.duration, sim->time() / wall);
        last_progress = now;
      }
    }
  } catch (const std::bad_alloc&) {
    result.status = RunStatus::kFailed;
    result.message = "out of memory";
  } catch (const std::exception& e) {
    result.status = RunStatus::kFailed;
    result.message = e.what();
  }

  // 3. Close run.h5: complete, or holding every row so far. A file that could not be
  // written is removed (on a full disk that also frees room for summary.json).
  if (writer) {
    try {
      writer->Close();
    } catch (const std::exception& e) {
      if (!run_file_broken) {
        run_file_broken = true;
        result.status = RunStatus::kFailed;
        result.message = e.what();
      }
    }
    writer.reset();
  }
  if (request.write_files) RemoveQuietly(summary_path);
  if (!request.write_files) {
    // Nothing on disk.
  } else if (run_file_broken) {
    // The previous run's run.h5 goes too: summary.json would not describe it.
    if (partial_created) RemoveQuietly(output::PartialPath(run_path));
    RemoveQuietly(run_path);
  } else if (sim) {
    std::error_code error;
    std::filesystem::rename(output::PartialPath(run_path), run_path, error);
    if (error) {
      run_file_broken = true;  // summary.json names no run.h5
      result.status = RunStatus::kFailed;
      result.message = run_path.string() + ": rename failed: " + error.message();
    }
  }

  // 4. summary.json.
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.simulated_time = sim ? sim->time() : 0.0;
  try {
    if (sim) {
      AddDetection(scenario, *sim, summary);
      AddStationKeeping(*sim, summary);
      if (design) summary["design"] = design->Summary();
    }
    summary["status"] = StatusName(result.status);
    if (!result.message.empty()) summary["error"] = result.message;
    if (result.status == RunStatus::kInterrupted) summary["signal"] = result.signal;
    summary["simulated_time"] = result.simulated_time;
    summary["wall_time"] = wall;
    summary["real_time_factor"] = wall > 0.0 ? result.simulated_time / wall : 0.0;
    if (sim) summary["integrator"] = Stats(sim->stats());
    summary["outputs"] = {{"run", run_file_broken || !sim || !request.write_files
                                      ? nlohmann::json(nullptr)
                                      : nlohmann::json("run.h5")}};
    if (request.write_files) {
      WriteFileAtomically(summary_path, summary.dump(2) + "\n");
      result.summary_written = true;
    }
  } catch (const std::exception& e) {
    if (result.status == RunStatus::kOk) result.status = RunStatus::kFailed;
    result.message += std::string(result.message.empty() ? "" : "; ") + e.what();
  }
  result.summary = std::move(summary);
  return result;
}

}  // namespace moorsim::runner
