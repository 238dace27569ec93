// Position-mooring controllers for the horizontal plane (surge, sway, yaw): discrete
// controllers that run at a fixed sample time between integrator stops, take the measured
// pose and return the commanded generalised thrust tau = [X, Y, N] in body axes.
//
// Frames and signs: eta = [x north, y east, psi] in NED [m, m, rad], heading psi from north
// toward east; body x forward, y starboard. R(psi) rotates body vectors into NED, so a
// force F_ned wanted in the Earth frame is commanded as tau = R(psi)^T F_ned. Heading
// errors are wrapped to (-pi, pi], so a vessel 2 deg past its setpoint across +-180 deg is
// 2 deg off, not 358 deg.
//
// Controllers, built by name through MakeController():
//   "none"          zero thrust;
//   "pi"            the TAPM thesis's controller (its section 4.3, eq. 4.1-4.2);
//   "observer_pid"  the MSS nonlinear MIMO PID (Fossen 2011 chapter 12; MSS
//                   PIDnonlinearMIMO) on the low-frequency estimates of the
//                   passive nonlinear observer with wave filtering (Fossen & Strand 1999,
//                   Automatica 35; Fossen 2011 section 11.4.1; TAPM thesis eq. 3.18-3.19).
//
// Update() is called once per sample and allocates nothing; everything is sized at
// construction.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/choice.h"
#include "core/passive_observer.h"
#include "core/types.h"
#include "vessel/vessel_model.h"

namespace moorsim::vessel {

/// One sample of the position reference (x, y) and the gyro (psi).
///
/// A channel whose `valid` flag is false, or whose value is not finite, is missing. The
/// controllers then hold that channel's last valid value (before the first valid value:
/// the setpoint, i.e. no action on that channel), stop integrating its error, and the
/// observer runs open-loop on it (no output injection on that channel). Each controller's
/// comment says exactly what it does.
struct PoseMeasurementInput {
  double time = 0.0;         ///< sample time [s]; informational, calls are assumed dt apart
  Vec3 pose = Vec3::Zero();  ///< measured [x m, y m, psi rad], NED
  std::array<bool, 3> valid = {true, true, true};  ///< per channel x, y, psi
};

/// The horizontal-plane low-frequency model the observer predicts with (Fossen 2011
/// section 7.1 low-speed model with a linearised position mooring; TAPM thesis eq. 3.13-3.14):
///   eta' = R(psi) nu,   M nu' + D nu + R(psi)^T G (eta) = tau + R(psi)^T b.
/// Rows and columns are surge, sway, yaw.
struct ManoeuvringModel {
  Mat3 mass = Mat3::Zero();               ///< M = M_RB + A(0) [kg; kg m^2 in yaw], body
  Mat3 damping = Mat3::Zero();            ///< D [N s/m, N m s/rad], body
  Mat3 mooring_stiffness = Mat3::Zero();  ///< G [N/m, N m/rad], NED, about eta = 0
};

/// The seed FPSO (docs/design.md section 9): M = diag(m + A11, m + A22, m 54^2 + A66) with
/// m = 1.0041e8 kg, A11 = 7.94e6 kg, A22 = 6.44e7 kg, A66 = 1.45e11 kg m^2; D by the MSS
/// rule D_ii = M_ii / T_i with T = 50, 100, 20 s; G linearised about the neutral pose of
/// scenarios/library/seed_tapm.yaml (`moorsim static --offset` at +-1 m and +-1 deg):
/// 81.57 kN/m in surge and sway, 5.657e8 N m/rad in yaw (body-fixed fairleads on the 20 m
/// turret). The yaw term is only meaningful near heading 0, the lines' neutral heading.
ManoeuvringModel SeedManoeuvringModel();

/// The controllers MakeController builds: zero thrust, the TAPM thesis's PI, or the
/// nonlinear PID on the passive observer's estimates.
enum class ControllerType { kNone, kObserverPid, kPi };
inline constexpr std::string_view kControllerTypeNames[] = {"none", "observer_pid", "pi"};
constexpr ChoiceInfo ChoicesOf(ControllerType) { return {"controller", kControllerTypeNames}; }

/// A discrete horizontal-plane position controller.
class PositionController {
 public:
  virtual ~PositionController() = default;

  /// Takes the sample at the current controller tick (calls are `sample_time()` apart) and
  /// returns the commanded tau = [X N, Y N, N N m] in body axes, to be held until the next
  /// call. Never returns a non-finite value for finite parameters; allocates nothing.
  virtual Vec3 Update(const PoseMeasurementInput& measurement) = 0;

  /// The controller's type name ("none", "pi", "observer_pid").
  virtual std::string_view name() const = 0;

  /// Internal estimates for logging: low-frequency pose eta_hat [m, m, rad] (NED), velocity
  /// nu_hat [m/s, m/s, rad/s] (body) and bias b_hat [N, N, N m] (NED). All NaN where the
  /// controller has no such estimate (the PI has none).
  virtual Vec3 EstimatedPose() const = 0;
  virtual Vec3 EstimatedVelocity() const = 0;
  virtual Vec3 EstimatedBias() const = 0;

  /// Moves the setpoint eta_d = [x m, y m, psi rad] (NED; psi is wrapped to (-pi, pi]).
  /// The integral state is kept: it holds the compensation of the slowly varying loads.
  /// Throws moorsim::InputError on a non-finite value.
  void SetSetpoint(const Vec3& eta_d);
  const Vec3& setpoint() const { return setpoint_; }
  /// Controller sample time dt [s].
  double sample_time() const { return dt_; }

 protected:
  PositionController(const Vec3& eta_d, double dt);

  Vec3 setpoint_ = Vec3::Zero();
  double dt_ = 1.0;
};

// ---------------------------------------------------------------------------------------
// Gains from a closed-loop bandwidth.

/// Gains of one degree of freedom m x'' + d x' + k x = tau under tau = -(kp x + kd x' + ki
/// int x), placed so that the closed loop's dominant poles have natural frequency omega_n =
/// 2 pi / natural_period and relative damping zeta, with the integral action a decade below
/// (the usual DP rule, Fossen 2011 section 12.2):
///   kp = max(0, m omega_n^2 - k),  kd = max(0, 2 zeta omega_n m - d),  ki = kp omega_n / 10.
/// A plant whose own damping d exceeds 2 zeta omega_n m needs no kd and ends more damped
/// than zeta; one whose stiffness exceeds m omega_n^2 needs no kp. Throws moorsim::InputError
/// on a non-positive mass, period or zeta, or a negative damping or stiffness.
struct AxisGains {
  double kp = 0.0, kd = 0.0, ki = 0.0;
};
AxisGains SizeAxisGains(double mass, double damping, double stiffness, double natural_period,
                        double damping_ratio);

// ---------------------------------------------------------------------------------------
// PI (PID) on the measured pose: the TAPM thesis's controller.

struct PiControllerOptions {
  /// TAPM thesis eq. 4.1-4.2 (the thesis calls them "in no way optimal"): note that the yaw
  /// gains are nearly six orders below the seed turret's yaw stiffness (5.7e8 N m/rad), so
  /// with them the mooring, not the controller, holds the heading.
  Vec3 kp = Vec3(1e5, 1e6, 1e3);  ///< [N/m, N/m, N m/rad], NED axes
  Vec3 ki = Vec3(1e3, 1e3, 1e2);  ///< [N/(m s), N/(m s), N m/(rad s)]
  Vec3 kd = Vec3::Zero();         ///< [N s/m, N s/m, N m s/rad]
  /// Anti-windup: the integral term's contribution |Ki_i z_i| is clamped to this per DOF
  /// [N, N, N m]; 0 = no limit.
  Vec3 integral_limit = Vec3::Zero();
  /// Time constant [s] of the first-order low-pass on the measured pose that the derivative
  /// term differentiates (backward difference); 0 = raw samples.
  double derivative_filter_time = 10.0;
  /// Per DOF: the P and I terms act on the low-passed pose instead of the raw sample (a
  /// heading loop with gains large enough to hold a free turret's hull would otherwise
  /// pass the gyro's noise straight to the thrusters). Default: raw, as the TAPM thesis.
  std::array<bool, 3> filtered_error = {false, false, false};
};

/// The TAPM controller of the TAPM thesis (section 4.3, the MSS PID block, eq. 4.1-4.2), in the
/// physically consistent form of Fossen's nonlinear PID for DP (Fossen 2011 chapter 12):
///   e = eta_m - eta_d (NED; e_psi wrapped),   z_k = z_{k-1} + dt e_k,
///   tau = -R(psi_m)^T (Kp e + Ki z + Kd e')
/// i.e. the gains act along NED axes and the resulting Earth-frame force is rotated into
/// body axes by the measured heading. The thesis does not state the frame of its error;
/// commanding the NED force as body thrust without the rotation would push the vessel the
/// wrong way at its -135 deg initial heading.
/// e' is the backward difference of the low-pass-filtered measurement (derivative on the
/// measurement, so setpoint steps give no kick).
/// Missing channel: its last valid value is held (setpoint before the first one), so its
/// proportional term stays at the last error, its integral is frozen and its filtered
/// value settles on the held value; a missing heading also holds the rotation.
class PiController final : public PositionController {
 public:
  /// Throws moorsim::InputError naming the field ("controller.pi.kp[1] = -5: ...") on a
  /// negative or non-finite option, or dt <= 0.
  PiController(const PiControllerOptions& options, const Vec3& eta_d, double dt);

  Vec3 Update(const PoseMeasurementInput& measurement) override;
  std::string_view name() const override { return ChoiceName(ControllerType::kPi); }
  Vec3 EstimatedPose() const override;
  Vec3 EstimatedVelocity() const override;
  Vec3 EstimatedBias() const override;

  /// Integral state z [m s, m s, rad s] (NED).
  const Vec3& integral() const { return integral_; }
  /// Sets the integral state (a bumpless start: the integral that makes Ki z the standing
  /// NED force already being delivered). Throws moorsim::InputError on a non-finite value.
  void SetIntegral(const Vec3& z);

 private:
  PiControllerOptions options_;
  Vec3 held_pose_ = Vec3::Zero();  // last valid measurement per channel
  std::array<bool, 3> seen_ = {false, false, false};
  Vec3 filtered_pose_ = Vec3::Zero();  // low-passed held pose for the derivative
  Vec3 integral_ = Vec3::Zero();
  double filter_gain_ = 1.0;  // 1 - exp(-dt / T_f)
  bool started_ = false;
};

// ---------------------------------------------------------------------------------------
// Passive nonlinear observer with wave filtering.

struct PassiveObserverOptions {
  /// Peak frequency of the wave-frequency motion per DOF, omega_0 [rad/s] (TAPM thesis table
  /// 4.3: 2 pi / 7 s).
  Vec3 wave_peak_frequency = Vec3::Constant(2.0 * 3.14159265358979323846 / 7.0);
  double wave_damping = 0.1;   ///< lambda [-] of the wave model (Fossen 2011: 0.1)
  double notch_damping = 1.0;  ///< zeta_n [-] of the notch (> lambda; Fossen 2011: 1.0)
  /// omega_c / omega_0 [-], the cut-off of the position low-pass K2 = diag(omega_c)
  /// (TAPM thesis section 4.5 after Fossen 2011: 1.2255; must be > 1).
  double cutoff_ratio = 1.2255;
  /// K4 per unit mass [1/s^2], an acceleration per metre (per rad) of innovation: the
  /// force-level gain is M_e K4 = R M R^T K4, diag(M) k4_per_mass [N/m, N/m, N m/rad] at
  /// heading 0 for a diagonal M. TAPM thesis eq. 4.8 (from Fossen 2011 example 11.6, as the
  /// thesis cites it) gives (0.1, 0.1, 0.01), values for a mass-normalised model: applied
  /// unscaled to SI masses they would move a 1e8 kg vessel's velocity estimate by 1e-9 m/s^2
  /// per metre of error and the bias would never converge (core/passive_observer.h).
  Vec3 k4_per_mass = Vec3(0.1, 0.1, 0.01);
  /// K3 = k3_ratio K4 [1/s^3] (TAPM thesis eq. 4.7: 0.1). Passivity needs
  /// 1/T < K3/K4 < omega_0 < omega_c per DOF (Fossen & Strand 1999).
  double k3_ratio = 0.1;
  Vec3 bias_time_constant = Vec3::Constant(1000.0);  ///< T [s] (TAPM thesis: 1000 s)
  /// true: the wave-frequency model xi_hat is on and eta_hat, nu_hat carry only the
  /// low-frequency motion. false: no wave model (K1 = 0, xi_hat = 0): eta_hat follows the
  /// measurement through K2 alone, wave motion included (a comparison case).
  bool wave_filter = true;
  /// Largest internal integration step [s] (RK4). Default 0.1 s: the fastest observer
  /// poles are near omega_c ~ 1.1 rad/s, so |lambda h| ~ 0.11 and RK4's error per step is
  /// ~ (lambda h)^5 / 120 ~ 1e-7 relative, far below what 1 Hz sampling already costs.
  double max_substep = 0.1;
};

/// The passive nonlinear observer of Fossen & Strand (1999), Fossen 2011 section 11.4.1, as
/// in TAPM thesis eq. 3.19: PassiveNonlinearObserver (core/passive_observer.h: equations,
/// gains and their units, the notch, the bias's leak, discretisation) on the controller's
/// model, with the linearised mooring as its load, g(eta) = -G eta (heading wrapped), the
/// mass-scaled gains K4 = k4_per_mass and K3 = k3_ratio K4, the measurement interpolated
/// between samples (first-order hold) and RK4 substeps of at most max_substep.
///
/// The bias b_hat is an Earth-frame force (it enters as R^T b_hat), so a constant NED load
/// shows up as a constant b_hat at any heading, read low by the bias's leak: 1.2 %, 1.1 %
/// and 6.1 % in surge, sway and yaw for the seed FPSO with the default gains. Unmodelled
/// mooring force (G = 0, or a broken line) is read as bias as well.
///
/// A missing channel gets no injection (its y_tilde is 0): the model runs open-loop on it,
/// its wave state decays, and when the channel returns the correction resumes from the
/// last value. The first valid value of a channel resets eta_hat on that channel to it.
class PassiveObserver {
 public:
  /// Throws moorsim::InputError on a non-positive-definite mass, non-finite matrices, or
  /// options that break the passivity conditions.
  PassiveObserver(const ManoeuvringModel& model, const PassiveObserverOptions& options, double dt);

  /// Forgets everything; eta_hat = `eta_initial` until each channel's first valid sample.
  void Reset(const Vec3& eta_initial) { observer_.Reset(eta_initial); }
  /// Advances the estimate by dt to the sample `measurement`, with the body-frame thrust
  /// `tau` [N, N, N m] that acted since the previous sample. The first call after Reset()
  /// only initialises.
  void Update(const PoseMeasurementInput& measurement, const Vec3& tau);

  /// [m, m, rad] NED, psi in (-pi, pi]
  Vec3 eta_hat() const { return observer_.state().segment<3>(PassiveNonlinearObserver::kPose); }
  /// [m/s, m/s, rad/s] body
  Vec3 nu_hat() const { return observer_.state().segment<3>(PassiveNonlinearObserver::kVelocity); }
  /// [N, N, N m] NED
  Vec3 bias() const { return observer_.state().segment<3>(PassiveNonlinearObserver::kBias); }
  /// Cw xi_hat [m, m, rad]
  Vec3 wave_motion() const {
    return observer_.state().segment<3>(PassiveNonlinearObserver::kWave + 3);
  }
  /// Whether the last sample's channel i was valid (it was injected).
  bool fresh(int i) const { return observer_.valid()[static_cast<std::size_t>(i)]; }

 private:
  PassiveNonlinearObserver observer_;
  double dt_ = 1.0;
};

// ---------------------------------------------------------------------------------------
// Observer-based nonlinear PID.

struct ObserverPidOptions {
  ManoeuvringModel model = SeedManoeuvringModel();
  /// Closed-loop natural frequency omega_n [rad/s]. Default 2 pi / 120 s = 0.052 rad/s:
  /// 17 times below the 7 s waves (so the loop does not chase what the notch leaves), above
  /// the moored surge/sway natural frequency (sqrt(81.6 kN/m / 1.08e8 kg) = 0.027 rad/s, so
  /// the thrusters, not the lines, set the response). Kp = M omega_n^2 is 0.30 MN/m in
  /// surge, well within the seed aft pair's 2 MN for metre offsets; in sway (0.45 MN/m) the
  /// seed layout's ~0.11 MN of pure sway saturates beyond ~0.25 m, so set integral_limit
  /// when running with saturating thrusters.
  double natural_frequency = 2.0 * 3.14159265358979323846 / 120.0;
  /// Relative damping zeta [-]. Default 0.8: with the hull's own damping (D_ii / (2 M_ii
  /// omega_n) = 0.19, 0.10, 0.48 for the seed FPSO) the total is 0.9-1.3, no overshoot.
  double relative_damping = 0.8;
  /// Anti-windup clamp on |Ki_i z_i| [N, N, N m]; 0 = no limit.
  Vec3 integral_limit = Vec3::Zero();
  PassiveObserverOptions observer;
};

/// The MSS nonlinear MIMO PID (Fossen 2011 chapter 12; MSS PIDnonlinearMIMO) on the
/// passive observer's low-frequency estimates:
///   e = eta_hat - eta_d (e_psi wrapped),   z_k = z_{k-1} + dt e_k,
///   tau = -R(psi_hat)^T (Kp e + Ki z) - Kd nu_hat,
///   Kp = diag(M) omega_n^2,  Kd = 2 zeta omega_n diag(M),  Ki = Kp omega_n / 10.
/// At each sample the observer is first advanced to the sample with the previous command
/// held, then the command is computed from the new estimate (no extra sample of delay).
/// Missing channel: the observer runs open-loop on it and its integral is frozen; the
/// P and D terms use the model-propagated estimate.
class ObserverPidController final : public PositionController {
 public:
  /// Throws moorsim::InputError naming the field on bad options or dt <= 0.
  ObserverPidController(const ObserverPidOptions& options, const Vec3& eta_d, double dt);

  Vec3 Update(const PoseMeasurementInput& measurement) override;
  std::string_view name() const override { return ChoiceName(ControllerType::kObserverPid); }
  Vec3 EstimatedPose() const override { return observer_.eta_hat(); }
  Vec3 EstimatedVelocity() const override { return observer_.nu_hat(); }
  Vec3 EstimatedBias() const override { return observer_.bias(); }

  const PassiveObserver& observer() const { return observer_; }
  /// Gains from the bandwidth rule: [N/m, N/m, N m/rad], [N s/m ...], [N/(m s) ...].
  const Vec3& kp() const { return kp_; }
  const Vec3& kd() const { return kd_; }
  const Vec3& ki() const { return ki_; }

 private:
  PassiveObserver observer_;
  Vec3 kp_, kd_, ki_, integral_limit_;
  Vec3 integral_ = Vec3::Zero();
  Vec3 tau_held_ = Vec3::Zero();
  bool started_ = false;
};

// ---------------------------------------------------------------------------------------
// No control.

/// "none": commands zero thrust at every sample (mooring-only runs, the thesis's
/// controller-off case). Estimates are NaN.
class IdleController final : public PositionController {
 public:
  /// Throws moorsim::InputError on dt <= 0 or a non-finite setpoint.
  IdleController(const Vec3& eta_d, double dt) : PositionController(eta_d, dt) {}

  Vec3 Update(const PoseMeasurementInput&) override { return Vec3::Zero(); }
  std::string_view name() const override { return ChoiceName(ControllerType::kNone); }
  Vec3 EstimatedPose() const override;
  Vec3 EstimatedVelocity() const override;
  Vec3 EstimatedBias() const override;
};

// ---------------------------------------------------------------------------------------
// Construction by name.

/// What the scenario's `controller:` section becomes. Only the options block of `type`
/// is used.
struct ControllerSpec {
  ControllerType type = ControllerType::kPi;
  Vec3 setpoint = Vec3::Zero();  ///< eta_d [m, m, rad], NED
  PiControllerOptions pi;
  ObserverPidOptions observer_pid;
};

/// A heading loop specified by its closed-loop behaviour: natural period [s] and damping
/// ratio [-], from which the pi controller's heading gains are sized on the hull.
struct HeadingLoopTuning {
  double natural_period = 0.0;
  double damping_ratio = 0.0;
};

/// `spec` with its pi heading gains (kp, ki, kd of yaw, error filtered) sized by
/// SizeAxisGains() on `vessel`'s yaw inertia with A66(0) and its linear yaw damping, with
/// no mooring stiffness (none about a turret on its bearing; a locked turret's only
/// shortens the period).
ControllerSpec WithHeadingLoop(ControllerSpec spec, const HeadingLoopTuning& tuning,
                               const VesselModel& vessel);

/// Builds the controller of spec.type with sample time dt [s]. Throws moorsim::InputError
/// for dt <= 0 or bad options.
std::unique_ptr<PositionController> MakeController(const ControllerSpec& spec, double dt);

}  // namespace moorsim::vessel
