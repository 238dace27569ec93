// A plant model filled in code, in the modules' own types and without YAML, is the plant
// the scenario describing it gives: the two run bit for bit alike, with waves, wind, the
// controller's sized heading loop, noisy sensors, a load cell that sticks, a parted line
// and two detectors. The scenario's conversion (scenarios::ToPlantModel) is then only one
// way to fill the model.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "scenarios/convert.h"
#include "scenarios/plant_builder.h"
#include "simulation/plant_model.h"
#include "simulation/simulation.h"
#include "tests/simulation/test_scenarios.h"

namespace moorsim::simulation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The scenario's own words for the plant built in code below.
const char kSections[] = R"(
environment:
  waves: {hs: 2.5, tp: 7, gamma: 3.3, direction_toward_deg: 315, components: 200}
  wind: {speed: 15, direction_from_deg: 30}
controller:
  type: pi
  rate_hz: 1
  setpoint: {x: 0, y: 0, heading_deg: 0}
  heading: {natural_period: 200, damping_ratio: 0.8}
sensors:
  tension_cells:
    rate_hz: 1
    noise: {std_dev: 1.0e4}
    faults: [{line: 3, mode: stuck, time: 20}]
failure: {line: 6, time: 40, mode: fairlead}
detectors: [{type: dht}, {type: cells}]
)";

// The same plant from the modules' types: the seed FPSO's hull, windage, thrusters and
// sensors from their own constants, the rest written out.
PlantModel PlantInCode(const mooring_fem::MooringParameters& mooring) {
  PlantModel m;
  m.name = "the seed plant, in code";
  m.mooring = mooring;
  m.hydrodynamics = MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso";
  m.wamit = {.water_density = mooring.water.density, .gravity = mooring.water.gravity};
  m.mass = {.mass = 1.0041e8, .r_g = Vec3(0, 0, 1), .radii_of_gyration = Vec3(16.3, 54, 54)};
  m.thrusters = vessel::SeedThrusters();
  m.turret.bearing = vessel::TurretBearing::kFree;
  // The turret's bearing radius: the fairleads' largest distance from its centre.
  m.turret.bearing_radius = 0.0;
  for (const mooring_fem::LineParameters& line : mooring.lines) {
    m.turret.bearing_radius =
        std::max(m.turret.bearing_radius, line.fairlead_body.head<2>().norm());
  }
  m.initial_pose = Vec3(2.0, 2.0, 0.0);

  m.hull_drag = vessel::SeedFpsoHull();
  m.hull_drag->water_density = mooring.water.density;
  SeaModel& sea = m.waves.emplace();
  sea.spectrum = {.significant_height = 2.5, .peak_period = 7.0, .peak_enhancement = 3.3};
  sea.realisation.mean_direction = 315.0 * kDeg;
  sea.realisation.components = 200;
  sea.realisation.gravity = mooring.water.gravity;
  m.wind = WindModel{.hull = vessel::SeedFpsoWind(),
                     .speed = {.mean_speed = 15.0},
                     .direction_from = 30.0 * kDeg,
                     .gust = true};
  m.pose_sensors = vessel::SeedPoseSensors();
  TensionCellsModel& cells = m.tension_cells.emplace();
  cells.noise.std_dev = 1.0e4;
  cells.faults.push_back(
      {.line = 2, .fault = {.mode = vessel::SensorFault::Mode::kStuck, .from = 20.0}});
  m.controller.spec.type = vessel::ControllerType::kPi;
  m.controller.spec.pi.kp = Vec3(1e5, 1e6, 1e3);
  m.controller.spec.pi.ki = Vec3(1e3, 1e3, 1e2);
  m.controller.heading = vessel::HeadingLoopTuning{.natural_period = 200, .damping_ratio = 0.8};
  m.failure = FailureEvent{.time = 40.0, .failure = {.line = 5}};

  DetectionSetup& detection = m.detection.emplace();
  detection.detectors.push_back({.type = "dht", .label = "dht", .parameters = {}, .plugin = ""});
  detection.detectors.push_back(
      {.type = "cells", .label = "cells", .parameters = {}, .plugin = ""});
  detection.bank.turret = detectors::TurretModel{Eigen::Vector2d::Zero(), 0.0};
  detection.ekf.measurement_variance = Vec3::Constant(0.005);
  return m;
}

TEST(PlantModel, FilledInCodeRunsAsItsScenarioBitForBit) {
  const scenarios::Scenario scenario = testing::SeedVesselScenario(
      kSections, "  turret: {bearing: free}\n  initial_pose: {x: 2, y: 2, heading_deg: 0}\n");
  Simulation from_scenario(scenarios::ToPlantModel(scenario), 7);
  Simulation in_code(PlantInCode(scenarios::ToMooringParameters(scenario.mooring)), 7);
  for (double t = 10.0; t <= 60.0; t += 10.0) {
    from_scenario.AdvanceTo(t);
    in_code.AdvanceTo(t);
    const Sample a = from_scenario.Record(), b = in_code.Record();
    SCOPED_TRACE("t = " + std::to_string(t));
    for (int i = 0; i < 6; ++i) ASSERT_EQ(a.pose_true(i), b.pose_true(i)) << "pose " << i;
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(a.pose_measured(i), b.pose_measured(i));
      ASSERT_EQ(a.thrust_commanded(i), b.thrust_commanded(i));
    }
    ASSERT_EQ(a.fairlead_tension, b.fairlead_tension);
    ASSERT_EQ(a.tension_measured, b.tension_measured);
    ASSERT_EQ(a.load_wind, b.load_wind);
    ASSERT_EQ(a.load_current, b.load_current);
    ASSERT_EQ(a.detectors.size(), 2u);
    ASSERT_EQ(b.detectors.size(), 2u);
    for (std::size_t d = 0; d < 2; ++d) ASSERT_EQ(a.detectors[d].score, b.detectors[d].score);
  }
  // The failure happened in both: line 6 went slack (its fairlead tension is zero).
  EXPECT_EQ(in_code.Record().fairlead_tension[5], 0.0);
  // The stuck cell repeats one reading.
  const double stuck = in_code.Record().tension_measured[2];
  in_code.AdvanceTo(61.0);
  EXPECT_EQ(in_code.Record().tension_measured[2], stuck);
}

TEST(PlantModel, ADetectorsBadParameterNamesItsEntry) {
  const scenarios::Scenario scenario = testing::SeedVesselScenario();
  PlantModel m = PlantInCode(scenarios::ToMooringParameters(scenario.mooring));
  m.detection->detectors[1].parameters["confirm"] = -1.0;
  try {
    Simulation sim(m, 1);
    FAIL() << "built";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("detectors[2].confirm: ", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace moorsim::simulation
