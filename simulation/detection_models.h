// The detectors' models of a scenario, as the simulation builds them (docs/design.md section 6):
// the hypothesis bank's options, the observers' horizontal-plane vessel model, their EKF
// options and how the observer bank couples them. One place, so `moorsim run` and
// `moorsim analyze` see the same models.
#pragma once

#include "core/types.h"
#include "detectors/ekf_observer.h"
#include "detectors/hypothesis_bank.h"
#include "scenarios/scenario.h"
#include "vessel/vessel_model.h"

namespace moorsim::simulation {

struct DetectionModels {
  /// Pairs from detection.pairs, the moored heave of the static start, the reference
  /// pose eta_ref = the controller's setpoint (default: the vessel's initial pose), and a
  /// turret on its bearing (vessel.turret free or friction) held at the initial heading.
  detectors::HypothesisBankOptions bank;
  /// The vessel's own mass (with A(0)) and linear damping in surge, sway and yaw.
  detectors::LowFrequencyModel model;
  /// The library's defaults with R = detection.measurement_variance per DOF and the fields
  /// detection.model sets.
  detectors::EkfOptions ekf;
  /// detection.switch_rate, or the library's default.
  detectors::ObserverBankOptions observer_bank;
};

/// `vessel` is the plant's model and `moored_pose` its static start (Simulation::
/// initial_pose(): heave, roll, pitch at the moored equilibrium). Throws
/// moorsim::InputError if the scenario has no vessel section.
DetectionModels MakeDetectionModels(const scenarios::Scenario& scenario,
                                    const vessel::VesselModel& vessel, const Vec6& moored_pose);

}  // namespace moorsim::simulation
