// Free points where lines meet or end, at rest: a buoy on a vertical tether against the
// closed form (the lumped-mass line is exact for a hanging column: its segment tensions
// sample a linear tension at the segments' midpoints), and a bridle whose apex must balance
// the forces of independent catenaries (the Simpson reference of catenary_reference.h) of
// its three lines at the position the FEM found for it. Bad topologies are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "catenary_reference.h"
#include "core/error.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

constexpr double kRho = 1025.0;
constexpr double kG = 9.81;

double ChainWeightInWater() {
  const LineType t = testing::ChainType();
  return (t.mass_per_length - kRho * std::numbers::pi / 4.0 * t.diameter * t.diameter) * kG;
}

// The state at rest with the fairleads held at their body-frame positions.
std::vector<double> AtRest(MooringSystem& mooring, std::vector<PointKinematics>* fairleads) {
  std::vector<Vec3> positions;
  for (int i = 0; i < mooring.num_lines(); ++i) {
    PointKinematics f;
    f.position = mooring.line(i).fairlead_body;
    fairleads->push_back(f);
    positions.push_back(f.position);
  }
  std::vector<double> x(mooring.StateSize());
  mooring.CatenaryState(positions, x.data());
  mooring.SettleStatic(positions, x.data());
  return x;
}

// A buoy of 120 m^3 and 20 t (1.01 MN of net lift) starting at `start` on 150 m of chain
// (397 kN in water) from an anchor on the seabed right below the origin.
MooringParameters BuoyOnATether(double depth, const Vec3& start) {
  MooringParameters spec;
  spec.water.depth = depth;
  spec.line_types = {testing::ChainType()};
  FreePoint buoy;
  buoy.position = start;
  buoy.body = {20000.0, 120.0, 1.0, 5.0};
  spec.points = {buoy};
  LineParameters tether =
      LineParameters::Uniform(1, "chain", 150.0, 30, Vec3(0.0, 0.0, depth), Vec3::Zero());
  tether.upper_point = 0;
  spec.lines = {tether};
  return spec;
}

TEST(FreePoints, ABuoyOnAVerticalTetherFloatsAtItsClosedFormHeight) {
  // Off its equilibrium: the solve moves it.
  const MooringParameters spec = BuoyOnATether(1000.0, Vec3(6.0, -4.0, 820.0));
  const LineParameters& tether = spec.lines.front();
  MooringSystem mooring(spec);
  std::vector<PointKinematics> fairleads;
  const std::vector<double> x = AtRest(mooring, &fairleads);

  // T(s) = B - w (L - s) from the anchor (s = 0) up: the tether stretches by
  // (B L - w L^2 / 2) / EA.
  const double lift = (kRho * 120.0 - 20000.0) * kG;
  const double w = ChainWeightInWater();
  const double L = 150.0;
  const double EA = testing::ChainType().axial_stiffness;
  const double height = L + (lift * L - 0.5 * w * L * L) / EA;
  const Vec3 p = mooring.PointPosition(x.data(), 0);
  EXPECT_NEAR(p.x(), 0.0, 1e-6);
  EXPECT_NEAR(p.y(), 0.0, 1e-6);
  EXPECT_NEAR(1000.0 - p.z(), height, 1e-6 * height);
  // The anchor's pull: the first segment's tension is the tension half a segment up.
  const double l0 = L / 30.0;
  const double stretched = (mooring.NodePosition(x.data(), 0, 1, fairleads) - tether.anchor).norm();
  EXPECT_NEAR(EA * (stretched / l0 - 1.0), lift - w * (L - 0.5 * l0), 1e-6 * lift);
  // It floats still: the points' force tolerance (1e-9 EA, 0.23 N) on its 143 t with added
  // mass leaves 2e-6 m/s^2.
  std::vector<double> xdot(x.size());
  mooring.Derivatives(x.data(), fairleads, xdot.data());
  for (double v : xdot) EXPECT_NEAR(v, 0.0, 1e-5);
}

// A mass on a neutral line (its weight is its displaced water) of EA 1e9 N hung from a
// fixed point at the surface above the origin, the mass starting at `start`.
MooringParameters NeutralPendulum(double depth, double length, double mass, const Vec3& start) {
  MooringParameters spec;
  spec.water = {1000.0, kG, depth};
  LineType neutral = testing::ChainType();
  neutral.name = "neutral";
  neutral.diameter = 0.1;
  neutral.mass_per_length = 1000.0 * std::numbers::pi / 4.0 * 0.01;
  neutral.axial_stiffness = 1e9;
  spec.line_types = {neutral};
  FreePoint point;
  point.position = start;
  point.body = {mass, 0.0, 0.0, 0.0};
  spec.points = {point};
  LineParameters line =
      LineParameters::Uniform(1, "neutral", length, 20, Vec3(0.0, 0.0, 0.0), Vec3::Zero());
  line.upper_point = 0;
  spec.lines = {line};
  return spec;
}

// A mass hanging from a fixed point above it on a line of neutral weight, slack at the
// start (MoorDyn's lifting test): the line folds along its vertical chord at the start and
// the mass settles L (1 + m g / EA) below the point.
TEST(FreePoints, AMassHangsBelowItsPointOnANeutralLine) {
  MooringSystem mooring(NeutralPendulum(500.0, 100.5, 1000.0, Vec3(0.0, 0.0, 100.0)));
  std::vector<PointKinematics> fairleads;
  const std::vector<double> x = AtRest(mooring, &fairleads);
  const Vec3 p = mooring.PointPosition(x.data(), 0);
  EXPECT_NEAR(p.x(), 0.0, 1e-9);
  EXPECT_NEAR(p.y(), 0.0, 1e-9);
  EXPECT_NEAR(p.z(), 100.5 * (1.0 + 1000.0 * kG / 1e9), 1e-9 * 100.5);
}

// A 10 kg mass on 32 m of line, started 10 m to the side and 28 m down (MoorDyn's
// pendulum over a seabed): the static solve swings it to rest below its point, L (1 +
// m g / EA) down.
TEST(FreePoints, AMassStartedToTheSideSettlesBelowItsPoint) {
  MooringSystem mooring(NeutralPendulum(500.0, 32.0, 10.0, Vec3(10.0, 0.0, 28.0)));
  std::vector<PointKinematics> fairleads;
  const std::vector<double> x = AtRest(mooring, &fairleads);
  const Vec3 p = mooring.PointPosition(x.data(), 0);
  // Sideways, the mass is held by W x / L: the points' force tolerance (1e-9 EA = 1 N)
  // bounds how far off the vertical it may stop.
  EXPECT_LT(std::hypot(p.x(), p.y()) * 10.0 * kG / 32.0, 1.0);
  EXPECT_NEAR(p.z(), 32.0 * (1.0 + 10.0 * kG / 1e9), 1e-9 * 32.0);
}

// In 30 m of water it would rest 2 m below the seabed, which a point does not touch.
TEST(FreePoints, AMassThatWouldRestBelowTheSeabedIsRefused) {
  MooringSystem mooring(NeutralPendulum(30.0, 32.0, 10.0, Vec3(10.0, 0.0, 28.0)));
  std::vector<PointKinematics> fairleads;
  try {
    AtRest(mooring, &fairleads);
    ADD_FAILURE() << "a mass resting 2 m below the seabed was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find("mooring.points[1]: rests below the seabed (32"), 0u) << what;
    EXPECT_NE(what.find("a point has no contact with the seabed"), std::string::npos) << what;
  }
}

TEST(FreePoints, ABuoyOnATetherLongerThanTheWaterIsDeepIsRefused) {
  MooringSystem mooring(BuoyOnATether(100.0, Vec3(0.0, 0.0, 40.0)));
  std::vector<PointKinematics> fairleads;
  try {
    AtRest(mooring, &fairleads);
    ADD_FAILURE() << "a buoy 50 m above the surface at rest was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "mooring.points[1]: rises above the water at rest: its buoyancy is more than its "
              "lines hold down below the surface");
  }
}

// A bridle in 500 m: a chain from an anchor 1400 m away up to the apex, which carries a
// clump weight, and two legs from the apex up to two fairleads 30 m apart.
MooringParameters Bridle(int scale) {
  MooringParameters spec;
  spec.water.depth = 500.0;
  spec.seabed.stiffness = 3e7;  // a hard seabed, as the reference's is rigid
  spec.seabed.contact_smoothing = 0.02;
  spec.line_types = {testing::ChainType()};
  FreePoint apex;
  apex.position = Vec3(-150.0, 0.0, 120.0);
  apex.body = {10000.0, 10000.0 / 7850.0, 1.0, 1.0};
  spec.points = {apex};
  LineParameters ground =
      LineParameters::Uniform(1, "chain", 1500.0, 60 * scale, Vec3(-1400.0, 0.0, 500.0), {});
  ground.upper_point = 0;
  spec.lines.push_back(ground);
  for (int side : {-1, 1}) {
    LineParameters leg =
        LineParameters::Uniform(static_cast<int>(spec.lines.size()) + 1, "chain", 160.0, 16 * scale,
                                Vec3::Zero(), Vec3(-40.0, 15.0 * side, 10.0));
    leg.lower_point = 0;
    spec.lines.push_back(leg);
  }
  return spec;
}

TEST(FreePoints, ABridleApexBalancesTheIndependentCatenariesOfItsLines) {
  const MooringParameters spec = Bridle(2);
  MooringSystem mooring(spec);
  std::vector<PointKinematics> fairleads;
  const std::vector<double> x = AtRest(mooring, &fairleads);
  const Vec3 apex = mooring.PointPosition(x.data(), 0);
  const LineType chain = testing::ChainType();
  const std::vector<reference::RefSection> sections = {
      {1500.0, ChainWeightInWater(), chain.axial_stiffness}};
  const Vec3 down(0.0, 0.0, 1.0);

  // The ground line from its anchor up to the apex, with the seabed.
  const Vec3 anchor = spec.lines[0].anchor;
  const Vec3 to_anchor = Vec3(anchor.x() - apex.x(), anchor.y() - apex.y(), 0.0).normalized();
  const CatenaryLineProperties props{1500.0, ChainWeightInWater(), chain.axial_stiffness};
  const LineCatenary guess = SolveLineCatenary(props, anchor, apex);
  const reference::Reference ground = reference::SolveReference(
      sections, {}, 0.0, (apex - anchor).head<2>().norm(), anchor.z() - apex.z(),
      guess.solution.horizontal_tension, guess.solution.vertical_tension);
  Vec3 net = ground.h * to_anchor + ground.v_fairlead * down;
  double largest = ground.FairleadTension();

  // The legs hang from the apex up to their fairleads, in the water all along.
  for (int leg = 1; leg <= 2; ++leg) {
    const Vec3 top = fairleads[leg].position;
    const Vec3 across = Vec3(top.x() - apex.x(), top.y() - apex.y(), 0.0);
    const std::vector<reference::RefSection> leg_sections = {
        {160.0, ChainWeightInWater(), chain.axial_stiffness}};
    const reference::Reference r =
        reference::SolveReference(leg_sections, {}, 0.0, across.norm(), apex.z() - top.z(),
                                  ground.h / 2.0, ChainWeightInWater() * 160.0, false);
    // On the apex: H toward the fairlead, and the vertical tension at the leg's lower end.
    net += r.h * across.normalized() - r.v_anchor * down;
    largest = std::max(largest, r.FairleadTension());
    // The leg's fairlead tension from the FEM.
    const Vec3 f = mooring.LineLoads(x.data(), fairleads)[leg].fairlead_force;
    EXPECT_NEAR(f.norm(), r.FairleadTension(), 1e-3 * r.FairleadTension()) << "leg " << leg;
    RecordProperty("leg_" + std::to_string(leg) + "_error",
                   std::to_string(f.norm() / r.FairleadTension() - 1.0));
  }
  const double clump = (10000.0 - kRho * 10000.0 / 7850.0) * kG;
  net += clump * down;
  EXPECT_LT(net.norm(), 1e-3 * largest)
      << "apex at " << apex.transpose() << ", net force " << net.transpose() << " N";
  RecordProperty("apex_imbalance", std::to_string(net.norm() / largest));
}

TEST(FreePoints, ABridleRunsOnTheBlockSolverAsOnKlu) {
  // Fairleads surging: the apex and the legs' chains coupled to the border at both ends.
  const MooringParameters spec = Bridle(1);
  PrescribedMotion motion;
  motion.components[PrescribedMotion::kSurge] = {{3.0, 40.0}};
  SolverSettings block;
  SolverSettings klu;
  klu.linear_solver = IntegratorOptions::LinearSolver::kKlu;
  LineSimulation a(spec, block, motion);
  LineSimulation b(spec, klu, motion);
  a.AdvanceTo(30.0);
  b.AdvanceTo(30.0);
  const Vec3 pa = a.mooring().PointPosition(a.state().data(), 0);
  const Vec3 pb = b.mooring().PointPosition(b.state().data(), 0);
  EXPECT_LT((pa - pb).norm(), 1e-3) << pa.transpose() << " / " << pb.transpose();
  const std::vector<Vec3> fa = a.FairleadForces();
  const std::vector<Vec3> fb = b.FairleadForces();
  for (int i = 1; i <= 2; ++i) EXPECT_NEAR(fa[i].norm(), fb[i].norm(), 1e-4 * fb[i].norm());
  // The apex moved with the fairleads.
  EXPECT_GT((pa - Vec3(-150.0, 0.0, 120.0)).norm(), 1.0);
}

void ExpectRefused(const MooringParameters& spec, const std::string& what) {
  try {
    MooringSystem mooring(spec);
    ADD_FAILURE() << "accepted: " << what;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(FreePoints, BadTopologiesAreRefused) {
  MooringParameters spec = Bridle(1);
  spec.lines[1].sections.front().segments = 1;
  ExpectRefused(spec, "mooring.lines[2]: a line from a free point to the vessel needs 2");
  spec = Bridle(1);
  spec.lines[0].upper_point = 1;
  ExpectRefused(spec, "mooring.lines[1]: no free point 2");
  spec = Bridle(1);
  spec.lines[1].upper_point = 0;
  ExpectRefused(spec, "mooring.lines[2]: both ends at free point 1");
  spec = Bridle(1);
  spec.points.push_back(spec.points.front());
  ExpectRefused(spec, "free point 2: no line ends at it");
}

}  // namespace
}  // namespace moorsim::mooring_fem
