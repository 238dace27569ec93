// The FEM lines settled to rest against the analytic elastic catenary (an independent
// continuum solution) for the seed mooring.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "mooring_fem/catenary.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

using testing::CatenaryProperties;
using testing::FairleadsAt;
using testing::SeedScenario;
using testing::StaticState;

struct TensionError {
  double total;       // |T_fem / T_cat - 1|
  double horizontal;  // |H_fem / H_cat - 1|
};

TensionError LineOneError(int segments) {
  const testing::SeedCase s = SeedScenario(segments);
  MooringSystem mooring(s.mooring);
  const std::vector<double> x = StaticState(mooring, {});
  const auto fairleads = FairleadsAt(mooring, {});
  const std::vector<LineLoad> loads = mooring.LineLoads(x.data(), fairleads);
  const LineProperties& lp = mooring.line(0);
  const CatenarySolution cat =
      SolveLineCatenary(CatenaryProperties(lp), lp.anchor, fairleads[0].position).solution;
  const Vec3& f = loads[0].fairlead_force;
  return {std::abs(f.norm() / cat.fairlead_tension - 1.0),
          std::abs(f.head<2>().norm() / cat.horizontal_tension - 1.0)};
}

TEST(StaticFem, FairleadTensionMatchesCatenaryAndConvergesWithSegments) {
  const TensionError e20 = LineOneError(20);
  const TensionError e50 = LineOneError(50);
  const TensionError e100 = LineOneError(100);
  // The bar: within 0.5 % from 50 segments on (measured: ~0.03 %).
  EXPECT_LT(e50.total, 5e-3);
  EXPECT_LT(e50.horizontal, 5e-3);
  EXPECT_LT(e100.total, 5e-3);
  EXPECT_LT(e100.horizontal, 5e-3);
  // Discretisation error falls as segments shrink.
  EXPECT_LT(e50.total, e20.total);
  EXPECT_LT(e100.total, e50.total);
  EXPECT_LT(e50.horizontal, e20.horizontal);
  EXPECT_LT(e100.horizontal, e50.horizontal);
  RecordProperty("error_20", std::to_string(e20.total));
  RecordProperty("error_50", std::to_string(e50.total));
  RecordProperty("error_100", std::to_string(e100.total));
}

TEST(StaticFem, SeedTensionMatchesTheReferenceSheet) {
  // Seed case (docs/design.md section 9): 3.497 MN horizontal, 4.948 MN vertical, 6.059 MN
  // total per line.
  const testing::SeedCase s = SeedScenario(50);
  MooringSystem mooring(s.mooring);
  const std::vector<double> x = StaticState(mooring, {});
  const std::vector<LineLoad> loads = mooring.LineLoads(x.data(), FairleadsAt(mooring, {}));
  for (int i = 0; i < 4; ++i) {  // lines 1-4: anchors exactly 1950 m out
    const Vec3& f = loads[i].fairlead_force;
    EXPECT_NEAR(f.norm(), 6.059e6, 0.002 * 6.059e6) << "line " << i + 1;
    EXPECT_NEAR(f.head<2>().norm(), 3.497e6, 0.002 * 3.497e6) << "line " << i + 1;
    EXPECT_NEAR(f.z(), 4.948e6, 0.002 * 4.948e6) << "line " << i + 1;
    // Grounded length: 380.8 m on a rigid seabed; the compliant contact lets the chain
    // sink up to ~0.1 m, which moves touchdown ~15 m (sqrt(2 H / w * 0.1 m)); allow 25 m.
    EXPECT_NEAR(loads[i].grounded_length, 380.8, 25.0) << "line " << i + 1;
  }
}

// Net horizontal force and yaw moment on the vessel from every line, Earth frame.
Vec3 NetForce(const std::vector<Vec3>& forces, const std::vector<PointKinematics>& fairleads,
              const PlanarPose& pose) {
  Vec3 net = Vec3::Zero();
  for (std::size_t i = 0; i < forces.size(); ++i) {
    const Vec3 arm = fairleads[i].position - Vec3(pose.x, pose.y, 0.0);
    net += Vec3(forces[i].x(), forces[i].y(), arm.x() * forces[i].y() - arm.y() * forces[i].x());
  }
  return net;
}

TEST(StaticFem, RestoringForceMatchesCatenarySumFromZeroToEightyMetres) {
  const testing::SeedCase s = SeedScenario(50);
  MooringSystem mooring(s.mooring);
  const double line5 = std::atan2(1378.9, 1378.9);  // toward line 5's anchor
  for (double direction : {0.0, line5}) {
    double previous = 0.0;
    for (double offset : {0.0, 5.0, 10.0, 20.0, 40.0, 60.0, 80.0}) {
      const PlanarPose pose{offset * std::cos(direction), offset * std::sin(direction), 0.0};
      const auto fairleads = FairleadsAt(mooring, pose);
      const std::vector<double> x = StaticState(mooring, pose);
      std::vector<Vec3> fem(mooring.num_lines()), cat(mooring.num_lines());
      mooring.FairleadForces(x.data(), fairleads, fem);
      for (int i = 0; i < mooring.num_lines(); ++i) {
        const LineProperties& lp = mooring.line(i);
        cat[i] = SolveLineCatenary(CatenaryProperties(lp), lp.anchor, fairleads[i].position)
                     .fairlead_force;
      }
      const Vec3 f_fem = NetForce(fem, fairleads, pose);
      const Vec3 f_cat = NetForce(cat, fairleads, pose);
      if (offset == 0.0) {
        // Opposite lines cancel: only round-off of 8 x 3.5 MN remains.
        EXPECT_LT(f_fem.head<2>().norm(), 1.0);
        EXPECT_LT(std::abs(f_fem.z()), 20.0);
        continue;
      }
      // 0.5 % of the restoring force (measured < 0.03 % at 50 segments), plus 2 kN for the
      // compliant seabed's slight shift of touchdown at small offsets.
      EXPECT_NEAR(f_fem.x(), f_cat.x(), 5e-3 * f_cat.head<2>().norm() + 2e3)
          << "offset " << offset << " direction " << direction;
      EXPECT_NEAR(f_fem.y(), f_cat.y(), 5e-3 * f_cat.head<2>().norm() + 2e3)
          << "offset " << offset << " direction " << direction;
      // Restoring: points back toward the origin, grows with the offset.
      const Vec3 outward(std::cos(direction), std::sin(direction), 0.0);
      const double restoring = -f_fem.head<2>().dot(outward.head<2>());
      EXPECT_GT(restoring, previous);
      previous = restoring;
    }
  }
}

TEST(StaticFem, SurgeStiffnessNearTheOriginMatchesTheReferenceSheet) {
  // Seed case (docs/design.md section 9): about 81 kN/m near the origin. Central difference
  // over +-1 m.
  const testing::SeedCase s = SeedScenario(50);
  MooringSystem mooring(s.mooring);
  auto fx = [&](double x0) {
    const PlanarPose pose{x0, 0.0, 0.0};
    const auto fairleads = FairleadsAt(mooring, pose);
    const std::vector<double> x = StaticState(mooring, pose);
    std::vector<Vec3> f(mooring.num_lines());
    mooring.FairleadForces(x.data(), fairleads, f);
    return NetForce(f, fairleads, pose).x();
  };
  const double stiffness = -(fx(1.0) - fx(-1.0)) / 2.0;
  EXPECT_NEAR(stiffness, 81e3, 0.05 * 81e3);
}

TEST(StaticFem, CatenaryPlacementIsCloseToFemEquilibrium) {
  // The static start is the catenary placement refined by Newton; the refinement moves
  // nodes by the chord-vs-arc discretisation and the seabed compliance only.
  const testing::SeedCase s = SeedScenario(50);
  MooringSystem mooring(s.mooring);
  const std::vector<Vec3> p = testing::Positions(FairleadsAt(mooring, {}));
  std::vector<double> catenary(mooring.StateSize());
  mooring.CatenaryState(p, catenary.data());
  std::vector<double> settled = catenary;
  const double residual = mooring.SettleStatic(p, settled.data());
  EXPECT_LT(residual, 1e-11 * mooring.line(0).sections.front().axial_stiffness);
  double largest = 0.0;
  for (std::size_t i = 0; i < settled.size(); ++i) {
    largest = std::max(largest, std::abs(settled[i] - catenary[i]));
  }
  EXPECT_LT(largest, 0.5);  // metres, out of a 2250 m line (measured 0.24 m)
}

TEST(StaticFem, BrokenLineSixLeavesThreePointFiveMeganewtonsAwayFromIt) {
  // Seed case (docs/design.md section 9): with line 6 gone the net force at the origin is
  // 3.50 MN toward (+x, -y), away from line 6's anchor at (-1378.9, 1378.9).
  testing::SeedCase s = SeedScenario(50);
  std::erase_if(s.mooring.lines, [](const LineParameters& l) { return l.id == 6; });
  MooringSystem mooring(s.mooring);
  const auto fairleads = FairleadsAt(mooring, {});
  const std::vector<double> x = StaticState(mooring, {});
  std::vector<Vec3> f(mooring.num_lines());
  mooring.FairleadForces(x.data(), fairleads, f);
  const Vec3 net = NetForce(f, fairleads, {});
  EXPECT_NEAR(net.head<2>().norm(), 3.50e6, 0.01 * 3.50e6);
  EXPECT_GT(net.x(), 0.0);
  EXPECT_LT(net.y(), 0.0);
  EXPECT_NEAR(net.x(), -net.y(), 1e-3 * net.head<2>().norm());
}

// --- Geometries that used to stop the static solution ------------------------------------

// Line 1 of the seed alone, with its anchor and length changed.
MooringSystem LineOne(const Vec3& anchor, double length) {
  testing::SeedCase s = SeedScenario(50);
  s.mooring.lines.resize(1);
  s.mooring.lines[0].anchor = anchor;
  s.mooring.lines[0].sections.front().length = length;
  return MooringSystem(s.mooring);
}

// The elastic catenary of a line hanging between two held points (Irvine 1981): with H the
// horizontal tension, V the vertical force the lower end takes (negative: the line first
// dips below it) and w the weight per unstretched metre, the upper end sits at
//   x = H/w [asinh((V + w L)/H) - asinh(V/H)] + H L/EA
//   z = H/w [sqrt(1 + ((V + w L)/H)^2) - sqrt(1 + (V/H)^2)] + (V L + w L^2/2)/EA
// above the lower end; solved here for H and V by Newton's method with its own differences.
double HeldCatenaryTopTension(double w, double ea, double length, double span, double rise) {
  const auto ends = [&](double h, double v) {
    const double top = v + w * length;
    return Eigen::Vector2d(
        h / w * (std::asinh(top / h) - std::asinh(v / h)) + h * length / ea - span,
        h / w * (std::hypot(1.0, top / h) - std::hypot(1.0, v / h)) +
            (v * length + 0.5 * w * length * length) / ea - rise);
  };
  double h = 0.1 * w * length, v = 0.0;
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector2d f = ends(h, v);
    const double dh = 1e-6 * h, dv = 1e-6 * w * length;
    Eigen::Matrix2d J;
    J.col(0) = (ends(h + dh, v) - f) / dh;
    J.col(1) = (ends(h, v + dv) - f) / dv;
    const Eigen::Vector2d step = J.fullPivLu().solve(-f);
    h = std::max(0.5 * h, h + step(0));
    v += step(1);
    if (f.norm() < 1e-10 * length) break;
  }
  return std::hypot(h, v + w * length);
}

TEST(StaticFem, ALineHeldInTheWaterHangsAsTheElasticCatenary) {
  // 800 m of the seed chain from a point held 500 m above the seabed, 480 m from the
  // fairlead: it dips below its lower end (the loader's anchor_in_water). The lower end is
  // not on the seabed, so the start hangs it free and the FEM settles onto the catenary.
  MooringSystem mooring = LineOne(Vec3(-480.0, 0.0, 500.0), 800.0);
  const auto fairleads = FairleadsAt(mooring, {});
  const std::vector<double> x = StaticState(mooring, {});
  const LineProperties& lp = mooring.line(0);
  const Vec3 chord = fairleads[0].position - lp.anchor;
  const double expected = HeldCatenaryTopTension(lp.sections.front().weight_per_length,
                                                 lp.sections.front().axial_stiffness, 800.0,
                                                 chord.head<2>().norm(), -chord.z());
  const Vec3 f = mooring.LineLoads(x.data(), fairleads)[0].fairlead_force;
  EXPECT_NEAR(f.norm() / expected, 1.0, 2e-3) << f.norm() << " vs " << expected;
  // It hangs below its lower end and stays off the seabed.
  double deepest = 0.0;
  for (int k = 0; k <= lp.segments; ++k) {
    deepest = std::max(deepest, mooring.NodePosition(x.data(), 0, k, fairleads).z());
  }
  EXPECT_GT(deepest, 510.0);
  EXPECT_LT(deepest, 990.0);
}

TEST(StaticFem, SlackSegmentsInTheCatenaryPlacementStillSettle) {
  // 2700 m to an anchor 1930 m out: H = 257 kN, so the curvature near touchdown is w/H =
  // 0.01 /m and a 54 m segment's chord falls 1.3 % short of its arc, more than the 0.11 %
  // stretch: the placed segments there are slack, their nodes have no stiffness and plain
  // Newton met a singular matrix. The line must still settle, onto the catenary's loads.
  MooringSystem mooring = LineOne(Vec3(1950.0, 0.0, 1000.0), 2700.0);
  const auto fairleads = FairleadsAt(mooring, {});
  const std::vector<double> x = StaticState(mooring, {});
  const std::vector<LineLoad> loads = mooring.LineLoads(x.data(), fairleads);
  const LineProperties& lp = mooring.line(0);
  const CatenarySolution cat =
      SolveLineCatenary(CatenaryProperties(lp), lp.anchor, fairleads[0].position).solution;
  const Vec3& f = loads[0].fairlead_force;
  EXPECT_NEAR(f.head<2>().norm(), cat.horizontal_tension, 0.02 * cat.horizontal_tension);
  EXPECT_NEAR(f.z(), cat.vertical_tension, 0.01 * cat.vertical_tension);
}

TEST(StaticFem, LineLongerThanSpanPlusDepthSettlesSlack) {
  // 20 km of chain to an anchor 1930 m out (the loader rejects this at the reference pose;
  // a vessel offset toward an anchor can still make a line slack): no horizontal tension,
  // the fairlead carries the vertical hanging part, ~ w x height = 2.6 MN.
  MooringSystem mooring = LineOne(Vec3(1950.0, 0.0, 1000.0), 20000.0);
  const auto fairleads = FairleadsAt(mooring, {});
  const std::vector<double> x = StaticState(mooring, {});
  const Vec3 f = mooring.LineLoads(x.data(), fairleads)[0].fairlead_force;
  const double hanging = mooring.line(0).sections.front().weight_per_length * (1000.0 - 12.0);
  EXPECT_LT(f.head<2>().norm(), 1e-3 * hanging);
  EXPECT_NEAR(f.z(), hanging, 0.02 * hanging);
}

TEST(StaticFem, UnsettleableStartStatesThrowErrorsNamingTheLine) {
  MooringSystem mooring = LineOne(Vec3(1950.0, 0.0, 1000.0), 2250.0);
  const std::vector<Vec3> p = testing::Positions(FairleadsAt(mooring, {}));
  // Forces that overflow (node 1 placed 1e300 m away) used to end the iteration at once
  // and report a residual of 0.
  std::vector<double> x(mooring.StateSize());
  mooring.CatenaryState(p, x.data());
  std::fill(x.begin(), x.begin() + 3, 1e300);
  try {
    mooring.SettleStatic(p, x.data());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "static equilibrium of line 1 did not converge: the node forces of the start "
              "state are not finite");
  }
  // Two nodes on top of each other: no tangent, no force.
  mooring.CatenaryState(p, x.data());
  std::copy(x.begin(), x.begin() + 3, x.begin() + 6);  // node 2 onto node 1
  try {
    mooring.SettleStatic(p, x.data());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "static equilibrium of line 1: the start state is degenerate (line 1 segment 2 "
              "has length 0 m)");
  }
}

}  // namespace
}  // namespace moorsim::mooring_fem

namespace moorsim::mooring_fem {
namespace {

TEST(StaticFem, CurrentDragsTheMooringDownstreamAndTheStateIsAtRest) {
  // A sheared current toward the north-west (315 deg: 1 m/s at the surface, 0.2 m/s at the
  // seabed). The static state includes the drag on the lines at rest, so (a) the net force
  // on the vessel points downstream, (b) line 8, whose anchor lies downstream, pulls
  // harder and line 6 upstream less, and (c) a dynamic run from that state stays put.
  testing::SeedCase s = testing::SeedScenario(50);
  s.mooring.current.direction = 315.0 * std::numbers::pi / 180.0;
  s.mooring.current.depth = {0.0, 1000.0};
  s.mooring.current.speed = {1.0, 0.2};
  LineSimulation sim(s.mooring, s.solver, PrescribedMotion{});
  const std::vector<Vec3> f = sim.FairleadForces();
  Vec3 net = Vec3::Zero();
  for (const Vec3& line : f) net += line;
  const Eigen::Vector2d downstream(std::cos(s.mooring.current.direction),
                                   std::sin(s.mooring.current.direction));
  EXPECT_GT(net.head<2>().dot(downstream), 10e3);  // measured 45.6 kN
  EXPECT_LT(std::abs(net.head<2>().dot(Eigen::Vector2d(-downstream.y(), downstream.x()))),
            1.0);                             // symmetric about the current's axis
  EXPECT_GT(f[7].norm(), f[5].norm() + 5e3);  // line 8 vs line 6, measured 14 kN apart
  const std::vector<double> start = sim.state();
  sim.AdvanceTo(300.0);
  double largest = 0.0;
  for (std::size_t i = 0; i < start.size(); ++i) {
    if (i % 6 < 3) largest = std::max(largest, std::abs(sim.state()[i] - start[i]));
  }
  EXPECT_LT(largest, 0.01);
}

}  // namespace
}  // namespace moorsim::mooring_fem
