#include "vessel/rigid_body.h"

#include <cmath>

#include "core/error.h"

namespace moorsim::vessel {

Mat3 RotationBodyToNed(double phi, double theta, double psi) {
  const double cf = std::cos(phi), sf = std::sin(phi);
  const double ct = std::cos(theta), st = std::sin(theta);
  const double cp = std::cos(psi), sp = std::sin(psi);
  Mat3 R;
  R << cp * ct, -sp * cf + cp * st * sf, sp * sf + cp * cf * st,  //
      sp * ct, cp * cf + sf * st * sp, -cp * sf + st * sp * cf,   //
      -st, ct * sf, ct * cf;
  return R;
}

void RotationDerivatives(double phi, double theta, double psi, Mat3 dR[3]) {
  const double cf = std::cos(phi), sf = std::sin(phi);
  const double ct = std::cos(theta), st = std::sin(theta);
  const double cp = std::cos(psi), sp = std::sin(psi);
  Mat3 Rx, Ry, Rz, dRx, dRy, dRz;
  Rx << 1, 0, 0, 0, cf, -sf, 0, sf, cf;
  Ry << ct, 0, st, 0, 1, 0, -st, 0, ct;
  Rz << cp, -sp, 0, sp, cp, 0, 0, 0, 1;
  dRx << 0, 0, 0, 0, -sf, -cf, 0, cf, -sf;
  dRy << -st, 0, ct, 0, 0, 0, -ct, 0, -st;
  dRz << -sp, -cp, 0, cp, -sp, 0, 0, 0, 0;
  dR[0] = Rz * Ry * dRx;
  dR[1] = Rz * dRy * Rx;
  dR[2] = dRz * Ry * Rx;
}

Mat3 EulerRateTransform(double phi, double theta) {
  const double ct = std::cos(theta);
  if (std::abs(ct) < 1e-6) {
    throw Error("Euler angle rates are singular at pitch theta = " + std::to_string(theta) +
                " rad (+-90 deg)");
  }
  const double cf = std::cos(phi), sf = std::sin(phi), tt = std::tan(theta);
  Mat3 T;
  T << 1.0, sf * tt, cf * tt,  //
      0.0, cf, -sf,            //
      0.0, sf / ct, cf / ct;
  return T;
}

Mat6 KinematicTransform(const Vec6& eta) {
  Mat6 J = Mat6::Zero();
  J.block<3, 3>(0, 0) = RotationBodyToNed(eta(3), eta(4), eta(5));
  J.block<3, 3>(3, 3) = EulerRateTransform(eta(3), eta(4));
  return J;
}

Mat3 Skew(const Vec3& a) {
  Mat3 S;
  S << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return S;
}

Mat6 RigidBodyMass(const MassProperties& m) {
  if (!(m.mass > 0.0))
    throw InputError("vessel mass " + std::to_string(m.mass) + " kg must be > 0");
  const Vec3 k = m.radii_of_gyration;
  const Mat3 I_g = m.mass * k.cwiseProduct(k).asDiagonal();
  const Mat3 S = Skew(m.r_g);
  Mat6 M;
  M.block<3, 3>(0, 0) = m.mass * Mat3::Identity();
  M.block<3, 3>(0, 3) = -m.mass * S;
  M.block<3, 3>(3, 0) = m.mass * S;
  M.block<3, 3>(3, 3) = I_g - m.mass * S * S;  // parallel-axis theorem
  return M;
}

Mat6 RigidBodyCoriolis(const Mat6& M, const Vec6& nu) {
  const Vec3 nu1 = nu.head<3>(), nu2 = nu.tail<3>();
  const Vec3 a = M.block<3, 3>(0, 0) * nu1 + M.block<3, 3>(0, 3) * nu2;
  const Vec3 b = M.block<3, 3>(3, 0) * nu1 + M.block<3, 3>(3, 3) * nu2;
  Mat6 C = Mat6::Zero();
  C.block<3, 3>(0, 3) = -Skew(a);
  C.block<3, 3>(3, 0) = -Skew(a);
  C.block<3, 3>(3, 3) = -Skew(b);
  return C;
}

}  // namespace moorsim::vessel
