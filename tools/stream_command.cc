// `moorsim stream SCENARIO --to CONFIG`: a sea trial on one machine. The scenario is
// simulated (its sea, its sensors' noise and faults, its failure) and each sample its
// detection would take is played to the feeds of a monitor's configuration as the vessel's
// receivers would send it (monitor/harness.h), in real time or --speed times faster, or
// written at once into the tagged log a replay configuration reads.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include "core/error.h"
#include "core/format.h"
#include "monitor/feeds.h"
#include "monitor/harness.h"
#include "runner/run.h"
#include "runner/scenario_plant.h"
#include "scenarios/load.h"
#include "scenarios/monitor_config.h"
#include "simulation/simulation.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct StreamOptions {
  std::string scenario;
  std::string config;
  std::vector<std::string> sets;
  std::optional<std::string> seed;
  std::string speed = "1";
  std::string wait = "10";
  std::string position, heading, cells;
  bool quiet = false;
};

int Stream(const StreamOptions& o) {
  const scenarios::MonitorConfig config =
      scenarios::LoadMonitorConfig(RequireText("--to", o.config));
  std::vector<std::string> overrides = o.sets;
  if (o.seed) overrides.push_back("simulation.seed=" + RequireText("--seed", *o.seed));
  const scenarios::Scenario scenario =
      scenarios::LoadScenario(RequireText("SCENARIO", o.scenario), overrides);
  const double speed = ParseNumber("--speed", o.speed);
  if (!(speed > 0.0 && speed <= 1e6)) {
    throw InputError("--speed: '" + o.speed + "' must be > 0 (1: real time) and at most 1e6");
  }
  const double wait = ParseNumber("--wait", o.wait);
  if (!(wait >= 0.0 && wait <= 3600.0)) {
    throw InputError("--wait: '" + o.wait + "' must be in [0, 3600] s");
  }
  if (scenario.detectors.empty()) {
    throw InputError(o.scenario +
                     ": the scenario has no detectors, so its sensors are not "
                     "sampled for detection; add the detectors the monitor runs");
  }
  const monitor::Routing routing = monitor::RouteFeeds(config, o.position, o.heading, o.cells);
  monitor::SentenceWriter writer(config, routing, scenario.sensors.tension_rate);
  monitor::Player player(config);
  const std::unique_ptr<simulation::Simulation> owned =
      runner::MakeSimulation(scenario, scenario.simulation.seed);
  simulation::Simulation& sim = *owned;
  sim.KeepDetectionInput(true);
  runner::InstallStopSignalHandlers();
  std::signal(SIGPIPE, SIG_IGN);

  const bool paced = !player.OnlyLogs();
  // A monitor connecting over TCP is given `wait` seconds to do so before the play starts.
  const auto clients = player.Clients();
  if (paced && std::any_of(clients.begin(), clients.end(), [](int c) { return c == 0; })) {
    const double until = monitor::UnixNow() + wait;
    while (monitor::UnixNow() < until && runner::StopSignal() == 0) {
      const auto now_clients = player.Clients();
      if (std::none_of(now_clients.begin(), now_clients.end(), [](int c) { return c == 0; })) {
        break;
      }
      player.Serve(50);
    }
  }
  // Sample instants on whole seconds of UNIX time, each line 1 ms after its instant.
  const double start = std::floor(monitor::UnixNow()) + 1.0;
  const double duration = scenario.simulation.duration;
  long sent = 0, samples = 0;
  for (double t = 0.0; t < duration && runner::StopSignal() == 0;) {
    t = std::min(duration, t + 10.0);
    sim.AdvanceTo(t);
    for (const detectors::Observation& obs : sim.Record().detection_input) {
      const double stamp = start + obs.t + 1e-3;
      if (paced) {
        const double at = start + (obs.t + 1e-3) / speed;
        for (double now = monitor::UnixNow(); now < at && runner::StopSignal() == 0;
             now = monitor::UnixNow()) {
          player.Serve(static_cast<int>(std::clamp((at - now) * 1000.0, 0.0, 50.0)));
        }
      }
      if (runner::StopSignal() != 0) break;
      for (const monitor::PlayedLine& line : writer.Lines(obs, stamp)) {
        player.Send(line, stamp);
        ++sent;
      }
      ++samples;
    }
  }
  if (!o.quiet) {
    std::cerr << "moorsim stream: " << samples << " samples, " << sent << " lines played from "
              << scenario.name << " (seed " << scenario.simulation.seed << ")" << std::endl;
  }
  const int signal = runner::StopSignal();
  return signal != 0 ? 128 + signal : 0;
}

}  // namespace

Command AddStreamCommand(CLI::App& app) {
  auto o = std::make_shared<StreamOptions>();
  CLI::App* sub = app.add_subcommand(
      "stream", "simulate a scenario and play its sensors to a monitor's feeds (a sea trial)");
  sub->add_option("scenario", o->scenario, "scenario YAML: the simulated vessel")->required();
  sub->add_option("--to", o->config, "the monitor configuration whose feeds are played to")
      ->required();
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_option("--seed", o->seed, "run seed (default simulation.seed of the scenario)");
  sub->add_option("--speed", o->speed, "times faster than real time (default 1)");
  sub->add_option("--wait", o->wait,
                  "seconds to wait for the monitor to connect to TCP feeds (default 10)");
  sub->add_option("--position", o->position, "the feed for GGA (default: the first NMEA feed)");
  sub->add_option("--heading", o->heading, "the feed for HDT (default: the first NMEA feed)");
  sub->add_option("--cells", o->cells,
                  "the feed for the cells' XDR (default: the first NMEA feed)");
  sub->add_flag("--quiet", o->quiet, "no summary line on stderr");
  AddPluginOption(sub);
  sub->footer(
      "\nEach sample the scenario's detection takes becomes GGA (the GNSS antenna), HDT, one\n"
      "XDR per load cell and a thrust line, sent 1 ms after the sample's instant to UDP ports\n"
      "and groups, to the monitor as a TCP server, or into a pipe; a feed timed by tags gets\n"
      "each line's time in a TAG block, so --speed 20 plays 20 s of the ship per second. A\n"
      "configuration whose one feed is a tagged log file gets the whole log written at once.");
  return [o] { return Stream(*o); };
}

}  // namespace moorsim::cli
