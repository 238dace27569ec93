// Load cells as evidence on the coupled plant: the expected reading the observers compute
// (the intact model's quasi-static fairlead tension at the pose) against the FEM lines'
// own static tension, and the cells test wired through a run: with healthy cells it names
// a parted line sooner than the pose alone; a stuck cell on the parting line hides the
// break from it (the pose-only test still names it); a cell drifting on a line that holds
// raises a false alarm only when the cells decide alone. One seed each: the campaign in
// benchmarks/README.md ("Load cells as evidence") has the statistics.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "detectors/hypothesis_bank.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/detection_models.h"
#include "simulation/simulation.h"

namespace moorsim::simulation {
namespace {

const std::string kCellsLibrary = MOORSIM_SOURCE_DIR "/scenarios/library/";
const std::string kCells = "sensors.tension_cells={rate_hz: 1, noise: {std_dev: 1.0e4}}";
const std::string kCellDetectors =
    "detectors=[{type: deficit}, {type: cells, label: cells_alone, confirm: 0, fall_time: 0}, "
    "{type: cells}]";

TEST(LoadCells, TheExpectedReadingIsTheFemLinesStaticTension) {
  // Calm water: the run starts on the FEM's static shape at the moored pose.
  const scenarios::Scenario scenario = scenarios::LoadScenario(
      kCellsLibrary + "thesis_no_failure.yaml", {"environment={}", kCells, kCellDetectors});
  Simulation sim(scenarios::ToPlantModel(scenario), 1);
  const std::vector<double> fem = sim.FairleadTensions();
  const DetectionModels models =
      MakeDetectionModels(*sim.model().detection, sim.plant_model(), sim.initial_pose());
  const detectors::HypothesisBank bank(scenarios::ToMooringParameters(scenario.mooring),
                                       models.bank);
  const Vec6& pose = sim.initial_pose();
  for (int i = 0; i < sim.num_lines(); ++i) {
    const double expected = bank.mooring(0).LineTension(i, Vec3(pose(0), pose(1), pose(5)));
    // The elastic catenary on a rigid seabed against the lumped masses on a seabed spring:
    // 0.008-0.020 % apart on the thesis lines; 0.1 % allowed.
    EXPECT_NEAR(expected / fem[static_cast<std::size_t>(i)], 1.0, 1e-3) << "line " << i + 1;
  }
}

// The first alarm after the failure of each detector, by label (NaN: none), and its false
// alarms.
struct CellRun {
  std::map<std::string, double> delay;
  std::map<std::string, int> line, false_alarms;
};

CellRun RunWithCells(const std::vector<std::string>& more) {
  std::vector<std::string> overrides = {kCells, kCellDetectors};
  overrides.insert(overrides.end(), more.begin(), more.end());
  const scenarios::Scenario scenario =
      scenarios::LoadScenario(kCellsLibrary + "thesis_line6.yaml", overrides);
  Simulation sim(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  sim.AdvanceTo(700.0);
  CellRun run;
  for (const DetectorRecord& r : sim.detector_records()) {
    const auto first = r.FirstAlarm();
    run.delay[r.label] = first ? first->time - 400.0 : std::nan("");
    run.line[r.label] = first ? first->hypothesis : 0;
    run.false_alarms[r.label] = r.FalseAlarms();
  }
  return run;
}

TEST(LoadCellsSlow, HealthyCellsNameTheLineSoonerStuckOnesHideItDriftingOnesNeedThePose) {
  const CellRun healthy = RunWithCells({});
  for (const char* label : {"deficit", "cells", "cells_alone"}) {
    EXPECT_EQ(healthy.line.at(label), 6) << label;
    EXPECT_EQ(healthy.false_alarms.at(label), 0) << label;
  }
  EXPECT_LT(healthy.delay.at("cells"), healthy.delay.at("deficit"));
  EXPECT_LT(healthy.delay.at("cells_alone"), healthy.delay.at("cells"));

  const CellRun stuck =
      RunWithCells({"sensors.tension_cells.faults=[{line: 6, mode: stuck, time: 300}]"});
  EXPECT_EQ(stuck.line.at("deficit"), 6);
  EXPECT_TRUE(std::isnan(stuck.delay.at("cells")));
  EXPECT_TRUE(std::isnan(stuck.delay.at("cells_alone")));

  // Line 3's cell drifts 10 kN/s low from 100 s: 1.5 MN (a quarter) gone by 250 s.
  const CellRun drift = RunWithCells(
      {"sensors.tension_cells.faults=[{line: 3, mode: drift, time: 100, rate: -10000}]"});
  EXPECT_EQ(drift.false_alarms.at("cells_alone"), 1);
  EXPECT_EQ(drift.false_alarms.at("cells"), 0);
  EXPECT_EQ(drift.line.at("cells"), 6);
}

}  // namespace
}  // namespace moorsim::simulation
