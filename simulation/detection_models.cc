#include "simulation/detection_models.h"

#include "core/error.h"

namespace moorsim::simulation {

DetectionModels MakeDetectionModels(const scenarios::Scenario& scenario,
                                    const vessel::VesselModel& vessel, const Vec6& moored_pose) {
  if (!scenario.vessel) {
    throw InputError(scenario.source_path +
                     ": vessel: the section is missing; the detectors' models need the vessel");
  }
  DetectionModels m;
  const scenarios::DetectionSpec& d = scenario.detection;
  m.bank.include_pairs = d.pairs;
  m.bank.moored_heave = moored_pose(2);
  m.bank.reference_pose = scenario.controller.setpoint.value_or(scenario.vessel->initial_pose);
  // A turret on its bearing keeps the absolute heading it starts at (the lines hold it):
  // its initial heading, by default the vessel's (angle 0 to the hull).
  const scenarios::TurretSpec& turret = scenario.vessel->turret;
  if (turret.bearing != "locked") {
    m.bank.turret =
        detectors::TurretModel{Eigen::Vector2d(turret.x, turret.y),
                               turret.initial_heading.value_or(scenario.vessel->initial_pose.z())};
  }
  const Mat6& M = vessel.mass();
  const Mat6& D = vessel.parameters().linear_damping;
  const int dof[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      m.model.mass(i, j) = M(dof[i], dof[j]);
      m.model.damping(i, j) = D(dof[i], dof[j]);
    }
  }
  detectors::EkfOptions& ekf = m.ekf;
  ekf.measurement_variance = Vec3::Constant(d.measurement_variance);
  ekf.wave_motion_std = d.model.wave_motion_std.value_or(ekf.wave_motion_std);
  ekf.bias_std = d.model.bias_std.value_or(ekf.bias_std);
  ekf.bias_time_constant = d.model.bias_time_constant.value_or(ekf.bias_time_constant);
  ekf.force_noise = d.model.force_noise.value_or(ekf.force_noise);
  ekf.mooring_damping_ratio = d.model.mooring_damping_ratio.value_or(ekf.mooring_damping_ratio);
  m.observer_bank.switch_rate = d.switch_rate.value_or(m.observer_bank.switch_rate);
  return m;
}

}  // namespace moorsim::simulation
