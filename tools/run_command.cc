// `moorsim run`: one coupled simulation of a scenario, written to DIR/run.h5 (every channel
// of DESIGN.md section 7, SI units in a `units` attribute) and DIR/summary.json.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "detectors/registry.h"
#include "scenarios/load.h"
#include "tools/commands.h"
#include "tools/output/hdf5_file.h"
#include "tools/simulation/simulation.h"

namespace moorsim::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::string out;
  std::string seed;
  std::string duration;
  std::vector<std::string> sets;
  bool quiet = false;
};

std::string Join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : "\n") + s;
  return out;
}

/// The tables of run.h5 and how each sample fills them.
class RunWriter {
 public:
  RunWriter(const std::string& path, const scenarios::Scenario& scenario,
            simulation::Simulation& sim)
      : file_(path) {
    using output::TableType;
    file_.SetAttribute("/", "scenario", scenario.text);
    file_.SetAttribute("/", "scenario_name", scenario.name);
    file_.SetAttribute("/", "scenario_path", scenario.source_path);
    file_.SetAttribute("/", "overrides", Join(scenario.overrides));
    file_.SetAttribute("/", "seed", static_cast<std::int64_t>(sim.seed()));
    file_.SetAttribute("/", "version", std::string(MOORSIM_VERSION));
    file_.SetAttribute("/", "failure_line", static_cast<std::int64_t>(scenario.failure.line));
    file_.SetAttribute("/", "failure_time",
                       scenario.failure.line > 0 ? scenario.failure.time
                                                 : std::numeric_limits<double>::quiet_NaN());
    file_.SetAttribute("/", "failure_mode",
                       scenario.failure.line > 0 ? scenario.failure.mode : std::string());
    const std::vector<std::string> eta = {"x", "y", "z", "phi", "theta", "psi"};
    const std::string eta_units = "m,m,m,rad,rad,rad";
    const std::string load_units = "N,N,N,N m,N m,N m";
    const std::vector<std::string> load = {"X", "Y", "Z", "K", "M", "N"};
    time_ = file_.CreateTable("/time", 0, "s");
    pose_true_ = file_.CreateTable("/vessel/pose_true", 6, eta_units, eta);
    pose_lf_ = file_.CreateTable("/vessel/pose_low_frequency", 6, eta_units, eta);
    velocity_ = file_.CreateTable("/vessel/velocity_true", 6, "m/s,m/s,m/s,rad/s,rad/s,rad/s",
                                  {"u", "v", "w", "p", "q", "r"});
    measured_ = file_.CreateTable("/vessel/pose_measured", 3, "m,m,rad", {"x", "y", "psi"});
    const int lines = sim.num_lines();
    std::vector<std::string> line_names;
    for (int i = 1; i <= lines; ++i) line_names.push_back("line " + std::to_string(i));
    tension_ = file_.CreateTable("/mooring/fairlead_tension", lines, "N", line_names);
    if (scenario.sensors.tension_cells) {
      tension_measured_ = file_.CreateTable("/mooring/tension_measured", lines, "N", line_names);
    }
    const output::TableId anchors =
        file_.CreateTable("/mooring/anchors", 3, "m,m,m", {"x", "y", "z"});
    for (int i = 0; i < lines; ++i) {
      const Vec3 a = sim.mooring().line(i).anchor;
      file_.Append(anchors, std::vector<double>{a.x(), a.y(), a.z()});
    }
    commanded_ = file_.CreateTable("/thrust/commanded", 3, "N,N,N m", {"X", "Y", "N"});
    delivered_ = file_.CreateTable("/thrust/delivered", 3, "N,N,N m", {"X", "Y", "N"});
    mooring_ = file_.CreateTable("/environment/mooring", 6, load_units, load);
    drift_ = file_.CreateTable("/environment/waves_drift", 6, load_units, load);
    current_ = file_.CreateTable("/environment/current", 6, load_units, load);
    wind_ = file_.CreateTable("/environment/wind", 6, load_units, load);
    thrust_ = file_.CreateTable("/environment/thrust", 6, load_units, load);
    file_.CreateGroup("/detectors");
    const std::vector<std::string> hypotheses = sim.HypothesisLabels();
    if (!hypotheses.empty()) {
      std::string joined;
      for (const std::string& h : hypotheses) joined += (joined.empty() ? "" : ",") + h;
      file_.SetAttribute("/detectors", "hypotheses", joined);
    }
    for (const simulation::DetectorRecord& d : sim.detector_records()) {
      const std::string group = "/detectors/" + d.label;
      const char* score_units = d.type == "dht"   ? "probability"
                                : d.type == "mle" ? "nats (negative log-likelihood)"
                                                  : "chi-square statistic";
      Tables t;
      t.score = file_.CreateTable(group + "/score", static_cast<int>(hypotheses.size()),
                                  score_units, hypotheses);
      t.decision = file_.CreateTable(group + "/decision", 0, "hypothesis (0 = intact, k = line k)",
                                     {}, output::TableType::kInt32);
      t.alarm = file_.CreateTable(group + "/alarm", 0, "0/1", {}, output::TableType::kInt8);
      file_.SetAttribute(group, "type", d.type);
      if (d.threshold) file_.SetAttribute(group, "threshold", *d.threshold);
      detector_tables_.push_back(t);
    }
  }

  void Append(const simulation::Sample& s) {
    file_.Append(time_, s.time);
    Row(pose_true_, s.pose_true);
    Row(pose_lf_, s.pose_low_frequency);
    Row(velocity_, s.velocity);
    Row(measured_, s.pose_measured);
    file_.Append(tension_, s.fairlead_tension);
    if (tension_measured_) {
      std::vector<double> row = s.tension_measured;
      row.resize(s.fairlead_tension.size(), std::numeric_limits<double>::quiet_NaN());
      file_.Append(*tension_measured_, row);
    }
    Row(commanded_, s.thrust_commanded);
    Row(delivered_, s.thrust_delivered);
    Row(mooring_, s.load_mooring);
    Row(drift_, s.load_wave_drift);
    Row(current_, s.load_current);
    Row(wind_, s.load_wind);
    Row(thrust_, s.load_thrust);
    for (std::size_t i = 0; i < detector_tables_.size() && i < s.detectors.size(); ++i) {
      const detectors::Verdict& v = s.detectors[i];
      file_.Append(detector_tables_[i].score, v.score);
      file_.Append(detector_tables_[i].decision, static_cast<std::int32_t>(v.hypothesis));
      file_.Append(detector_tables_[i].alarm, static_cast<std::int32_t>(v.alarm ? 1 : 0));
    }
  }

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
  struct Tables {
    output::TableId score, decision, alarm;
  };
  std::vector<Tables> detector_tables_;
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

int Run(const RunOptions& o) {
  std::vector<std::string> overrides = o.sets;
  if (!o.seed.empty()) overrides.push_back("simulation.seed=" + o.seed);
  if (!o.duration.empty()) overrides.push_back("simulation.duration=" + o.duration);
  const scenarios::Scenario scenario = scenarios::LoadScenario(o.scenario, overrides);
  const std::uint64_t seed = scenario.simulation.seed;
  const std::filesystem::path dir =
      o.out.empty() ? std::filesystem::path("out") / scenario.name : std::filesystem::path(o.out);
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) {
    throw InputError("--out " + dir.string() + ": cannot create the directory: " + error.message());
  }

  const auto start = std::chrono::steady_clock::now();
  simulation::Simulation sim(scenario, seed);
  RunWriter writer((dir / "run.h5").string(), scenario, sim);
  const double duration = scenario.simulation.duration;
  const double rate = scenario.simulation.output_rate;
  const long samples = static_cast<long>(std::floor(duration * rate + 1e-9)) + 1;
  auto last_progress = std::chrono::steady_clock::now();
  nlohmann::json summary;
  summary["scenario"] = scenario.name;
  summary["scenario_path"] = scenario.source_path;
  summary["overrides"] = scenario.overrides;
  summary["seed"] = seed;
  summary["version"] = MOORSIM_VERSION;
  summary["duration"] = duration;
  if (scenario.failure.line > 0) {
    summary["failure"] = {{"line", scenario.failure.line},
                          {"time", scenario.failure.time},
                          {"mode", scenario.failure.mode}};
  } else {
    summary["failure"] = nullptr;
  }
  std::string status = "ok";
  std::string message;
  try {
    for (long k = 0; k < samples; ++k) {
      sim.AdvanceTo(static_cast<double>(k) / rate);
      writer.Append(sim.Record());
      const auto now = std::chrono::steady_clock::now();
      if (!o.quiet && std::chrono::duration<double>(now - last_progress).count() > 2.0) {
        const double wall = std::chrono::duration<double>(now - start).count();
        std::fprintf(stderr, "moorsim run: t = %.0f / %.0f s (%.0f %%), %.0fx real time\n",
                     sim.time(), duration, 100.0 * sim.time() / duration, sim.time() / wall);
        last_progress = now;
      }
    }
  } catch (const SolverError& e) {
    status = "failed";
    message = e.what();
  }
  writer.Close();
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json detectors = nlohmann::json::object();
  const std::vector<std::string> labels = sim.HypothesisLabels();
  for (const simulation::DetectorRecord& d : sim.detector_records()) {
    nlohmann::json j;
    j["type"] = d.type;
    j["alarm_time"] = d.alarm_time ? nlohmann::json(*d.alarm_time) : nlohmann::json(nullptr);
    // Hypothesis k <= number of lines is "line k failed"; pairs are named by their label.
    const int lines = sim.num_lines();
    if (!d.alarm_time) {
      j["isolated_line"] = nullptr;
    } else if (d.isolated >= 1 && d.isolated <= lines) {
      j["isolated_line"] = d.isolated;
    } else {
      j["isolated_line"] = nullptr;
      j["isolated_hypothesis"] = labels.at(d.isolated);
    }
    j["delay"] = (d.alarm_time && scenario.failure.line > 0)
                     ? nlohmann::json(*d.alarm_time - scenario.failure.time)
                     : nlohmann::json(nullptr);
    j["false_alarms"] = d.false_alarms;
    detectors[d.label] = j;
  }
  summary["detectors"] = detectors;
  const simulation::DetectionTiming& timing = sim.detection_timing();
  summary["detection"] = {{"setup_seconds", timing.setup_seconds},
                          {"update_seconds", timing.update_seconds},
                          {"samples", timing.samples}};
  summary["status"] = status;
  if (!message.empty()) summary["error"] = message;
  summary["simulated_time"] = sim.time();
  summary["wall_time"] = wall;
  summary["real_time_factor"] = sim.time() / wall;
  summary["integrator"] = Stats(sim.stats());
  summary["outputs"] = {{"run", "run.h5"}};
  std::ofstream((dir / "summary.json").string()) << summary.dump(2) << "\n";
  if (status != "ok") throw SolverError(message);
  if (!o.quiet) {
    std::fprintf(stderr, "moorsim run: %.0f s simulated in %.1f s (%.0fx real time) -> %s\n",
                 sim.time(), wall, sim.time() / wall, dir.string().c_str());
    // One line per detector: what it concluded (summary.json has the same).
    for (const simulation::DetectorRecord& d : sim.detector_records()) {
      if (d.alarm_time) {
        std::fprintf(stderr, "  %s: alarm at %.0f s, line %d", d.label.c_str(), *d.alarm_time,
                     d.isolated);
        if (scenario.failure.line > 0) {
          std::fprintf(stderr, " (delay %.0f s after line %d parted)",
                       *d.alarm_time - scenario.failure.time, scenario.failure.line);
        }
      } else {
        std::fprintf(stderr, "  %s: no alarm", d.label.c_str());
      }
      std::fprintf(stderr, ", %d false alarm%s\n", d.false_alarms, d.false_alarms == 1 ? "" : "s");
    }
  }
  return 0;
}

}  // namespace

Command AddRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand(
      "run",
      "simulate the vessel on its FEM lines with waves, current, wind, thrusters, controller "
      "and sensors; writes DIR/run.h5 and DIR/summary.json");
  sub->add_option("scenario", o->scenario, "scenario YAML file")->required();
  sub->footer("\n" + detectors::DetectorHelp());
  sub->add_option("--out", o->out, "output directory (default out/<scenario name>)");
  sub->add_option("--seed", o->seed, "run seed (default simulation.seed of the scenario)");
  sub->add_option("--duration", o->duration, "simulated time [s] (default simulation.duration)");
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_flag("--quiet", o->quiet, "no progress lines on stderr");
  return [o] { return Run(*o); };
}

}  // namespace moorsim::cli
