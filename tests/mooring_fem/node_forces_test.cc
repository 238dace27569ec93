// Forces on a single node against hand-computed Morison drag, current, weight and added
// mass: a straight, unstretched, horizontal chain in mid-water, so tension and seabed play
// no part and every term has a closed form.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <numbers>

#include "core/angles.h"
#include "mooring_fem/mooring_system.h"

namespace moorsim::mooring_fem {
namespace {

// The structured solve of a node's mass matrix against the inverse of the matrix it stands
// for: no, one or two half segments, with and without added mass, segments in line, at a
// right angle and folded back on each other.
TEST(NodeMass, SolveEqualsTheInverseOfTheMatrix) {
  const Vec3 F(3.0e4, -1.2e4, 7.5e4);
  const Vec3 dirs[] = {Vec3(1, 0, 0),  Vec3(0, 0, 1),        Vec3(0.6, 0.0, 0.8),
                       Vec3(-1, 0, 0), Vec3(0.6, 0.0, -0.8), Vec3(0, 1, 0)};
  int cases = 0;
  // Tangential added mass too: none, less than the normal, more than it.
  for (double added : {0.0, 400.0, 2.0e5}) {
    for (double tangential : {0.0, 0.3, 2.5}) {
      for (int segments = 0; segments <= 2; ++segments) {
        for (const Vec3& t0 : dirs) {
          for (const Vec3& t1 : dirs) {
            NodeMass mass;
            mass.m = 12375.0;
            if (segments >= 1) mass.Add(added, t0, tangential * added);
            if (segments == 2) mass.Add(0.5 * added, t1, 0.5 * tangential * added);
            const Vec3 reference = mass.Matrix().inverse() * F;
            EXPECT_LT((mass.Solve(F) - reference).norm(), 1e-13 * reference.norm())
                << "added " << added << " tangential " << tangential << " segments " << segments;
            ++cases;
          }
        }
      }
    }
  }
  EXPECT_EQ(cases, 3 * 3 * 3 * 36);
}

constexpr double kRho = 1025.0, kG = 9.81, kD = 0.08, kMass = 275.0;
constexpr double kCdn = 0.3, kCdt = 1.0, kCmn = 1.5;
constexpr int kSegments = 4;
constexpr double kLength = 400.0, kL0 = kLength / kSegments;

MooringParameters StraightChain(double current_speed, double current_direction) {
  MooringParameters spec;
  spec.water = {kRho, kG, 1000.0};
  if (current_speed > 0.0) {
    spec.current.direction = current_direction;
    spec.current.depth = {0.0};
    spec.current.speed = {current_speed};
  }
  LineType type;
  type.name = "chain";
  type.diameter = kD;
  type.mass_per_length = kMass;
  type.axial_stiffness = 1e9;
  type.axial_damping = 1e6;  // acts on strain rate only: zero here
  type.drag_normal = kCdn;
  type.drag_tangential = kCdt;
  type.added_mass_normal = kCmn;
  spec.line_types.push_back(type);
  // Anchor mid-water: no seabed contact.
  spec.lines.push_back(LineParameters::Uniform(1, "chain", kLength, kSegments,
                                               Vec3(0.0, 0.0, 500.0), Vec3(kLength, 0.0, 500.0)));
  return spec;
}

// Acceleration of interior node 2 for the chain straight along x, every node moving at
// `velocity`, in a current.
Vec3 NodeAcceleration(const Vec3& velocity, double current_speed, double current_direction) {
  const MooringParameters spec = StraightChain(current_speed, current_direction);
  MooringSystem mooring(spec);
  std::vector<PointKinematics> fairleads(1);
  fairleads[0].position = Vec3(kLength, 0.0, 500.0);
  fairleads[0].velocity = velocity;
  std::vector<double> x(mooring.StateSize()), xdot(mooring.StateSize());
  for (int k = 1; k < kSegments; ++k) {
    double* node = x.data() + 6 * (k - 1);
    node[0] = k * kL0;
    node[1] = 0.0;
    node[2] = 500.0;
    node[3] = velocity.x();
    node[4] = velocity.y();
    node[5] = velocity.z();
  }
  mooring.Derivatives(x.data(), fairleads, xdot.data());
  const double* a = xdot.data() + 6 * (2 - 1) + 3;
  return Vec3(a[0], a[1], a[2]);
}

// The same from the formulas of Ren & Skjetne 2016, eq. 7, written out for a node with two
// collinear half segments along x (total length l0).
Vec3 ExpectedAcceleration(const Vec3& velocity, const Vec3& current) {
  const double area = kPi * kD * kD / 4.0;
  const Vec3 u = velocity - current;
  const Vec3 t = Vec3::UnitX();
  const Vec3 u_t = u.dot(t) * t;
  const Vec3 u_n = u - u_t;
  Vec3 force = Vec3(0.0, 0.0, (kMass - kRho * area) * kG * kL0);  // submerged weight, +z down
  force += -0.5 * kRho * kCdn * kD * kL0 * u_n.norm() * u_n;      // normal drag
  force += -0.5 * kRho * kCdt * kD * kL0 * u_t.norm() * u_t;      // tangential drag
  Mat3 mass = kMass * kL0 * Mat3::Identity();
  mass += kCmn * kRho * area * kL0 * (Mat3::Identity() - t * t.transpose());  // normal added mass
  return mass.inverse() * force;
}

TEST(NodeForces, StillWaterWeightAndAddedMass) {
  const Vec3 a = NodeAcceleration(Vec3::Zero(), 0.0, 0.0);
  const Vec3 expected = ExpectedAcceleration(Vec3::Zero(), Vec3::Zero());
  EXPECT_NEAR((a - expected).norm(), 0.0, 1e-12);
  // Sinking is slowed by the added mass of the water around the chain: below g (1 - rho/rho_c).
  EXPECT_GT(a.z(), 0.0);
  EXPECT_LT(a.z(), kG);
}

TEST(NodeForces, NormalAndTangentialDragAndCurrent) {
  const double east = kPi / 2.0;
  struct Case {
    Vec3 velocity;
    double current_speed;
  };
  for (const Case& c :
       {Case{{0.0, 0.7, 0.0}, 0.0}, Case{{0.9, 0.0, 0.0}, 0.0}, Case{{0.3, -0.4, 0.2}, 0.0},
        Case{{0.0, 0.0, 0.0}, 1.2}, Case{{0.5, 0.5, -0.1}, 0.8}}) {
    const Vec3 current = c.current_speed * Vec3(std::cos(east), std::sin(east), 0.0);
    const Vec3 a = NodeAcceleration(c.velocity, c.current_speed, east);
    const Vec3 expected = ExpectedAcceleration(c.velocity, current);
    EXPECT_NEAR((a - expected).norm(), 0.0, 1e-12 * (1.0 + expected.norm()))
        << "velocity " << c.velocity.transpose() << " current " << c.current_speed;
  }
  // A node at rest in a current toward the east is pushed east.
  EXPECT_GT(NodeAcceleration(Vec3::Zero(), 1.0, east).y(), 0.0);
}

}  // namespace
}  // namespace moorsim::mooring_fem
