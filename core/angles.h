// Angle constants and wrapping, shared by the plant, the sensors and the observers.
#pragma once

#include <cmath>
#include <numbers>

namespace moorsim {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
inline constexpr double kDegree = std::numbers::pi / 180.0;  ///< one degree in radians

/// Maps an angle [rad] to (-pi, pi].
inline double WrapAngle(double angle) {
  double wrapped = std::remainder(angle, kTwoPi);
  if (wrapped <= -kPi) wrapped += kTwoPi;
  return wrapped;
}

}  // namespace moorsim
