// What a run records for the design checks (summary.json's "design"): per line its top
// tension (the fairlead's) through the run, its largest, when, mean and standard deviation
// (and its largest after the scheduled failure, the standards' transient), the fatigue
// damage its rainflow-counted cycles do on the top section's T-N curve; its largest
// segment tension anywhere along the line; the tension of its touchdown segment (where it
// leaves the seabed at the run's static start) with the damage there. And the vessel's
// largest horizontal offset from where it started. For the extremes of one long run, each
// record's peaks above its mean plus one standard deviation, Weibull-fitted.
//
// It is fed every output row, so its resolution is the run's output rate
// (simulation.output_rate_hz): the fatigue damage needs the waves' cycles, 5 Hz or more
// for sea states of 8 s peak period and up. A campaign's runs keep no run.h5 unless asked,
// so a design campaign sets that rate without the files growing.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/fatigue.h"
#include "core/types.h"
#include "scenarios/scenario.h"
#include "simulation/simulation.h"

namespace moorsim::runner {

class DesignRecord {
 public:
  /// For `sim`, built from `scenario` and at its static start (the offsets are measured
  /// from its initial pose).
  DesignRecord(const scenarios::Scenario& scenario, simulation::Simulation& sim);

  /// One output row (the simulation at the row's time, `sample` its record); rows before
  /// simulation.statistics_from are left out.
  void Add(simulation::Simulation& sim, const simulation::Sample& sample);

  /// summary.json's "design" object.
  nlohmann::json Summary() const;

 private:
  struct Place {
    std::string type;  // the line type there
    double breaking = 0.0;
    std::optional<analysis::FatigueComponent> fatigue;
  };
  struct Line {
    Place top, touchdown;
    int touchdown_segment = 0;  // 0-based, from the anchor
    std::vector<double> top_tension, touchdown_tension;
    double max_along = 0.0;
  };
  std::vector<Line> lines_;
  std::vector<double> times_;
  double failure_time_ = kNaN;  // the scheduled failure (NaN: none)
  double from_ = 0.0;           // rows before this time are left out
  double output_rate_ = 0.0;
  Vec3 start_ = Vec3::Zero();
  std::vector<double> offsets_;  // per row, from start_
  double max_offset_ = 0.0, time_of_max_offset_ = 0.0;
};

}  // namespace moorsim::runner
