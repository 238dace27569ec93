#include "simulation/simulation.h"

#include "simulation/detection_models.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "core/random.h"
#include "core/sample_clock.h"
#include "detectors/dht.h"
#include "detectors/ekf_observer.h"
#include "detectors/glr.h"
#include "detectors/glr_signatures.h"
#include "detectors/hypothesis_bank.h"
#include "detectors/innovation_covariance.h"
#include "detectors/passive_observer.h"
#include "detectors/registry.h"
#include "mooring_fem/environment.h"
#include "mooring_fem/line_simulation.h"
#include "simulation/shared_parts.h"
#include "vessel/controller.h"
#include "vessel/fpso_model.h"
#include "vessel/hull_loads.h"
#include "vessel/rigid_body.h"
#include "vessel/sensors.h"
#include "vessel/thrusters.h"
#include "vessel/wave_response.h"
#include "vessel/waves.h"

namespace moorsim::simulation {

namespace {

/// A constant Earth-frame horizontal force and yaw moment, rotated into body axes.
class ExternalLoad final : public vessel::EnvironmentLoad {
 public:
  std::string_view name() const override { return "external"; }
  Vec6 Load(double /*t*/, const Vec6& eta, const Vec6& /*nu*/) const override {
    const double c = std::cos(eta(5)), s = std::sin(eta(5));
    Vec6 tau = Vec6::Zero();
    tau(0) = c * load_.x() + s * load_.y();
    tau(1) = -s * load_.x() + c * load_.y();
    tau(5) = load_.z();
    return tau;
  }
  void Jacobian(double /*t*/, const Vec6& eta, const Vec6& /*nu*/, Mat6* J_eta,
                Mat6* J_nu) const override {
    const double c = std::cos(eta(5)), s = std::sin(eta(5));
    J_eta->setZero();
    J_nu->setZero();
    (*J_eta)(0, 5) = -s * load_.x() + c * load_.y();
    (*J_eta)(1, 5) = -c * load_.x() - s * load_.y();
  }
  Vec3 load_ = Vec3::Zero();
};

/// Viscous hull load from the velocity relative to the current: the profile's surface
/// speed, or a table's horizontal velocity at the surface where the vessel is (its
/// variation over the vessel's position is left out of the Jacobian, which only steers
/// Newton's iteration).
class HullCurrentLoad final : public vessel::EnvironmentLoad {
 public:
  HullCurrentLoad(const vessel::HullGeometry& hull, const mooring_fem::CurrentProfile& current)
      : load_(hull), table_(current.table != nullptr), field_(current) {
    if (!table_) {
      current_ = current.SurfaceSpeed() *
                 Vec3(std::cos(current.direction), std::sin(current.direction), 0.0);
    }
  }
  std::string_view name() const override { return "current"; }
  Vec6 Load(double t, const Vec6& eta, const Vec6& nu) const override {
    return load_.Load(eta, nu, CurrentAt(t, eta));
  }
  void Jacobian(double t, const Vec6& eta, const Vec6& nu, Mat6* J_eta, Mat6* J_nu) const override {
    load_.Jacobian(eta, nu, CurrentAt(t, eta), J_eta, J_nu);
  }

 private:
  Vec3 CurrentAt(double t, const Vec6& eta) const {
    if (!table_) return current_;
    Vec3 c = field_.VelocityAt(t, Vec3(eta(0), eta(1), 0.0));
    c.z() = 0.0;
    return c;
  }

  vessel::CurrentLoad load_;
  bool table_;  // the current is a table (field_), not a profile
  mooring_fem::CurrentField field_;
  Vec3 current_ = Vec3::Zero();  // a profile's surface current
};

/// Wind on the superstructure: mean speed plus the NPD gust, from a fixed direction. Its
/// Jacobian is left out (the relative-wind dependence on the vessel's velocity is ~1e-3 of
/// the hull's viscous damping; the Jacobian only steers Newton's iteration).
class HullWindLoad final : public vessel::EnvironmentLoad {
 public:
  HullWindLoad(const WindModel& wind, std::uint64_t seed) : load_(wind.hull), wind_(wind) {
    if (wind.gust && wind.speed.mean_speed > 0.0) {
      RandomStream stream = RandomStream::Derive(seed, "wind.gust");
      gust_.emplace(wind.speed, stream);
    }
  }
  std::string_view name() const override { return "wind"; }
  Vec6 Load(double t, const Vec6& eta, const Vec6& nu) const override {
    const double speed = gust_ ? gust_->Speed(t) : wind_.speed.mean_speed;
    return load_.Load(eta, nu, speed, wind_.direction_from);
  }
  void Jacobian(double, const Vec6&, const Vec6&, Mat6* J_eta, Mat6* J_nu) const override {
    J_eta->setZero();
    J_nu->setZero();
  }

 private:
  vessel::WindLoad load_;
  WindModel wind_;
  std::optional<vessel::WindGust> gust_;
};

}  // namespace

vessel::WaveRealisation RealiseSea(const SeaModel& sea, std::uint64_t seed) {
  if (!sea.trains.empty()) return vessel::WaveRealisation(sea.trains, sea.realisation.gravity);
  const vessel::JonswapSpectrum spectrum(sea.spectrum);
  RandomStream stream = RandomStream::Derive(seed, "waves");
  return vessel::WaveRealisation(spectrum, sea.realisation, stream);
}

std::shared_ptr<const mooring_fem::WaveKinematics> LineWaves(
    const vessel::WaveRealisation& sea, const mooring_fem::Water& water,
    mooring_fem::WaveStretching stretching) {
  std::vector<mooring_fem::WaveTrain> trains;
  for (const vessel::WaveComponent& c : sea.components()) {
    trains.push_back({c.omega, c.amplitude, c.phase, c.direction});
  }
  return std::make_shared<const mooring_fem::WaveKinematics>(trains, water.depth, water.gravity,
                                                             stretching);
}

namespace {

/// The realised sea of the model: JONSWAP, random phases and frequencies from the stream
/// "waves" of the run seed, and the hull's response to it.
class Sea final : public vessel::SeaResponse {
 public:
  Sea(const SeaModel& sea, const vessel::HydroData& hydro, std::uint64_t seed)
      : realisation_(RealiseSea(sea, seed)),
        response_(hydro, realisation_, {.gravity = sea.realisation.gravity}) {}
  void Evaluate(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot,
                Vec6* drift) const override {
    response_.Evaluate(t, x, y, psi, xi, xi_dot, drift);
  }
  const vessel::WaveRealisation& realisation() const { return realisation_; }

 private:
  vessel::WaveRealisation realisation_;
  vessel::WaveResponse response_;
};

/// The WAMIT data of `stem` read with `options`, once per process (shared_parts.h).
std::shared_ptr<const vessel::HydroData> SharedHydroData(const std::string& stem,
                                                         const vessel::WamitOptions& options) {
  char key[128];
  std::snprintf(key, sizeof key, "\n%.17g %.17g %.17g", options.water_density, options.gravity,
                options.length_scale);
  std::string name = "WAMIT ";  // built in steps: GCC 12 warns wrongly on "..." + string
  name += stem;
  name += key;
  return SharedPart<vessel::HydroData>(name, [&] { return vessel::ReadWamit(stem, options); });
}

}  // namespace

struct Simulation::Parts {
  ExternalLoad external;
  std::optional<HullCurrentLoad> current;
  std::optional<HullWindLoad> wind;
  std::optional<Sea> sea;
  std::optional<vessel::PoseSensors> sensors;
  std::optional<vessel::TensionCells> tension_cells;
  std::unique_ptr<vessel::PositionController> controller;
  std::optional<vessel::ThrustAllocator> allocator;
  std::optional<vessel::ThrusterDynamics> thruster_dynamics;
  Eigen::VectorXd directions;
  std::vector<double> measured_tensions;
  Vec3 thrust_issued = Vec3::Zero();  // what the allocation sent to the thrusters
};

Simulation::Simulation(const PlantModel& model, std::uint64_t seed)
    : model_(model),
      seed_(seed),
      hydro_(SharedHydroData(model.hydrodynamics, model.wamit)),
      mooring_(model.mooring),
      attachment_(mooring_),
      parts_(std::make_unique<Parts>()),
      controller_clock_(model.controller.rate, "controller.rate_hz") {
  plant_ = std::make_unique<vessel::VesselPlant>(
      vessel::LowFrequencyVessel(*hydro_, model_.mass, model_.damping), model_.thrusters);
  plant_->SetTurret(model_.turret);
  plant_->AddLoad(&parts_->external);
  if (model_.hull_drag) {
    parts_->current.emplace(*model_.hull_drag, model_.mooring.current);
    plant_->AddLoad(&*parts_->current);
  }
  if (model_.waves) {
    parts_->sea.emplace(*model_.waves, *hydro_, seed_);
    plant_->SetSea(&*parts_->sea);
    // The same components, in the lines' finite depth.
    if (model_.waves->on_lines) {
      mooring_.SetWaves(
          LineWaves(parts_->sea->realisation(), model_.mooring.water, *model_.waves->on_lines));
    }
  }
  if (model_.wind) {
    parts_->wind.emplace(*model_.wind, seed_);
    plant_->AddLoad(&*parts_->wind);
  }
  parts_->sensors.emplace(model_.pose_sensors, seed_);
  for (const PoseFault& f : model_.pose_faults) parts_->sensors->AddFault(f.channel, f.fault);
  parts_->controller = vessel::MakeController(model_.controller.SizedFor(plant_->model()),
                                              1.0 / model_.controller.rate);
  parts_->allocator.emplace(plant_->thrusters());
  parts_->thruster_dynamics.emplace(plant_->thrusters());
  parts_->directions.resize(plant_->num_thrusters());
  for (int k = 0; k < plant_->num_thrusters(); ++k) {
    parts_->directions(k) = plant_->thrusters()[k].angle;
  }
  if (model_.tension_cells) {
    const TensionCellsModel& cells = *model_.tension_cells;
    parts_->tension_cells.emplace(mooring_.num_lines(), cells.noise, cells.rate, seed_);
    for (const vessel::CellFault& fault : cells.faults) parts_->tension_cells->AddFault(fault);
  }
  failure_pending_ = model_.failure.has_value();

  system_ = std::make_unique<CoupledSystem>(*plant_, attachment_);
  x_.assign(system_->StateSize(), 0.0);
  SettleMooredEquilibrium();
  if (model_.detection && !model_.detection->detectors.empty()) {
    detection_ = std::make_unique<Detection>(model_, plant_->model(), initial_pose_);
  }
  StartIntegrator();
}

Simulation::~Simulation() = default;

std::unique_ptr<Detection> MakeDetection(const PlantModel& model, std::uint64_t seed) {
  if (!model.detection || model.detection->detectors.empty()) {
    throw InputError("detectors: none (detection needs at least one)");
  }
  PlantModel plant_only = model;
  plant_only.detection.reset();
  const Simulation start(plant_only, seed);
  return std::make_unique<Detection>(model, start.plant_model(), start.initial_pose());
}

int Simulation::num_hypotheses() const { return detection_ ? detection_->num_hypotheses() : 0; }

std::vector<std::string> Simulation::HypothesisLabels() const {
  return detection_ ? detection_->HypothesisLabels() : std::vector<std::string>();
}

const std::vector<DetectorRecord>& Simulation::detector_records() const {
  static const std::vector<DetectorRecord> kNone;
  return detection_ ? detection_->records() : kNone;
}

const DetectionTiming& Simulation::detection_timing() const {
  static const DetectionTiming kNone;
  return detection_ ? detection_->timing() : kNone;
}

void Simulation::KeepDetectionInput(bool keep) {
  if (detection_) detection_->KeepInput(keep);
}

std::vector<PointKinematics> Simulation::Points() {
  std::vector<PointKinematics> points(mooring_.num_lines());
  for (int i = 0; i < mooring_.num_lines(); ++i) {
    points[i] = plant_->PointMotion(t_, x_.data(), mooring_.line(i).fairlead_body, nullptr);
  }
  return points;
}

void Simulation::SettleMooredEquilibrium() {
  // Heave, roll and pitch balance the lines' weight in calm water: G (z, phi, theta) =
  // tau_mooring with the fairleads where the low-frequency pose puts them. The mooring's
  // vertical stiffness is small next to the hydrostatic one (8 lines x ~5 MN over C33 =
  // 8.4e7 N/m: 0.47 m), so the fixed-point iteration converges in a few steps. This
  // equilibrium depends on the model alone, not on the run's seed, so the detectors'
  // models built on it are shared by every seed (shared_parts.h); the first-order wave
  // motion rides on it with zero mean.
  const Vec3 pose = model_.initial_pose;
  x_.assign(system_->StateSize(), 0.0);
  x_[0] = pose.x();
  x_[1] = pose.y();
  x_[5] = pose.z();
  // A turret on its bearing starts at its own heading (default: the hull's), its angle to
  // the hull the difference; the fairleads turn with it about the turret centre.
  const double turret_angle = model_.initial_turret_angle;
  if (plant_->turret_turns()) {
    x_[static_cast<std::size_t>(plant_->turret_state())] = turret_angle;
  }
  const int nb = plant_->StateSize();
  double* lines = x_.data() + nb;
  const Eigen::Matrix3d G = plant_->model().parameters().restoring.block<3, 3>(2, 2);
  std::vector<Vec3> fairleads(mooring_.num_lines());
  std::vector<Vec3> forces(mooring_.num_lines());
  std::vector<PointKinematics> calm(mooring_.num_lines());  // at rest, no wave motion
  auto calm_fairleads = [&] {
    const Vec3 origin(x_[0], x_[1], x_[2]);
    const Mat3 R = vessel::RotationBodyToNed(x_[3], x_[4], x_[5]);
    for (int i = 0; i < mooring_.num_lines(); ++i) {
      calm[i].position =
          origin + R * plant_->OnTurret(mooring_.line(i).fairlead_body, turret_angle);
      fairleads[i] = calm[i].position;
    }
  };
  bool first = true;
  constexpr int kMaxIterations = 30;
  double change = std::numeric_limits<double>::infinity();
  for (int iteration = 0; iteration < kMaxIterations && !(change < 1e-9); ++iteration) {
    calm_fairleads();
    if (first) mooring_.CatenaryState(fairleads, lines);
    first = false;
    mooring_.SettleStatic(fairleads, lines);
    mooring_.FairleadForces(lines, calm, forces);
    Vec6 tau = Vec6::Zero();
    for (int i = 0; i < mooring_.num_lines(); ++i) {
      tau += plant_->PointLoad(x_.data(), mooring_.line(i).fairlead_body, forces[i], nullptr);
    }
    const Eigen::Vector3d updated = G.lu().solve(tau.segment<3>(2));
    change = (updated - Eigen::Vector3d(x_[2], x_[3], x_[4])).norm();
    x_[2] = updated(0);
    x_[3] = updated(1);
    x_[4] = updated(2);
  }
  if (!(change < 1e-9)) {
    std::ostringstream message;
    message << "moored static equilibrium (heave, roll, pitch) did not converge in "
            << kMaxIterations << " iterations: last change " << change
            << " (m, rad; tolerance 1e-9); the lines' vertical load is too large for the "
               "hull's hydrostatic stiffness";
    throw Error(message.str());
  }
  initial_pose_ = Eigen::Map<const Vec6>(x_.data());
  plant_->SetStaticVerticalLoad((plant_->model().parameters().restoring * initial_pose_)(2));
  // The lines start settled to the fairleads where the wave motion puts them at t = 0, so
  // that the run starts without a transient (in calm water these are the calm ones).
  calm_fairleads();
  const std::vector<Vec3> at_rest = fairleads;
  const std::vector<PointKinematics> points = Points();
  for (int i = 0; i < mooring_.num_lines(); ++i) fairleads[i] = points[i].position;
  if (fairleads != at_rest) mooring_.SettleStatic(fairleads, lines);
}

void Simulation::StartIntegrator() {
  if (integrator_) finished_ += integrator_->stats();
  system_->Rebuild();
  const mooring_fem::SolverSettings& solver = model_.solver;
  IntegratorOptions options = mooring_fem::MakeIntegratorOptions(solver, mooring_);
  const int nb = plant_->StateSize();
  // Body tolerances: positions like the nodes; angles so that 20 m from the turret centre
  // the fairlead moves by atol_position; thrust to 10 N (out of ~1e5-1e6); the turret's
  // angle and rate like the hull's.
  const double angle = solver.atol_position / 20.0;
  const double rate = solver.atol_velocity / 20.0;
  std::vector<double> body_atol = {
      solver.atol_position, solver.atol_position, solver.atol_position, angle, angle, angle,
      solver.atol_velocity, solver.atol_velocity, solver.atol_velocity, rate,  rate,  rate};
  body_atol.resize(12 + plant_->num_thrusters(), 10.0);
  if (plant_->turret_turns()) {
    body_atol.push_back(angle);
    body_atol.push_back(rate);
  }
  options.atol.insert(options.atol.begin(), body_atol.begin(), body_atol.end());
  // Error weights relative to each position's displacement since this start.
  const std::vector<char> kinds = mooring_.StateKinds();
  options.reference.assign(x_.size(), 0.0);
  for (int i = 0; i < 6; ++i) options.reference[i] = x_[i];
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    if (kinds[i] == 'p') options.reference[nb + i] = x_[nb + i];
  }
  integrator_ = std::make_unique<Integrator>(*system_, t_, x_.data(), options);
}

double Simulation::NextEventTime() const {
  // Every clock is asked by its integer sample index (core/sample_clock.h), and every
  // instant at or before t_ has been handled by DiscreteEvents, so each candidate lies
  // strictly after t_.
  double next = std::numeric_limits<double>::infinity();
  if (failure_pending_) next = std::min(next, model_.failure->time);
  next = std::min(next, parts_->sensors->NextSampleTime(t_));
  next = std::min(next, controller_clock_.Instant(next_control_index_));
  if (parts_->tension_cells) next = std::min(next, parts_->tension_cells->NextSampleTime(t_));
  return next;
}

void Simulation::DiscreteEvents() {
  // Sensors first (they see the state at this instant), then the controller acts on them,
  // then the detectors take the sample with the thrust just issued, which holds until the
  // next sample (Observation::tau_command), and the tension cells' sample of this instant.
  std::array<bool, 3> fresh = {false, false, false};
  std::optional<vessel::PoseMeasurement> sampled;
  if (parts_->sensors->Due(t_) && t_ > last_sensor_time_) {
    const Vec6 pose = plant_->TotalPose(t_, x_.data());
    const vessel::PoseMeasurement m = parts_->sensors->Sample(t_, Vec3(pose(0), pose(1), pose(5)));
    for (int i = 0; i < 3; ++i) {
      if (m.valid[i]) last_measurement_(i) = m.value(i);
      fresh[i] = m.valid[i];
    }
    last_sensor_time_ = t_;
    sampled = m;
  }
  if (parts_->tension_cells && parts_->tension_cells->Due(t_) && t_ > last_tension_time_) {
    parts_->measured_tensions = parts_->tension_cells->Sample(t_, FairleadTensions());
    last_tension_time_ = t_;
  }
  const double dt = 1.0 / controller_clock_.rate();
  if (const std::int64_t k = controller_clock_.LastIndex(t_); k >= next_control_index_) {
    next_control_index_ = k + 1;
    vessel::PoseMeasurementInput input;
    input.time = t_;
    input.pose = last_measurement_;
    input.valid = fresh;
    tau_command_ = thrust_override_ ? *thrust_override_ : parts_->controller->Update(input);
    const vessel::Allocation a = parts_->allocator->Allocate(tau_command_);
    parts_->thrust_issued = a.achieved;
    const double heading_error = std::abs(WrapAngle(x_[5] - parts_->controller->setpoint()(2)));
    station_keeping_.updates += 1;
    station_keeping_.saturated += a.saturated ? 1 : 0;
    // The largest error up to the failure: what a parted line does to the heading afterwards
    // is the failure's doing, not the station keeping's.
    if (!model_.failure || failure_pending_) {
      station_keeping_.heading_error_max =
          std::max(station_keeping_.heading_error_max, heading_error);
    }
    station_keeping_.heading_error_last = heading_error;
    parts_->thruster_dynamics->Step(a.thrust, dt);
    parts_->directions = a.direction;
    plant_->SetThrustCommand(parts_->thruster_dynamics->command(), parts_->directions);
  }
  if (sampled && detection_) {
    // The detectors see what a real system has: the measured pose and the thrust the
    // allocation sent to the thrusters (after its saturation handling) from now on.
    detectors::Observation observation;
    observation.t = t_;
    observation.pose = sampled->value;
    observation.valid = sampled->valid;
    observation.tau_command = parts_->thrust_issued;
    if (!parts_->measured_tensions.empty()) {
      observation.tensions = Eigen::Map<const VecX>(parts_->measured_tensions.data(),
                                                    parts_->measured_tensions.size());
    }
    detection_->Update(observation);
  }
  if (failure_pending_ && t_ >= model_.failure->time) {
    failure_pending_ = false;
    const int nb = plant_->StateSize();
    const std::vector<PointKinematics> points = Points();
    std::vector<double> lines =
        mooring_.ApplyFailure(model_.failure->failure, x_.data() + nb, points);
    x_.resize(nb);
    x_.insert(x_.end(), lines.begin(), lines.end());
    StartIntegrator();
  }
}

void Simulation::AdvanceTo(double t, const std::function<bool()>& interrupt) {
  const auto start = std::chrono::steady_clock::now();
  AdvanceThroughEvents(
      t, [this]() -> Integrator& { return *integrator_; },
      [this](double) { return NextEventTime(); },
      [this, t, &interrupt](double now) {
        if (now > t_) {
          t_ = now;
          std::copy(integrator_->state(), integrator_->state() + x_.size(), x_.begin());
        }
        DiscreteEvents();
        if (interrupt && t_ < t && interrupt()) {
          throw Interrupted("interrupted at t = " + FormatNumber(t_) + " s");
        }
      });
  integrator_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Simulation::SetExternalLoad(const Vec3& load) { parts_->external.load_ = load; }

bool Simulation::estimates_load() const { return detection_ && detection_->estimates_load(); }

Sample Simulation::Record() {
  Sample s;
  s.time = t_;
  const Eigen::Map<const Vec6> eta(x_.data()), nu(x_.data() + 6);
  s.pose_low_frequency = eta;
  s.velocity = nu;
  s.pose_true = plant_->TotalPose(t_, x_.data());
  s.pose_measured = last_measurement_;
  s.fairlead_tension = FairleadTensions();  // also leaves the mooring load in system_
  s.load_mooring = system_->attachment_load();
  if (plant_->turret_turns()) {
    double lines = 0.0, bearing = 0.0;
    plant_->TurretMoments(x_.data(), s.load_mooring, &lines, &bearing);
    const int a = plant_->turret_state();
    s.turret = Eigen::Vector4d(x_[a], x_[a + 1] - nu(5), lines, bearing);
    s.load_mooring(5) += bearing - lines;
  }
  s.load_thrust = plant_->ThrustLoad(x_.data());
  s.thrust_delivered = Vec3(s.load_thrust(0), s.load_thrust(1), s.load_thrust(5));
  s.thrust_commanded = tau_command_;
  s.tension_measured = parts_->measured_tensions;
  if (detection_) {
    s.detectors = detection_->verdicts();
    s.observer_bias = detection_->bias();
    s.observer_wave_motion = detection_->wave_motion();
    s.detection_input = detection_->TakeInput();
  }
  Vec6 xi, xi_dot;
  plant_->Sea(t_, x_.data(), &xi, &xi_dot, &s.load_wave_drift);
  if (parts_->current) s.load_current = parts_->current->Load(t_, eta, nu);
  if (parts_->wind) s.load_wind = parts_->wind->Load(t_, eta, nu);
  return s;
}

std::vector<double> Simulation::FairleadTensions() {
  std::vector<double> xdot(x_.size());
  system_->Derivatives(t_, x_.data(), xdot.data());
  std::vector<Vec3> forces(system_->forces().begin(), system_->forces().end());
  // The lines up to free points: their tension at the point.
  mooring_.PointEndForces(x_.data() + plant_->StateSize(), system_->points(), forces);
  std::vector<double> tensions(mooring_.num_lines());
  for (int i = 0; i < mooring_.num_lines(); ++i) tensions[i] = forces[i].norm();
  return tensions;
}

std::vector<std::vector<double>> Simulation::SegmentTensions() {
  const std::vector<PointKinematics> points = Points();
  const double* lines = x_.data() + plant_->StateSize();
  std::vector<std::vector<double>> tensions(mooring_.num_lines());
  for (int i = 0; i < mooring_.num_lines(); ++i) {
    tensions[i] = mooring_.SegmentTensions(lines, i, points);
  }
  return tensions;
}

std::vector<std::vector<Vec3>> Simulation::NodePositions() {
  const std::vector<PointKinematics> points = Points();
  const double* lines = x_.data() + plant_->StateSize();
  std::vector<std::vector<Vec3>> nodes(mooring_.num_lines());
  for (int i = 0; i < mooring_.num_lines(); ++i) {
    const int n = mooring_.line(i).segments;
    for (int node = 0; node <= n; ++node) {
      nodes[i].push_back(mooring_.NodePosition(lines, i, node, points));
    }
  }
  return nodes;
}

double Simulation::MechanicalEnergy() {
  const Eigen::Map<const Vec6> eta(x_.data()), nu(x_.data() + 6);
  const int nb = plant_->StateSize();
  const std::vector<PointKinematics> points = Points();
  double turret = 0.0;  // the turret's own kinetic energy of turning
  if (plant_->turret_turns()) {
    const double omega = x_[plant_->turret_state() + 1];
    turret = 0.5 * plant_->turret().inertia * omega * omega;
  }
  return plant_->model().Energy(eta, nu) + turret +
         mooring_.MechanicalEnergy(x_.data() + nb, points);
}

IntegratorStats Simulation::stats() const {
  IntegratorStats s = finished_;
  if (integrator_) s += integrator_->stats();
  return s;
}

}  // namespace moorsim::simulation
