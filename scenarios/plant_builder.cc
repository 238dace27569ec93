#include "scenarios/plant_builder.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

#include "core/error.h"
#include "scenarios/convert.h"

namespace moorsim::scenarios {

namespace {

const VesselSpec& RequireVessel(const Scenario& scenario) {
  if (!scenario.vessel) {
    throw InputError(scenario.source_path +
                     ": vessel: the section is missing; a coupled run "
                     "needs the vessel (simulate-lines runs lines only)");
  }
  return *scenario.vessel;
}

vessel::ChannelNoise ToNoise(const ChannelNoiseSpec& n) {
  return {.std_dev = n.std_dev,
          .bias_walk = n.bias_walk,
          .bias_time_constant = n.bias_time_constant,
          .initial_bias = n.initial_bias,
          .outlier_probability = n.outlier_probability,
          .outlier_std_dev = n.outlier_std_dev};
}

vessel::PoseSensorSpec ToPoseSensorSpec(const SensorsSpec& s) {
  vessel::PoseSensorSpec spec;
  spec.gnss_rate = s.gnss_rate;
  spec.gyro_rate = s.gyro_rate;
  spec.north = ToNoise(s.north);
  spec.east = ToNoise(s.east);
  spec.heading = ToNoise(s.heading);
  spec.gnss_dropout_probability = s.gnss_dropout_probability;
  spec.gyro_dropout_probability = s.gyro_dropout_probability;
  spec.gnss_dropout_mean_duration = s.gnss_dropout_mean_duration;
  return spec;
}

vessel::SensorFault ToSensorFault(const SensorsSpec::Fault& f) {
  const FaultModeSize& mode = FaultModeSizeOf(f.mode);
  vessel::SensorFault fault;
  fault.mode = f.mode;
  fault.from = f.time;
  fault.until = f.end.value_or(std::numeric_limits<double>::infinity());
  if (mode.size != nullptr) fault.size = f.*mode.size;
  return fault;
}

std::vector<simulation::PoseFault> ToPoseFaults(const SensorsSpec& s) {
  std::vector<simulation::PoseFault> faults;
  for (const SensorsSpec::Fault& f : s.gnss_faults) {
    // The receiver (both channels) or one of its channels.
    if (f.channel != GnssFaultChannel::kEast) {
      faults.push_back({vessel::PoseChannel::kNorth, ToSensorFault(f)});
    }
    if (f.channel != GnssFaultChannel::kNorth) {
      faults.push_back({vessel::PoseChannel::kEast, ToSensorFault(f)});
    }
  }
  for (const SensorsSpec::Fault& f : s.gyro_faults) {
    faults.push_back({vessel::PoseChannel::kHeading, ToSensorFault(f)});
  }
  return faults;
}

std::optional<simulation::TensionCellsModel> ToTensionCells(const SensorsSpec& s) {
  if (!s.tension_cells) return std::nullopt;
  simulation::TensionCellsModel cells;
  cells.noise = ToNoise(s.tension_noise);
  cells.rate = s.tension_rate;
  for (const SensorsSpec::Fault& f : s.tension_faults) {
    cells.faults.push_back({.line = f.line - 1, .fault = ToSensorFault(f)});
  }
  return cells;
}

std::vector<vessel::ThrusterSpec> ToThrusters(const VesselSpec& v) {
  if (v.thrusters.empty()) return vessel::SeedThrusters();
  std::vector<vessel::ThrusterSpec> out;
  for (const ThrusterEntry& e : v.thrusters) {
    out.push_back({.name = e.name,
                   .x = e.x,
                   .y = e.y,
                   .angle = e.angle,
                   .azimuth = e.azimuth,
                   .max_thrust = e.max_thrust,
                   .min_thrust = e.min_thrust,
                   .weight = e.weight,
                   .time_constant = e.time_constant,
                   .rate_limit = e.rate_limit});
  }
  return out;
}

vessel::TurretParameters ToTurretParameters(const Scenario& scenario) {
  const TurretSpec& t = scenario.vessel->turret;
  vessel::TurretParameters p;
  p.bearing = t.bearing;
  p.x = t.x;
  p.y = t.y;
  p.inertia = t.inertia;
  p.friction_coefficient = t.friction_coefficient;
  p.bearing_radius = t.bearing_radius.value_or(TurretRadius(scenario));
  p.damping = t.damping;
  p.slip_rate = t.slip_rate;
  return p;
}

simulation::ControllerModel ToControllerModel(const ControllerSpec& c, const Vec3& initial) {
  simulation::ControllerModel model;
  model.rate = c.rate;
  vessel::ControllerSpec& spec = model.spec;
  spec.type = c.type;
  spec.setpoint = c.setpoint.value_or(initial);
  spec.pi.kp = c.kp;
  spec.pi.ki = c.ki;
  spec.pi.kd = c.kd;
  if (c.heading) {
    model.heading = vessel::HeadingLoopTuning{.natural_period = c.heading->natural_period,
                                              .damping_ratio = c.heading->damping_ratio};
  }
  if (c.natural_period > 0.0) {
    spec.observer_pid.natural_frequency = 2 * std::numbers::pi / c.natural_period;
  }
  if (c.damping_ratio > 0.0) spec.observer_pid.relative_damping = c.damping_ratio;
  return model;
}

std::optional<simulation::FailureEvent> ToFailure(const Scenario& scenario) {
  const FailureSpec& f = scenario.failure;
  if (f.line == 0) return std::nullopt;
  simulation::FailureEvent event;
  event.time = f.time;
  mooring_fem::LineFailure& failure = event.failure;
  failure.line = f.line - 1;
  failure.mode = f.mode;
  if (f.mode == mooring_fem::FailureMode::kNode) {
    const LineSpec& line = scenario.mooring.lines[failure.line];
    failure.node = f.arc_length ? line.NodeNearest(*f.arc_length) : f.node;
    failure.node = std::clamp(failure.node, 1, line.Segments() - 1);
  }
  return event;
}

/// What determines the detectors' hypothesis bank and GLR signatures: the scenario (its
/// file, text and overrides) without the keys that cannot change them, the seed, the
/// failure and the simulation's length and output rate. Conservative: any other override
/// gives another identity (a rebuild, never a wrong share).
std::string DetectionIdentity(const Scenario& s) {
  std::string key = "detection " + s.source_path + "\n" + s.text;
  for (const std::string& o : s.overrides) {
    if (o.rfind("simulation.", 0) == 0 || o.rfind("failure.", 0) == 0 ||
        o.rfind("failure=", 0) == 0) {
      continue;
    }
    key += "\nset " + o;
  }
  return key;
}

}  // namespace

std::span<const FaultModeSize> FaultModeSizes() {
  using Mode = vessel::SensorFault::Mode;
  using F = SensorsSpec::Fault;
  static constexpr FaultModeSize kModes[] = {
      {Mode::kStep, &F::offset, 0.0, "a step needs a nonzero offset [{unit}]"},
      {Mode::kStuck, nullptr, 0.0, ""},
      {Mode::kDegraded, &F::factor, 1.0, "a degraded sensor needs its noise factor (> 1)"},
      {Mode::kDrift, &F::rate, 0.0, "a drift needs a nonzero rate [{unit}/s]"},
      {Mode::kDead, nullptr, 0.0, ""},
      {Mode::kGain, &F::gain, 1.0, "a gain error needs its gain (> 0, not 1)"},
  };
  // One row per mode, at the mode's place.
  static_assert(std::size(kModes) == ChoiceNames<Mode>().size());
  static_assert([] {
    for (std::size_t i = 0; i < std::size(kModes); ++i) {
      if (static_cast<std::size_t>(kModes[i].mode) != i) return false;
    }
    return true;
  }());
  return kModes;
}

const FaultModeSize& FaultModeSizeOf(vessel::SensorFault::Mode mode) {
  return FaultModeSizes()[static_cast<std::size_t>(mode)];
}

vessel::HullGeometry ToHullGeometry(const VesselSpec& spec, double water_density) {
  const HullSpec& h = spec.hull;
  vessel::HullGeometry hull;
  hull.length = h.length;
  hull.beam = h.beam;
  hull.draught = h.draught;
  hull.displaced_volume = h.displaced_volume;
  hull.wetted_surface = h.wetted_surface;
  hull.cross_flow_drag_coefficient = h.cross_flow_drag_coefficient;
  hull.form_factor =
      h.form_factor ? *h.form_factor
                    : vessel::WatanabeFormFactor(h.length, h.beam, h.draught, h.displaced_volume);
  hull.water_density = water_density;
  hull.kinematic_viscosity = h.kinematic_viscosity;
  return hull;
}

vessel::WindParameters ToWindParameters(const VesselSpec& spec) {
  const WindageSpec& w = spec.windage;
  vessel::WindParameters wind;
  wind.air_density = w.air_density;
  wind.frontal_area = w.frontal_area;
  wind.lateral_area = w.lateral_area;
  wind.length = w.length.value_or(spec.hull.length);
  wind.coefficients = vessel::LoadedTankerWindCoefficients(wind.frontal_area, wind.lateral_area,
                                                           w.lateral_centroid / wind.length);
  return wind;
}

simulation::SeaModel ToSeaModel(const WavesSpec& spec, double gravity) {
  simulation::SeaModel sea;
  sea.spectrum = {.significant_height = spec.significant_height,
                  .peak_period = spec.peak_period,
                  .peak_enhancement = spec.gamma};
  sea.realisation.mean_direction = spec.direction_toward;
  sea.realisation.spreading_exponent = spec.spreading;
  sea.realisation.components = spec.components;
  sea.realisation.gravity = gravity;
  sea.trains = spec.trains;
  if (spec.on_lines) {
    sea.on_lines = spec.stretching;
  }
  return sea;
}

simulation::DetectionSetup ToDetectionSetup(const Scenario& scenario) {
  simulation::DetectionSetup setup;
  for (const DetectorEntry& e : scenario.detectors) {
    setup.detectors.push_back(
        {.type = e.type, .label = e.label, .parameters = e.parameters, .plugin = e.plugin});
  }
  const DetectionSpec& d = scenario.detection;
  setup.observer = d.observer;
  setup.training_seed = d.training_seed;
  setup.bank.include_pairs = d.pairs;
  const Vec3 initial = scenario.vessel ? scenario.vessel->initial_pose : Vec3::Zero();
  setup.bank.reference_pose = scenario.controller.setpoint.value_or(initial);
  // A turret on its bearing keeps the absolute heading it starts at (the lines hold it):
  // its initial heading, by default the vessel's (angle 0 to the hull).
  const TurretSpec turret = scenario.vessel ? scenario.vessel->turret : TurretSpec{};
  if (turret.bearing != vessel::TurretBearing::kLocked) {
    setup.bank.turret = detectors::TurretModel{Eigen::Vector2d(turret.x, turret.y),
                                               turret.initial_heading.value_or(initial.z())};
  }
  detectors::EkfOptions& ekf = setup.ekf;
  ekf.measurement_variance = Vec3::Constant(d.measurement_variance);
  ekf.wave_motion_std = d.model.wave_motion_std.value_or(ekf.wave_motion_std);
  ekf.bias_std = d.model.bias_std.value_or(ekf.bias_std);
  ekf.bias_time_constant = d.model.bias_time_constant.value_or(ekf.bias_time_constant);
  ekf.force_noise = d.model.force_noise.value_or(ekf.force_noise);
  ekf.mooring_damping_ratio = d.model.mooring_damping_ratio.value_or(ekf.mooring_damping_ratio);
  setup.observer_bank.switch_rate = d.switch_rate.value_or(setup.observer_bank.switch_rate);
  const bool fused = std::any_of(scenario.detectors.begin(), scenario.detectors.end(),
                                 [](const DetectorEntry& e) { return e.type == "fused"; });
  if (d.sensor_checks.value_or(fused)) {
    setup.observer_bank.sensor_checks = detectors::SensorCheckOptions{};
  }
  setup.identity = DetectionIdentity(scenario);
  return setup;
}

simulation::PlantModel ToPlantModel(const Scenario& scenario) {
  const VesselSpec& v = RequireVessel(scenario);
  simulation::PlantModel model;
  model.name = scenario.source_path;
  model.mooring = ToMooringParameters(scenario.mooring);
  model.solver = scenario.solver;
  const mooring_fem::Water& water = scenario.mooring.water;
  model.hydrodynamics = v.hydrodynamics;
  model.wamit = {
      .water_density = water.density, .gravity = water.gravity, .length_scale = v.length_scale};
  model.mass.mass = v.mass;
  model.mass.r_g = v.centre_of_gravity;
  model.mass.radii_of_gyration = v.radii_of_gyration;
  model.damping = {.surge_time = v.damping.surge_time,
                   .sway_time = v.damping.sway_time,
                   .yaw_time = v.damping.yaw_time,
                   .heave_ratio = v.damping.heave_ratio,
                   .roll_ratio = v.damping.roll_ratio,
                   .pitch_ratio = v.damping.pitch_ratio};
  model.thrusters = ToThrusters(v);
  model.turret = ToTurretParameters(scenario);
  model.initial_turret_angle = v.InitialTurretAngle();
  model.initial_pose = v.initial_pose;

  const EnvironmentSpec& env = scenario.environment;
  if (env.hull_viscous_drag) model.hull_drag = ToHullGeometry(v, water.density);
  if (env.waves.enabled) model.waves = ToSeaModel(env.waves, water.gravity);
  if (env.wind.enabled) {
    simulation::WindModel& wind = model.wind.emplace();
    wind.hull = ToWindParameters(v);
    wind.speed = {.mean_speed = env.wind.speed, .components = env.wind.components};
    wind.direction_from = env.wind.direction_from;
    wind.gust = env.wind.gust;
  }
  model.pose_sensors = ToPoseSensorSpec(scenario.sensors);
  model.pose_faults = ToPoseFaults(scenario.sensors);
  model.tension_cells = ToTensionCells(scenario.sensors);
  model.controller = ToControllerModel(scenario.controller, v.initial_pose);
  model.failure = ToFailure(scenario);
  if (!scenario.detectors.empty()) model.detection = ToDetectionSetup(scenario);
  return model;
}

}  // namespace moorsim::scenarios
