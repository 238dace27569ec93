// The 6-DOF low-frequency vessel model: analytic Jacobian against finite differences, and
// free decay on CVODE against the generalised eigenvalues of (G, M).
#include "vessel/vessel_model.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "free_vessel.h"

namespace moorsim::vessel {
namespace {

// Seed-like FPSO numbers (docs/design.md section 9): mass, radii of gyration, CG 1 m below the
// waterline; added mass and restoring of the right size, with couplings so that the test
// is not trivially diagonal.
VesselParameters TestVessel(double damping_scale) {
  VesselParameters p;
  p.rigid_body_mass = RigidBodyMass({1.0041e8, Vec3(0.0, 0.0, 1.0), Vec3(16.3, 54.0, 54.0)});
  Vec6 a;
  a << 7.94e6, 6.44e7, 1.1e8, 4.0e9, 1.9e11, 1.45e11;
  p.added_mass = a.asDiagonal();
  p.added_mass(1, 3) = p.added_mass(3, 1) = -2.0e8;  // sway-roll
  p.added_mass(2, 4) = p.added_mass(4, 2) = 1.0e8;   // heave-pitch
  p.restoring(2, 2) = 8.363e7;
  p.restoring(3, 3) = 1025.0 * 9.81 * 97961.0 * 7.95;  // rho g V GM_T
  p.restoring(4, 4) = 2.6e11;
  p.restoring(2, 4) = p.restoring(4, 2) = -6.0e7;
  Vec6 d;
  d << 3.6e5, 1.6e6, 2.0e6, 1.0e8, 1.0e10, 6.0e9;
  p.linear_damping = damping_scale * Mat6(d.asDiagonal());
  p.quadratic_damping = damping_scale * Vec3(5e4, 5e5, 1e9);
  return p;
}

TEST(VesselModel, JacobianMatchesFiniteDifferences) {
  const VesselModel model(TestVessel(1.0));
  Vec6 eta, nu, tau;
  eta << 3.0, -2.0, 0.4, 0.05, -0.03, 0.7;
  nu << 0.6, -0.3, 0.1, 0.02, -0.01, 0.015;
  tau << 1e5, -2e5, 3e4, 1e6, -2e6, 5e6;
  const VesselModel::Jacobian J = model.Jacobians(eta, nu);
  Mat6 fd_ee, fd_en, fd_ne, fd_nn;
  for (int k = 0; k < 6; ++k) {
    const double h = 1e-6;
    Vec6 ep = eta, em = eta, np = nu, nm = nu, a, b, c, d;
    ep(k) += h;
    em(k) -= h;
    np(k) += h;
    nm(k) -= h;
    model.Derivatives(ep, nu, tau, &a, &b);
    model.Derivatives(em, nu, tau, &c, &d);
    fd_ee.col(k) = (a - c) / (2 * h);
    fd_ne.col(k) = (b - d) / (2 * h);
    model.Derivatives(eta, np, tau, &a, &b);
    model.Derivatives(eta, nm, tau, &c, &d);
    fd_en.col(k) = (a - c) / (2 * h);
    fd_nn.col(k) = (b - d) / (2 * h);
  }
  // Central differences with h = 1e-6 on smooth functions of size ~1: ~1e-10 truncation.
  EXPECT_LT((J.J_etadot_eta - fd_ee).norm(), 1e-7 * (1.0 + fd_ee.norm()));
  EXPECT_LT((J.J_etadot_nu - fd_en).norm(), 1e-7 * (1.0 + fd_en.norm()));
  EXPECT_LT((J.J_nudot_eta - fd_ne).norm(), 1e-7 * (1.0 + fd_ne.norm()));
  EXPECT_LT((J.J_nudot_nu - fd_nn).norm(), 1e-7 * (1.0 + fd_nn.norm()));
}

using testing::DecayPeriod;

TEST(VesselModel, FreeDecayPeriodsMatchTheGeneralisedEigenvalues) {
  const VesselModel model(TestVessel(0.0));  // undamped: periods are the natural ones
  const VesselParameters p = TestVessel(0.0);
  // Natural frequencies: G v = w^2 M v restricted to heave, roll, pitch (and what they
  // couple to through M); surge, sway and yaw have no restoring and drop out.
  Eigen::GeneralizedSelfAdjointEigenSolver<Mat6> eig(p.restoring, model.mass());
  std::vector<double> periods;
  for (int i = 0; i < 6; ++i) {
    if (eig.eigenvalues()(i) > 1e-9)
      periods.push_back(2 * std::numbers::pi / std::sqrt(eig.eigenvalues()(i)));
  }
  ASSERT_EQ(periods.size(), 3u);
  // Start each mode from its own eigenvector so one period is excited at a time, and
  // compare the simulated period with the eigenvalue's (0.3 %: zero-crossing timing on a
  // 0.02 s grid over ~10 periods, small-angle nonlinearity of J(eta)).
  for (int i = 0; i < 6; ++i) {
    const double w2 = eig.eigenvalues()(i);
    if (w2 <= 1e-9) continue;
    Vec6 v = eig.eigenvectors().col(i);
    int dominant;
    v.cwiseAbs().maxCoeff(&dominant);
    // Small amplitudes (heave <= 0.1 m, angles <= 0.005 rad): the model is linear there;
    // larger pitch with surge drift brings in the -theta u term of J(eta).
    const double scale = std::min(0.1 / std::max(std::abs(v(2)), 1e-30),
                                  0.005 / std::max(v.tail<3>().cwiseAbs().maxCoeff(), 1e-30));
    const double expected = 2 * std::numbers::pi / std::sqrt(w2);
    double drift = 0.0;
    const double period = DecayPeriod(model, scale * v, dominant, 12 * expected, &drift);
    EXPECT_NEAR(period, expected, 3e-3 * expected) << "mode " << i << " (DOF " << dominant << ")";
    // Without damping or loads the energy stays (small angles: J(eta) ~ I).
    EXPECT_LT(drift, 1e-3) << "mode " << i;
  }
}

TEST(VesselModel, DampingTakesEnergyOut) {
  const VesselModel model(TestVessel(1.0));
  Vec6 eta0 = Vec6::Zero();
  eta0(2) = 1.0;
  double ratio = 0.0;
  DecayPeriod(model, eta0, 2, 60.0, &ratio);
  Vec6 eta_dot, nu_dot;
  // Energy after 60 s is well below the start (ratio here is |E1 - E0| / E0).
  EXPECT_GT(ratio, 0.1);
  model.Derivatives(eta0, Vec6::Zero(), Vec6::Zero(), &eta_dot, &nu_dot);
  EXPECT_LT(nu_dot(2), 0.0);  // sunk 1 m (z down): buoyancy pushes up (-z)
}

}  // namespace
}  // namespace moorsim::vessel
