// The turret on its bearing (vessel/turret.h) in the coupled plant: with the turret free at
// the reference point the mooring has no yaw stiffness (the hull's yaw follows its own
// inertia and damping, checked against the closed-form response); a turret forward of the
// reference point weathervanes into the current while the lines stay put; friction holds
// below the breakaway moment (creeping at the regularisation's closed-form rate) and slips
// above it; energy never grows; `locked` is today's plant to the bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/angles.h"
#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"
#include "tests/simulation/test_scenarios.h"
#include "vessel/turret.h"

namespace moorsim::simulation {
namespace {

/// The seed FPSO on the seed mooring in calm water, no controller, no hull drag (so that
/// the hull's yaw damping is the linear B66 alone), with `turret` as the vessel.turret map.
scenarios::Scenario TurretScenario(const std::string& turret, const std::string& vessel = "") {
  return testing::SeedVesselScenario("environment: {hull_viscous_drag: false}\n",
                                     "  turret: " + turret + "\n" + vessel);
}

double TurretAngle(Simulation& sim) { return sim.state()[sim.plant().turret_state()]; }
double Heading(Simulation& sim) { return sim.state()[5]; }

TEST(Turret, LockedIsTheTurretlessPlantToTheBit) {
  Simulation plain(scenarios::ToPlantModel(
                       testing::SeedVesselScenario("", "  initial_pose: {x: 2, heading_deg: 3}\n")),
                   1);
  Simulation locked(
      scenarios::ToPlantModel(testing::SeedVesselScenario(
          "", "  initial_pose: {x: 2, heading_deg: 3}\n  turret: {bearing: locked}\n")),
      1);
  ASSERT_EQ(plain.state().size(), locked.state().size());
  plain.AdvanceTo(60.0);
  locked.AdvanceTo(60.0);
  EXPECT_EQ(plain.state(), locked.state());
  EXPECT_EQ(plain.stats().steps, locked.stats().steps);
}

TEST(Turret, FreeAtTheReferencePointLeavesYawWithoutMooringStiffness) {
  // A constant moment N on the hull: with the turret free at the reference point nothing
  // resists yaw but the hull's linear damping B66, so (I66 + A66) r' = N - B66 r from rest:
  //   psi(t) = (N / B66) (t - T (1 - exp(-t / T))),  T = (I66 + A66) / B66 (= yaw_time).
  // The lines hold the turret where it was: the turret's own heading psi + alpha stays ~0.
  constexpr double kMoment = 2.0e7;  // [N m], ~2 deg of a locked turret's yaw offset
  Simulation sim(scenarios::ToPlantModel(TurretScenario("{bearing: free}")), 1);
  sim.SetExternalLoad(Vec3(0.0, 0.0, kMoment));
  const vessel::VesselParameters& p = sim.plant().model().parameters();
  const double inertia = p.rigid_body_mass(5, 5) + p.added_mass(5, 5);
  const double damping = p.linear_damping(5, 5);
  const double T = inertia / damping;
  for (double t : {100.0, 200.0, 300.0}) {
    sim.AdvanceTo(t);
    const double expected = kMoment / damping * (t - T * (1.0 - std::exp(-t / T)));
    // 2 %: the mass matrix's sway-yaw coupling and the lines' drag on the turning turret
    // (through the free bearing, none) are all that separate the plant from the formula.
    EXPECT_NEAR(Heading(sim), expected, 0.02 * expected) << "t = " << t;
    EXPECT_LT(std::abs(Heading(sim) + TurretAngle(sim)), 0.2 * kDegree) << "t = " << t;
  }
  EXPECT_GT(Heading(sim), 10.0 * kDegree);

  // The same moment on a locked turret: the mooring's yaw stiffness holds the hull near
  // N / K_yaw (5.7e8 N m/rad: 2 deg).
  Simulation locked(scenarios::ToPlantModel(TurretScenario("{bearing: locked}")), 1);
  locked.SetExternalLoad(Vec3(0.0, 0.0, kMoment));
  locked.AdvanceTo(300.0);
  EXPECT_LT(std::abs(Heading(locked)), 3.0 * kDegree);
}

TEST(TurretSlow, ForwardOfTheReferencePointWeathervanesIntoTheCurrent) {
  // The turret 80 m forward of midship, over the middle of the spread (the vessel starts
  // 80 m aft of the origin), 1.5 m/s of current from 30 deg off the bow, no thrusters. The
  // current's sway force acts behind the turret, so the hull turns until it heads into the
  // current (heading 30 deg) while the turret keeps its orientation and the lines theirs.
  // The hull's cross-flow drag goes as sin(beta) |sin(beta)| of the relative angle beta, so
  // near alignment the restoring moment is quadratic in the error e and the overdamped yaw
  // (B66 e' = -k e^2) closes it as 1 / t: doubling the time halves the error. The yaw
  // damping time is 100 s here (the library's 20 s only slows the same approach 5-fold).
  scenarios::Scenario s = TurretScenario("{bearing: free}",
                                         "  initial_pose: {x: -80, y: 0, heading_deg: 0}\n"
                                         "  damping: {yaw_time: 100}\n");
  for (scenarios::LineSpec& line : s.mooring.lines) line.fairlead_body.x() += 80.0;
  s.vessel->turret.x = 80.0;
  s.mooring.current.depth = {0.0, 2000.0};
  s.mooring.current.speed = {1.5, 1.5};
  s.mooring.current.direction = 210.0 * kDegree;  // toward 210 deg: from 30 deg
  s.environment.hull_viscous_drag = true;         // the current's load on the hull
  Simulation sim(scenarios::ToPlantModel(s), 1);
  std::vector<double> error;  // at 1000, 2000, ..., 6000 s
  for (double t = 1000.0; t <= 6000.0; t += 1000.0) {
    sim.AdvanceTo(t);
    error.push_back(std::abs(Heading(sim) - 30.0 * kDegree));
    // The turret's own heading psi + alpha stays where the lines hold it.
    EXPECT_LT(std::abs(Heading(sim) + TurretAngle(sim)), 0.1 * kDegree) << "t = " << t;
  }
  for (std::size_t k = 1; k < error.size(); ++k) EXPECT_LT(error[k], error[k - 1]);
  // 1 / t: e(6000 s) / e(3000 s) = 1/2, within 20 % (the approach is not yet asymptotic).
  EXPECT_NEAR(error[2] / error[5], 2.0, 0.4);
  EXPECT_LT(error.back(), 1.0 * kDegree);
  RecordProperty("heading_error_deg_at_6000s", std::to_string(error.back() / kDegree));
}

/// The bearing's breakaway moment at the start: mu r_b (|F_z| + |F_h|) of the lines' load.
double Breakaway(Simulation& sim) {
  std::vector<double> xdot(sim.state().size());
  sim.system().Derivatives(0.0, sim.state().data(), xdot.data());
  const vessel::TurretParameters& t = sim.plant().turret();
  const Vec3 F = sim.system().attachment_load().head<3>();
  return t.friction_coefficient * t.bearing_radius * (std::abs(F.z()) + F.head<2>().norm());
}

TEST(TurretSlow, FrictionHoldsBelowTheBreakawayMomentAndSlipsAbove) {
  const std::string turret = "{bearing: friction, friction_coefficient: 0.01, slip_rate: 1.0e-5}";
  Simulation probe(scenarios::ToPlantModel(TurretScenario(turret)), 1);
  const double breakaway = Breakaway(probe);  // 0.01 x 20 m x ~40 MN of line weight
  ASSERT_GT(breakaway, 5e6);
  ASSERT_LT(breakaway, 1.2e7);

  // Half the breakaway moment: the bearing holds. The regularised Coulomb moment creeps at
  // the rate where it balances the load, w_s atanh(N_bearing / N_breakaway); with the hull
  // held by the lines' yaw stiffness nearly all of N passes through the bearing.
  Simulation hold(scenarios::ToPlantModel(TurretScenario(turret)), 1);
  hold.SetExternalLoad(Vec3(0.0, 0.0, 0.5 * breakaway));
  hold.AdvanceTo(100.0);
  const double alpha100 = TurretAngle(hold);
  hold.AdvanceTo(300.0);
  const double creep = (TurretAngle(hold) - alpha100) / 200.0;
  const double expected_creep = -1.0e-5 * std::atanh(0.5);  // the turret lags the hull
  EXPECT_NEAR(creep, expected_creep, 0.3 * std::abs(expected_creep));
  EXPECT_LT(std::abs(TurretAngle(hold)), 0.2 * kDegree);
  EXPECT_LT(std::abs(Heading(hold)), 1.5 * kDegree);  // ~N / K_yaw, as if locked

  // Twice the breakaway moment: the bearing slips and the hull turns away.
  Simulation slip(scenarios::ToPlantModel(TurretScenario(turret)), 1);
  slip.SetExternalLoad(Vec3(0.0, 0.0, 2.0 * breakaway));
  slip.AdvanceTo(300.0);
  EXPECT_GT(Heading(slip), 5.0 * kDegree);
  EXPECT_GT(std::abs(TurretAngle(slip)), 5.0 * kDegree);
}

TEST(Turret, StartsAtItsInitialHeadingWhereTheLinesHoldIt) {
  // The seed mooring's fairleads point at their anchors with the hull (and turret) at
  // heading 0. A hull started at heading 90 deg with the turret at its own initial heading
  // 0 (angle -90 deg to the hull) starts with the lines at rest: in calm water the
  // turret's absolute heading stays put. Started at angle 0 instead, the fairleads are a
  // quarter turn off their anchors and the lines swing the turret round.
  const std::string hull = "  initial_pose: {x: 0, y: 0, heading_deg: 90}\n";
  Simulation held(
      scenarios::ToPlantModel(TurretScenario("{bearing: free, initial_heading_deg: 0}", hull)), 1);
  EXPECT_NEAR(TurretAngle(held), -90.0 * kDegree, 1e-12);
  Simulation swung(scenarios::ToPlantModel(TurretScenario("{bearing: free}", hull)), 1);
  EXPECT_EQ(TurretAngle(swung), 0.0);
  double held_most = 0.0, swung_most = 0.0;
  for (int t = 1; t <= 60; ++t) {
    held.AdvanceTo(t);
    swung.AdvanceTo(t);
    held_most = std::max(held_most, std::abs(WrapAngle(Heading(held) + TurretAngle(held))));
    swung_most =
        std::max(swung_most, std::abs(WrapAngle(Heading(swung) + TurretAngle(swung) - kPi / 2)));
  }
  EXPECT_LT(held_most, 0.01 * kDegree);
  EXPECT_NEAR(Heading(held), kPi / 2, 0.01 * kDegree);
  EXPECT_GT(swung_most, 30.0 * kDegree);
}

TEST(Turret, EnergyNeverGrowsWithoutInput) {
  // Free, undamped bearing; the hull starts 10 deg off the lines' rest heading, so the lines
  // swing the turret back (it turns relative to the hull) and their drag takes the energy.
  Simulation sim(scenarios::ToPlantModel(
                     TurretScenario("{bearing: free}", "  initial_pose: {heading_deg: 10}\n")),
                 1);
  double energy = sim.MechanicalEnergy();
  for (double t = 1.0; t <= 200.0; t += 1.0) {
    sim.AdvanceTo(t);
    const double e = sim.MechanicalEnergy();
    // 1 kJ per second of integration error, as for the moored vessel's surge decay.
    EXPECT_LE(e, energy + 1e3) << "t = " << t;
    energy = e;
  }
  // The turret came back to the lines' orientation: the turret's heading psi + alpha ~ 0.
  EXPECT_LT(std::abs(Heading(sim) + TurretAngle(sim)), 0.5 * kDegree);
  EXPECT_NEAR(Heading(sim), 10.0 * kDegree, 0.5 * kDegree);  // no yaw stiffness on the hull
}

// The thesis sea state (Hs 2.5 m, Tp 7 s) with the turret free, as the library has it: the
// heading is the thrusters' alone, on the pi controller's heading loop sized for a 200 s
// closed-loop period at 0.8 of critical damping (the hull's own yaw damping gives that: no
// derivative on the noisy gyro; P and I on the 10 s low-passed heading). Over an hour, without and
// with the thesis's current, the low-frequency heading stays within 1.5 deg of the setpoint
// (measured at seed 1: -0.9 to +1.0 deg, standard deviation 0.35 deg), and the vessel within 25 m
// of the field origin (the locked turret's band: 7-16 m).
class FreeTurretHeadingAcceptance : public ::testing::TestWithParam<const char*> {};

TEST_P(FreeTurretHeadingAcceptance, StaysWithinItsBandForAnHour) {
  const scenarios::Scenario scenario = scenarios::LoadScenario(
      std::string(MOORSIM_SOURCE_DIR "/scenarios/library/") + GetParam() + ".yaml",
      {"simulation.duration=3600"});
  ASSERT_EQ(scenario.vessel->turret.bearing,
            vessel::TurretBearing::kFree);  // the library's own set-up
  Simulation sim(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  const double setpoint = scenario.controller.setpoint->z();
  double worst = 0.0;
  for (double t = 300.0; t <= 3600.0; t += 1.0) {
    sim.AdvanceTo(t);
    worst =
        std::max(worst, std::abs(std::remainder(Heading(sim) - setpoint, 2 * std::numbers::pi)));
    ASSERT_LT(std::hypot(sim.state()[0], sim.state()[1]), 25.0) << "t = " << t;
  }
  EXPECT_LT(worst, 1.5 * kDegree);
  RecordProperty("worst_heading_error_deg", std::to_string(worst / kDegree));
}

INSTANTIATE_TEST_SUITE_P(ThesisSea, FreeTurretHeadingAcceptance,
                         ::testing::Values("thesis_no_failure", "thesis_no_failure_current"));

}  // namespace
}  // namespace moorsim::simulation
