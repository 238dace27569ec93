// The detectors' models of a plant, as the simulation builds them (docs/design.md section 6):
// the hypothesis bank's options, the observers' horizontal-plane vessel model, their EKF
// options and how the observer bank couples them. One place, so `moorsim run` and
// `moorsim analyze` see the same models.
#pragma once

#include "core/types.h"
#include "detectors/ekf_observer.h"
#include "detectors/hypothesis_bank.h"
#include "simulation/plant_model.h"
#include "vessel/vessel_model.h"

namespace moorsim::simulation {

struct DetectionModels {
  /// The set-up's bank options (pairs, reference pose, turret) with the moored heave of
  /// the static start.
  detectors::HypothesisBankOptions bank;
  /// The vessel's own mass (with A(0)) and linear damping in surge, sway and yaw.
  detectors::LowFrequencyModel model;
  /// The set-up's observer model.
  detectors::EkfOptions ekf;
  detectors::ObserverBankOptions observer_bank;
};

/// `vessel` is the plant's model and `moored_pose` its static start (Simulation::
/// initial_pose(): heave, roll, pitch at the moored equilibrium).
DetectionModels MakeDetectionModels(const DetectionSetup& setup, const vessel::VesselModel& vessel,
                                    const Vec6& moored_pose);

}  // namespace moorsim::simulation
