#include "vessel/vessel_plant.h"

#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "core/error.h"

namespace moorsim::vessel {

namespace {

Vec6 Eta(const double* x) { return Eigen::Map<const Vec6>(x); }
Vec6 Nu(const double* x) { return Eigen::Map<const Vec6>(x + 6); }

}  // namespace

VesselPlant::VesselPlant(const VesselParameters& parameters, std::vector<ThrusterSpec> thrusters)
    : model_(parameters), thrusters_(std::move(thrusters)) {
  const int n = num_thrusters();
  thrust_columns_.setZero(6, n);
  command_.setZero(n);
  Eigen::VectorXd direction(n);
  for (int k = 0; k < n; ++k) direction(k) = thrusters_[k].angle;
  SetThrustCommand(command_, direction);
}

void VesselPlant::SetTurret(const TurretParameters& turret) {
  if (turret.bearing != TurretBearing::kLocked && !(turret.inertia > 0.0)) {
    throw InputError("turret inertia must be > 0 for a turning turret");
  }
  turret_ = turret;
  turret_states_[0] = turret_state();
  turret_states_[1] = turret_state() + 1;
}

std::span<const int> VesselPlant::ExtraKinematicStates() const {
  if (!turret_turns()) return {};
  return {turret_states_, 2};
}

Vec3 VesselPlant::OnTurret(const double* x, const Vec3& r_fixed, Vec3* arm) {
  // Every attachment point asks twice per right-hand side (motion, load) at the same angle.
  const double alpha = x[turret_state()];
  if (alpha != turret_angle_) {
    turret_cos_ = std::cos(alpha);
    turret_sin_ = std::sin(alpha);
    turret_angle_ = alpha;
  }
  return TurnAboutCentre(turret_cos_, turret_sin_, r_fixed, arm);
}

Vec3 VesselPlant::TurnAboutCentre(double c, double s, const Vec3& r_fixed, Vec3* arm) const {
  const double dx = r_fixed.x() - turret_.x, dy = r_fixed.y() - turret_.y;
  *arm = Vec3(c * dx - s * dy, s * dx + c * dy, r_fixed.z());
  return Vec3(turret_.x + arm->x(), turret_.y + arm->y(), r_fixed.z());
}

Vec3 VesselPlant::OnTurret(const Vec3& r_fixed, double alpha) const {
  if (!turret_turns()) return r_fixed;
  Vec3 arm;
  return TurnAboutCentre(std::cos(alpha), std::sin(alpha), r_fixed, &arm);
}

void VesselPlant::TurretMoments(const double* x, const Vec6& tau_attached, double* lines,
                                double* bearing) const {
  *lines = 0.0;
  *bearing = 0.0;
  if (!turret_turns()) return;
  *lines = MomentAboutTurret(turret_, tau_attached);
  const double rate = x[turret_state() + 1] - x[11];
  *bearing = BearingMoment(turret_, rate, tau_attached.head<3>());
}

void VesselPlant::SetThrustCommand(const Eigen::VectorXd& command,
                                   const Eigen::VectorXd& direction) {
  const int n = num_thrusters();
  if (command.size() != n || direction.size() != n) {
    throw Error("VesselPlant::SetThrustCommand: expected " + std::to_string(n) + " thrusters");
  }
  command_ = command;
  for (int k = 0; k < n; ++k) {
    const Vec3 column = ThrustColumn(thrusters_[k].x, thrusters_[k].y, direction(k));
    thrust_columns_.col(k) << column(0), column(1), 0.0, 0.0, 0.0, column(2);
  }
}

Vec6 VesselPlant::ThrustLoad(const double* x) const {
  const int n = num_thrusters();
  return thrust_columns_ * Eigen::Map<const Eigen::VectorXd>(x + 12, n);
}

void VesselPlant::UpdateRotation(const double* x) {
  const Vec3 angles(x[3], x[4], x[5]);
  if (angles == rotation_angles_) return;
  rotation_ = RotationBodyToNed(angles(0), angles(1), angles(2));
  RotationDerivatives(angles(0), angles(1), angles(2), rotation_derivatives_);
  rotation_angles_ = angles;
}

void VesselPlant::UpdateSea(double t, const double* x) {
  if (sea_ == nullptr) return;
  const Vec3 pose(x[0], x[1], x[5]);
  if (t == sea_t_ && pose == sea_pose_) return;
  sea_->Evaluate(t, pose.x(), pose.y(), pose.z(), &xi_, &xi_dot_, &drift_);
  sea_t_ = t;
  sea_pose_ = pose;
}

void VesselPlant::Sea(double t, const double* x, Vec6* xi, Vec6* xi_dot, Vec6* drift) {
  UpdateSea(t, x);
  *xi = xi_;
  *xi_dot = xi_dot_;
  *drift = drift_;
}

Vec6 VesselPlant::TotalPose(double t, const double* x) {
  UpdateSea(t, x);
  UpdateRotation(x);
  Vec6 eta = Eta(x);
  eta.head<3>() += rotation_ * xi_.head<3>();
  eta.tail<3>() += xi_.tail<3>();
  return eta;
}

Vec6 VesselPlant::PreloadCorrection(const double* x) {
  UpdateRotation(x);
  const Vec3 up(0.0, 0.0, -static_vertical_load_);
  Vec6 tau = Vec6::Zero();
  tau.head<3>() = rotation_.transpose() * up - up;
  return tau;
}

void VesselPlant::Derivatives(double t, const double* x, const Vec6& tau_attached, double* xdot) {
  UpdateSea(t, x);
  const Vec6 eta = Eta(x);
  const Vec6 nu = Nu(x);
  Vec6 tau = tau_attached + ThrustLoad(x) + drift_ + PreloadCorrection(x);
  for (const EnvironmentLoad* load : loads_) tau += load->Load(t, eta, nu);
  double lines = 0.0, bearing = 0.0;
  if (turret_turns()) {
    // The hull keeps the yaw moment of the net force at the turret centre and the bearing's.
    TurretMoments(x, tau_attached, &lines, &bearing);
    tau(5) += bearing - lines;
  }
  Vec6 eta_dot, nu_dot;
  model_.Derivatives(eta, nu, tau, &eta_dot, &nu_dot);
  Eigen::Map<Vec6> out_eta(xdot), out_nu(xdot + 6);
  out_eta = eta_dot;
  out_nu = nu_dot;
  for (int k = 0; k < num_thrusters(); ++k) {
    xdot[12 + k] = (command_(k) - x[12 + k]) / thrusters_[k].time_constant;
  }
  if (turret_turns()) {
    const int a = turret_state();
    xdot[a] = x[a + 1] - x[11];
    xdot[a + 1] = (lines - bearing) / turret_.inertia;
  }
}

void VesselPlant::Jacobian(double t, const double* x, const Vec6& tau_attached, MatX* J) {
  const Vec6 eta = Eta(x);
  const Vec6 nu = Nu(x);
  const VesselModel::Jacobian B = model_.Jacobians(eta, nu);
  const Mat6& Minv = model_.inverse_mass();
  Mat6 dtau_deta = Mat6::Zero(), dtau_dnu = Mat6::Zero();
  for (const EnvironmentLoad* load : loads_) {
    Mat6 Je, Jn;
    load->Jacobian(t, eta, nu, &Je, &Jn);
    dtau_deta += Je;
    dtau_dnu += Jn;
  }
  UpdateRotation(x);
  for (int a = 0; a < 3; ++a) {
    dtau_deta.block<3, 1>(0, 3 + a) +=
        rotation_derivatives_[a].transpose() * Vec3(0.0, 0.0, -static_vertical_load_);
  }
  J->setZero(StateSize(), StateSize());
  J->block<6, 6>(0, 0) = B.J_etadot_eta;
  J->block<6, 6>(0, 6) = B.J_etadot_nu;
  J->block<6, 6>(6, 0) = B.J_nudot_eta + Minv * dtau_deta;
  J->block<6, 6>(6, 6) = B.J_nudot_nu + Minv * dtau_dnu;
  const int n = num_thrusters();
  J->block(6, 12, 6, n) = Minv * thrust_columns_;
  for (int k = 0; k < n; ++k) (*J)(12 + k, 12 + k) = -1.0 / thrusters_[k].time_constant;
  if (turret_turns()) {
    // The bearing moment depends on the relative rate Omega - r (the load held).
    const int a = turret_state();
    double d_rate = 0.0;
    BearingMoment(turret_, x[a + 1] - x[11], tau_attached.head<3>(), &d_rate);
    J->block<6, 1>(6, a + 1) += Minv.col(5) * d_rate;
    J->block<6, 1>(6, 11) -= Minv.col(5) * d_rate;
    (*J)(a, a + 1) = 1.0;
    (*J)(a, 11) = -1.0;
    (*J)(a + 1, a + 1) = -d_rate / turret_.inertia;
    (*J)(a + 1, 11) = d_rate / turret_.inertia;
  }
}

void VesselPlant::LoadSensitivity(const double* x, const Vec6& tau_attached,
                                  Eigen::Matrix<double, Eigen::Dynamic, 6>* S) {
  S->setZero(StateSize(), 6);
  if (!turret_turns()) {
    S->block<6, 6>(6, 0) = model_.inverse_mass();
    return;
  }
  // d(hull load)/d tau_attached: the identity but for the yaw moment, which is that of the
  // net force at the turret centre plus the bearing's (through the bearing's normal loads).
  const int a = turret_state();
  double d_rate = 0.0;
  Vec3 d_force = Vec3::Zero();
  BearingMoment(turret_, x[a + 1] - x[11], tau_attached.head<3>(), &d_rate, &d_force);
  Eigen::Matrix<double, 1, 6> d_lines;  // d M_lines / d tau_attached
  d_lines << turret_.y, -turret_.x, 0.0, 0.0, 0.0, 1.0;
  Eigen::Matrix<double, 1, 6> d_bearing = Eigen::Matrix<double, 1, 6>::Zero();
  d_bearing.head<3>() = d_force.transpose();
  Mat6 T = Mat6::Identity();
  T.row(5) += d_bearing - d_lines;
  S->block<6, 6>(6, 0) = model_.inverse_mass() * T;
  S->row(a + 1) = (d_lines - d_bearing) / turret_.inertia;
}

PointKinematics VesselPlant::PointMotion(double t, const double* x, const Vec3& r_fixed,
                                         PointMotionJacobian* J) {
  UpdateSea(t, x);
  UpdateRotation(x);
  const Mat3& R = rotation_;
  const Vec3 v_lin(x[6], x[7], x[8]);
  const Vec3 omega(x[9], x[10], x[11]);
  // On a turning turret the point turns about the turret centre at the relative rate.
  const bool turns = turret_turns();
  Vec3 arm = Vec3::Zero();
  const Vec3 r_body = turns ? OnTurret(x, r_fixed, &arm) : r_fixed;
  const Vec3 d_alpha(-arm.y(), arm.x(), 0.0);  // d r_body / d alpha = e_z x arm
  const double relative_rate = turns ? x[turret_state() + 1] - x[11] : 0.0;
  // Wave-frequency displacement and velocity of the point in body axes. On a turning turret
  // the hull's wave-frequency yaw does not turn the fairleads: the bearing leaves the
  // turret's rotation about its axis to the lines; its centre and its roll and pitch follow
  // the hull.
  const Vec3 xi_r_arm(xi_(3), xi_(4), 0.0), xi_dot_r_arm(xi_dot_(3), xi_dot_(4), 0.0);
  Vec3 r_rel, v_body;
  if (turns) {
    const Vec3 centre = r_body - arm;
    r_rel = r_body + xi_.head<3>() + xi_.tail<3>().cross(centre) + xi_r_arm.cross(arm);
    v_body = v_lin + omega.cross(r_body) + xi_dot_.head<3>() + xi_dot_.tail<3>().cross(centre) +
             xi_dot_r_arm.cross(arm) + relative_rate * d_alpha;
  } else {
    r_rel = r_body + xi_.head<3>() + xi_.tail<3>().cross(r_body);
    v_body = v_lin + omega.cross(r_body) + xi_dot_.head<3>() + xi_dot_.tail<3>().cross(r_body);
  }
  PointKinematics k;
  k.position = Vec3(x[0], x[1], x[2]) + R * r_rel;
  k.velocity = R * v_body;
  if (J != nullptr) {
    const Mat3* dR = rotation_derivatives_;
    J->J_pos_eta.setZero();
    J->J_vel_eta.setZero();
    J->J_pos_eta.leftCols<3>() = Mat3::Identity();
    for (int a = 0; a < 3; ++a) {
      J->J_pos_eta.col(3 + a) = dR[a] * r_rel;
      J->J_vel_eta.col(3 + a) = dR[a] * v_body;
    }
    J->J_vel_nu.leftCols<3>() = R;
    J->J_vel_nu.rightCols<3>() = -R * Skew(r_body);
    if (turns) {
      J->J_vel_nu.col(5) -= R * d_alpha;             // the relative rate is Omega - r
      const Vec3 dd_alpha(-arm.x(), -arm.y(), 0.0);  // d (e_z x arm) / d alpha
      J->J_pos_extra.col(0) = R * (d_alpha + xi_r_arm.cross(d_alpha));
      J->J_pos_extra.col(1).setZero();
      J->J_vel_extra.col(0) =
          R * (omega.cross(d_alpha) + xi_dot_r_arm.cross(d_alpha) + relative_rate * dd_alpha);
      J->J_vel_extra.col(1) = R * d_alpha;
    }
  }
  return k;
}

Vec6 VesselPlant::PointLoad(const double* x, const Vec3& r_fixed, const Vec3& F,
                            PointLoadJacobian* J) {
  const bool turns = turret_turns();
  Vec3 arm = Vec3::Zero();
  const Vec3 r_body = turns ? OnTurret(x, r_fixed, &arm) : r_fixed;
  UpdateRotation(x);
  const Mat3& R = rotation_;
  const Vec3 F_body = R.transpose() * F;
  Vec6 tau;
  tau.head<3>() = F_body;
  tau.tail<3>() = r_body.cross(F_body);
  if (J != nullptr) {
    const Mat3 S = Skew(r_body);
    J->J_load_force.topRows<3>() = R.transpose();
    J->J_load_force.bottomRows<3>() = S * R.transpose();
    const Mat3* dR = rotation_derivatives_;
    J->J_load_eta.setZero();
    for (int a = 0; a < 3; ++a) {
      const Vec3 dF = dR[a].transpose() * F;
      J->J_load_eta.block<3, 1>(0, 3 + a) = dF;
      J->J_load_eta.block<3, 1>(3, 3 + a) = S * dF;
    }
    if (turns) {
      J->J_load_extra.setZero();
      J->J_load_extra.block<3, 1>(3, 0) = Vec3(-arm.y(), arm.x(), 0.0).cross(F_body);
    }
  }
  return tau;
}

}  // namespace moorsim::vessel
