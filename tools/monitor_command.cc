// `moorsim monitor CONFIG`: the detection on a vessel's own sensor feeds, as a service that
// runs until SIGINT or SIGTERM (or to the end of a replayed log). monitor/service.h says what
// it does; scenarios/monitor_config.h what the configuration holds.
#include <csignal>
#include <iostream>
#include <memory>

#include "core/error.h"
#include "core/format.h"
#include "monitor/service.h"
#include "runner/run.h"
#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "scenarios/monitor_config.h"
#include "scenarios/plant_builder.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct MonitorOptions {
  std::string config;
  bool quiet = false;
};

// The vessel of the configuration's scenario file: its plant model, with what the display and
// the store take from the file besides. Its detectors are checked first, so that a bad one
// is named at its place in the file.
monitor::MonitoredVessel VesselOf(const scenarios::Scenario& scenario) {
  monitor::MonitoredVessel vessel;
  vessel.model = scenarios::ToPlantModel(scenario);  // names a missing vessel section
  runner::CheckDetectors(scenario);
  vessel.seed = scenario.simulation.seed;
  vessel.name = scenario.name;
  vessel.hull_length = scenario.vessel->hull.length;
  vessel.hull_beam = scenario.vessel->hull.beam;
  vessel.source_path = scenario.source_path;
  vessel.source_text = scenario.text;
  return vessel;
}

int Monitor(const MonitorOptions& o) {
  const scenarios::MonitorConfig config =
      scenarios::LoadMonitorConfig(RequireText("CONFIG", o.config));
  const scenarios::Scenario scenario = scenarios::LoadScenario(config.scenario_path);
  runner::InstallStopSignalHandlers();
  // A bridge or a display that goes away must not take the monitor with it.
  std::signal(SIGPIPE, SIG_IGN);
  monitor::MonitorOptions options;
  options.stop = [] { return runner::StopSignal() != 0; };
  if (!o.quiet) {
    options.log = [](const std::string& line) {
      std::cerr << "moorsim monitor: " << line << std::endl;
    };
  }
  monitor::Monitor service(config, VesselOf(scenario), options);
  const monitor::MonitorSummary summary = service.Run();
  if (!o.quiet) {
    std::cerr << "moorsim monitor: " << summary.lines << " lines, " << summary.samples
              << " samples, " << summary.events << " detector events, " << summary.alarm_changes
              << " alarm changes; latency from a line's arrival to its events "
              << summary.sample_latency.dump() << ", to its ALR " << summary.alarm_latency.dump()
              << std::endl;
  }
  const int signal = runner::StopSignal();
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace

Command AddMonitorCommand(CLI::App& app) {
  auto o = std::make_shared<MonitorOptions>();
  CLI::App* sub = app.add_subcommand(
      "monitor", "watch a vessel's mooring live from its own sensor feeds (NMEA 0183)");
  sub->add_option("config", o->config,
                  "monitor configuration (YAML): the vessel's scenario, its place on the Earth, "
                  "the feeds, the store and the outputs")
      ->required();
  sub->add_flag("--quiet", o->quiet, "no operator log on stderr");
  AddPluginOption(sub);
  sub->footer(
      "\nRuns until SIGINT or SIGTERM (exit 128 + signal), or to the end of a replayed log\n"
      "(exit 0). Detector events are printed as `moorsim detect` prints them, one JSON line\n"
      "each, and alarm changes as JSON lines {unix, utc, alarm, state, text}; both go to the\n"
      "configuration's `alarms` (default standard output). Everything read and decided is\n"
      "recorded in the store first; a monitor started again on its store lists its alarms\n"
      "as they were and warms its observers on what it recorded.");
  return [o] { return Monitor(*o); };
}

}  // namespace moorsim::cli
