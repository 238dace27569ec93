// The coupled plant as typed parameters: everything a Simulation is built from, in the
// physics modules' own types (mooring_fem, vessel, detectors) and without YAML. A program
// fills one in code; the scenario loader is one way to make one
// (scenarios::ToPlantModel()). Every value is SI, NED, radians; line indices are 0-based
// here, as in the modules (the scenario's 1-based numbers are converted on the way in).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/types.h"
#include "detectors/detector.h"
#include "detectors/ekf_observer.h"
#include "detectors/hypothesis_bank.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"
#include "mooring_fem/wave_kinematics.h"
#include "simulation/observer_type.h"
#include "vessel/controller.h"
#include "vessel/fpso_model.h"
#include "vessel/hull_loads.h"
#include "vessel/hydro_data.h"
#include "vessel/rigid_body.h"
#include "vessel/sensors.h"
#include "vessel/thrusters.h"
#include "vessel/turret.h"
#include "vessel/waves.h"

namespace moorsim::simulation {

/// An irregular sea: a JONSWAP spectrum realised from the run seed's stream "waves" with
/// `realisation`'s options (its gravity is the water's), acting on the hull through its
/// WAMIT response and, with `on_lines` set, on the lines' drag and inertia with that
/// stretching rule above the mean surface.
struct SeaModel {
  vessel::JonswapParameters spectrum;
  vessel::WaveRealisationOptions realisation;
  /// A given sea in place of the spectrum's realisation (empty: the spectrum's).
  std::vector<vessel::WaveComponent> trains;
  std::optional<mooring_fem::WaveStretching> on_lines;
};

/// Wind on the hull above water from `direction_from` [rad, meteorological]: the 1-hour
/// mean speed `speed.mean_speed` [m/s] at 10 m, with the NPD gust realised from `speed`'s
/// options on top (stream "wind.gust") where `gust` is set, steady without it.
struct WindModel {
  vessel::WindParameters hull;
  vessel::WindGustOptions speed;
  double direction_from = 0.0;
  bool gust = true;
};

/// Fairlead load cells, one per line, with one error model and rate, and the faults that
/// befall them during the run.
struct TensionCellsModel {
  vessel::ChannelNoise noise;
  double rate = 1.0;  ///< [Hz]
  std::vector<vessel::CellFault> faults;
};

/// A fault of one channel of the pose sensors (GNSS north, east; gyro heading).
struct PoseFault {
  vessel::PoseChannel channel = vessel::PoseChannel::kNorth;
  vessel::SensorFault fault;
};

/// The position-mooring controller sampled at `rate` [Hz]; with `heading` its pi heading
/// gains are sized on the hull (vessel::WithHeadingLoop()).
struct ControllerModel {
  vessel::ControllerSpec spec;
  double rate = 1.0;
  std::optional<vessel::HeadingLoopTuning> heading;

  /// The spec the plant runs: `spec` with its heading loop sized on `vessel` where
  /// `heading` asks for it.
  vessel::ControllerSpec SizedFor(const vessel::VesselModel& vessel) const {
    return heading ? vessel::WithHeadingLoop(spec, *heading, vessel) : spec;
  }
};

/// A line that fails at `time` [s].
struct FailureEvent {
  double time = 0.0;
  mooring_fem::LineFailure failure;
};

/// The detection: its detectors (in the order their verdicts are reported), the hypothesis
/// bank and the observers' models. The bank's moored heave is the plant's static start's,
/// filled in when the plant is built.
struct DetectionSetup {
  std::vector<detectors::DetectorSpec> detectors;
  ObserverType observer = ObserverType::kEkf;
  /// Seed of the passive observers' training runs (streams "training.*"): a property of
  /// the set-up, not of the run.
  std::uint64_t training_seed = 1;
  detectors::HypothesisBankOptions bank;
  /// The observers' disturbance and measurement model (surge, sway, yaw).
  detectors::EkfOptions ekf;
  detectors::ObserverBankOptions observer_bank;
  /// A text naming everything the bank, the signatures and the passive training depend on
  /// (besides the moored heave): runs whose identities are equal share them within the
  /// process. Empty: never shared, built for each plant.
  std::string identity;
};

struct PlantModel {
  /// Names the model in messages (a scenario's file path).
  std::string name;
  mooring_fem::MooringParameters mooring;
  mooring_fem::SolverSettings solver;

  /// WAMIT output stem (stem.1, .hst, .3, .4, .9) and how to read it; the options' water
  /// density and gravity must be the mooring's.
  std::string hydrodynamics;
  vessel::WamitOptions wamit;
  vessel::MassProperties mass;
  vessel::LowFrequencyDamping damping;
  std::vector<vessel::ThrusterSpec> thrusters;
  vessel::TurretParameters turret;
  /// The turret's angle to the hull at the start [rad] (0 for a locked turret).
  double initial_turret_angle = 0.0;
  /// x, y [m] and heading [rad] of the low-frequency start; heave, roll and pitch start at
  /// the moored static equilibrium.
  Vec3 initial_pose = Vec3::Zero();

  /// The hull's viscous load relative to the current (unset: none).
  std::optional<vessel::HullGeometry> hull_drag;
  std::optional<SeaModel> waves;
  std::optional<WindModel> wind;

  vessel::PoseSensorSpec pose_sensors;
  std::vector<PoseFault> pose_faults;
  std::optional<TensionCellsModel> tension_cells;
  ControllerModel controller;
  std::optional<FailureEvent> failure;
  /// Unset (or no detectors): no detection.
  std::optional<DetectionSetup> detection;
};

}  // namespace moorsim::simulation
