// The vessel as the body of the coupled simulation (core/coupled_system.h): the 6-DOF
// low-frequency model of vessel_model.h, first-order thruster dynamics, environmental loads,
// and the first-order wave-frequency motion superposed on the low-frequency pose.
//
// States: [eta (6), nu (6), delivered thrust of each thruster (N)] and, with a turret on a
// bearing (vessel/turret.h), [turret angle alpha relative to the hull (rad), the turret's
// rate of turn Omega about its axis (rad/s)]. The low-frequency equations are
//   eta' = J(eta) nu
//   M nu' + C(nu) nu + D nu + G eta = tau_attached + tau_thrust + tau_drift + sum tau_env
//   f_k' = (f_k,cmd - f_k) / T_k
// where tau_attached is the moorings' load (from the coupled assembler), tau_thrust = B(alpha)
// f, tau_drift the slowly varying wave drift and tau_env the other loads (current, wind).
// With a turret, the attachment points turn with it, and of tau_attached's yaw moment the
// hull keeps only that of the net force at the turret centre plus the bearing moment; the
// lines' moment about the turret axis drives the turret (vessel/turret.h).
// The commands f_cmd and directions alpha are held between controller samples.
//
// Wave-frequency motion xi (body axes; surge, sway, heave [m], roll, pitch, yaw [rad]) is
// superposed kinematically (the usual separation of low- and wave-frequency motion, Fossen
// 2011 section 10.2.2): a body point r sits at p + R(Theta) (r + xi_t + xi_r x r). The
// Jacobian treats xi as a function of time only (its dependence on the slowly varying pose
// through the phases and relative headings is left out of the derivatives, not the values).
#pragma once

#include <limits>
#include <span>
#include <string>
#include <vector>

#include "core/coupled_system.h"
#include "core/types.h"
#include "vessel/rigid_body.h"
#include "vessel/thrusters.h"
#include "vessel/turret.h"
#include "vessel/vessel_model.h"

namespace moorsim::vessel {

/// First-order wave-frequency motion and second-order drift of the hull in a realised sea.
class SeaResponse {
 public:
  virtual ~SeaResponse() = default;
  /// WF motion xi and its rate (body axes) and the drift load (body frame) at time t for the
  /// low-frequency position (x, y) [m] and heading psi [rad].
  virtual void Evaluate(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot,
                        Vec6* drift) const = 0;
};

/// A load on the hull that depends on time and the low-frequency state (current, wind).
class EnvironmentLoad {
 public:
  virtual ~EnvironmentLoad() = default;
  virtual std::string_view name() const = 0;
  /// Body-frame load [N, N m].
  virtual Vec6 Load(double t, const Vec6& eta, const Vec6& nu) const = 0;
  /// d load / d eta and d load / d nu.
  virtual void Jacobian(double t, const Vec6& eta, const Vec6& nu, Mat6* J_eta,
                        Mat6* J_nu) const = 0;
};

class VesselPlant final : public BodyPlant {
 public:
  VesselPlant(const VesselParameters& parameters, std::vector<ThrusterSpec> thrusters);

  /// Not owned; may be null (calm water).
  void SetSea(const SeaResponse* sea) { sea_ = sea; }
  /// Not owned.
  void AddLoad(const EnvironmentLoad* load) { loads_.push_back(load); }
  /// The turret that carries the attachment points. Call before the coupled system is built:
  /// a bearing other than kLocked adds two states. Default: locked at the body origin.
  void SetTurret(const TurretParameters& turret);
  const TurretParameters& turret() const { return turret_; }
  /// Whether the turret turns on its bearing (has states).
  bool turret_turns() const { return turret_.bearing != TurretBearing::kLocked; }
  /// Index of the turret angle (the rate follows it); valid if turret_turns().
  int turret_state() const { return 12 + num_thrusters(); }
  /// Where the attachment point r_fixed (body frame, turret angle 0) is at turret angle
  /// `alpha` (body frame); r_fixed itself for a locked turret.
  Vec3 OnTurret(const Vec3& r_fixed, double alpha) const;
  /// The lines' moment about the turret axis and the bearing's moment on the hull [N m]
  /// for the attachment load tau_attached at state x (both 0 for a locked turret).
  void TurretMoments(const double* x, const Vec6& tau_attached, double* lines,
                     double* bearing) const;

  /// Held thrust commands [N] and directions [rad] per thruster until the next call.
  void SetThrustCommand(const Eigen::VectorXd& command, const Eigen::VectorXd& direction);

  /// The part of the hydrostatic load that carries a static vertical load on the hull (the
  /// lines' weight at the moored draught): F0 = (G eta_0)_heave [N]. The linear restoring
  /// G eta acts along the body axes; the buoyancy that balances F0 is vertical in the Earth
  /// frame, so the plant adds R^T (0, 0, -F0) - (0, 0, -F0): without it, a trimmed vessel
  /// feels the lines' vertical load projected on its surge axis (a spurious 6 kN for the seed
  /// FPSO's 0.009 deg trim) and creeps.
  void SetStaticVerticalLoad(double F0) { static_vertical_load_ = F0; }

  int num_thrusters() const { return static_cast<int>(thrusters_.size()); }
  const std::vector<ThrusterSpec>& thrusters() const { return thrusters_; }
  const VesselModel& model() const { return model_; }
  const std::vector<const EnvironmentLoad*>& loads() const { return loads_; }

  int StateSize() const override { return 12 + num_thrusters() + (turret_turns() ? 2 : 0); }
  std::span<const int> ExtraKinematicStates() const override;
  void Derivatives(double t, const double* x, const Vec6& tau_attached, double* xdot) override;
  void Jacobian(double t, const double* x, const Vec6& tau_attached, MatX* J) override;
  void LoadSensitivity(const double* x, const Vec6& tau_attached,
                       Eigen::Matrix<double, Eigen::Dynamic, 6>* S) override;
  PointKinematics PointMotion(double t, const double* x, const Vec3& r_body,
                              PointMotionJacobian* J) override;
  Vec6 PointLoad(const double* x, const Vec3& r_body, const Vec3& F, PointLoadJacobian* J) override;

  /// The body-frame thrust load of the delivered thrust in x (X, Y, 0, 0, 0, N).
  Vec6 ThrustLoad(const double* x) const;
  /// Wave-frequency motion, its rate and the drift load at (t, x) (zero in calm water).
  void Sea(double t, const double* x, Vec6* xi, Vec6* xi_dot, Vec6* drift);
  /// Total pose: low-frequency pose plus the wave-frequency motion (translation rotated
  /// into NED, angles added).
  Vec6 TotalPose(double t, const double* x);

 private:
  // The attachment point r_fixed (body frame, turret angle 0) where the turret angle in x
  // puts it; `arm` = its offset from the turret centre (body frame).
  Vec3 OnTurret(const double* x, const Vec3& r_fixed, Vec3* arm);
  // r_fixed turned by (cos, sin) about the turret centre; `arm` its offset from the centre.
  Vec3 TurnAboutCentre(double c, double s, const Vec3& r_fixed, Vec3* arm) const;
  void UpdateSea(double t, const double* x);
  void UpdateRotation(const double* x);
  Vec6 PreloadCorrection(const double* x);

  VesselModel model_;
  std::vector<ThrusterSpec> thrusters_;
  TurretParameters turret_;
  int turret_states_[2] = {0, 0};
  // cos and sin of the turret angle last asked for.
  double turret_angle_ = 0.0, turret_cos_ = 1.0, turret_sin_ = 0.0;
  Eigen::Matrix<double, 6, Eigen::Dynamic> thrust_columns_;  // per thruster, body load of 1 N
  Eigen::VectorXd command_;
  const SeaResponse* sea_ = nullptr;
  std::vector<const EnvironmentLoad*> loads_;
  // The last sea evaluation (every attachment point and the body asks at the same t).
  double sea_t_ = kNaN;
  Vec3 sea_pose_ = Vec3::Zero();
  double static_vertical_load_ = 0.0;
  // R(Theta) and its derivatives at the last angles asked for: every attachment point asks
  // twice per right-hand side (motion, load) at the same angles.
  Vec3 rotation_angles_ = Vec3::Constant(kNaN);
  Mat3 rotation_ = Mat3::Identity();
  Mat3 rotation_derivatives_[3];
  Vec6 xi_ = Vec6::Zero(), xi_dot_ = Vec6::Zero(), drift_ = Vec6::Zero();
};

}  // namespace moorsim::vessel
