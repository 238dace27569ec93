// Every analytic Jacobian block of the lumped-mass lines against central finite
// differences of the right-hand side, with every force model active: elasticity with
// structural damping, drag on velocity relative to a sheared current, normal added mass,
// seabed penalty contact and anisotropic regularised friction; and after failures (free
// ends, split chains).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <utility>

#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

MooringParameters TestSpec(int segments) {
  MooringParameters spec;
  spec.water.depth = 1000.0;
  spec.current.direction = 30.0 * std::numbers::pi / 180.0;
  spec.current.depth = {0.0, 200.0, 1000.0};
  spec.current.speed = {0.8, 0.4, 0.1};
  spec.line_types.push_back(testing::ChainType());
  for (int i = 0; i < 2; ++i) {
    const double angle = i * 2.0 * std::numbers::pi / 3.0;
    spec.lines.push_back(
        LineParameters::Uniform(i + 1, "chain", 2250.0, segments,
                                Vec3(1950.0 * std::cos(angle), 1950.0 * std::sin(angle), 1000.0),
                                Vec3(20.0 * std::cos(angle), 20.0 * std::sin(angle), 12.0)));
  }
  return spec;
}

// Compares df/dx from MooringSystem::Jacobian with central differences, 3x3 block by
// block. Step sizes: 1e-4 m and 1e-5 m/s keep truncation error (~h^2 f''') and round-off
// (~eps f / h) both far below 1e-5 of the block norms here.
void ExpectJacobianMatchesFiniteDifferences(MooringSystem& mooring, std::vector<double> x,
                                            std::span<const PointKinematics> fairleads) {
  const int n = mooring.StateSize();
  const SparsityPattern& p = mooring.JacobianPattern();
  std::vector<double> values(p.nnz());
  mooring.Jacobian(x.data(), fairleads, values.data());
  Eigen::MatrixXd analytic = Eigen::MatrixXd::Zero(n, n);
  for (int r = 0; r < n; ++r) {
    for (int64_t e = p.row_start[r]; e < p.row_start[r + 1]; ++e)
      analytic(r, p.column[e]) = values[e];
  }
  Eigen::MatrixXd fd(n, n);
  std::vector<double> fp(n), fm(n);
  for (int c = 0; c < n; ++c) {
    const double h = (c % 6) < 3 ? 1e-4 : 1e-5;
    const double saved = x[c];
    x[c] = saved + h;
    mooring.Derivatives(x.data(), fairleads, fp.data());
    x[c] = saved - h;
    mooring.Derivatives(x.data(), fairleads, fm.data());
    x[c] = saved;
    for (int r = 0; r < n; ++r) fd(r, c) = (fp[r] - fm[r]) / (2.0 * h);
  }
  int checked = 0;
  for (int br = 0; br < n / 3; ++br) {
    for (int bc = 0; bc < n / 3; ++bc) {
      const Eigen::Matrix3d A = analytic.block<3, 3>(3 * br, 3 * bc);
      const Eigen::Matrix3d F = fd.block<3, 3>(3 * br, 3 * bc);
      // Scale: the larger of the block itself and a tiny fraction of its row block, so
      // blocks that are exactly zero in both are not divided by zero.
      const double scale = std::max(F.norm(), 1e-9 * fd.block(3 * br, 0, 3, n).norm()) + 1e-300;
      ASSERT_LT((A - F).norm() / scale, 1e-5) << "block (" << br << ", " << bc << ")\nanalytic\n"
                                              << A << "\nfinite difference\n"
                                              << F;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  // Row by row too, for the rows and columns past the last whole block (the creep states
  // of visco-elastic segments, one each).
  for (int r = 3 * (n / 3); r < n; ++r) {
    ASSERT_LT((analytic.row(r) - fd.row(r)).norm(), 1e-5 * fd.row(r).norm() + 1e-12)
        << "row " << r << "\nanalytic " << analytic.row(r) << "\nfinite difference " << fd.row(r);
  }
  for (int c = 3 * (n / 3); c < n; ++c) {
    ASSERT_LT((analytic.col(c) - fd.col(c)).norm(), 1e-5 * fd.col(c).norm() + 1e-12)
        << "column " << c;
  }
}

// Line 2 made of three sections (chain, a lighter and more compliant rope, chain) with a
// clump weight and a buoy with drag at the joints.
MooringParameters CompositeTestSpec() {
  MooringParameters spec = TestSpec(12);
  spec.line_types.push_back(testing::PolyesterType());
  LineParameters& line = spec.lines[1];
  line.sections = {{"chain", 700.0, 4}, {"polyester", 1200.0, 6}, {"chain", 350.0, 3}};
  line.joints = {{20000.0, 2.5, 1.0, 2.0}, {4000.0, 12.0, 0.8, 5.0}};
  return spec;
}

struct Fixture {
  explicit Fixture(int segments) : Fixture(TestSpec(segments)) {}
  explicit Fixture(MooringParameters parameters) : spec(std::move(parameters)), mooring(spec) {
    for (int i = 0; i < mooring.num_lines(); ++i) {
      PointKinematics f;
      f.position = mooring.line(i).fairlead_body + Vec3(3.0, -2.0, 0.5);
      f.velocity = Vec3(0.4, -0.3, 0.2);
      f.acceleration = Vec3(0.05, 0.02, -0.1);
      fairleads.push_back(f);
      positions.push_back(f.position);
    }
    x.resize(mooring.StateSize());
    mooring.CatenaryState(positions, x.data());
    mooring.SettleStatic(positions, x.data());
    // Random node velocities (drag, friction, structural damping all active) and small
    // position jitter so no segment is exactly aligned with an axis.
    std::mt19937 rng(42);
    std::normal_distribution<double> dist(0.0, 1.0);
    for (int i = 0; i < mooring.StateSize(); ++i) {
      x[i] += (i % 6) < 3 ? 0.05 * dist(rng) : 0.5 * dist(rng);
    }
  }
  MooringParameters spec;
  MooringSystem mooring;
  std::vector<PointKinematics> fairleads;
  std::vector<Vec3> positions;
  std::vector<double> x;
};

TEST(MooringJacobian, IntactLinesMatchFiniteDifferences) {
  Fixture f(12);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
}

TEST(MooringJacobian, CompositeLinesWithBodiesMatchFiniteDifferences) {
  Fixture f(CompositeTestSpec());
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
  // Parted at the joint that carries the buoy: both pieces keep a free copy of it.
  const std::vector<double> x =
      f.mooring.ApplyFailure({1, FailureMode::kNode, 10}, f.x.data(), f.fairleads);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, x, f.fairleads);
}

TEST(MooringJacobian, ARopeOnATensionStrainCurveWithTangentialAddedMassMatchesFiniteDifferences) {
  MooringParameters spec = CompositeTestSpec();
  LineType& rope = spec.line_types.back();
  rope.axial_stiffness = 0.0;
  rope.tension_strain = {{0.005, 0.3e6}, {0.01, 0.8e6}, {0.02, 2.0e6}, {0.04, 5.0e6}};
  rope.added_mass_tangential = 0.4;  // and added mass along it
  spec.line_types.front().added_mass_tangential = 0.5;
  Fixture f(spec);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
}

// The anchors moved onto the seabed below them.
MooringParameters OnTheSeabed(MooringParameters spec) {
  const SeabedSurface seabed(spec.seabed, spec.water.depth);
  for (LineParameters& line : spec.lines) {
    line.anchor.z() = seabed.DepthAt(line.anchor.x(), line.anchor.y());
  }
  return spec;
}

// How many nodes of the fixture's lines touch the seabed.
int NodesInContact(const Fixture& f, int segments) {
  int in_contact = 0;
  for (int line = 0; line < f.mooring.num_lines(); ++line) {
    for (int k = 1; k < segments; ++k) {
      const Vec3 r = f.mooring.NodePosition(f.x.data(), line, k, f.fairleads);
      in_contact += f.mooring.seabed().Below(r) > 0.0;
    }
  }
  return in_contact;
}

TEST(MooringJacobian, ASlopingSeabedMatchesFiniteDifferences) {
  // The contact normal and the friction plane tilted 4 deg; friction acts on the grounded
  // nodes' random velocities.
  MooringParameters spec = TestSpec(12);
  spec.seabed.slope = 4.0 * std::numbers::pi / 180.0;
  spec.seabed.slope_direction = 70.0 * std::numbers::pi / 180.0;
  Fixture f(OnTheSeabed(spec));
  EXPECT_GE(NodesInContact(f, 12), 2);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
}

TEST(MooringJacobian, ATwistedDepthGridMatchesFiniteDifferences) {
  // A 3 x 3 grid of h = 1000 + 0.01 x - 0.02 y + 4e-6 x y, which bilinear interpolation
  // reproduces everywhere: no kinks at the cell edges, and a normal that turns with
  // position (h_xy = 4e-6 /m), whose derivative the Jacobian carries.
  MooringParameters spec = TestSpec(12);
  DepthGrid& grid = spec.seabed.grid;
  grid.x = {-3000.0, 0.0, 3000.0};
  grid.y = {-3000.0, 0.0, 3000.0};
  for (double x : grid.x) {
    for (double y : grid.y) grid.depth.push_back(1000.0 + 0.01 * x - 0.02 * y + 4e-6 * x * y);
  }
  Fixture f(OnTheSeabed(spec));
  EXPECT_GE(NodesInContact(f, 12), 2);
  EXPECT_NE(f.mooring.seabed().surface.At(1500.0, 800.0).dxy, 0.0);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
}

TEST(MooringJacobian, LinesInWavesMatchFiniteDifferences) {
  // A long-period sea that reaches a few hundred metres down: drag on the velocity relative
  // to current and waves, the water's inertia on the segments and on the joints' bodies,
  // all with their dependence on position; Wheeler stretching and linear theory.
  const std::vector<WaveTrain> sea = {
      {0.35, 3.0, 0.4, 0.5}, {0.55, 2.0, 1.9, -0.3}, {0.9, 1.0, 4.4, 0.8}};
  for (const WaveStretching stretching : {WaveStretching::kWheeler, WaveStretching::kNone}) {
    Fixture f(CompositeTestSpec());
    f.mooring.SetWaves(std::make_shared<const WaveKinematics>(sea, 1000.0, 9.81, stretching));
    f.mooring.SetTime(17.3);
    int in_waves = 0;
    for (int line = 0; line < f.mooring.num_lines(); ++line) {
      for (int k = 1; k < f.mooring.line(line).segments; ++k) {
        const Vec3 r = f.mooring.NodePosition(f.x.data(), line, k, f.fairleads);
        in_waves += f.mooring.waves()->At(17.3, r, false).velocity.norm() > 1e-3;
      }
    }
    EXPECT_GE(in_waves, 4);
    ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
  }
}

TEST(MooringJacobian, ACurrentTableMatchesFiniteDifferences) {
  // A current over north, east, depth and time that turns and shears, different in every
  // cell and strongly so (up to 0.04 /s across a 50 m cell, so that its gradient's share of
  // the drag's Jacobian is well above the check's tolerance): drag on the velocity
  // relative to it, with its gradient in all three directions.
  MooringParameters spec = TestSpec(12);
  auto table = std::make_shared<CurrentTable>();
  for (int i = 0; i <= 30; ++i) table->x.push_back(-3000.0 + 200.0 * i);
  for (int j = 0; j <= 30; ++j) table->y.push_back(-3000.0 + 200.0 * j);
  for (int k = 0; k <= 22; ++k) table->z.push_back(50.0 * k);
  table->t = {0.0, 30.0};
  for (int i = 0; i <= 30; ++i) {
    for (int j = 0; j <= 30; ++j) {
      for (int k = 0; k <= 22; ++k) {
        for (int l = 0; l < 2; ++l) {
          table->velocity.emplace_back(std::sin(1.3 * i + 0.7 * k) + 0.1 * l,
                                       std::cos(0.9 * j - 1.1 * k), 0.2 * std::sin(i + j + k + l));
        }
      }
    }
  }
  spec.current = {};
  spec.current.table = table;
  Fixture f(spec);
  f.mooring.SetTime(11.0);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
}

TEST(MooringJacobian, GroundedNodesAreExercised) {
  // The test above is only meaningful if some nodes are in seabed contact, in the
  // smoothed zone and beyond it.
  Fixture f(12);
  int in_contact = 0;
  for (int line = 0; line < f.mooring.num_lines(); ++line) {
    for (int k = 1; k < 12; ++k) {
      in_contact += f.mooring.NodePosition(f.x.data(), line, k, f.fairleads).z() > 1000.0;
    }
  }
  EXPECT_GE(in_contact, 2);
}

TEST(MooringJacobian, FreeEndsAfterFailuresMatchFiniteDifferences) {
  Fixture f(12);
  std::vector<double> x =
      f.mooring.ApplyFailure({0, FailureMode::kFairlead, 0}, f.x.data(), f.fairleads);
  x = f.mooring.ApplyFailure({1, FailureMode::kNode, 6}, x.data(), f.fairleads);
  x = f.mooring.ApplyFailure({1, FailureMode::kAnchor, 0}, x.data(), f.fairleads);
  ASSERT_EQ(f.mooring.chains().size(), 3u);
  // The released anchor sits exactly on the seabed (delta = 0), where the contact law has
  // its kink: move every node off such points before differencing.
  std::mt19937 rng(7);
  std::normal_distribution<double> dist(0.0, 0.01);
  for (double& value : x) value += dist(rng);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, x, f.fairleads);
}

// TestSpec's two lines and a bridle: a ground line from an anchor up to an apex carrying a
// clump weight with drag and added mass, two legs from the apex up to fairleads (one of
// two segments, whose only node neighbours both the apex and the fairlead), and a buoy on
// a one-segment pendant above the apex (two points coupled directly).
MooringParameters BridleTestSpec() {
  MooringParameters spec = TestSpec(12);
  const double angle = 4.0 * std::numbers::pi / 3.0;
  const Vec3 out(std::cos(angle), std::sin(angle), 0.0);
  const Vec3 side(-out.y(), out.x(), 0.0);
  FreePoint apex;
  apex.position = 120.0 * out + Vec3(0.0, 0.0, 100.0);
  apex.body = {8000.0, 1.0, 1.2, 3.0};
  FreePoint buoy;
  buoy.position = apex.position - Vec3(0.0, 0.0, 29.0);
  buoy.body = {500.0, 3.0, 0.8, 2.0};
  spec.points = {apex, buoy};
  LineParameters ground =
      LineParameters::Uniform(3, "chain", 2250.0, 10, 1950.0 * out + Vec3(0.0, 0.0, 1000.0), {});
  ground.upper_point = 0;
  spec.lines.push_back(ground);
  for (int k : {0, 1}) {
    LineParameters leg =
        LineParameters::Uniform(4 + k, "chain", 140.0, k == 0 ? 6 : 2, Vec3::Zero(),
                                20.0 * out + (k == 0 ? 6.0 : -6.0) * side + Vec3(0.0, 0.0, 12.0));
    leg.lower_point = 0;
    spec.lines.push_back(leg);
  }
  LineParameters pendant = LineParameters::Uniform(6, "chain", 30.0, 1, Vec3::Zero(), {});
  pendant.lower_point = 0;
  pendant.upper_point = 1;
  spec.lines.push_back(pendant);
  return spec;
}

TEST(MooringJacobian, FreePointsMatchFiniteDifferences) {
  Fixture f(BridleTestSpec());
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
  // In waves: the water's inertia and velocity on the points' bodies too.
  const std::vector<WaveTrain> sea = {{0.35, 3.0, 0.4, 0.5}, {0.55, 2.0, 1.9, -0.3}};
  f.mooring.SetWaves(
      std::make_shared<const WaveKinematics>(sea, 1000.0, 9.81, WaveStretching::kWheeler));
  f.mooring.SetTime(4.1);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
}

TEST(MooringJacobian, LinesLeavingFreePointsMatchFiniteDifferences) {
  Fixture f(BridleTestSpec());
  // The pendant lets go of the buoy, the ground line of the apex, a leg's lower end of it.
  std::vector<double> x =
      f.mooring.ApplyFailure({5, FailureMode::kFairlead, 0}, f.x.data(), f.fairleads);
  x = f.mooring.ApplyFailure({2, FailureMode::kFairlead, 0}, x.data(), f.fairleads);
  x = f.mooring.ApplyFailure({3, FailureMode::kAnchor, 0}, x.data(), f.fairleads);
  EXPECT_FALSE(f.mooring.attached(5));
  EXPECT_FALSE(f.mooring.attached(2));
  EXPECT_TRUE(f.mooring.at_vessel(3));
  ExpectJacobianMatchesFiniteDifferences(f.mooring, x, f.fairleads);
}

TEST(MooringJacobian, ViscoElasticRopesMatchFiniteDifferences) {
  // Every line of the bridle a visco-elastic rope: creep states on the chains' segments, on
  // the segments at the points and on the pendant between them.
  MooringParameters spec = BridleTestSpec();
  spec.line_types[0].visco_elastic = ViscoElastic{3.0 * spec.line_types[0].axial_stiffness, 30.0};
  Fixture f(spec);
  ASSERT_FALSE(f.mooring.has_blocks());
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
  // With lines parted at a node, at a point and at the vessel: the creep states stay.
  std::vector<double> x =
      f.mooring.ApplyFailure({1, FailureMode::kNode, 5}, f.x.data(), f.fairleads);
  x = f.mooring.ApplyFailure({3, FailureMode::kAnchor, 0}, x.data(), f.fairleads);
  x = f.mooring.ApplyFailure({0, FailureMode::kFairlead, 0}, x.data(), f.fairleads);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, x, f.fairleads);
}

// The dynamic stiffness rising with the mean load (the creep spring's tension): the creep
// rows' and the node rows' derivatives with respect to the creep stretch carry its slope.
TEST(MooringJacobian, RopesStiffeningWithLoadMatchFiniteDifferences) {
  MooringParameters spec = BridleTestSpec();
  spec.line_types[0].visco_elastic =
      ViscoElastic{3.0 * spec.line_types[0].axial_stiffness, 30.0, 200.0};
  Fixture f(spec);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, f.x, f.fairleads);
  std::vector<double> x =
      f.mooring.ApplyFailure({1, FailureMode::kNode, 5}, f.x.data(), f.fairleads);
  ExpectJacobianMatchesFiniteDifferences(f.mooring, x, f.fairleads);
}

TEST(MooringJacobian, PatternHasDiagonalAndBlockTridiagonalShape) {
  Fixture f(20);
  const SparsityPattern& p = f.mooring.JacobianPattern();
  ASSERT_EQ(p.size, f.mooring.StateSize());
  for (int r = 0; r < p.size; ++r) {
    bool diagonal = false;
    for (int64_t e = p.row_start[r]; e < p.row_start[r + 1]; ++e) {
      diagonal |= p.column[e] == r;
      if (e > p.row_start[r]) {
        EXPECT_LT(p.column[e - 1], p.column[e]);
      }
      EXPECT_LE(std::abs(p.column[e] / 6 - r / 6), 1);
    }
    EXPECT_TRUE(diagonal) << "row " << r;
  }
}

}  // namespace
}  // namespace moorsim::mooring_fem

namespace moorsim::mooring_fem {
namespace {

// The blocks a vessel needs to couple implicitly to a line, against central differences
// of the fairlead force and of node n-1's acceleration.
TEST(MooringJacobian, FairleadCouplingBlocksMatchFiniteDifferences) {
  Fixture f(12);
  const int line = 1;
  const FairleadCoupling J = f.mooring.FairleadJacobian(f.x.data(), f.fairleads, line);
  ASSERT_GE(J.node_state, 0);
  std::vector<Vec3> forces(f.mooring.num_lines());
  std::vector<double> xdot(f.mooring.StateSize());
  auto force = [&](const std::vector<double>& x, const std::vector<PointKinematics>& k) {
    f.mooring.FairleadForces(x.data(), k, forces);
    return forces[line];
  };
  auto accel = [&](const std::vector<double>& x, const std::vector<PointKinematics>& k) {
    f.mooring.Derivatives(x.data(), k, xdot.data());
    return Vec3(xdot[J.node_state + 3], xdot[J.node_state + 4], xdot[J.node_state + 5]);
  };
  Mat3 fd_force_node_pos, fd_force_node_vel, fd_force_pos, fd_force_vel, fd_accel_pos, fd_accel_vel;
  for (int m = 0; m < 3; ++m) {
    for (int kind = 0; kind < 2; ++kind) {  // 0: position, 1: velocity
      const double h = kind == 0 ? 1e-4 : 1e-5;
      std::vector<double> xp = f.x, xm = f.x;
      xp[J.node_state + 3 * kind + m] += h;
      xm[J.node_state + 3 * kind + m] -= h;
      const Vec3 d_node = (force(xp, f.fairleads) - force(xm, f.fairleads)) / (2 * h);
      std::vector<PointKinematics> kp = f.fairleads, km = f.fairleads;
      (kind == 0 ? kp[line].position : kp[line].velocity)(m) += h;
      (kind == 0 ? km[line].position : km[line].velocity)(m) -= h;
      const Vec3 d_fair_force = (force(f.x, kp) - force(f.x, km)) / (2 * h);
      const Vec3 d_fair_accel = (accel(f.x, kp) - accel(f.x, km)) / (2 * h);
      (kind == 0 ? fd_force_node_pos : fd_force_node_vel).col(m) = d_node;
      (kind == 0 ? fd_force_pos : fd_force_vel).col(m) = d_fair_force;
      (kind == 0 ? fd_accel_pos : fd_accel_vel).col(m) = d_fair_accel;
    }
  }
  auto expect_close = [](const Mat3& analytic, const Mat3& fd, const char* name) {
    EXPECT_LT((analytic - fd).norm(), 1e-5 * fd.norm() + 1e-9)
        << name << "\nanalytic\n"
        << analytic << "\nfinite difference\n"
        << fd;
  };
  expect_close(J.J_force_node_pos, fd_force_node_pos, "dF/dr_{n-1}");
  expect_close(J.J_force_node_vel, fd_force_node_vel, "dF/dv_{n-1}");
  expect_close(J.J_force_fairlead_pos, fd_force_pos, "dF/dr_n");
  expect_close(J.J_force_fairlead_vel, fd_force_vel, "dF/dv_n");
  expect_close(J.J_accel_fairlead_pos, fd_accel_pos, "da_{n-1}/dr_n");
  expect_close(J.J_accel_fairlead_vel, fd_accel_vel, "da_{n-1}/dv_n");
}

}  // namespace
}  // namespace moorsim::mooring_fem
