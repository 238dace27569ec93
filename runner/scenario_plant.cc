#include "runner/scenario_plant.h"

#include <algorithm>
#include <string_view>
#include <vector>

#include "core/choice.h"
#include "core/error.h"
#include "io/hdf5_reader.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"

namespace moorsim::runner {
namespace {

// Rethrows what the model refused about a free point or a detector at its key in the
// scenario's file; anything else as it is.
[[noreturn]] void PlaceInScenario(const scenarios::Scenario& scenario, const InputError& e) {
  const std::string_view message = e.what();
  scenarios::PlaceAtKey(scenario, e,
                        message.starts_with("mooring.points[") ? "mooring.points[" : "detectors[");
}

/// The loader's message about a run.h5's recorded scenario, each line restated to name the
/// run.h5: the loader names the scenario's source file, whose lines (and perhaps whose
/// content) are not those of the text the run recorded.
std::string InRecordedScenario(const std::string& path, const std::string& source,
                               const std::string& message) {
  const std::string scenario = path + ": the scenario it records (from " + source + ")";
  std::string restated;
  for (std::size_t begin = 0; begin <= message.size();) {
    const std::size_t end = std::min(message.find('\n', begin), message.size());
    std::string line = message.substr(begin, end - begin);
    begin = end + 1;
    if (!restated.empty()) restated += '\n';
    const std::string prefix = source + ":";
    if (line.rfind(prefix, 0) != 0) {
      restated += scenario + ": " + line;
      continue;
    }
    line.erase(0, prefix.size());
    // "12:5: key: what" (a located message) or " what".
    const std::size_t digits = line.find_first_not_of("0123456789:");
    if (digits != std::string::npos && digits > 0 && line.compare(digits - 1, 2, ": ") == 0) {
      restated += scenario + ", line " + line;
    } else {
      restated += scenario + ":" + line;
    }
  }
  return restated;
}

}  // namespace

std::unique_ptr<simulation::Simulation> MakeSimulation(const scenarios::Scenario& scenario,
                                                       std::uint64_t seed) {
  try {
    return std::make_unique<simulation::Simulation>(scenarios::ToPlantModel(scenario), seed);
  } catch (const InputError& e) {
    PlaceInScenario(scenario, e);
  }
}

std::unique_ptr<simulation::Detection> MakeDetection(const scenarios::Scenario& scenario) {
  if (scenario.detectors.empty()) {
    throw InputError(scenario.source_path + ": detectors: none (detection needs at least one)");
  }
  try {
    return simulation::MakeDetection(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  } catch (const InputError& e) {
    PlaceInScenario(scenario, e);
  }
}

void CheckDetectors(const scenarios::Scenario& scenario) {
  try {
    simulation::CheckDetectors(scenarios::ToDetectionSetup(scenario));
  } catch (const InputError& e) {
    scenarios::PlaceAtKey(scenario, e, "detectors[");
  }
}

nlohmann::json FailureSummary(const scenarios::Scenario& scenario) {
  if (scenario.failure.line == 0) return nullptr;
  return {{"line", scenario.failure.line},
          {"time", scenario.failure.time},
          {"mode", ChoiceName(scenario.failure.mode)}};
}

nlohmann::json DetectorsSummary(const scenarios::Scenario& scenario,
                                const simulation::Detection& detection, double end_time) {
  nlohmann::json detectors = nlohmann::json::object();
  const std::vector<std::string> labels = detection.HypothesisLabels();
  const int lines = static_cast<int>(scenario.mooring.lines.size());
  for (const simulation::DetectorRecord& d : detection.records()) {
    nlohmann::json j;
    j["type"] = d.type;
    if (d.threshold) j["threshold"] = *d.threshold;
    const std::optional<detectors::AlarmEvent> first = d.FirstAlarm();
    j["alarm_time"] = first ? nlohmann::json(first->time) : nlohmann::json(nullptr);
    // Hypothesis k <= number of lines is "line k failed"; pairs are named by their label.
    if (!first) {
      j["isolated_line"] = nullptr;
    } else if (first->hypothesis >= 1 && first->hypothesis <= lines) {
      j["isolated_line"] = first->hypothesis;
    } else {
      j["isolated_line"] = nullptr;
      j["isolated_hypothesis"] = labels.at(first->hypothesis);
    }
    j["delay"] = (first && d.failure_time) ? nlohmann::json(first->time - *d.failure_time)
                                           : nlohmann::json(nullptr);
    j["false_alarms"] = d.FalseAlarms();
    // The verdict as it evolved (detectors::AlarmHistory): when it first named the failed
    // line after the break, by an onset, a revision or an alarm already standing on it;
    // what it said at the end; how long an alarm stood before and after the break.
    const bool failed = scenario.failure.line > 0 && scenario.failure.time <= end_time;
    const double t_failure = failed ? scenario.failure.time : end_time;
    const std::optional<double> named =
        failed ? d.history.FirstNamed(scenario.failure.line, t_failure) : std::nullopt;
    j["isolation_time"] = named ? nlohmann::json(*named) : nlohmann::json(nullptr);
    j["isolation_delay"] = named ? nlohmann::json(*named - t_failure) : nlohmann::json(nullptr);
    j["final_alarm"] = d.history.alarm();
    j["final_hypothesis"] = d.history.alarm() ? nlohmann::json(labels.at(d.history.hypothesis()))
                                              : nlohmann::json(nullptr);
    const int final_hypothesis = d.history.hypothesis();
    j["final_line"] = final_hypothesis >= 1 && final_hypothesis <= lines
                          ? nlohmann::json(final_hypothesis)
                          : nlohmann::json(nullptr);
    j["alarm_seconds_before_failure"] = d.history.AlarmSeconds(0.0, t_failure);
    j["alarm_seconds_after_failure"] =
        failed ? nlohmann::json(d.history.AlarmSeconds(t_failure, end_time))
               : nlohmann::json(nullptr);
    nlohmann::json history = nlohmann::json::array();
    for (const detectors::AlarmEvent& e : d.history.events()) {
      history.push_back({{"time", e.time},
                         {"event", detectors::AlarmEventName(e.kind)},
                         {"hypothesis", e.kind == detectors::AlarmEvent::Kind::kEnd
                                            ? nlohmann::json(nullptr)
                                            : nlohmann::json(labels.at(e.hypothesis))}});
    }
    j["history"] = history;
    // The sensors it judged faulty (not a line's failure), each spell.
    nlohmann::json sensor_faults = nlohmann::json::array();
    for (const detectors::SensorFaultSpell& spell : d.sensor_faults.spells()) {
      sensor_faults.push_back(
          {{"sensor", spell.sensor.Name()},
           {"fault", detectors::SensorSymptomName(spell.symptom)},
           {"since", spell.since},
           {"until", spell.until ? nlohmann::json(*spell.until) : nlohmann::json(nullptr)}});
    }
    j["sensor_faults"] = sensor_faults;
    detectors[d.label] = j;
  }
  return detectors;
}

scenarios::Scenario ReadRunScenario(const std::string& path) {
  const output::Hdf5Reader file(path);
  const std::string text = file.StringAttribute("/", "scenario");
  const std::string source = file.StringAttribute("/", "scenario_path");
  std::vector<std::string> overrides;
  const std::string joined = file.StringAttribute("/", "overrides");
  for (std::size_t begin = 0; begin < joined.size();) {
    const std::size_t end = std::min(joined.find('\n', begin), joined.size());
    overrides.push_back(joined.substr(begin, end - begin));
    begin = end + 1;
  }
  try {
    return scenarios::ParseScenario(text, source, overrides);
  } catch (const InputError& error) {
    throw InputError(InRecordedScenario(path, source, error.what()));
  }
}

}  // namespace moorsim::runner
