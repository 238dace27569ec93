#include "simulation/detection_models.h"

namespace moorsim::simulation {

DetectionModels MakeDetectionModels(const DetectionSetup& setup, const vessel::VesselModel& vessel,
                                    const Vec6& moored_pose) {
  DetectionModels m;
  m.bank = setup.bank;
  m.bank.moored_heave = moored_pose(2);
  const Mat6& M = vessel.mass();
  const Mat6& D = vessel.parameters().linear_damping;
  const int dof[3] = {0, 1, 5};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      m.model.mass(i, j) = M(dof[i], dof[j]);
      m.model.damping(i, j) = D(dof[i], dof[j]);
    }
  }
  m.ekf = setup.ekf;
  m.observer_bank = setup.observer_bank;
  return m;
}

}  // namespace moorsim::simulation
