// `moorsim run`: one coupled simulation of a scenario, written to DIR/run.h5 and
// DIR/summary.json by the library's RunScenario (runner/run.h), which batch runs
// and the tests call too.
#include <cstdio>
#include <iostream>
#include <memory>

#include "detectors/registry.h"
#include "runner/run.h"
#include "tools/commands.h"
#include "tools/exit_codes.h"

namespace moorsim::cli {
namespace {

struct RunOptions {
  std::string scenario;
  std::optional<std::string> out;
  std::optional<std::string> seed;
  std::optional<std::string> duration;
  std::vector<std::string> sets;
  bool quiet = false;
};

/// One line per detector: what it concluded (summary.json has the same).
void PrintDetectors(const nlohmann::json& summary) {
  const nlohmann::json& failure = summary.at("failure");
  for (const auto& [label, d] : summary.at("detectors").items()) {
    const int false_alarms = d.at("false_alarms").get<int>();
    if (d.at("alarm_time").is_null()) {
      std::fprintf(stderr, "  %s: no alarm", label.c_str());
    } else {
      const nlohmann::json& line = d.at("isolated_line");
      std::fprintf(stderr, "  %s: alarm at %.0f s, %s", label.c_str(),
                   d.at("alarm_time").get<double>(),
                   line.is_null() ? d.value("isolated_hypothesis", std::string("?")).c_str()
                                  : ("line " + std::to_string(line.get<int>())).c_str());
      if (!failure.is_null()) {
        std::fprintf(stderr, " (delay %.0f s after line %d parted)", d.at("delay").get<double>(),
                     failure.at("line").get<int>());
      }
    }
    std::fprintf(stderr, ", %d false alarm%s\n", false_alarms, false_alarms == 1 ? "" : "s");
  }
}

int Run(const RunOptions& o) {
  runner::RunRequest request;
  request.scenario_path = o.scenario;
  request.overrides = o.sets;
  if (o.seed) request.overrides.push_back("simulation.seed=" + RequireText("--seed", *o.seed));
  if (o.duration) {
    request.overrides.push_back("simulation.duration=" + RequireText("--duration", *o.duration));
  }
  if (o.out) request.out = RequireText("--out", *o.out);
  request.progress = !o.quiet;
  runner::InstallStopSignalHandlers();
  request.stop_requested = runner::StopSignal;
  const runner::RunResult result = runner::RunScenario(request);
  if (result.status == runner::RunStatus::kRejected) {
    std::cerr << "moorsim: " << FlagMessage(result.message, result.option_error) << "\n";
    return ExitCodeOf(result);
  }
  if (result.status != runner::RunStatus::kOk) {
    std::cerr << "moorsim: " << runner::StatusName(result.status) << ": " << result.message << "\n";
  }
  if (!o.quiet && result.summary_written) {
    const double wall = result.summary.at("wall_time").get<double>();
    std::fprintf(stderr, "moorsim run: %.0f s simulated in %.1f s (%.0fx real time) -> %s\n",
                 result.simulated_time, wall, wall > 0 ? result.simulated_time / wall : 0.0,
                 result.directory.string().c_str());
    if (result.summary.contains("detectors")) PrintDetectors(result.summary);
  }
  return ExitCodeOf(result);
}

}  // namespace

Command AddRunCommand(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand(
      "run",
      "simulate the moored vessel with waves, current, wind, thrusters, controller and sensors");
  sub->add_option("scenario", o->scenario, "scenario YAML file")->required();
  sub->footer(
      "\nWrites DIR/run.h5 and DIR/summary.json. Exit codes: 0 ok, 1 failed (integrator, static\n"
      "start or an output write), 2 bad input, 130/143 interrupted by SIGINT/SIGTERM (the run\n"
      "stops at the next output row and summary.json says \"interrupted\").\n\n" +
      detectors::DetectorHelp());
  sub->add_option("--out", o->out, "output directory (default out/<scenario name>)");
  sub->add_option("--seed", o->seed, "run seed (default simulation.seed of the scenario)");
  sub->add_option("--duration", o->duration, "simulated time [s] (default simulation.duration)");
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_flag("--quiet", o->quiet, "no progress lines on stderr");
  AddPluginOption(sub);
  return [o] { return Run(*o); };
}

}  // namespace moorsim::cli
