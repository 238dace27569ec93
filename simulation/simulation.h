// The coupled simulation of a plant model (plant_model.h; a scenario gives one through the
// runner, runner/scenario_plant.h): the seed
// FPSO (or any vessel with WAMIT data) on its FEM mooring lines in one CVODE system
// (core/coupled_system.h), with the realised sea, current and wind, thrusters, a discrete
// position-mooring controller, sensors and a scheduled line failure. Everything random comes from
// named streams of the run seed, so a model and a seed determine the run bit for bit.
//
// Timeline: the integrator stops at every controller sample, sensor sample and failure, the
// discrete parts act there (sensors sample the true total pose, the controller computes a
// command from the measurement, the allocator distributes it, the rate limits move the held
// thrust commands), and integration resumes; thrust itself follows through first-order
// dynamics, so the right-hand side stays continuous. A failure restarts CVODE with the
// states carried over.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/coupled_system.h"
#include "core/integrator.h"
#include "core/sample_clock.h"
#include "core/types.h"
#include "detectors/detector.h"
#include "mooring_fem/mooring_attachment.h"
#include "mooring_fem/mooring_system.h"
#include "simulation/detection.h"
#include "simulation/plant_model.h"
#include "vessel/controller.h"
#include "vessel/hull_loads.h"
#include "vessel/hydro_data.h"
#include "vessel/vessel_plant.h"
#include "vessel/waves.h"

namespace moorsim::vessel {
class PositionController;
class PoseSensors;
class ThrustAllocator;
class ThrusterDynamics;
}  // namespace moorsim::vessel

namespace moorsim::simulation {

/// Everything recorded at one output instant (docs/design.md section 7), SI units.
struct Sample {
  double time = 0.0;
  Vec6 pose_true = Vec6::Zero();           ///< low-frequency + wave-frequency eta (NED)
  Vec6 pose_low_frequency = Vec6::Zero();  ///< eta of the integrated low-frequency model
  Vec6 velocity = Vec6::Zero();            ///< nu (body), low-frequency
  /// The latest measurement x, y, psi (NaN until a channel has delivered one).
  Vec3 pose_measured = Vec3::Constant(kNaN);
  /// Tension cells' latest readings [N] (empty without tension cells).
  std::vector<double> tension_measured;
  std::vector<double> fairlead_tension;  ///< per line [N]
  Vec3 thrust_commanded = Vec3::Zero();  ///< controller output X, Y, N (body)
  Vec3 thrust_delivered = Vec3::Zero();  ///< from the delivered thrust states
  /// With the turret on a bearing: its angle to the hull [rad], its rate relative to the
  /// hull [rad/s], the lines' moment about its axis and the bearing's moment on the hull
  /// [N m]; unset for a locked turret.
  std::optional<Eigen::Vector4d> turret;
  /// Body-frame loads on the hull about its origin (the mooring's as the hull feels it:
  /// with a turret on a bearing, its yaw moment is the net force's at the turret centre
  /// plus the bearing's).
  Vec6 load_mooring = Vec6::Zero();
  Vec6 load_wave_drift = Vec6::Zero();
  Vec6 load_current = Vec6::Zero();
  Vec6 load_wind = Vec6::Zero();
  Vec6 load_thrust = Vec6::Zero();
  /// Every detector's latest verdict (the model's order), empty without detectors.
  std::vector<detectors::Verdict> detectors;
  /// The samples the detection took since the previous row (Simulation::KeepDetectionInput).
  std::vector<detectors::Observation> detection_input;
  /// The intact observer's latest load picture (EKF observer bank only): its bias state b
  /// [N, N, N m] and wave-frequency motion estimate C_w xi [m, m, rad], Earth frame; what
  /// the force-deficit test reads. Unset without an EKF bank or before its first sample.
  std::optional<Vec3> observer_bias;
  std::optional<Vec3> observer_wave_motion;
};

/// How well the station keeping held over the controller updates so far: how many of them
/// the thrust allocation had to scale down (a thruster at its rating: the controller asked
/// for more than the thrusters give), and the low-frequency heading's largest distance from
/// the controller's setpoint heading [rad] up to the failure (the whole run without one)
/// and its latest. A hull that has lost its heading
/// meets other seas than its campaign meant to test (a turret at the reference point
/// leaves the heading to the thrusters alone).
struct StationKeeping {
  std::int64_t updates = 0;
  std::int64_t saturated = 0;
  double heading_error_max = 0.0;
  double heading_error_last = 0.0;
  double SaturatedShare() const {
    return updates > 0 ? static_cast<double>(saturated) / static_cast<double>(updates) : 0.0;
  }
};

/// The realised sea of `sea` for the run seed `seed` (its own stream, "waves"): the hull's
/// and, where the lines see them, the lines' wave components.
vessel::WaveRealisation RealiseSea(const SeaModel& sea, std::uint64_t seed);

/// The lines' wave kinematics of a realised sea in `water`'s depth, with `stretching` above
/// the mean surface.
std::shared_ptr<const mooring_fem::WaveKinematics> LineWaves(
    const vessel::WaveRealisation& sea, const mooring_fem::Water& water,
    mooring_fem::WaveStretching stretching);

/// The model's detection (its `detection` set) as a run of it with seed `seed` builds it,
/// without the run: the plant is built and put at its moored static start (the models
/// depend on it) and nothing is integrated. For `moorsim detect` on recorded data and the
/// monitor on live feeds. Throws InputError for a model without detectors or one that
/// cannot be simulated.
std::unique_ptr<Detection> MakeDetection(const PlantModel& model, std::uint64_t seed);

class Simulation {
 public:
  /// Builds every part of `model` and puts the vessel at its moored static equilibrium
  /// (heave, roll, pitch) at the initial pose with the lines on their static FEM shape.
  /// Throws moorsim::InputError for a model that cannot be simulated (its message starts
  /// with the offending part: "detectors[2].floor: ...", "mooring.points[1]: ..."),
  /// moorsim::Error if the static start fails.
  Simulation(const PlantModel& model, std::uint64_t seed);
  ~Simulation();

  /// Integrates to t, acting on every discrete event on the way. Throws SolverError (with t
  /// and the CVODE flag) if the integrator fails. `interrupt` (empty: never) is asked after
  /// each event: once it returns true, the simulation stops there, at an instant it would
  /// have stopped at anyway (so going on from it changes nothing), and throws
  /// moorsim::Interrupted.
  void AdvanceTo(double t, const std::function<bool()>& interrupt = {});

  /// A constant load on the hull in Earth axes (X north, Y east [N], moment about z [N m]),
  /// for verification runs (static offset, decay tests). Replaces the previous one.
  void SetExternalLoad(const Vec3& force_ned_xy_moment_z);

  /// The thrust command X, Y, N [N, N, N m] (body frame) issued at every controller instant
  /// from now on in place of the controller's: the allocation, the thrusters' rate limits
  /// and dynamics, the detectors and the record take it as they take the controller's.
  /// std::nullopt gives the command back to the controller.
  void SetThrustCommand(const std::optional<Vec3>& command) { thrust_override_ = command; }

  const PlantModel& model() const { return model_; }
  double time() const { return t_; }
  const std::vector<double>& state() const { return x_; }
  Sample Record();
  /// Each line's fairlead tension [N] at the current state.
  std::vector<double> FairleadTensions();
  /// Each line's segment tensions [N], from the anchor up (MooringSystem::SegmentTensions),
  /// at the current state.
  std::vector<std::vector<double>> SegmentTensions();
  /// Each line's node positions (Earth frame, NED [m]), from the anchor up, at the current
  /// state.
  std::vector<std::vector<Vec3>> NodePositions();
  /// Vessel energy (kinetic + hydrostatic) plus line energy (kinetic, gravitational,
  /// elastic, seabed) [J], relative to nothing in particular: differences matter.
  double MechanicalEnergy();
  IntegratorStats stats() const;

  mooring_fem::MooringSystem& mooring() { return mooring_; }
  vessel::VesselPlant& plant() { return *plant_; }
  const vessel::VesselModel& plant_model() const { return plant_->model(); }
  CoupledSystem& system() { return *system_; }
  const vessel::HydroData& hydro() const { return *hydro_; }
  int num_lines() const { return mooring_.num_lines(); }
  /// Number of hypotheses of the detectors' bank (0 without detectors) and their labels.
  int num_hypotheses() const;
  const std::vector<DetectorRecord>& detector_records() const;
  std::vector<std::string> HypothesisLabels() const;
  /// The detection (nullptr without detectors).
  const Detection* detection() const { return detection_.get(); }
  /// Record() hands over every sample the detection took since the previous Record
  /// (Sample::detection_input): what run.h5 keeps as /detection/input.
  void KeepDetectionInput(bool keep);
  /// Whether the detection has an EKF observer bank, whose load picture Record() reports.
  bool estimates_load() const;
  /// Mooring load (body frame) of the static start and the pose found there.
  const Vec6& initial_pose() const { return initial_pose_; }
  std::uint64_t seed() const { return seed_; }
  /// Controller updates so far (one per controller instant k / rate reached).
  std::int64_t controller_updates() const { return next_control_index_; }
  /// Seconds of wall time spent in the integrator so far.
  double integrator_seconds() const { return integrator_seconds_; }
  /// Time in detection; included in integrator_seconds() for the updates (they run at the
  /// sensor events inside AdvanceTo), not for the setup (in the constructor).
  const DetectionTiming& detection_timing() const;
  const StationKeeping& station_keeping() const { return station_keeping_; }

 private:
  struct Parts;
  void SettleMooredEquilibrium();
  void StartIntegrator();
  void DiscreteEvents();
  double NextEventTime() const;
  std::vector<PointKinematics> Points();

  PlantModel model_;
  std::uint64_t seed_;
  std::shared_ptr<const vessel::HydroData> hydro_;  // shared between runs (read only)
  mooring_fem::MooringSystem mooring_;
  mooring_fem::MooringAttachment attachment_;
  std::unique_ptr<vessel::VesselPlant> plant_;
  std::unique_ptr<Parts> parts_;
  std::unique_ptr<CoupledSystem> system_;
  std::unique_ptr<Integrator> integrator_;
  IntegratorStats finished_;
  std::vector<double> x_;
  double t_ = 0.0;
  Vec6 initial_pose_ = Vec6::Zero();
  double integrator_seconds_ = 0.0;
  std::unique_ptr<Detection> detection_;
  StationKeeping station_keeping_;

  // Discrete schedule: integer sample indices, instants k / rate (core/sample_clock.h).
  SampleClock controller_clock_;
  std::int64_t next_control_index_ = 0;  // first controller instant not yet acted on
  double last_sensor_time_ = -1.0;
  double last_tension_time_ = -1.0;
  bool failure_pending_ = false;
  Vec3 last_measurement_ = Vec3::Constant(kNaN);
  Vec3 tau_command_ = Vec3::Zero();
  std::optional<Vec3> thrust_override_;
};

}  // namespace moorsim::simulation
