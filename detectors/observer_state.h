// The state layout the hypothesis observers share (HypothesisEkf in
// detectors/ekf_observer.h, HypothesisPassiveObserver in detectors/passive_observer.h):
// x = [xi (6), eta (3), b (3), nu (3)], the wave-frequency motion, the pose, the
// Earth-frame bias and the body velocity.
#pragma once

#include <Eigen/Core>

namespace moorsim::detectors {

struct ObserverStateLayout {
  static constexpr int kStates = 15;
  static constexpr int kWave = 0;       ///< xi1 (3), xi2 (3)
  static constexpr int kPose = 6;       ///< eta = x, y [m] NED, psi [rad]
  static constexpr int kBias = 9;       ///< b [N, N, N m] Earth
  static constexpr int kVelocity = 12;  ///< nu = u, v [m/s], r [rad/s] body
  using State = Eigen::Matrix<double, kStates, 1>;
};

}  // namespace moorsim::detectors
