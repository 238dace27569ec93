#include "vessel/controller.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "core/observer_state.h"

namespace moorsim::vessel {

namespace {

// R(psi)^T v: a [force, force, moment] vector from NED into body axes.
Vec3 NedToBody(const Vec3& v, double psi) {
  return YawRotation(std::cos(psi), std::sin(psi)).transpose() * v;
}

void Require(bool ok, const std::string& field, double value, const char* rule) {
  if (!ok) throw InputError(field + " = " + FormatNumber(value) + ": " + rule);
}

std::string Indexed(const std::string& field, int i) {
  return field + "[" + std::to_string(i) + "]";
}

void RequireNonNegative(const Vec3& v, const std::string& field) {
  for (int i = 0; i < 3; ++i) {
    Require(std::isfinite(v[i]) && v[i] >= 0.0, Indexed(field, i), v[i], "must be finite and >= 0");
  }
}

void RequirePositive(const Vec3& v, const std::string& field) {
  for (int i = 0; i < 3; ++i) {
    Require(std::isfinite(v[i]) && v[i] > 0.0, Indexed(field, i), v[i], "must be finite and > 0");
  }
}

void RequireFinite(const Mat3& m, const std::string& field) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      Require(std::isfinite(m(r, c)),
              field + "(" + std::to_string(r) + "," + std::to_string(c) + ")", m(r, c),
              "must be finite");
    }
  }
}

// Keeps |ki z| <= limit where a limit is set.
void ClampIntegral(const Vec3& ki, const Vec3& limit, int i, Vec3* z) {
  if (limit[i] > 0.0 && ki[i] > 0.0) {
    const double z_max = limit[i] / ki[i];
    (*z)[i] = std::clamp((*z)[i], -z_max, z_max);
  }
}

bool Fresh(const PoseMeasurementInput& m, int i) {
  return m.valid[static_cast<std::size_t>(i)] && std::isfinite(m.pose[i]);
}

}  // namespace

ManoeuvringModel SeedManoeuvringModel() {
  const double m = 1.0041e8;                        // [kg]
  const double inertia_z = m * 54.0 * 54.0;         // radius of gyration 54 m
  const Vec3 added(7.94e6, 6.44e7, 1.45e11);        // A11, A22, A66 at zero frequency
  const Vec3 mass = Vec3(m, m, inertia_z) + added;  // M_RB + A(0), CG on the centreline
  const Vec3 damping_time(50.0, 100.0, 20.0);       // MSS rule T_i [s]
  ManoeuvringModel model;
  model.mass = mass.asDiagonal();
  model.damping = mass.cwiseQuotient(damping_time).asDiagonal();
  model.mooring_stiffness = Vec3(8.157e4, 8.157e4, 5.657e8).asDiagonal();
  return model;
}

// ---------------------------------------------------------------------------------------

PositionController::PositionController(const Vec3& eta_d, double dt) : dt_(dt) {
  Require(std::isfinite(dt) && dt > 0.0, "controller.sample_time", dt, "must be finite and > 0 s");
  SetSetpoint(eta_d);
}

void PositionController::SetSetpoint(const Vec3& eta_d) {
  for (int i = 0; i < 3; ++i) {
    Require(std::isfinite(eta_d[i]), Indexed("controller.setpoint", i), eta_d[i], "must be finite");
  }
  setpoint_ = eta_d;
  setpoint_[2] = WrapAngle(eta_d[2]);
}

// ---------------------------------------------------------------------------------------

PiController::PiController(const PiControllerOptions& options, const Vec3& eta_d, double dt)
    : PositionController(eta_d, dt), options_(options) {
  RequireNonNegative(options.kp, "controller.pi.kp");
  RequireNonNegative(options.ki, "controller.pi.ki");
  RequireNonNegative(options.kd, "controller.pi.kd");
  RequireNonNegative(options.integral_limit, "controller.pi.integral_limit");
  Require(std::isfinite(options.derivative_filter_time) && options.derivative_filter_time >= 0.0,
          "controller.pi.derivative_filter_time", options.derivative_filter_time,
          "must be finite and >= 0 s");
  filter_gain_ = options.derivative_filter_time > 0.0
                     ? -std::expm1(-dt / options.derivative_filter_time)
                     : 1.0;
}

Vec3 PiController::Update(const PoseMeasurementInput& measurement) {
  std::array<bool, 3> fresh{};
  for (int i = 0; i < 3; ++i) {
    const auto k = static_cast<std::size_t>(i);
    fresh[k] = Fresh(measurement, i);
    if (fresh[k]) {
      held_pose_[i] = i == 2 ? WrapAngle(measurement.pose[i]) : measurement.pose[i];
      seen_[k] = true;
    } else if (!seen_[k]) {
      held_pose_[i] = setpoint_[i];  // nothing known yet: no action on this channel
    }
  }

  // The low-passed measurement (exact discrete first-order lag) and its derivative.
  Vec3 rate = Vec3::Zero();
  if (!started_) {
    filtered_pose_ = held_pose_;
    started_ = true;
  } else {
    Vec3 step = held_pose_ - filtered_pose_;
    step[2] = WrapAngle(step[2]);
    step *= filter_gain_;
    filtered_pose_ += step;
    filtered_pose_[2] = WrapAngle(filtered_pose_[2]);
    rate = step / dt_;
  }

  Vec3 error = held_pose_ - setpoint_;
  for (int i = 0; i < 3; ++i) {
    if (options_.filtered_error[static_cast<std::size_t>(i)])
      error[i] = filtered_pose_[i] - setpoint_[i];
  }
  error[2] = WrapAngle(error[2]);
  for (int i = 0; i < 3; ++i) {
    if (!fresh[static_cast<std::size_t>(i)]) continue;  // no integration on held data
    integral_[i] += dt_ * error[i];
    ClampIntegral(options_.ki, options_.integral_limit, i, &integral_);
  }

  const Vec3 force_ned = options_.kp.cwiseProduct(error) + options_.ki.cwiseProduct(integral_) +
                         options_.kd.cwiseProduct(rate);
  return NedToBody(-force_ned, held_pose_[2]);
}

void PiController::SetIntegral(const Vec3& z) {
  for (int i = 0; i < 3; ++i) {
    Require(std::isfinite(z[i]), Indexed("controller.pi.integral", i), z[i], "must be finite");
  }
  integral_ = z;
}

AxisGains SizeAxisGains(double mass, double damping, double stiffness, double natural_period,
                        double damping_ratio) {
  Require(std::isfinite(mass) && mass > 0.0, "gains.mass", mass, "must be finite and > 0");
  Require(std::isfinite(damping) && damping >= 0.0, "gains.damping", damping,
          "must be finite and >= 0");
  Require(std::isfinite(stiffness) && stiffness >= 0.0, "gains.stiffness", stiffness,
          "must be finite and >= 0");
  Require(std::isfinite(natural_period) && natural_period > 0.0, "gains.natural_period",
          natural_period, "must be finite and > 0 s");
  Require(std::isfinite(damping_ratio) && damping_ratio > 0.0, "gains.damping_ratio", damping_ratio,
          "must be finite and > 0");
  const double wn = 2.0 * std::numbers::pi / natural_period;
  AxisGains g;
  g.kp = std::max(0.0, mass * wn * wn - stiffness);
  g.kd = std::max(0.0, 2.0 * damping_ratio * wn * mass - damping);
  g.ki = g.kp * wn / 10.0;
  return g;
}

Vec3 PiController::EstimatedPose() const { return Vec3::Constant(std::nan("")); }
Vec3 PiController::EstimatedVelocity() const { return Vec3::Constant(std::nan("")); }
Vec3 PiController::EstimatedBias() const { return Vec3::Constant(std::nan("")); }

// ---------------------------------------------------------------------------------------

namespace {

// The observer options as ValidatePassiveObserver's messages name them.
constexpr PassiveObserverKeys kObserverKeys{.prefix = "controller.observer_pid.observer.",
                                            .first_index = 0,
                                            .wave_frequency = {"wave_peak_frequency"},
                                            .wave_damping = {"wave_damping", false},
                                            .notch_damping = {"notch_damping", false},
                                            .cutoff_ratio = {"cutoff_ratio", false},
                                            .velocity_gain = {"k4_per_mass"},
                                            .bias_gain = {"k3_ratio", false},
                                            .bias_gain_is_ratio = true};

// The observer of PassiveObserver's comment, after the checks of dt and the model.
PassiveNonlinearObserver MakeObserver(const ManoeuvringModel& model,
                                      const PassiveObserverOptions& options, double dt) {
  const std::string prefix = "controller.observer_pid.";
  Require(std::isfinite(dt) && dt > 0.0, "controller.sample_time", dt, "must be finite and > 0 s");
  RequireFinite(model.mass, prefix + "model.mass");
  RequireFinite(model.damping, prefix + "model.damping");
  RequireFinite(model.mooring_stiffness, prefix + "model.mooring_stiffness");
  RequirePositive(model.mass.diagonal(), prefix + "model.mass.diagonal");
  const Mat3 mass_symmetric = 0.5 * (model.mass + model.mass.transpose());
  if (Eigen::LLT<Mat3>(mass_symmetric).info() != Eigen::Success) {
    throw InputError(prefix + "model.mass: must be positive definite");
  }
  PassiveNonlinearObserverOptions observer;
  observer.wave_frequency = options.wave_peak_frequency;
  observer.wave_damping = Vec3::Constant(options.wave_damping);
  observer.notch_damping = Vec3::Constant(options.notch_damping);
  observer.cutoff_ratio = Vec3::Constant(options.cutoff_ratio);
  observer.bias_time_constant = options.bias_time_constant;
  observer.velocity_gain = options.k4_per_mass;
  observer.bias_gain = options.k3_ratio * options.k4_per_mass;
  observer.mass_scaled_gains = true;
  observer.wave_filter = options.wave_filter;
  observer.hold = PassiveNonlinearObserverOptions::Hold::kFirstOrder;
  observer.start = PassiveNonlinearObserverOptions::Start::kEachChannel;
  observer.max_substep = options.max_substep;
  // G about the neutral pose eta = 0: the heading's distance from it, wrapped.
  auto linear_mooring = [stiffness = model.mooring_stiffness](const Vec3& eta) {
    Vec3 from_neutral = eta;
    from_neutral.z() = WrapAngle(eta.z());
    return Vec3(-stiffness * from_neutral);
  };
  return PassiveNonlinearObserver(observer, model.mass, model.damping, linear_mooring,
                                  kObserverKeys);
}

}  // namespace

PassiveObserver::PassiveObserver(const ManoeuvringModel& model,
                                 const PassiveObserverOptions& options, double dt)
    : observer_(MakeObserver(model, options, dt)), dt_(dt) {}

void PassiveObserver::Update(const PoseMeasurementInput& measurement, const Vec3& tau) {
  std::array<bool, 3> fresh{};
  for (int i = 0; i < 3; ++i) fresh[static_cast<std::size_t>(i)] = Fresh(measurement, i);
  observer_.Update(dt_, tau, measurement.pose, fresh);
}

// ---------------------------------------------------------------------------------------

ObserverPidController::ObserverPidController(const ObserverPidOptions& options, const Vec3& eta_d,
                                             double dt)
    : PositionController(eta_d, dt), observer_(options.model, options.observer, dt) {
  const std::string p = "controller.observer_pid.";
  Require(std::isfinite(options.natural_frequency) && options.natural_frequency > 0.0,
          p + "natural_frequency", options.natural_frequency, "must be finite and > 0 rad/s");
  Require(std::isfinite(options.relative_damping) && options.relative_damping > 0.0,
          p + "relative_damping", options.relative_damping, "must be finite and > 0");
  RequireNonNegative(options.integral_limit, p + "integral_limit");
  const Vec3 mass = options.model.mass.diagonal();
  const double wn = options.natural_frequency;
  kp_ = mass * (wn * wn);
  kd_ = mass * (2.0 * options.relative_damping * wn);
  ki_ = kp_ * (wn / 10.0);
  integral_limit_ = options.integral_limit;
}

Vec3 ObserverPidController::Update(const PoseMeasurementInput& measurement) {
  if (!started_) {
    observer_.Reset(setpoint_);  // channels not yet measured start at the setpoint
    started_ = true;
  }
  observer_.Update(measurement, tau_held_);
  const Vec3 eta = observer_.eta_hat();
  Vec3 error = eta - setpoint_;
  error[2] = WrapAngle(error[2]);
  for (int i = 0; i < 3; ++i) {
    if (!observer_.fresh(i)) continue;
    integral_[i] += dt_ * error[i];
    ClampIntegral(ki_, integral_limit_, i, &integral_);
  }
  const Vec3 force_ned = kp_.cwiseProduct(error) + ki_.cwiseProduct(integral_);
  tau_held_ = NedToBody(-force_ned, eta[2]) - kd_.cwiseProduct(observer_.nu_hat());
  return tau_held_;
}

// ---------------------------------------------------------------------------------------

Vec3 IdleController::EstimatedPose() const { return Vec3::Constant(std::nan("")); }
Vec3 IdleController::EstimatedVelocity() const { return Vec3::Constant(std::nan("")); }
Vec3 IdleController::EstimatedBias() const { return Vec3::Constant(std::nan("")); }

// ---------------------------------------------------------------------------------------

std::unique_ptr<PositionController> MakeController(const ControllerSpec& spec, double dt) {
  switch (spec.type) {
    case ControllerType::kNone:
      return std::make_unique<IdleController>(spec.setpoint, dt);
    case ControllerType::kObserverPid:
      return std::make_unique<ObserverPidController>(spec.observer_pid, spec.setpoint, dt);
    case ControllerType::kPi:
      return std::make_unique<PiController>(spec.pi, spec.setpoint, dt);
  }
  throw ContractError("MakeController: a controller type without a controller");
}

ControllerSpec WithHeadingLoop(ControllerSpec spec, const HeadingLoopTuning& tuning,
                               const VesselModel& vessel) {
  const AxisGains yaw = SizeAxisGains(vessel.mass()(5, 5), vessel.parameters().linear_damping(5, 5),
                                      0.0, tuning.natural_period, tuning.damping_ratio);
  spec.pi.kp(2) = yaw.kp;
  spec.pi.kd(2) = yaw.kd;
  spec.pi.ki(2) = yaw.ki;
  spec.pi.filtered_error[2] = true;
  return spec;
}

}  // namespace moorsim::vessel
