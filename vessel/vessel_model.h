// The 6-DOF low-frequency vessel model in Fossen's matrix-vector form (Fossen 2011 eq. 6.1
// and section 7.1, low-speed manoeuvring model):
//   eta' = J(eta) nu
//   (M_RB + A(0)) nu' + C(nu) nu + D nu + d_q(nu) + G eta = tau
// with C the Coriolis-centripetal matrix of the total mass (rigid body and zero-frequency
// added mass, Theorem 3.2 parametrisation), D linear damping, d_q quadratic damping in
// surge, sway and yaw (d_i |nu_i| nu_i), and G the linear hydrostatic restoring acting on
// heave, roll and pitch (z, phi, theta). tau holds every external load in the body frame
// (moorings, thrusters, environment). The Jacobian is analytic.
#pragma once

#include "vessel/rigid_body.h"

namespace moorsim::vessel {

struct VesselParameters {
  Mat6 rigid_body_mass = Mat6::Zero();    ///< M_RB about the body origin
  Mat6 added_mass = Mat6::Zero();         ///< A(0), body frame
  Mat6 linear_damping = Mat6::Zero();     ///< D [N s/m, N m s/rad]
  Vec3 quadratic_damping = Vec3::Zero();  ///< surge, sway, yaw [N s^2/m^2, N m s^2/rad^2]
  Mat6 restoring = Mat6::Zero();          ///< G: nonzero in rows/columns 3-5 (z, phi, theta)
};

class VesselModel {
 public:
  explicit VesselModel(const VesselParameters& p);

  /// eta' and nu' for the state (eta, nu) under the body-frame load tau.
  void Derivatives(const Vec6& eta, const Vec6& nu, const Vec6& tau, Vec6* eta_dot,
                   Vec6* nu_dot) const;

  /// The 12x12 Jacobian blocks d(eta', nu')/d(eta, nu), tau held fixed; and
  /// d nu'/d tau = M^-1 (for the loads' own dependence on the state).
  struct Jacobian {
    Mat6 J_etadot_eta, J_etadot_nu, J_nudot_eta, J_nudot_nu;
  };
  Jacobian Jacobians(const Vec6& eta, const Vec6& nu) const;
  const Mat6& inverse_mass() const { return M_inv_; }
  const Mat6& mass() const { return M_; }
  const VesselParameters& parameters() const { return p_; }

  /// Kinetic plus hydrostatic potential energy [J] (conserved without damping or loads).
  double Energy(const Vec6& eta, const Vec6& nu) const;

 private:
  VesselParameters p_;
  Mat6 M_;
  Mat6 M_inv_;
};

}  // namespace moorsim::vessel
