// The scenario's hull and windage (vessel.hull, vessel.windage) as the vessel's loads take
// them: the defaults are exactly the seed FPSO's constants (so every library scenario runs
// bit for bit as before they were keys), given values arrive, and the run uses them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"
#include "tests/simulation/test_scenarios.h"
#include "tests/support/scratch_directory.h"
#include "vessel/hull_loads.h"

namespace moorsim::simulation {
namespace {

TEST(VesselConversion, DefaultsAreTheSeedFpso) {
  const scenarios::VesselSpec spec;
  const vessel::HullGeometry hull = scenarios::ToHullGeometry(spec, 1030.0);
  const vessel::HullGeometry seed = vessel::SeedFpsoHull();
  EXPECT_EQ(hull.length, seed.length);
  EXPECT_EQ(hull.beam, seed.beam);
  EXPECT_EQ(hull.draught, seed.draught);
  EXPECT_EQ(hull.displaced_volume, seed.displaced_volume);
  EXPECT_EQ(hull.wetted_surface, seed.wetted_surface);
  EXPECT_EQ(hull.cross_flow_drag_coefficient, seed.cross_flow_drag_coefficient);
  EXPECT_EQ(hull.form_factor, seed.form_factor);
  EXPECT_EQ(hull.kinematic_viscosity, seed.kinematic_viscosity);
  EXPECT_EQ(hull.water_density, 1030.0);  // mooring.water.density

  const vessel::WindParameters wind = scenarios::ToWindParameters(spec);
  const vessel::WindParameters seed_wind = vessel::SeedFpsoWind();
  EXPECT_EQ(wind.air_density, seed_wind.air_density);
  EXPECT_EQ(wind.frontal_area, seed_wind.frontal_area);
  EXPECT_EQ(wind.lateral_area, seed_wind.lateral_area);
  EXPECT_EQ(wind.length, seed_wind.length);
  EXPECT_EQ(wind.coefficients.angle, seed_wind.coefficients.angle);
  EXPECT_EQ(wind.coefficients.surge, seed_wind.coefficients.surge);
  EXPECT_EQ(wind.coefficients.sway, seed_wind.coefficients.sway);
  EXPECT_EQ(wind.coefficients.yaw, seed_wind.coefficients.yaw);
}

TEST(VesselConversion, GivenValuesArrive) {
  scenarios::VesselSpec spec;
  spec.hull.length = 250.0;
  spec.hull.beam = 50.0;
  spec.hull.draught = 15.0;
  spec.hull.displaced_volume = 150000.0;
  spec.hull.kinematic_viscosity = 1.3e-6;
  vessel::HullGeometry hull = scenarios::ToHullGeometry(spec, 1025.0);
  EXPECT_EQ(hull.length, 250.0);
  EXPECT_EQ(hull.beam, 50.0);
  EXPECT_EQ(hull.draught, 15.0);
  EXPECT_EQ(hull.displaced_volume, 150000.0);
  EXPECT_EQ(hull.kinematic_viscosity, 1.3e-6);
  EXPECT_EQ(hull.form_factor, vessel::WatanabeFormFactor(250.0, 50.0, 15.0, 150000.0));
  spec.hull.wetted_surface = 20000.0;
  spec.hull.cross_flow_drag_coefficient = 0.8;
  spec.hull.form_factor = 0.3;
  hull = scenarios::ToHullGeometry(spec, 1025.0);
  EXPECT_EQ(hull.wetted_surface, 20000.0);
  EXPECT_EQ(hull.cross_flow_drag_coefficient, 0.8);
  EXPECT_EQ(hull.form_factor, 0.3);

  spec.windage.frontal_area = 1500.0;
  spec.windage.lateral_area = 6000.0;
  spec.windage.lateral_centroid = -25.0;
  spec.windage.air_density = 1.25;
  vessel::WindParameters wind = scenarios::ToWindParameters(spec);
  EXPECT_EQ(wind.frontal_area, 1500.0);
  EXPECT_EQ(wind.lateral_area, 6000.0);
  EXPECT_EQ(wind.air_density, 1.25);
  EXPECT_EQ(wind.length, 250.0);  // the hull's
  EXPECT_EQ(wind.coefficients.yaw, vessel::LoadedTankerWindCoefficients(1500.0, 6000.0, -0.1).yaw);
  spec.windage.length = 200.0;
  wind = scenarios::ToWindParameters(spec);
  EXPECT_EQ(wind.length, 200.0);
  EXPECT_EQ(wind.coefficients.yaw,
            vessel::LoadedTankerWindCoefficients(1500.0, 6000.0, -0.125).yaw);
}

const vessel::EnvironmentLoad& LoadNamed(Simulation& sim, std::string_view name) {
  for (const vessel::EnvironmentLoad* load : sim.plant().loads()) {
    if (load->name() == name) return *load;
  }
  throw std::runtime_error("no load named " + std::string(name));
}

// The coupled run's current and wind loads are built from the scenario's hull and windage.
TEST(VesselConversion, TheRunUsesTheScenariosHullAndWindage) {
  const scenarios::Scenario s = testing::SeedVesselScenario(
      "environment:\n"
      "  current: {direction_deg: 30, profile: [{depth: 0, speed: 0.5}]}\n"
      "  wind: {speed: 15, direction_from_deg: 100, gust: false}\n",
      "  hull: {draught: 16, displaced_volume: 130000}\n"
      "  windage: {lateral_area: 6000, lateral_centroid: -20}\n");
  Simulation sim(scenarios::ToPlantModel(s), 1);
  Vec6 eta = Vec6::Zero();
  eta(5) = 0.3;
  Vec6 nu = Vec6::Zero();
  nu << 0.2, -0.1, 0.0, 0.0, 0.0, 0.001;

  const scenarios::CurrentProfile& c = s.mooring.current;
  const Vec3 current = c.SurfaceSpeed() * Vec3(std::cos(c.direction), std::sin(c.direction), 0.0);
  const vessel::CurrentLoad expected_current(
      scenarios::ToHullGeometry(*s.vessel, s.mooring.water.density));
  const Vec6 tau_current = LoadNamed(sim, "current").Load(0.0, eta, nu);
  EXPECT_EQ(tau_current, expected_current.Load(eta, nu, current));
  vessel::HullGeometry seed_hull = vessel::SeedFpsoHull();
  seed_hull.water_density = s.mooring.water.density;
  EXPECT_NE(tau_current, vessel::CurrentLoad(seed_hull).Load(eta, nu, current));

  const vessel::WindLoad expected_wind(scenarios::ToWindParameters(*s.vessel));
  const double direction = s.environment.wind.direction_from;
  const Vec6 tau_wind = LoadNamed(sim, "wind").Load(0.0, eta, nu);
  EXPECT_EQ(tau_wind, expected_wind.Load(eta, nu, 15.0, direction));
  EXPECT_NE(tau_wind, vessel::WindLoad(vessel::SeedFpsoWind()).Load(eta, nu, 15.0, direction));
}

// With a current table the hull feels the table's horizontal velocity at the surface where
// the vessel is, at the time of the load (here a surface current that grows toward north
// and over ten minutes, with a vertical part the hull does not feel).
TEST(VesselConversion, TheHullFeelsACurrentTableWhereTheVesselIs) {
  const std::filesystem::path dir = moorsim::testing::FreshDirectory("hull_current_table");
  const std::string flow = (dir / "flow.txt").string();
  std::ofstream(flow) << "x: -1000 1000\ny: 0\ndepth: 0 100\ntime: 0 600\n"
                         "-1000 0 0 0 0.2 0.1 0.05\n-1000 0 0 600 0.4 0.1 0.05\n"
                         "1000 0 0 0 0.6 0.1 0.05\n1000 0 0 600 0.8 0.1 0.05\n"
                         "-1000 0 100 0 0 0 0\n-1000 0 100 600 0 0 0\n"
                         "1000 0 100 0 0 0 0\n1000 0 100 600 0 0 0\n";
  const scenarios::Scenario s = testing::SeedVesselScenario(
      "environment:\n  current: {file: " + flow + "}\n", "  hull: {draught: 16}\n");
  Simulation sim(scenarios::ToPlantModel(s), 1);
  Vec6 eta = Vec6::Zero();
  eta(0) = 500.0;  // three quarters of the way north: 0.5 at 0 s, 0.7 at 600 s
  eta(5) = 0.3;
  Vec6 nu = Vec6::Zero();
  nu << 0.2, -0.1, 0.0, 0.0, 0.0, 0.001;
  const vessel::CurrentLoad hull(scenarios::ToHullGeometry(*s.vessel, s.mooring.water.density));
  const Vec6 tau = LoadNamed(sim, "current").Load(300.0, eta, nu);
  const Vec6 expected = hull.Load(eta, nu, Vec3(0.6, 0.1, 0.0));
  EXPECT_LT((tau - expected).norm(), 1e-9 * expected.norm());
  EXPECT_GT((tau - hull.Load(eta, nu, Vec3(0.5, 0.1, 0.0))).norm(), 1e-3 * expected.norm());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace moorsim::simulation
