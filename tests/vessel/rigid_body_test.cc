// Fossen's rigid-body kinematics and kinetics checked against their defining properties.
#include "vessel/rigid_body.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "core/error.h"

namespace moorsim::vessel {
namespace {

Mat3 Rx(double a) { return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(); }
Mat3 Ry(double a) { return Eigen::AngleAxisd(a, Vec3::UnitY()).toRotationMatrix(); }
Mat3 Rz(double a) { return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix(); }

TEST(RigidBody, RotationIsZyxAndOrthonormal) {
  const double phi = 0.1, theta = -0.2, psi = 2.3;
  const Mat3 R = RotationBodyToNed(phi, theta, psi);
  EXPECT_LT((R - Rz(psi) * Ry(theta) * Rx(phi)).norm(), 1e-14);
  EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-14);
  EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
  // Heading 90 deg: the bow (body x) points east (NED y).
  EXPECT_LT((RotationBodyToNed(0, 0, std::numbers::pi / 2) * Vec3::UnitX() - Vec3::UnitY()).norm(),
            1e-15);
}

TEST(RigidBody, EulerRatesReproduceTheRotationRate) {
  // d/dt R(Theta(t)) = R S(omega_body) with Theta' = T(Theta) omega_body (Fossen eq. 2.33).
  const Vec3 angles(0.2, -0.3, 1.1), omega(0.05, -0.02, 0.03);
  const Vec3 rates = EulerRateTransform(angles.x(), angles.y()) * omega;
  const double h = 1e-6;
  const Vec3 ap = angles + h * rates, am = angles - h * rates;
  const Mat3 dR =
      (RotationBodyToNed(ap.x(), ap.y(), ap.z()) - RotationBodyToNed(am.x(), am.y(), am.z())) /
      (2 * h);
  const Mat3 expected = RotationBodyToNed(angles.x(), angles.y(), angles.z()) * Skew(omega);
  EXPECT_LT((dR - expected).norm(), 1e-9);  // central difference, h^2 = 1e-12
  EXPECT_THROW(EulerRateTransform(0.0, std::numbers::pi / 2), Error);
}

MassProperties SeedFpso() {
  // Seed case (docs/design.md section 9): 1.0041e8 kg, radii of gyration 16.3 / 54 / 54 m,
  // CG 1 m below the waterline (z = +1 in the body frame, z down), on the centreline.
  return {1.0041e8, Vec3(0.0, 0.0, 1.0), Vec3(16.3, 54.0, 54.0)};
}

TEST(RigidBody, MassMatrixIsSymmetricPositiveDefiniteWithParallelAxisTerms) {
  const MassProperties m = SeedFpso();
  const Mat6 M = RigidBodyMass(m);
  EXPECT_LT((M - M.transpose()).norm(), 1e-6 * M.norm());
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Mat6>(M).eigenvalues().minCoeff(), 0.0);
  // Roll inertia about the waterline: m (k_x^2 + z_g^2).
  EXPECT_NEAR(M(3, 3), m.mass * (16.3 * 16.3 + 1.0), 1e-6 * M(3, 3));
  // Surge-pitch coupling m z_g (Fossen eq. 3.44: M(0, 4) = m z_g).
  EXPECT_NEAR(M(0, 4), m.mass * 1.0, 1e-6 * m.mass);
  EXPECT_NEAR(M(1, 3), -m.mass * 1.0, 1e-6 * m.mass);
  EXPECT_THROW(RigidBodyMass({0.0, Vec3::Zero(), Vec3::Ones()}), InputError);
}

TEST(RigidBody, CoriolisDoesNoWorkAndIsSkewSymmetric) {
  const Mat6 M = RigidBodyMass(SeedFpso());
  const Vec6 nu = (Vec6() << 1.2, -0.4, 0.1, 0.01, -0.02, 0.03).finished();
  const Mat6 C = RigidBodyCoriolis(M, nu);
  EXPECT_LT((C + C.transpose()).norm(), 1e-9 * C.norm());
  EXPECT_NEAR(nu.dot(C * nu), 0.0, 1e-9 * (M * nu).norm() * nu.norm());
  // Pure yaw rate with surge: the centripetal sway force -m u r (Fossen eq. 3.46).
  Vec6 turn = Vec6::Zero();
  turn(0) = 2.0;
  turn(5) = 0.01;
  EXPECT_NEAR((RigidBodyCoriolis(M, turn) * turn)(1), 1.0041e8 * 2.0 * 0.01, 1.0);
}

}  // namespace
}  // namespace moorsim::vessel
