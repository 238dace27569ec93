#include "vessel/fpso_model.h"

#include <cmath>

namespace moorsim::vessel {

MassProperties SeedFpsoMass() {
  return {1025.0 * 97961.0, Vec3(0.0, 0.0, 1.0), Vec3(16.3, 54.0, 54.0)};
}

VesselParameters LowFrequencyVessel(const HydroData& hydro, const MassProperties& mass,
                                    const LowFrequencyDamping& d) {
  VesselParameters p;
  p.rigid_body_mass = RigidBodyMass(mass);
  p.added_mass = hydro.added_mass_zero_frequency;
  p.restoring = hydro.restoring;
  const Mat6 M = p.rigid_body_mass + p.added_mass;
  p.linear_damping.setZero();
  p.linear_damping(0, 0) = M(0, 0) / d.surge_time;
  p.linear_damping(1, 1) = M(1, 1) / d.sway_time;
  p.linear_damping(5, 5) = M(5, 5) / d.yaw_time;
  const double ratio[3] = {d.heave_ratio, d.roll_ratio, d.pitch_ratio};
  for (int i = 2; i <= 4; ++i) {
    p.linear_damping(i, i) = 2.0 * ratio[i - 2] * std::sqrt(M(i, i) * hydro.restoring(i, i));
  }
  return p;
}

}  // namespace moorsim::vessel
