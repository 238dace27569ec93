#include "vessel/vessel_model.h"

#include <Eigen/Dense>
#include <cmath>

#include "core/error.h"

namespace moorsim::vessel {

namespace {

// Partial derivatives of R(Theta) = Rz(psi) Ry(theta) Rx(phi) with respect to phi, theta
// and psi: d/da Ri(a) = Ri(a) S(e_i).
void RotationPartials(double phi, double theta, double psi, Mat3* dphi, Mat3* dtheta, Mat3* dpsi) {
  const Mat3 Rx = RotationBodyToNed(phi, 0.0, 0.0);
  const Mat3 Ry = RotationBodyToNed(0.0, theta, 0.0);
  const Mat3 Rz = RotationBodyToNed(0.0, 0.0, psi);
  *dphi = Rz * Ry * Rx * Skew(Vec3::UnitX());
  *dtheta = Rz * Ry * Skew(Vec3::UnitY()) * Rx;
  *dpsi = Rz * Skew(Vec3::UnitZ()) * Ry * Rx;
}

// d(C(nu) nu)/d nu for the Theorem 3.2 parametrisation: with a = M11 nu1 + M12 nu2 and
// b = M21 nu1 + M22 nu2, C(nu) nu = [nu2 x a ; nu1 x a + nu2 x b].
Mat6 CoriolisJacobian(const Mat6& M, const Vec6& nu) {
  const Vec3 n1 = nu.head<3>(), n2 = nu.tail<3>();
  const Mat3 M11 = M.block<3, 3>(0, 0), M12 = M.block<3, 3>(0, 3);
  const Mat3 M21 = M.block<3, 3>(3, 0), M22 = M.block<3, 3>(3, 3);
  const Vec3 a = M11 * n1 + M12 * n2;
  const Vec3 b = M21 * n1 + M22 * n2;
  Mat6 J;
  J.block<3, 3>(0, 0) = Skew(n2) * M11;
  J.block<3, 3>(0, 3) = -Skew(a) + Skew(n2) * M12;
  J.block<3, 3>(3, 0) = -Skew(a) + Skew(n1) * M11 + Skew(n2) * M21;
  J.block<3, 3>(3, 3) = Skew(n1) * M12 - Skew(b) + Skew(n2) * M22;
  return J;
}

constexpr int kQuadratic[3] = {0, 1, 5};  // surge, sway, yaw

}  // namespace

VesselModel::VesselModel(const VesselParameters& p) : p_(p) {
  M_ = p.rigid_body_mass + p.added_mass;
  // The low-frequency model uses the symmetric part (A(0) from a BEM code is symmetric to
  // its accuracy; Theorem 3.2 needs M = M^T > 0).
  M_ = 0.5 * (M_ + M_.transpose()).eval();
  Eigen::LLT<Mat6> llt(M_);
  if (llt.info() != Eigen::Success) {
    throw InputError("vessel: M_RB + A(0) is not positive definite");
  }
  M_inv_ = llt.solve(Mat6::Identity());
}

void VesselModel::Derivatives(const Vec6& eta, const Vec6& nu, const Vec6& tau, Vec6* eta_dot,
                              Vec6* nu_dot) const {
  *eta_dot = KinematicTransform(eta) * nu;
  Vec6 load = tau - RigidBodyCoriolis(M_, nu) * nu - p_.linear_damping * nu - p_.restoring * eta;
  for (int i : kQuadratic) {
    load(i) -= p_.quadratic_damping(i == 5 ? 2 : i) * std::abs(nu(i)) * nu(i);
  }
  *nu_dot = M_inv_ * load;
}

VesselModel::Jacobian VesselModel::Jacobians(const Vec6& eta, const Vec6& nu) const {
  Jacobian j;
  const double phi = eta(3), theta = eta(4), psi = eta(5);
  j.J_etadot_nu = KinematicTransform(eta);
  j.J_etadot_eta.setZero();
  Mat3 dR[3];
  RotationPartials(phi, theta, psi, &dR[0], &dR[1], &dR[2]);
  for (int k = 0; k < 3; ++k) j.J_etadot_eta.block<3, 1>(0, 3 + k) = dR[k] * nu.head<3>();
  const double cf = std::cos(phi), sf = std::sin(phi);
  const double ct = std::cos(theta), st = std::sin(theta), tt = std::tan(theta);
  Mat3 dT_dphi, dT_dtheta;
  dT_dphi << 0.0, cf * tt, -sf * tt,  //
      0.0, -sf, -cf,                  //
      0.0, cf / ct, -sf / ct;
  dT_dtheta << 0.0, sf / (ct * ct), cf / (ct * ct),  //
      0.0, 0.0, 0.0,                                 //
      0.0, sf * st / (ct * ct), cf * st / (ct * ct);
  j.J_etadot_eta.block<3, 1>(3, 3) = dT_dphi * nu.tail<3>();
  j.J_etadot_eta.block<3, 1>(3, 4) = dT_dtheta * nu.tail<3>();

  Mat6 dload_dnu = -CoriolisJacobian(M_, nu) - p_.linear_damping;
  for (int i : kQuadratic) {
    dload_dnu(i, i) -= 2.0 * p_.quadratic_damping(i == 5 ? 2 : i) * std::abs(nu(i));
  }
  j.J_nudot_nu = M_inv_ * dload_dnu;
  j.J_nudot_eta = -M_inv_ * p_.restoring;
  return j;
}

double VesselModel::Energy(const Vec6& eta, const Vec6& nu) const {
  return 0.5 * nu.dot(M_ * nu) + 0.5 * eta.dot(p_.restoring * eta);
}

}  // namespace moorsim::vessel
