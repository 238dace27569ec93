// Shared small types and physical constants. SI units throughout; Earth frame is NED
// (x north, y east, z down) with the origin on the mean free surface.
#pragma once

#include <Eigen/Core>
#include <limits>

namespace moorsim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Quiet NaN: the value of a quantity that is not defined (yet), e.g. a delay with no alarm.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Rigid-body kinematics of one attachment point in the Earth frame: position [m],
/// velocity [m/s] and acceleration [m/s^2]. This is what the mooring takes in from
/// whatever moves the fairlead (a prescribed motion now, the vessel later).
struct PointKinematics {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero();
};

}  // namespace moorsim
