// A scenario's plant and detection: the scenario file's way into the simulation, which
// itself knows only the typed plant model (simulation/plant_model.h). Each function converts
// with scenarios::ToPlantModel() and places what the model refuses at its key in the file
// ("<file>:<line>:<col>: mooring.points[1]: ..."), as `moorsim validate` would.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "scenarios/scenario.h"
#include "simulation/detection.h"
#include "simulation/simulation.h"

namespace moorsim::runner {

/// The coupled plant of `scenario` for run seed `seed` at its moored static start (as
/// simulation::Simulation builds it), its errors placed in the file.
std::unique_ptr<simulation::Simulation> MakeSimulation(const scenarios::Scenario& scenario,
                                                       std::uint64_t seed);

/// The scenario's detection as a run of it builds it (simulation::MakeDetection() with the
/// scenario's seed), without the run. Throws InputError naming the file for a scenario
/// without detectors or one that cannot be simulated.
std::unique_ptr<simulation::Detection> MakeDetection(const scenarios::Scenario& scenario);

/// simulation::CheckDetectors() for a scenario, the error placed at the detector's entry in
/// the file. `moorsim validate` and `run` call it.
void CheckDetectors(const scenarios::Scenario& scenario);

/// summary.json's "failure": the scenario's line, time and mode, or null without one.
nlohmann::json FailureSummary(const scenarios::Scenario& scenario);

/// summary.json's "detectors" object (one entry per detector: alarm time, isolated line,
/// delay, false alarms, isolation, final verdict, alarm seconds, the event history) for a
/// detection that ran up to `end_time` [s]; the scenario's failure, if any, is the truth
/// the verdicts are scored against.
nlohmann::json DetectorsSummary(const scenarios::Scenario& scenario,
                                const simulation::Detection& detection, double end_time);

/// The scenario a run.h5 records (its text, source path and overrides), loaded as the run
/// loaded it. Throws InputError naming the run.h5 for a file that is not one, and for a
/// recorded scenario that does not load: "<path>: the scenario it records (from <source>),
/// line L:C: ...", the line being that of the recorded text.
scenarios::Scenario ReadRunScenario(const std::string& path);

}  // namespace moorsim::runner
