// The state layout of the horizontal-plane observers (PassiveNonlinearObserver in
// core/passive_observer.h, which the controller and the detection observers run, and
// HypothesisEkf in detectors/ekf_observer.h): x = [xi (6), eta (3), b (3), nu (3)], the
// wave-frequency motion, the pose, the Earth-frame bias and the body velocity; and the yaw
// rotation R(psi) they turn forces and velocities with.
#pragma once

#include <Eigen/Core>

#include "core/types.h"

namespace moorsim {

struct ObserverStateLayout {
  static constexpr int kStates = 15;
  static constexpr int kWave = 0;       ///< xi1 (3), xi2 (3)
  static constexpr int kPose = 6;       ///< eta = x, y [m] NED, psi [rad]
  static constexpr int kBias = 9;       ///< b [N, N, N m] Earth
  static constexpr int kVelocity = 12;  ///< nu = u, v [m/s], r [rad/s] body
  using State = Eigen::Matrix<double, kStates, 1>;
};

/// Yaw rotation R(psi) of a [force, force, moment] vector (the moment is unchanged), from
/// c = cos psi and s = sin psi.
inline Mat3 YawRotation(double c, double s) {
  Mat3 r;
  r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

}  // namespace moorsim
