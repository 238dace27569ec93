// Tests of the current, wind and gust models (vessel/hull_loads.h).
//
// References independent of the implementation: hand calculations of the seed vessel's
// loads from the published formulas, closed forms of the strip integrals (constant
// cross-flow; pure yaw), sign conventions stated physically (which way the wind pushes),
// central finite differences for the Jacobian, and the random-phase model's own
// statistics for the gusts. The random seeds are fixed so a pass repeats.
#include "vessel/hull_loads.h"
#include "core/angles.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/random.h"

namespace moorsim::vessel {
namespace {

constexpr double kWaterDensity = 1025.0;
constexpr double kAirDensity = 1.226;

/// Runs `action` and checks that it throws InputError whose message contains every
/// fragment (the field name and the offending value).
void ExpectInputError(const std::function<void()>& action,
                      const std::vector<std::string>& fragments) {
  try {
    action();
    ADD_FAILURE() << "no InputError; expected one mentioning " << fragments.front();
  } catch (const InputError& e) {
    for (const std::string& fragment : fragments) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(fragment));
    }
  }
}

Vec6 Pose(double psi) {
  Vec6 eta = Vec6::Zero();
  eta[5] = psi;
  return eta;
}

Vec6 Velocity(double u, double v, double r) {
  Vec6 nu = Vec6::Zero();
  nu[0] = u;
  nu[1] = v;
  nu[5] = r;
  return nu;
}

/// Hoerner's curve at the seed FPSO's B / (2 T) = 1.8333, interpolated by hand between the
/// digitised points (1.639, 0.6914) and (1.860, 0.6571).
double SeedCrossFlowDrag() {
  const double ratio = 44.0 / 24.0;
  return 0.6914 + (ratio - 1.639) / (1.860 - 1.639) * (0.6571 - 0.6914);
}

// --- hull particulars ----------------------------------------------------------------

TEST(CurrentHullEstimatesTest, SeedParticularsFollowTheCitedFormulas) {
  const HullGeometry hull = SeedFpsoHull();
  // C_B = 97961 / (200 * 44 * 12) = 0.92766; Watanabe:
  // k = -0.095 + 25.6 * 0.92766 / (4.5455^2 * sqrt(3.6667)) = 0.50526.
  EXPECT_NEAR(hull.form_factor, 0.50526, 1e-5);
  const CurrentLoad load(hull);
  // Denny-Mumford: 1.7 * 200 * 12 + 97961 / 12 = 4080 + 8163.42 = 12243.42 m^2.
  EXPECT_NEAR(load.wetted_surface(), 12243.42, 0.01);
  EXPECT_NEAR(load.cross_flow_drag_coefficient(), SeedCrossFlowDrag(), 1e-12);
  EXPECT_NEAR(load.cross_flow_drag_coefficient(), 0.6612, 1e-4);
}

TEST(CurrentHullEstimatesTest, HoernerCurveEndsAndIttcLine) {
  // Deep thin section: the plate value ~2; wide flat section: ~0.56; held outside.
  EXPECT_NEAR(HoernerCrossFlowDragCoefficient(0.001), 1.966, 1e-12);
  EXPECT_NEAR(HoernerCrossFlowDragCoefficient(10.0), 0.5593, 1e-12);
  EXPECT_NEAR(HoernerCrossFlowDragCoefficient(1.0),
              0.8284 + (1.0 - 0.988) / (1.308 - 0.988) * (0.7599 - 0.8284), 1e-12);
  // ITTC-57 at Re = 1e9: 0.075 / 7^2 = 1.5306e-3; held below Re = 1e5 at 0.075 / 9.
  EXPECT_NEAR(IttcFrictionCoefficient(1e9), 0.075 / 49.0, 1e-15);
  EXPECT_NEAR(IttcFrictionCoefficient(10.0), 0.075 / 9.0, 1e-15);
  EXPECT_NEAR(IttcFrictionCoefficient(0.0), 0.075 / 9.0, 1e-15);
}

// --- current load --------------------------------------------------------------------

TEST(CurrentLoadTest, ZeroWhenTheHullMovesWithTheWater) {
  const CurrentLoad load(SeedFpsoHull());
  const Vec3 current(0.3, -0.2, 0.05);  // the vertical component is ignored
  for (const double psi : {0.0, 0.7, -2.5}) {
    // Body velocity equal to the current resolved into body axes, no yaw rate.
    const double u = std::cos(psi) * current[0] + std::sin(psi) * current[1];
    const double v = -std::sin(psi) * current[0] + std::cos(psi) * current[1];
    const Vec6 tau = load.Load(Pose(psi), Velocity(u, v, 0.0), current);
    // Rounding of u, v leaves relative speeds ~1e-17 m/s: loads ~1e-25 N.
    EXPECT_LT(tau.cwiseAbs().maxCoeff(), 1e-9) << "psi = " << psi;
  }
  EXPECT_EQ(load.Load(Pose(0.3), Vec6::Zero(), Vec3::Zero()), Vec6::Zero());
}

TEST(CurrentLoadTest, OpposesTheRelativeMotion) {
  // The power of the load on the relative motion, X u_r + Y v_r + N r, is minus a sum of
  // |.|^3 terms (each strip's |w| w^2 and |u_r|^3), so strictly negative unless all are 0.
  const CurrentLoad load(SeedFpsoHull());
  RandomStream stream = RandomStream::Derive(7, "hull_loads_test.dissipative");
  for (int trial = 0; trial < 500; ++trial) {
    const double psi = kPi * (2.0 * stream.Uniform() - 1.0);
    const Vec3 current(stream.Uniform() - 0.5, stream.Uniform() - 0.5, 0.0);
    const Vec6 nu = Velocity(2.0 * stream.Uniform() - 1.0, stream.Uniform() - 0.5,
                             0.01 * (stream.Uniform() - 0.5));
    const Vec6 tau = load.Load(Pose(psi), nu, current);
    const double u_c = std::cos(psi) * current[0] + std::sin(psi) * current[1];
    const double v_c = -std::sin(psi) * current[0] + std::cos(psi) * current[1];
    const double power = tau[0] * (nu[0] - u_c) + tau[1] * (nu[1] - v_c) + tau[5] * nu[5];
    EXPECT_LT(power, 0.0) << "trial " << trial;
    EXPECT_EQ(tau[2], 0.0);
    EXPECT_EQ(tau[3], 0.0);
    EXPECT_EQ(tau[4], 0.0);
  }
}

TEST(CurrentLoadTest, CurrentPushesTheVesselDownstream) {
  const CurrentLoad load(SeedFpsoHull());
  // Water moving east (+y) past a vessel at rest heading north: pushed to starboard (+y).
  Vec6 tau = load.Load(Pose(0.0), Vec6::Zero(), Vec3(0.0, 0.5, 0.0));
  EXPECT_GT(tau[1], 0.0);
  EXPECT_EQ(tau[0], 0.0);
  // The strips are symmetric about midship: the moment cancels to rounding.
  EXPECT_LT(std::abs(tau[5]), 1e-9 * std::abs(tau[1]) * 200.0);
  // The same current on a vessel heading east is a following current: pushed forward.
  tau = load.Load(Pose(0.5 * kPi), Vec6::Zero(), Vec3(0.0, 0.5, 0.0));
  EXPECT_GT(tau[0], 0.0);
  EXPECT_LT(std::abs(tau[1]), 1e-9 * tau[0] * 1e3);
}

TEST(CurrentLoadTest, SeedSurgeDragInOneMetrePerSecondHeadCurrent) {
  // Heading north, water moving south at 1 m/s: u_r = +1 m/s. By hand:
  //   Re = 1 * 200 / 1.19e-6 = 1.6807e8, log10 Re = 8.2255,
  //   C_F = 0.075 / 6.2255^2 = 1.9352e-3,
  //   X = -0.5 * 1025 * 12243.4 * (1 + 0.50526) * 1.9352e-3 * 1^2 = -18.28 kN.
  // Plausibility: 0.0148 on 1/2 rho V^2 L T (1.23 MN), at the low end of published
  // head-current coefficients for loaded tankers (friction only; see the class comment).
  const CurrentLoad load(SeedFpsoHull());
  const Vec6 tau = load.Load(Pose(0.0), Vec6::Zero(), Vec3(-1.0, 0.0, 0.0));
  EXPECT_NEAR(tau[0], -18278.0, 5.0);
  EXPECT_GT(-tau[0], 10e3);
  EXPECT_LT(-tau[0], 60e3);
  EXPECT_EQ(tau[1], 0.0);
  EXPECT_EQ(tau[5], 0.0);
  RecordProperty("seed_surge_drag_1mps_N", std::to_string(tau[0]));
}

TEST(CurrentLoadTest, BeamCurrentSwayDragMatchesClosedForm) {
  // 0.1 m/s current from starboard (water moving west) on a vessel heading north at rest:
  // v_r = +0.1 m/s everywhere along the hull, so the strip integral is exact:
  //   Y = -0.5 rho C_d L T v^2 = -0.5 * 1025 * 0.6612 * 200 * 12 * 0.01 = -8.13 kN.
  // The midpoint sum of 20 equal terms only rounds: 1e-12 relative.
  const CurrentLoad load(SeedFpsoHull());
  const Vec6 tau = load.Load(Pose(0.0), Vec6::Zero(), Vec3(0.0, -0.1, 0.0));
  const double expected = -0.5 * kWaterDensity * SeedCrossFlowDrag() * 200.0 * 12.0 * 0.1 * 0.1;
  EXPECT_NEAR(tau[1], expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(tau[1], -8133.0, 1.0);
  EXPECT_EQ(tau[0], 0.0);
  RecordProperty("seed_sway_drag_0p1mps_N", std::to_string(tau[1]));
}

TEST(CurrentLoadTest, PureYawMomentMatchesClosedForm) {
  // v_r = 0: N = -0.5 rho T C_d r|r| integral x^2 |x| dx = -0.5 rho T C_d r|r| L^4 / 32.
  // The midpoint rule on 10 strips per half-length sums (i + 1/2)^3 for i < 10, which is
  // 10^4/4 - 10^2/8 = 2487.5 instead of 2500: exactly 0.5 % low. Y cancels by symmetry.
  const CurrentLoad load(SeedFpsoHull());
  const double r = 0.004;
  const Vec6 tau = load.Load(Pose(0.0), Velocity(0.0, 0.0, r), Vec3::Zero());
  const double exact =
      -0.5 * kWaterDensity * 12.0 * SeedCrossFlowDrag() * r * r * std::pow(200.0, 4) / 32.0;
  EXPECT_NEAR(tau[5] / exact, 0.995, 1e-12);
  EXPECT_LT(std::abs(tau[1]), 1e-12 * std::abs(tau[5]));
}

TEST(CurrentLoadTest, JacobianMatchesCentralDifferences) {
  // Y and N are piecewise quadratic in (v, r): central differences are exact for them
  // except where a strip's cross-flow changes sign within the step (none does in these
  // states). X has C_F(Re) and psi enters through sin/cos, so their truncation error is
  // O(h^2) ~ 1e-12 relative. Rounding gives eps |tau| / h ~ 1e-10 relative. The tolerance
  // 1e-6 of each column's largest entry (plus 1e-9 N) leaves margin over both and is far
  // below any real mistake (a missing term is O(1) relative).
  const CurrentLoad load(SeedFpsoHull());
  struct State {
    double psi, u, v, r;
    Vec3 current;
  };
  const std::vector<State> states = {
      {0.3, 0.2, -0.1, 0.002, Vec3(0.5, -0.3, 0.0)},
      {-2.0, -0.4, 0.3, -0.003, Vec3(-0.2, 0.8, 0.0)},
      {1.2, 0.0, 0.0, 0.001, Vec3(0.0, 0.1, 0.0)},  // cross-flow changes sign along the hull
      {2.9, 1.5, 0.05, 0.0, Vec3(0.1, 0.1, 0.0)},
  };
  const double h = 1e-6;  // m/s and rad
  for (const State& s : states) {
    Vec6 eta = Pose(s.psi);
    eta[0] = 12.0;  // position does not enter
    const Vec6 nu = Velocity(s.u, s.v, s.r);
    Mat6 J_eta;
    Mat6 J_nu;
    load.Jacobian(eta, nu, s.current, &J_eta, &J_nu);
    Mat6 fd_eta;
    Mat6 fd_nu;
    for (int j = 0; j < 6; ++j) {
      Vec6 plus = eta;
      Vec6 minus = eta;
      plus[j] += h;
      minus[j] -= h;
      fd_eta.col(j) = (load.Load(plus, nu, s.current) - load.Load(minus, nu, s.current)) / (2 * h);
      Vec6 nu_plus = nu;
      Vec6 nu_minus = nu;
      nu_plus[j] += h;
      nu_minus[j] -= h;
      fd_nu.col(j) =
          (load.Load(eta, nu_plus, s.current) - load.Load(eta, nu_minus, s.current)) / (2 * h);
    }
    for (int j = 0; j < 6; ++j) {
      const double tol_eta = 1e-6 * fd_eta.col(j).cwiseAbs().maxCoeff() + 1e-9;
      const double tol_nu = 1e-6 * fd_nu.col(j).cwiseAbs().maxCoeff() + 1e-9;
      for (int i = 0; i < 6; ++i) {
        EXPECT_NEAR(J_eta(i, j), fd_eta(i, j), tol_eta)
            << "d tau[" << i << "]/d eta[" << j << "] at psi = " << s.psi;
        EXPECT_NEAR(J_nu(i, j), fd_nu(i, j), tol_nu)
            << "d tau[" << i << "]/d nu[" << j << "] at psi = " << s.psi;
      }
    }
    // The psi column is not trivially zero in these states.
    EXPECT_GT(J_eta.col(5).cwiseAbs().maxCoeff(), 1.0);
    // One block alone is the same block.
    Mat6 J_nu_only;
    load.Jacobian(eta, nu, s.current, nullptr, &J_nu_only);
    EXPECT_EQ(J_nu_only, J_nu);
  }
}

TEST(CurrentLoadTest, RejectsBadGeometry) {
  const auto with = [](const std::function<void(HullGeometry&)>& change) {
    HullGeometry hull = SeedFpsoHull();
    change(hull);
    return [hull] { CurrentLoad load(hull); };
  };
  ExpectInputError(with([](HullGeometry& h) { h.length = -200.0; }), {"hull.length", "-200"});
  ExpectInputError(with([](HullGeometry& h) { h.beam = 0.0; }), {"hull.beam", "0"});
  ExpectInputError(with([](HullGeometry& h) { h.draught = std::nan(""); }), {"hull.draught"});
  ExpectInputError(with([](HullGeometry& h) { h.displaced_volume = 0.0; }),
                   {"hull.displaced_volume", "hull.wetted_surface"});
  ExpectInputError(with([](HullGeometry& h) { h.wetted_surface = -1.0; }),
                   {"hull.wetted_surface", "-1"});
  ExpectInputError(with([](HullGeometry& h) { h.cross_flow_drag_coefficient = -0.5; }),
                   {"hull.cross_flow_drag_coefficient", "-0.5"});
  ExpectInputError(with([](HullGeometry& h) { h.form_factor = -1.0; }), {"hull.form_factor", "-1"});
  ExpectInputError(with([](HullGeometry& h) { h.water_density = 0.0; }), {"hull.water_density"});
  ExpectInputError(with([](HullGeometry& h) { h.kinematic_viscosity = -1e-6; }),
                   {"hull.kinematic_viscosity", "-1e-06"});
  // A given wetted surface needs no volume; given coefficients are used as they are.
  HullGeometry given = SeedFpsoHull();
  given.displaced_volume = 0.0;
  given.wetted_surface = 13000.0;
  given.cross_flow_drag_coefficient = 0.8;
  const CurrentLoad load(given);
  EXPECT_EQ(load.wetted_surface(), 13000.0);
  EXPECT_EQ(load.cross_flow_drag_coefficient(), 0.8);
}

// --- wind load -----------------------------------------------------------------------

/// 1/2 rho_a U^2 at U = 20 m/s: 245.2 Pa.
constexpr double kQ20 = 0.5 * kAirDensity * 20.0 * 20.0;

TEST(WindLoadTest, HeadWindPushesTheVesselAft) {
  // Blendermann's loaded tanker: C_X(0) = -0.90, so X = -0.90 * 245.2 Pa * 1200 m^2 =
  // -264.8 kN at 20 m/s; no side force or moment in a head wind.
  const WindLoad wind(SeedFpsoWind());
  for (const double psi : {0.0, 0.5 * kPi, -2.0}) {
    // Wind coming from the direction the bow points.
    const Vec6 tau = wind.Load(Pose(psi), Vec6::Zero(), 20.0, psi);
    EXPECT_NEAR(tau[0], -0.90 * kQ20 * 1200.0, 1e-6 * 264.8e3) << "psi = " << psi;
    EXPECT_LT(std::abs(tau[1]), 1e-6 * 264.8e3);
    EXPECT_LT(std::abs(tau[5]), 1e-6 * 264.8e3 * 200.0);
  }
  const Vec6 tau = wind.Load(Pose(0.0), Vec6::Zero(), 20.0, 0.0);
  RecordProperty("seed_head_wind_20mps_X_N", std::to_string(tau[0]));
}

TEST(WindLoadTest, BeamWindFromStarboardPushesTheVesselToPort) {
  // Heading north, wind from the east (starboard beam): C_Y(pi/2) = -0.70, so
  // Y = -0.70 * 245.2 * 4500 = -772.4 kN; the centre of effort is at the lateral-area
  // centroid (midship for the seed), so N = 0; C_X(pi/2) = 0.
  const WindLoad wind(SeedFpsoWind());
  const Vec6 tau = wind.Load(Pose(0.0), Vec6::Zero(), 20.0, 0.5 * kPi);
  EXPECT_NEAR(tau[1], -0.70 * kQ20 * 4500.0, 1e-6 * 772.4e3);
  EXPECT_LT(std::abs(tau[0]), 1e-6 * 772.4e3);
  EXPECT_LT(std::abs(tau[5]), 1e-6 * 772.4e3 * 200.0);
  RecordProperty("seed_beam_wind_20mps_Y_N", std::to_string(tau[1]));
  // From port (west) it pushes to starboard.
  EXPECT_NEAR(wind.Load(Pose(0.0), Vec6::Zero(), 20.0, -0.5 * kPi)[1], -tau[1], 1e-6);
}

TEST(WindLoadTest, SternWindPushesForwardAndBowQuarterWindTurnsTheBowAway) {
  const WindLoad wind(SeedFpsoWind());
  // From astern: C_X(pi) = +0.55, X = 0.55 * 245.2 * 1200 = +161.8 kN.
  const Vec6 stern = wind.Load(Pose(0.0), Vec6::Zero(), 20.0, kPi);
  EXPECT_NEAR(stern[0], 0.55 * kQ20 * 1200.0, 1e-6 * 161.8e3);
  // From the starboard bow (45 deg): pushed aft and to port, and the centre of effort is
  // forward of midship, so the bow turns to port, away from the wind (N < 0).
  const Vec6 bow = wind.Load(Pose(0.0), Vec6::Zero(), 20.0, 0.25 * kPi);
  EXPECT_LT(bow[0], 0.0);
  EXPECT_LT(bow[1], 0.0);
  EXPECT_LT(bow[5], 0.0);
  // Blendermann at 45 deg: x_cp / L = 0.18 pi / 4 = 0.1414, so N = 0.1414 L Y.
  EXPECT_NEAR(bow[5], 0.18 * 0.25 * kPi * 200.0 * bow[1], 1e-6 * std::abs(bow[5]));
}

TEST(WindLoadTest, MirrorSymmetryBetweenPortAndStarboard) {
  // A port-starboard symmetric vessel: the wind at -gamma gives the same X and opposite
  // Y and N (the table is mirrored, so this holds to rounding).
  const WindLoad wind(SeedFpsoWind());
  for (const double psi : {0.0, 1.0, -2.7}) {
    for (int deg = 0; deg <= 180; deg += 7) {
      const double gamma = deg * kPi / 180.0;
      const Vec6 starboard = wind.Load(Pose(psi), Vec6::Zero(), 15.0, psi + gamma);
      const Vec6 port = wind.Load(Pose(psi), Vec6::Zero(), 15.0, psi - gamma);
      const double scale = 1e-9 * (starboard.cwiseAbs().maxCoeff() + 1.0);
      EXPECT_NEAR(port[0], starboard[0], scale) << deg << " deg";
      EXPECT_NEAR(port[1], -starboard[1], scale) << deg << " deg";
      EXPECT_NEAR(port[5], -starboard[5], scale * 200.0) << deg << " deg";
    }
  }
  for (double gamma = -3.1; gamma < 3.1; gamma += 0.05) {
    const Vec3 a = wind.Coefficients(gamma);
    const Vec3 b = wind.Coefficients(-gamma);
    EXPECT_EQ(a[0], b[0]);
    EXPECT_EQ(a[1], -b[1]);
    EXPECT_EQ(a[2], -b[2]);
  }
}

TEST(WindLoadTest, UsesTheWindRelativeToTheMovingHull) {
  const WindLoad wind(SeedFpsoWind());
  // Still air, vessel moving ahead at 5 m/s: a 5 m/s head wind.
  const Vec6 moving = wind.Load(Pose(0.4), Velocity(5.0, 0.0, 0.0), 0.0, 0.0);
  EXPECT_NEAR(moving[0], -0.90 * 0.5 * kAirDensity * 25.0 * 1200.0, 1e-9);
  // Drifting downwind at the wind's own velocity: no relative wind, no load.
  // Wind 10 m/s from the north moves south; the vessel heads east, so south is to
  // starboard: v = +10 m/s.
  const Vec6 drifting = wind.Load(Pose(0.5 * kPi), Velocity(0.0, 10.0, 0.0), 10.0, 0.0);
  EXPECT_LT(drifting.cwiseAbs().maxCoeff(), 1e-9);
}

TEST(WindLoadTest, LoadedTankerTableShape) {
  const WindCoefficientTable table = LoadedTankerWindCoefficients(1200.0, 4500.0);
  ASSERT_EQ(table.angle.size(), 37u);
  EXPECT_EQ(table.angle.front(), 0.0);
  EXPECT_EQ(table.angle.back(), kPi);
  EXPECT_DOUBLE_EQ(table.surge.front(), -0.90);
  EXPECT_DOUBLE_EQ(table.surge.back(), 0.55);
  EXPECT_DOUBLE_EQ(table.sway[18], -0.70);  // 90 deg
  // At 45 deg the cross-force denominator is 1 - 0.2 (1 - 0.9 * 1200/4500 / 0.7) = 0.8686.
  const double d = 1.0 - 0.2 * (1.0 - 0.9 * 1200.0 / 4500.0 / 0.7);
  EXPECT_NEAR(table.surge[9], -0.90 * std::cos(0.25 * kPi) / d, 1e-12);
  EXPECT_NEAR(table.sway[9], -0.70 * std::sin(0.25 * kPi) / d, 1e-12);
  for (std::size_t i = 1; i + 1 < table.angle.size(); ++i) {
    EXPECT_LT(table.sway[i], 0.0) << "row " << i;  // every starboard wind pushes to port
  }
}

TEST(WindLoadTest, AcceptsAUserTable) {
  WindParameters parameters = SeedFpsoWind();
  parameters.coefficients.angle = {0.0, 0.5 * kPi, kPi};
  parameters.coefficients.surge = {-1.0, 0.0, 0.6};
  parameters.coefficients.sway = {0.0, -0.8, 0.0};
  parameters.coefficients.yaw = {0.0, 0.04, 0.0};
  const WindLoad wind(parameters);
  const Vec3 at_45 = wind.Coefficients(0.25 * kPi);  // halfway between the first rows
  EXPECT_NEAR(at_45[0], -0.5, 1e-12);
  EXPECT_NEAR(at_45[1], -0.4, 1e-12);
  EXPECT_NEAR(at_45[2], 0.02, 1e-12);
  const Vec6 beam = wind.Load(Pose(0.0), Vec6::Zero(), 20.0, 0.5 * kPi);
  EXPECT_NEAR(beam[1], -0.8 * kQ20 * 4500.0, 1e-6);
  EXPECT_NEAR(beam[5], 0.04 * kQ20 * 4500.0 * 200.0, 1e-3);
  // A table whose last angle is pi typed to 7 digits is accepted.
  parameters.coefficients.angle.back() = 3.1415927;
  EXPECT_NO_THROW(WindLoad{parameters});
}

TEST(WindLoadTest, RejectsBadParameters) {
  const auto with = [](const std::function<void(WindParameters&)>& change) {
    WindParameters parameters = SeedFpsoWind();
    parameters.coefficients.angle = {0.0, 0.5 * kPi, kPi};
    parameters.coefficients.surge = {-1.0, 0.0, 0.6};
    parameters.coefficients.sway = {0.0, -0.8, 0.0};
    parameters.coefficients.yaw = {0.0, 0.04, 0.0};
    change(parameters);
    return [parameters] { WindLoad wind(parameters); };
  };
  ExpectInputError(with([](WindParameters& p) { p.air_density = 0.0; }), {"wind.air_density"});
  ExpectInputError(with([](WindParameters& p) { p.frontal_area = -5.0; }),
                   {"wind.frontal_area", "-5"});
  ExpectInputError(with([](WindParameters& p) { p.lateral_area = 0.0; }), {"wind.lateral_area"});
  ExpectInputError(with([](WindParameters& p) { p.length = std::nan(""); }), {"wind.length"});
  ExpectInputError(with([](WindParameters& p) {
                     p.coefficients.angle = {0.0, 2.0, 1.5};
                   }),
                   {"wind.coefficients.angle[2]", "1.5", "increasing"});
  ExpectInputError(with([](WindParameters& p) {
                     p.coefficients.angle = {0.1, 2.0, kPi};
                   }),
                   {"wind.coefficients.angle[0]", "0.1"});
  ExpectInputError(with([](WindParameters& p) {
                     p.coefficients.angle = {0.0, 1.0, 3.0};
                   }),
                   {"wind.coefficients.angle[2]", "3", "pi"});
  ExpectInputError(with([](WindParameters& p) {
                     p.coefficients.surge = {-1.0, 0.0};
                   }),
                   {"wind.coefficients.surge size", "2"});
  ExpectInputError(with([](WindParameters& p) { p.coefficients.yaw[1] = INFINITY; }),
                   {"wind.coefficients.yaw[1]", "inf"});
  ExpectInputError(with([](WindParameters& p) { p.coefficients.sway[0] = -0.01; }),
                   {"wind.coefficients.sway[0]", "-0.01", "mirror"});
  ExpectInputError(with([](WindParameters& p) { p.coefficients.yaw[2] = 0.01; }),
                   {"wind.coefficients.yaw[2]", "0.01"});
  ExpectInputError(with([](WindParameters& p) {
                     p.coefficients = {{0.0}, {-1.0}, {0.0}, {0.0}};
                   }),
                   {"wind.coefficients.angle size", "1"});
  ExpectInputError([] { LoadedTankerWindCoefficients(1200.0, 4500.0, 0.0, 1); }, {"samples", "1"});
}

// --- gusts ---------------------------------------------------------------------------

/// Integral of the spectrum over [f_min, f_max] by composite Simpson in ln f (S(f) f is
/// smooth in ln f); 20000 panels are converged to ~1e-12 relative.
double SpectrumVariance(const NpdWindSpectrum& spectrum, double f_min, double f_max) {
  const int panels = 20000;
  const double a = std::log(f_min);
  const double h = (std::log(f_max) - a) / panels;
  double sum = 0.0;
  for (int j = 0; j <= panels; ++j) {
    const double f = std::exp(a + j * h);
    const double weight = (j == 0 || j == panels) ? 1.0 : (j % 2 == 1 ? 4.0 : 2.0);
    sum += weight * spectrum.Density(f) * f;
  }
  return sum * h / 3.0;
}

WindGust Realise(std::uint64_t seed, double mean_speed = 20.0, int components = 100) {
  WindGustOptions options;
  options.mean_speed = mean_speed;
  options.components = components;
  RandomStream stream = RandomStream::Derive(seed, "wind.gust");
  return WindGust(options, stream);
}

TEST(WindNpdSpectrumTest, MatchesTheFormulaByHand) {
  // U0 = 20 m/s, z = 10 m, f = 0.01 Hz: x = 172 * 0.01 * 2^-0.75 = 1.02272,
  // x^0.468 = 1.010570, (2.010570)^(5 / 1.404) = 12.0287, S = 320 * 4 / 12.0287
  // = 106.418 m^2/s^2 per Hz.
  const NpdWindSpectrum spectrum(20.0);
  EXPECT_NEAR(spectrum.Density(0.01), 106.418, 0.001);
  // f -> 0: 320 (U0/10)^2 (at 1e-30 Hz, x^n = 1e-13).
  EXPECT_NEAR(spectrum.Density(1e-30), 1280.0, 1e-6);
  EXPECT_EQ(spectrum.Density(0.0), 0.0);
  EXPECT_EQ(spectrum.MeanSpeedAtHeight(), 20.0);
  // NPD profile at 50 m: C = 0.0573 sqrt(1 + 0.148 * 20) = 0.11403; U = 20 (1 + C ln 5).
  EXPECT_NEAR(NpdWindSpectrum(20.0, 50.0).MeanSpeedAtHeight(),
              20.0 * (1.0 + 0.0573 * std::sqrt(3.96) * std::log(5.0)), 1e-12);
}

TEST(WindGustTest, RealisedVarianceMatchesTheSpectrum) {
  // sum a_k^2 / 2 is a stratified estimate of the spectrum's integral over the realised
  // range (one random frequency per log bin): unbiased, and for N = 100 the measured
  // spread over 2000 seeds is 0.06 % (worst 0.24 %). The 2 % bound is the brief's.
  const NpdWindSpectrum spectrum(20.0);
  const double target = SpectrumVariance(spectrum, 1.0 / 3600.0, 0.5);
  // sigma_u / U0 = 0.121 at U0 = 20 m/s (the header's number).
  EXPECT_NEAR(std::sqrt(target) / 20.0, 0.121, 0.001);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const WindGust gust = Realise(seed);
    ASSERT_EQ(gust.components().size(), 100u);
    EXPECT_NEAR(gust.RealisedVariance() / target, 1.0, 0.02) << "seed " << seed;
  }
}

TEST(WindGustTest, LongRecordAveragesToTheMeanSpeed) {
  // Over M samples dt apart, a component's sample mean is bounded by
  // a_k / (M |sin(pi f_k dt)|) (geometric sum of a rotating phasor). Over 10 hours at
  // dt = 1 s this bound, summed over the components, is what the test allows. It is
  // itself checked to be small, below 1 % of U0 (0.2 m/s against a gust standard
  // deviation of 2.4 m/s; the slowest components, ~1/3600 Hz, set it), so the test has
  // teeth.
  const WindGust gust = Realise(3);
  const int samples = 36000;
  const double dt = 1.0;
  double sum = 0.0;
  for (int j = 0; j < samples; ++j) sum += gust.Speed(j * dt);
  const double mean = sum / samples;
  double bound = 0.0;
  for (const GustComponent& c : gust.components()) {
    bound += c.amplitude / (samples * std::abs(std::sin(kPi * c.frequency * dt)));
  }
  EXPECT_LT(bound, 0.01 * 20.0);
  RecordProperty("mean_minus_U0", std::to_string(mean - 20.0));
  EXPECT_NEAR(mean, 20.0, bound);
  EXPECT_EQ(gust.mean_speed(), 20.0);
}

TEST(WindGustTest, StreamsDecideTheRealisation) {
  const WindGust a = Realise(11);
  const WindGust b = Realise(11);
  const WindGust c = Realise(12);
  for (std::size_t k = 0; k < a.components().size(); ++k) {
    EXPECT_EQ(a.components()[k].frequency, b.components()[k].frequency);
    EXPECT_EQ(a.components()[k].phase, b.components()[k].phase);
    EXPECT_EQ(a.components()[k].amplitude, b.components()[k].amplitude);
  }
  EXPECT_EQ(a.Speed(123.4), b.Speed(123.4));
  EXPECT_NE(a.components()[0].phase, c.components()[0].phase);
  EXPECT_NE(a.Speed(123.4), c.Speed(123.4));
  // Frequencies lie in their own log bins, phases in [0, 2 pi).
  const double log_bin = std::log(0.5 * 3600.0) / 100.0;
  for (std::size_t k = 0; k < a.components().size(); ++k) {
    const GustComponent& g = a.components()[k];
    const double position = std::log(g.frequency * 3600.0) / log_bin;
    EXPECT_GE(position, k - 1e-9);
    EXPECT_LE(position, k + 1 + 1e-9);
    EXPECT_GE(g.phase, 0.0);
    EXPECT_LT(g.phase, 2.0 * kPi);
  }
}

TEST(WindGustTest, RejectsBadOptions) {
  const auto with = [](const std::function<void(WindGustOptions&)>& change) {
    WindGustOptions options;
    options.mean_speed = 20.0;
    change(options);
    return [options] {
      RandomStream stream = RandomStream::Derive(1, "wind.gust");
      WindGust gust(options, stream);
    };
  };
  ExpectInputError(with([](WindGustOptions& o) { o.mean_speed = 0.0; }),
                   {"wind.gust.mean_speed", "0"});
  ExpectInputError(with([](WindGustOptions& o) { o.height = -10.0; }), {"wind.gust.height", "-10"});
  ExpectInputError(with([](WindGustOptions& o) { o.components = 0; }),
                   {"wind.gust.components", "0"});
  ExpectInputError(with([](WindGustOptions& o) { o.frequency_min = 0.0; }),
                   {"wind.gust.frequency_min", "0"});
  ExpectInputError(with([](WindGustOptions& o) { o.frequency_max = 1e-4; }),
                   {"wind.gust.frequency_max", "1e-04"});
  ExpectInputError(with([](WindGustOptions& o) { o.frequency_max = INFINITY; }),
                   {"wind.gust.frequency_max", "inf"});
  ExpectInputError([] { NpdWindSpectrum spectrum(std::nan(""), 10.0); },
                   {"wind.gust.mean_speed", "nan"});
}

}  // namespace
}  // namespace moorsim::vessel
