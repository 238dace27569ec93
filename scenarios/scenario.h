// The scenario model: plain structs filled from YAML by LoadScenario(). All values are SI
// and Earth-frame NED unless a name says otherwise; angles are radians here (the YAML
// gives them in degrees under keys ending in `_deg`). Line numbers are 1-based.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/fatigue.h"
#include "core/angles.h"
#include "core/types.h"
#include "mooring_fem/parameters.h"
#include "mooring_fem/wave_kinematics.h"
#include "simulation/observer_type.h"
#include "vessel/controller.h"
#include "vessel/sensors.h"
#include "vessel/turret.h"
#include "vessel/waves.h"

namespace moorsim::scenarios {

/// Where a value came from in the YAML text (1-based line and column), for messages.
struct SourceMark {
  int line = 0;
  int column = 0;
};

// The mooring and solver blocks use the FEM's own parameter types (mooring_fem/parameters.h:
// the same fields and defaults), plus where each entry was written where messages need it.
// scenarios::ToMooringParameters (convert.h) strips the source marks for the FEM and the
// detectors, which never include this header.

using Water = mooring_fem::Water;
using Seabed = mooring_fem::Seabed;
/// Integrator settings (CVODE BDF).
using SolverSpec = mooring_fem::SolverSettings;

/// A line type (mooring_fem::LineType) and where its list entry was written.
/// A line type (mooring_fem::LineType), where it was written, and what the design checks
/// take from it: its strength and its fatigue curve.
struct LineType : mooring_fem::LineType {
  SourceMark mark;
  /// Minimum breaking load [N]; 0: not given.
  double minimum_breaking_load = 0.0;
  /// The T-N curve of its fatigue and the nominal area [m^2] a stress curve divides the
  /// tension range by; unset: not given.
  std::optional<analysis::TnCurve> fatigue_curve;
  double fatigue_area = 0.0;
};

/// A free point (mooring_fem::FreePoint), its name and where it was written.
struct PointSpec : mooring_fem::FreePoint {
  std::string name;
  SourceMark mark;  ///< the list entry
};

/// A line (mooring_fem::LineParameters) and where it was written.
struct LineSpec : mooring_fem::LineParameters {
  SourceMark mark;  ///< the list entry
  /// The free points' names its ends are at (`from`, `to`), "" for the anchor and the
  /// fairlead; lower_point and upper_point are their indices.
  std::string from, to;
  SourceMark length_mark;  ///< the `length` key's value, or `sections` (for the distance check)
  bool written_in_sections = false;  ///< given as `sections` (messages name them)
  /// The lower end is a fixed point held in the water (a jumper's or a riser's base), not an
  /// anchor on the seabed: it may lie anywhere under water and the line may hang below it.
  bool anchor_in_water = false;
  /// 1-based position of the entry in the YAML list (0 = not from YAML). Lines are sorted
  /// by id after loading, so messages use this to name the entry the user wrote.
  int entry = 0;
};

/// The current (mooring_fem::CurrentProfile) and the key it was written under.
struct CurrentProfile : mooring_fem::CurrentProfile {
  /// Where it was written ("mooring.current" or "environment.current"), for messages.
  std::string key = "mooring.current";
};

/// Values that apply to every line unless the line says otherwise.
struct LineDefaults {
  int segments = 50;
};

struct MooringSpec {
  Water water;
  Seabed seabed;
  CurrentProfile current;  ///< empty profile = no current
  std::vector<LineType> line_types;
  LineDefaults defaults;
  std::vector<LineSpec> lines;    ///< ordered by id after loading: lines[k - 1] is line k
  std::vector<PointSpec> points;  ///< the free points, in the order written
};

/// The vessel (docs/design.md section 5). Defaults are the seed FPSO (docs/design.md section 9).
struct LowFrequencyDampingSpec {
  double surge_time = 50.0;  ///< B_11 = (M + A)_11 / T [s]
  double sway_time = 100.0;  ///< [s]
  double yaw_time = 20.0;    ///< [s]
  double heave_ratio = 0.1;  ///< fraction of critical [-]
  double roll_ratio = 0.07;
  double pitch_ratio = 0.1;
};

struct ThrusterEntry {
  std::string name;
  double x = 0.0, y = 0.0;  ///< body frame [m]
  double angle = 0.0;       ///< thrust direction from the bow toward starboard [rad]
  bool azimuth = false;
  double max_thrust = 0.0;     ///< [N]
  double min_thrust = 0.0;     ///< [N], <= 0
  double weight = 1.0;         ///< allocation weight [-]
  double time_constant = 5.0;  ///< [s]
  double rate_limit = 0.0;     ///< [N/s], 0 = none
};

/// The hull's particulars for the viscous current load (`vessel.hull`; vessel::HullGeometry,
/// with the water density of mooring.water). Defaults: the seed FPSO (vessel::SeedFpsoHull()).
struct HullSpec {
  double length = 200.0;              ///< L, length between perpendiculars [m]
  double beam = 44.0;                 ///< B [m]
  double draught = 12.0;              ///< T [m]
  double displaced_volume = 97961.0;  ///< nabla [m^3]
  double wetted_surface = 0.0;        ///< S [m^2]; 0 = Denny-Mumford estimate from L, T, nabla
  /// C_d2D [-] of a hull section; 0 = Hoerner's curve at B / (2 T).
  double cross_flow_drag_coefficient = 0.0;
  /// k of the viscous resistance (1 + k) C_F [-]; unset = Watanabe's regression from L, B,
  /// T and nabla (vessel::WatanabeFormFactor; 0.505 for the seed).
  std::optional<double> form_factor;
  double kinematic_viscosity = 1.19e-6;  ///< of the water [m^2/s]
};

/// The hull and superstructure above water for the wind load (`vessel.windage`;
/// vessel::WindParameters with Blendermann's loaded-tanker coefficients). Defaults: the
/// seed FPSO (vessel::SeedFpsoWind()).
struct WindageSpec {
  double frontal_area = 1200.0;  ///< A_F, projected area seen from ahead [m^2]
  double lateral_area = 4500.0;  ///< A_L, projected area seen from the side [m^2]
  /// Reference length of the yaw moment [m]; unset = hull.length.
  std::optional<double> length;
  /// s_L, the lateral area's centroid forward of midship [m].
  double lateral_centroid = 0.0;
  double air_density = 1.226;  ///< [kg/m^3]
};

/// The turret that carries the fairleads (`vessel.turret`; vessel::TurretParameters). The
/// fairleads (mooring.lines[].fairlead) are body points at turret angle 0. Defaults: locked
/// at the reference point, as the TAPM thesis's model.
struct TurretSpec {
  vessel::TurretBearing bearing = vessel::TurretBearing::kLocked;
  double x = 0.0, y = 0.0;  ///< turret centre, body frame [m]
  /// [m]; every fairlead lies within it. Unset = the fairleads' largest horizontal distance
  /// from the turret centre.
  std::optional<double> radius;
  double inertia = 6.0e8;                ///< about its axis [kg m^2]
  double friction_coefficient = 0.0;     ///< friction: Coulomb coefficient [-]
  std::optional<double> bearing_radius;  ///< friction: lever arm [m]; unset = radius
  double damping = 0.0;                  ///< viscous [N m s/rad]
  double slip_rate = 1.0e-5;             ///< friction: regularisation rate [rad/s]
  /// free / friction: the turret's heading at the start [rad, NED like the hull's]; its
  /// angle to the hull starts at this minus the hull's initial heading. Unset = the hull's
  /// initial heading (angle 0). Lets a scenario start the hull at another heading with the
  /// fairleads where its lines hold them, instead of the lines swinging the turret round.
  std::optional<double> initial_heading;
};

struct VesselSpec {
  /// WAMIT output stem (files stem.1, .hst, .3, .4, .9), relative paths resolved against
  /// the scenario file's directory at load time.
  std::string hydrodynamics;
  double length_scale = 1.0;                        ///< WAMIT ULEN [m]
  double mass = 1.0041e8;                           ///< [kg]
  Vec3 centre_of_gravity = Vec3(0.0, 0.0, 1.0);     ///< body frame [m]
  Vec3 radii_of_gyration = Vec3(16.3, 54.0, 54.0);  ///< roll, pitch, yaw [m]
  LowFrequencyDampingSpec damping;
  /// Initial low-frequency pose: x, y [m], heading [rad]; heave, roll and pitch start at
  /// the moored static equilibrium.
  Vec3 initial_pose = Vec3::Zero();
  std::vector<ThrusterEntry> thrusters;  ///< empty = the seed layout (vessel/thrusters.h)
  HullSpec hull;
  WindageSpec windage;
  TurretSpec turret;

  /// The turret's angle to the hull at the start [rad, in (-pi, pi]]: a turret on its
  /// bearing given its own initial heading starts at that heading, so at it minus the
  /// hull's; otherwise 0 (the fairleads where the hull puts them).
  double InitialTurretAngle() const {
    if (turret.bearing == vessel::TurretBearing::kLocked || !turret.initial_heading) return 0.0;
    return WrapAngle(*turret.initial_heading - initial_pose.z());
  }
};

struct WavesSpec {
  bool enabled = false;
  double significant_height = 0.0;  ///< Hs [m]
  double peak_period = 0.0;         ///< Tp [s]
  double gamma = 3.3;               ///< JONSWAP peak enhancement [-]
  double direction_toward = 0.0;    ///< mean direction the waves travel TOWARD [rad]
  std::optional<double> spreading;  ///< cos-2s exponent s; unset = long-crested
  int components = 200;
  /// A given sea in place of the JONSWAP one: these regular waves, summed as they are
  /// (the spectrum's fields above are then unused).
  std::vector<vessel::WaveComponent> trains;
  /// The lines see the waves' water velocity and acceleration (finite-depth Airy,
  /// mooring_fem/wave_kinematics.h) in their drag and inertia; off: only the hull does.
  bool on_lines = false;
  /// Above the mean surface: Wheeler stretching or none.
  mooring_fem::WaveStretching stretching = mooring_fem::WaveStretching::kWheeler;
};

struct WindSpec {
  bool enabled = false;
  double speed = 0.0;           ///< 1-hour mean at 10 m [m/s]
  double direction_from = 0.0;  ///< direction the wind comes FROM [rad] (meteorological)
  bool gust = true;             ///< NPD (ISO 19901-1) gust spectrum on top of the mean
  int components = 100;
};

struct EnvironmentSpec {
  WavesSpec waves;
  WindSpec wind;
  /// Viscous load on the hull from its velocity relative to the water (quadratic cross-flow
  /// drag and friction, with the current if there is one); the lines see the current anyway.
  bool hull_viscous_drag = true;
};

struct ControllerSpec {
  vessel::ControllerType type = vessel::ControllerType::kNone;
  double rate = 1.0;  ///< sample rate [Hz]
  /// Setpoint x, y [m], heading [rad]; unset = the initial pose.
  std::optional<Vec3> setpoint;
  Vec3 kp = Vec3(1e5, 1e6, 1e3);  ///< pi: [N/m, N/m, N m/rad]
  Vec3 ki = Vec3(1e3, 1e3, 1e2);  ///< pi: [N/(m s), N/(m s), N m/(rad s)]
  Vec3 kd = Vec3::Zero();         ///< pi: [N s/m, N s/m, N m s/rad]
  double natural_period = 0.0;    ///< observer_pid: 2 pi / omega_n [s]; 0 = its default
  double damping_ratio = 0.0;     ///< observer_pid: zeta [-]; 0 = its default
  /// pi: the heading loop's gains sized from a closed-loop natural period [s] and damping
  /// ratio (vessel::SizeAxisGains with the yaw inertia and damping); they replace kp[3],
  /// ki[3] and kd[3]. Unset = the given gains. The other controllers do not read it.
  struct HeadingLoop {
    double natural_period = 0.0;
    double damping_ratio = 0.0;
  };
  std::optional<HeadingLoop> heading;
};

/// The GNSS channels a fault of the receiver takes: both (the receiver), north or east.
enum class GnssFaultChannel { kBoth, kNorth, kEast };

inline constexpr std::string_view kGnssFaultChannelNames[] = {"both", "north", "east"};
constexpr ChoiceInfo ChoicesOf(GnssFaultChannel) {
  return {"GNSS channel", kGnssFaultChannelNames};
}

struct ChannelNoiseSpec {
  double std_dev = 0.0;             ///< white noise [m or rad]
  double bias_walk = 0.0;           ///< [m/sqrt(s) or rad/sqrt(s)]
  double bias_time_constant = 0.0;  ///< [s]; 0 = random walk
  double initial_bias = 0.0;
  double outlier_probability = 0.0;
  double outlier_std_dev = 0.0;
};

struct SensorsSpec {
  double gnss_rate = 1.0;  ///< [Hz]
  double gyro_rate = 1.0;  ///< [Hz]
  /// Seed case (docs/design.md section 9): measurement variance 0.005 m^2 / rad^2 per DOF.
  ChannelNoiseSpec north{.std_dev = 0.070710678118654752};
  ChannelNoiseSpec east{.std_dev = 0.070710678118654752};
  ChannelNoiseSpec heading{.std_dev = 0.070710678118654752};
  double gnss_dropout_probability = 0.0;
  double gnss_dropout_mean_duration = 0.0;  ///< [s]
  double gyro_dropout_probability = 0.0;
  bool tension_cells = false;
  ChannelNoiseSpec tension_noise;  ///< [N]
  double tension_rate = 1.0;       ///< [Hz]
  /// A sensor that goes wrong during the run (`faults:` of gnss, gyro and tension_cells),
  /// from `time` to `end` (unset: the end of the run), in the sensor's unit u (m, rad, N):
  /// "step" (reads `offset` [u] off), "stuck" (repeats its last reading before `time`),
  /// "degraded" (its white noise `factor` times larger), "drift" (runs off by `rate`
  /// [u/s] x (t - time)), "dead" (GNSS, gyro: no reading; a cell reads its noise about
  /// zero), "gain" (reads `gain` x the true value).
  struct Fault {
    vessel::SensorFault::Mode mode = vessel::SensorFault::Mode::kStep;
    double time = 0.0;
    std::optional<double> end;
    double offset = 0.0;
    double rate = 0.0;
    double factor = 1.0;
    double gain = 1.0;
    int line = 0;                                        ///< tension cells: the line, 1-based
    GnssFaultChannel channel = GnssFaultChannel::kBoth;  ///< gnss: the channel that goes wrong
  };
  std::vector<Fault> gnss_faults;
  std::vector<Fault> gyro_faults;
  std::vector<Fault> tension_faults;
};

struct FailureSpec {
  int line = 0;       ///< 1-based; 0 = no failure
  double time = 0.0;  ///< [s]
  mooring_fem::FailureMode mode = mooring_fem::FailureMode::kFairlead;
  int node = 0;                      ///< for mode node: node index from the anchor (1..n-1)
  std::optional<double> arc_length;  ///< for mode node: unstretched length from the anchor [m]
};

/// One entry of the `detectors:` list: a registered detector type, a unique label (default
/// the type) and numeric parameters by name, checked by the detector registry.
struct DetectorEntry {
  std::string type;
  std::string label;
  std::map<std::string, double> parameters;
  /// `plugin:` the shared library that provides `type` (empty: built in); a relative path
  /// is resolved against the scenario file's directory at load time.
  std::string plugin;
};

/// How the hypothesis bank and its observers are built (`detection:`).
struct DetectionSpec {
  /// Per-hypothesis observer: "ekf" (an EKF each, mixed by switch_rate) or "passive" (the
  /// TAPM thesis's passive observer with a covariance from training runs; never mixed).
  simulation::ObserverType observer = simulation::ObserverType::kEkf;
  /// Seed of the passive observers' training runs (streams "training.*"). A property of the
  /// detector's set-up, like a vessel's once-trained covariances, not of the run: every run
  /// of a scenario, whatever its simulation.seed, uses the same trained covariances.
  std::uint64_t training_seed = 1;
  bool pairs = false;                   ///< also every pair of failed lines
  double measurement_variance = 0.005;  ///< observers' R per DOF [m^2, rad^2]
  /// Rate [1/s] at which the observer bank lets the truth switch hypothesis (IMM mixing,
  /// detectors/ekf_observer.h); 0 = independent filters as in the papers.
  std::optional<double> switch_rate;
  /// Whether the observers check the sensors before they take a sample (frozen readings,
  /// jumps, noisy spells; detectors/sensor_monitor.h). Unset: on when a fused detector is
  /// listed, off otherwise (the papers' observers take every sample as delivered).
  std::optional<bool> sensor_checks;
  /// The observers' disturbance model (`detection.model`, detectors::EkfOptions); unset
  /// fields keep the detectors library's defaults. Per DOF [surge, sway, yaw].
  struct Model {
    std::optional<Vec3> wave_motion_std;        ///< [m, m, rad]
    std::optional<Vec3> bias_std;               ///< [N, N, N m]
    std::optional<Vec3> bias_time_constant;     ///< [s]
    std::optional<Vec3> force_noise;            ///< [N sqrt(s), N sqrt(s), N m sqrt(s)]
    std::optional<Vec3> mooring_damping_ratio;  ///< fraction of critical [-]
  } model;
};

struct SimulationSpec {
  double duration = 1000.0;  ///< [s]
  double output_rate = 1.0;  ///< [Hz]
  std::uint64_t seed = 1;
  /// [s] The design record's statistics (extremes, fatigue damage, offset) start here:
  /// what comes before (a line removed at 0 s and the vessel settling) is left out.
  double statistics_from = 0.0;
};

struct Scenario {
  std::string name;
  std::string source_path;             ///< file it was read from
  std::string text;                    ///< the full YAML text, recorded in outputs
  std::vector<std::string> overrides;  ///< "key.path=value" applied on top of `text`
  MooringSpec mooring;
  SolverSpec solver;
  /// The coupled-simulation sections; `vessel` unset means a lines-only scenario.
  std::optional<VesselSpec> vessel;
  EnvironmentSpec environment;
  ControllerSpec controller;
  SensorsSpec sensors;
  FailureSpec failure;
  SimulationSpec simulation;
  std::vector<DetectorEntry> detectors;
  DetectionSpec detection;
  /// Where each value was written, by key path ("mooring.lines[3].length", list indices
  /// 1-based), so checks after parsing can point at the offending text.
  std::map<std::string, SourceMark> marks;
  /// Key paths whose values were written in another file (a base scenario, `base:`), with
  /// that file; the deepest path wins. Empty when the scenario has no base.
  std::map<std::string, std::string> origins;
};

}  // namespace moorsim::scenarios
