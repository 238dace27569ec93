// Rigid-body kinematics and kinetics of the vessel in Fossen's notation (Fossen 2011,
// "Handbook of Marine Craft Hydrodynamics and Motion Control", chapters 2-3):
// eta = [x y z phi theta psi] (NED position, zyx Euler angles), nu = [u v w p q r] (body
// velocities), eta' = J(eta) nu with J = diag(R(Theta), T(Theta)).
#pragma once

#include <Eigen/Core>

#include "core/types.h"

namespace moorsim::vessel {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// R(Theta) = Rz(psi) Ry(theta) Rx(phi): body-to-NED rotation (Fossen 2011 eq. 2.18).
Mat3 RotationBodyToNed(double phi, double theta, double psi);

/// dR/dphi, dR/dtheta and dR/dpsi of RotationBodyToNed, in that order.
void RotationDerivatives(double phi, double theta, double psi, Mat3 dR[3]);

/// T(Theta): body angular rates [p q r] to Euler angle rates (Fossen 2011 eq. 2.28).
/// Singular at theta = +-90 deg; throws moorsim::Error within 1e-6 rad of it.
Mat3 EulerRateTransform(double phi, double theta);

/// J(eta) = diag(R, T), eta' = J(eta) nu.
Mat6 KinematicTransform(const Vec6& eta);

/// S(a) b = a x b.
Mat3 Skew(const Vec3& a);

/// Mass properties about the body origin (midship, waterline, centreline): mass [kg],
/// centre of gravity r_g [m] (body frame, z down) and radii of gyration about axes
/// through the CG parallel to the body axes [m].
struct MassProperties {
  double mass = 0.0;
  Vec3 r_g = Vec3::Zero();
  Vec3 radii_of_gyration = Vec3::Zero();
};

/// Rigid-body mass matrix about the body origin (Fossen 2011 eq. 3.44), with the inertia
/// tensor about the CG diag(m r_i^2) moved to the origin by the parallel-axis terms.
Mat6 RigidBodyMass(const MassProperties& m);

/// Rigid-body Coriolis and centripetal matrix C_RB(nu) from M_RB (Fossen 2011 eq. 3.46,
/// the parametrisation independent of linear velocity, Theorem 3.2): nu^T C nu = 0.
Mat6 RigidBodyCoriolis(const Mat6& M_rb, const Vec6& nu);

}  // namespace moorsim::vessel
