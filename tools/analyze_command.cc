// `moorsim analyze`: how well the detectors' hypotheses can be told apart, from the models
// alone, before a campaign (Hassani et al. 2018, Theorem 2; detectors/distinguishability.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/version.h"
#include "detectors/distinguishability.h"
#include "detectors/hypothesis_bank.h"
#include "runner/scenario_plant.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/detection_models.h"
#include "simulation/simulation.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct AnalyzeOptions {
  std::string scenario;
  std::vector<std::string> sets;
  std::string min_rate = "0.01";
  std::string window = "60";
  bool json = false;
};

/// `text` broken at spaces into lines of at most `width` characters.
std::string Wrap(const std::string& text, std::size_t width) {
  std::string out, line, word;
  std::istringstream words(text);
  while (words >> word) {
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  return out + line + "\n";
}

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

int Analyze(const AnalyzeOptions& o) {
  detectors::DistinguishabilityOptions options;
  options.min_rate = ParseNumber("--min-rate", o.min_rate);
  if (options.min_rate < 0.0) {
    throw InputError("--min-rate: '" + o.min_rate + "' must be >= 0 [nats/sample]");
  }
  options.transient_duration = ParseNumber("--window", o.window);
  if (options.transient_duration <= 0.0) {
    throw InputError("--window: '" + o.window + "' must be > 0 [s]");
  }
  const scenarios::Scenario scenario = scenarios::LoadScenario(o.scenario, o.sets);
  if (!scenario.vessel) {
    throw InputError(scenario.source_path +
                     ": vessel: the section is missing; analyze needs the vessel's mass and "
                     "damping for the observers' model");
  }
  const auto start = std::chrono::steady_clock::now();
  // The simulation's static start gives the moored heave the bank's fairleads sit at, and
  // its plant the observers' mass and damping: the same models a run would detect with.
  // Its own detectors are not needed (and passive observers would train for seconds).
  scenarios::Scenario plant_only = scenario;
  plant_only.detectors.clear();
  const std::unique_ptr<simulation::Simulation> owned =
      runner::MakeSimulation(plant_only, scenario.simulation.seed);
  simulation::Simulation& sim = *owned;
  const simulation::DetectionModels models = simulation::MakeDetectionModels(
      scenarios::ToDetectionSetup(scenario), sim.plant().model(), sim.initial_pose());
  const detectors::HypothesisBank bank(scenarios::ToMooringParameters(scenario.mooring),
                                       models.bank);
  options.sample_interval = 1.0 / scenario.sensors.gnss_rate;
  const Vec3& pose = models.bank.reference_pose;
  const scenarios::ControllerSpec& controller = scenario.controller;
  if (controller.type == vessel::ControllerType::kPi) {
    // The analysis closes the controller the run has, sampled with the observations.
    if (std::abs(controller.rate - scenario.sensors.gnss_rate) >
        1e-12 * scenario.sensors.gnss_rate) {
      throw InputError(scenario.source_path + ": controller.rate_hz: '" +
                       FormatNumber(controller.rate) +
                       "': analyze closes the pi controller at the position sensors' rate (" +
                       FormatNumber(scenario.sensors.gnss_rate) + " Hz); they must be equal");
    }
    const vessel::ControllerSpec spec = sim.model().controller.SizedFor(sim.plant().model());
    options.feedback =
        detectors::PoseFeedback{.kp = spec.pi.kp,
                                .ki = spec.pi.ki,
                                .kd = spec.pi.kd,
                                .derivative_filter_time = spec.pi.derivative_filter_time,
                                .filtered_error = spec.pi.filtered_error};
  } else if (scenario.vessel->turret.bearing != vessel::TurretBearing::kLocked) {
    // Each model must hold its pose (Hassani et al. 2018, Theorem 2's stationary filters);
    // on its bearing the turret leaves the heading to the controller, and the analysis
    // models the pi controller only.
    throw InputError(scenario.source_path + ": controller.type: '" +
                     std::string(ChoiceName(controller.type)) +
                     "': with the turret on its bearing (vessel.turret.bearing '" +
                     std::string(ChoiceName(scenario.vessel->turret.bearing)) +
                     "') the controller holds the heading, and analyze models only the 'pi' "
                     "controller");
  }
  const detectors::Distinguishability d =
      detectors::AnalyzeDistinguishability(bank, models.model, models.ekf, pose, options);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int n = bank.size();
  std::vector<std::string> labels;
  for (int h = 0; h < n; ++h) labels.push_back(bank.Label(h));
  const double heading_deg = pose.z() * 180.0 / std::numbers::pi;
  // The analysis is of the bank of Hassani et al. 2018: one EKF per hypothesis,
  // independent. Say so when the scenario's detectors would see something else.
  std::vector<std::string> notes;
  const double switch_rate = models.observer_bank.switch_rate;
  if (scenario.detection.observer != simulation::ObserverType::kEkf) {
    notes.push_back("the scenario's observers are '" +
                    std::string(ChoiceName(scenario.detection.observer)) +
                    "'; this is the EKF bank's analysis");
  }
  if (switch_rate > 0.0) {
    notes.push_back(
        "these are independent filters (Hassani et al. 2018; detection.switch_rate 0); the "
        "scenario's bank mixes them (IMM, switch_rate " +
        FormatNumber(switch_rate) +
        "/s), which pulls the failure filters back to the intact estimate while intact holds, so "
        "its evidence after a break differs from (and is mostly larger than) the transient "
        "column");
  }

  if (o.json) {
    nlohmann::json out;
    out["scenario"] = scenario.source_path;
    out["scenario_name"] = scenario.name;
    out["overrides"] = scenario.overrides;
    out["version"] = moorsim::kVersion;
    out["hypotheses"] = labels;
    out["reference_pose"] = {pose.x(), pose.y(), heading_deg};
    out["sample_interval"] = d.sample_interval;
    out["rate_units"] = "nats/sample";
    nlohmann::json rate = nlohmann::json::array();
    for (int i = 0; i < n; ++i) {
      nlohmann::json row = nlohmann::json::array();
      for (int j = 0; j < n; ++j) row.push_back(NumberOrNull(d.rate(i, j)));
      rate.push_back(row);
    }
    out["rate"] = rate;
    out["min_rate"] = options.min_rate;
    nlohmann::json hard = nlohmann::json::array();
    for (const auto& [i, j] : d.hard_pairs) {
      hard.push_back({{"hypotheses", {labels[i], labels[j]}},
                      {"indices", {i, j}},
                      {"rate", {d.rate(i, j), d.rate(j, i)}}});
    }
    out["hard_pairs"] = hard;
    nlohmann::json lines = nlohmann::json::array();
    for (const detectors::TransientEvidence& t : d.transient) {
      nlohmann::json line = {{"line", bank.failed_lines(t.hypothesis).front()},
                             {"hypothesis", labels[t.hypothesis]},
                             {"against_intact", t.against_intact},
                             {"against_intact_heading", t.against_intact_heading}};
      line["rival"] = t.rival >= 0 ? nlohmann::json(labels[t.rival]) : nlohmann::json(nullptr);
      line["against_rival"] = t.rival >= 0 ? NumberOrNull(t.against_rival) : nullptr;
      lines.push_back(line);
    }
    out["transient"] = {{"duration", d.transient_samples * d.sample_interval},
                        {"samples", d.transient_samples},
                        {"units", "nats"},
                        {"lines", lines}};
    out["filters"] = "independent";
    out["controller"] = options.feedback ? "pi (closed, linearised)" : "thrust held";
    out["scenario_switch_rate"] = switch_rate;
    out["notes"] = notes;
    out["wall_time"] = wall;
    std::cout << out.dump(2) << "\n";
    return 0;
  }

  std::printf("moorsim %s analyze: %s, %d hypotheses\n", moorsim::kVersion,
              scenario.source_path.c_str(), n);
  std::printf(
      "EKF models linearised at x %.3g m, y %.3g m, heading %.4g deg (the station-keeping "
      "pose); sample interval %g s\n\n",
      pose.x(), pose.y(), heading_deg, d.sample_interval);
  std::printf(
      "Expected log-likelihood ratio per sample D(row || column) [nats/sample]: data from the "
      "row's\nmodel, the row's filter against the column's (Hassani et al. 2018, Theorem 2)\n\n");
  std::size_t width = 10;
  for (const std::string& l : labels) width = std::max(width, l.size() + 2);
  const int w = static_cast<int>(width);
  std::printf("%-*s", w, "");
  for (const std::string& l : labels) std::printf("%*s", w, l.c_str());
  std::printf("\n");
  for (int i = 0; i < n; ++i) {
    std::printf("%-*s", w, labels[i].c_str());
    for (int j = 0; j < n; ++j) {
      if (!std::isfinite(d.rate(i, j))) {
        std::printf("%*s", w, "-");
      } else if (i == j) {
        std::printf("%*s", w, "0");
      } else {
        std::printf("%*.4g", w, d.rate(i, j));
      }
    }
    std::printf("\n");
  }
  std::printf(
      "\nHard to tell apart: %zu of %d pairs (D below %g nats/sample both ways, i.e. 10 nats\n"
      "take more than %.0f s):\n",
      d.hard_pairs.size(), n * (n - 1) / 2, options.min_rate,
      options.min_rate > 0.0 ? 10.0 / options.min_rate * d.sample_interval : 0.0);
  if (d.hard_pairs.empty()) std::printf("  none\n");
  for (const auto& [i, j] : d.hard_pairs) {
    std::printf("  %s / %s: %.4g and %.4g nats/sample\n", labels[i].c_str(), labels[j].c_str(),
                d.rate(i, j), d.rate(j, i));
  }
  std::printf(
      "\nExpected evidence in the first %g s after a line parts [nats] (filters converged on "
      "the intact\nvessel at rest, %s; for the line's hypothesis over the other; "
      "'heading': what the\nheading channel adds to the position channels' evidence against "
      "intact):\n\n",
      d.transient_samples * d.sample_interval,
      options.feedback ? "the pi controller closed" : "thrust held");
  std::printf("%-*s%*s%*s   %-*s%*s\n", w, "line", 12, "vs intact", 10, "heading", w,
              "closest rival", 12, "vs rival");
  for (const detectors::TransientEvidence& t : d.transient) {
    std::printf("%-*s%*.4g%*.4g   ", w, labels[t.hypothesis].c_str(), 12, t.against_intact, 10,
                t.against_intact_heading);
    if (t.rival < 0) {
      std::printf("%-*s%*s\n", w, "-", 12, "-");
      continue;
    }
    std::printf("%-*s%*.4g\n", w, labels[t.rival].c_str(), 12, t.against_rival);
  }
  for (const std::string& note : notes)
    std::printf("\n%s", Wrap("Note: " + note + ".", 92).c_str());
  std::printf("\n(%.2f s)\n", wall);
  return 0;
}

}  // namespace

Command AddAnalyzeCommand(CLI::App& app) {
  auto o = std::make_shared<AnalyzeOptions>();
  CLI::App* sub = app.add_subcommand(
      "analyze", "how well the failure hypotheses can be told apart, before a campaign");
  sub->footer(
      "\n"
      "Each hypothesis (intact, line k failed, pairs if detection.pairs) is its EKF's model\n"
      "linearised at the station-keeping pose (the controller setpoint) and sampled at the\n"
      "GNSS rate. For every pair it prints the expected growth of the log-likelihood ratio,\n"
      "D(i||j) in nats per sample, on data from model i (a Kullback-Leibler rate, Hassani et\n"
      "al. 2018, Theorem 2): the DHT's odds against a wrong j shrink like exp(-n D). A pair\n"
      "with D below --min-rate both ways is flagged hard to tell apart. It then prints the\n"
      "expected evidence gathered in the first --window seconds after each line parts, against\n"
      "intact and against the most confusable other failure: this is what sets the detection\n"
      "delay (a parted line is, to a wrong filter, mostly a constant force its bias absorbs, so\n"
      "the steady rates are small and the evidence comes from the transient).\n"
      "Assumptions: independent filters (Hassani et al. 2018; detection.switch_rate 0), the\n"
      "thrust holding each model at rest at the setpoint (a 'pi' controller is closed around\n"
      "each model, linearised, at the GNSS rate; any other keeps the thrust held, which needs a\n"
      "locked turret), noise as detection.model and detection.measurement_variance state\n"
      "(wave motion, bias, force noise).");
  sub->add_option("scenario", o->scenario, "scenario YAML file")->required();
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_option("--min-rate", o->min_rate,
                  "flag pairs with D below this both ways [nats/sample] (default 0.01: at 1 Hz, "
                  "10 nats (odds e^10 ~ 2e4) then take over 1000 s, longer than the 600 s the "
                  "thesis runs watch after the break)");
  sub->add_option("--window", o->window,
                  "seconds after a break over which the transient evidence is summed "
                  "(default 60: a detector that has not decided by then is slow)");
  sub->add_flag("--json", o->json, "print one JSON object instead of the tables");
  return [o] { return Analyze(*o); };
}

}  // namespace moorsim::cli
