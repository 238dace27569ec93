// The coupled plant under position-mooring control: the thesis's PI removes a constant
// offset that the mooring alone would keep; every controller name the loader accepts builds.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"
#include "tests/simulation/test_scenarios.h"
#include "vessel/controller.h"

namespace moorsim::simulation {
namespace {

TEST(ControlledVesselSlow, PiRemovesTheOffsetOfAConstantLoad) {
  // 300 kN toward north on the seed FPSO at heading 0. Moorings alone: ~3.7 m offset (the
  // catenary's 81 kN/m). With the PI (Kp 1e5 N/m, Ki 1e3 N/(m s)) the integral takes the
  // load over with a time constant of about (Kp + k_mooring) / Ki = 180 s; after 2000 s
  // the mean offset over the last 300 s is within 0.2 m of the setpoint. Calm water; the
  // sensors have their default noise (7 cm, 4 deg), which makes the command jitter by
  // Kp x 7 cm = 7 kN, so the thrust is judged by its mean too.
  const std::string pi =
      "controller: {type: pi, rate_hz: 1, setpoint: {x: 0, y: 0, heading_deg: 0}}\n";
  Simulation controlled(scenarios::ToPlantModel(testing::SeedVesselScenario(pi)), 1);
  Simulation free(scenarios::ToPlantModel(testing::SeedVesselScenario()), 1);
  for (Simulation* sim : {&controlled, &free}) sim->SetExternalLoad(Vec3(3e5, 0, 0));
  double mean_controlled = 0.0, mean_free = 0.0, mean_thrust = 0.0;
  int samples = 0;
  for (double t = 10.0; t <= 2000.0; t += 10.0) {
    controlled.AdvanceTo(t);
    free.AdvanceTo(t);
    if (t > 1700.0) {
      mean_controlled += controlled.state()[0];
      mean_free += free.state()[0];
      mean_thrust += controlled.Record().thrust_delivered.x();
      ++samples;
    }
  }
  mean_controlled /= samples;
  mean_free /= samples;
  mean_thrust /= samples;
  EXPECT_GT(mean_free, 3.0);
  EXPECT_LT(std::abs(mean_controlled), 0.2);
  // The thrusters deliver what holds the vessel: the surge thrust balances the load.
  EXPECT_NEAR(mean_thrust, -3e5, 0.05 * 3e5);
}

TEST(ControlledVessel, EveryControllerTypeTheLoaderAcceptsBuilds) {
  for (std::string_view type : ChoiceNames<vessel::ControllerType>()) {
    const std::string yaml = "controller: {type: " + std::string(type) + "}\n";
    Simulation sim(scenarios::ToPlantModel(testing::SeedVesselScenario(yaml)), 1);
    sim.AdvanceTo(2.0);
    EXPECT_EQ(sim.time(), 2.0) << type;
  }
}

}  // namespace
}  // namespace moorsim::simulation
