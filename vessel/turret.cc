#include "vessel/turret.h"

#include <cmath>

#include "core/error.h"

namespace moorsim::vessel {

namespace {

// |F| smoothed at zero over 1 N (out of MN), so that the friction moment is differentiable
// where the net horizontal force passes through zero.
constexpr double kForceSmoothing = 1.0;

}  // namespace

double BearingMoment(const TurretParameters& turret, double rate, const Vec3& F, double* d_rate,
                     Vec3* d_force) {
  if (d_rate != nullptr) *d_rate = 0.0;
  if (d_force != nullptr) d_force->setZero();
  if (turret.bearing == TurretBearing::kLocked) return 0.0;
  double moment = turret.damping * rate;
  if (d_rate != nullptr) *d_rate = turret.damping;
  if (turret.bearing == TurretBearing::kFriction) {
    const double eps2 = kForceSmoothing * kForceSmoothing;
    const double vertical = std::sqrt(F.z() * F.z() + eps2);
    const double horizontal = std::sqrt(F.x() * F.x() + F.y() * F.y() + eps2);
    const double arm = turret.friction_coefficient * turret.bearing_radius;
    const double slip = std::tanh(rate / turret.slip_rate);
    moment += arm * (vertical + horizontal) * slip;
    if (d_rate != nullptr) {
      *d_rate += arm * (vertical + horizontal) * (1.0 - slip * slip) / turret.slip_rate;
    }
    if (d_force != nullptr) {
      *d_force = arm * slip * Vec3(F.x() / horizontal, F.y() / horizontal, F.z() / vertical);
    }
  }
  return moment;
}

double MomentAboutTurret(const TurretParameters& turret, const Vec6& tau) {
  return tau(5) - (turret.x * tau(1) - turret.y * tau(0));
}

}  // namespace moorsim::vessel
