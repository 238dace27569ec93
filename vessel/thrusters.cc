#include "vessel/thrusters.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"

namespace moorsim::vessel {

std::vector<ThrusterSpec> SeedThrusters() {
  const double half_pi = 1.5707963267948966;
  return {
      {"aft_port", -90.0, -8.0, 0.0, false, 1.0e6, -0.6e6, 1.0, 5.0, 0.2e6},
      {"aft_starboard", -90.0, 8.0, 0.0, false, 1.0e6, -0.6e6, 1.0, 5.0, 0.2e6},
      {"bow_tunnel", 90.0, 0.0, half_pi, false, 0.6e6, -0.6e6, 1.0, 5.0, 0.2e6},
  };
}

namespace {

void Check(bool ok, const ThrusterSpec& t, const std::string& field, double value,
           const std::string& rule) {
  if (!ok) {
    throw InputError("thruster '" + t.name + "': " + field + " " + std::to_string(value) + " " +
                     rule);
  }
}

Vec3 Column(double x, double y, double alpha) { return ThrustColumn(x, y, alpha); }

}  // namespace

Vec3 ThrustColumn(double x, double y, double alpha) {
  return Vec3(std::cos(alpha), std::sin(alpha), x * std::sin(alpha) - y * std::cos(alpha));
}

ThrustAllocator::ThrustAllocator(std::vector<ThrusterSpec> thrusters)
    : thrusters_(std::move(thrusters)) {
  int columns = 0;
  for (const ThrusterSpec& t : thrusters_) {
    Check(t.max_thrust > 0.0, t, "max_thrust", t.max_thrust, "N must be > 0");
    Check(t.min_thrust <= 0.0, t, "min_thrust", t.min_thrust, "N must be <= 0");
    Check(t.weight > 0.0, t, "weight", t.weight, "must be > 0");
    Check(t.time_constant > 0.0, t, "time_constant", t.time_constant, "s must be > 0");
    Check(t.rate_limit >= 0.0, t, "rate_limit", t.rate_limit, "N/s must be >= 0");
    first_column_.push_back(columns);
    columns += t.azimuth ? 2 : 1;
  }
  Eigen::MatrixXd B(3, columns);
  Eigen::VectorXd w_inv(columns);
  for (std::size_t i = 0; i < thrusters_.size(); ++i) {
    const ThrusterSpec& t = thrusters_[i];
    const int c = first_column_[i];
    if (t.azimuth) {
      B.col(c) = Column(t.x, t.y, 0.0);
      B.col(c + 1) = Column(t.x, t.y, 1.5707963267948966);
      w_inv(c) = w_inv(c + 1) = 1.0 / t.weight;
    } else {
      B.col(c) = Column(t.x, t.y, t.angle);
      w_inv(c) = 1.0 / t.weight;
    }
  }
  const Eigen::MatrixXd BWBt = B * w_inv.asDiagonal() * B.transpose();
  Eigen::FullPivLU<Eigen::MatrixXd> lu(BWBt);
  if (lu.rank() < 3) {
    throw InputError("thrusters: the layout cannot produce surge, sway and yaw independently");
  }
  pseudo_inverse_ = w_inv.asDiagonal() * B.transpose() * lu.inverse();
  for (int j = 0; j < 3; ++j) {
    capacity_positive_(j) = Capacity(Vec3::Unit(j))(j);
    capacity_negative_(j) = -Capacity(-Vec3::Unit(j))(j);
  }
}

Allocation ThrustAllocator::Allocate(const Vec3& tau_command) const {
  // Each DOF first within what the layout can deliver in that DOF alone, so that a command
  // far beyond one DOF's capacity (sway, for the seed layout) does not shrink the others.
  Vec3 tau = tau_command;
  for (int j = 0; j < 3; ++j)
    tau(j) = std::clamp(tau(j), -capacity_negative_(j), capacity_positive_(j));
  const Eigen::VectorXd f = pseudo_inverse_ * tau;
  const int n = static_cast<int>(thrusters_.size());
  Allocation a;
  a.thrust.resize(n);
  a.direction.resize(n);
  // Magnitudes and directions of the unconstrained solution, then one common scale factor
  // that brings every thruster within its rating: the delivered tau keeps the commanded
  // direction (clipping thrusters one by one would turn a saturated sway command into a
  // large spurious yaw moment, since sway needs the bow and aft thrusters in balance).
  double scale = 1.0;
  for (int i = 0; i < n; ++i) {
    const ThrusterSpec& t = thrusters_[i];
    const int c = first_column_[i];
    if (t.azimuth) {
      a.thrust(i) = std::hypot(f(c), f(c + 1));
      a.direction(i) = std::atan2(f(c + 1), f(c));
    } else {
      a.thrust(i) = f(c);
      a.direction(i) = t.angle;
    }
    const double low = t.azimuth ? 0.0 : t.min_thrust;
    if (a.thrust(i) > t.max_thrust) scale = std::min(scale, t.max_thrust / a.thrust(i));
    if (a.thrust(i) < low) scale = std::min(scale, low / a.thrust(i));
  }
  a.saturated = scale < 1.0 || tau != tau_command;
  a.thrust *= scale;
  a.achieved = Force(a.thrust, a.direction);
  return a;
}

Vec3 ThrustAllocator::Capacity(const Vec3& direction) const {
  // The largest s with the unconstrained allocation of s * direction within every rating.
  const Eigen::VectorXd f = pseudo_inverse_ * direction;
  double s = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < thrusters_.size(); ++i) {
    const ThrusterSpec& t = thrusters_[i];
    const int c = first_column_[i];
    if (t.azimuth) {
      const double m = std::hypot(f(c), f(c + 1));
      if (m > 0) s = std::min(s, t.max_thrust / m);
    } else if (f(c) > 0) {
      s = std::min(s, t.max_thrust / f(c));
    } else if (f(c) < 0) {
      s = std::min(s, t.min_thrust / f(c));
    }
  }
  return s * direction;
}

Vec3 ThrustAllocator::Force(const Eigen::VectorXd& thrust, const Eigen::VectorXd& direction) const {
  Vec3 tau = Vec3::Zero();
  for (std::size_t i = 0; i < thrusters_.size(); ++i) {
    tau += thrust(i) * Column(thrusters_[i].x, thrusters_[i].y, direction(i));
  }
  return tau;
}

ThrusterDynamics::ThrusterDynamics(const std::vector<ThrusterSpec>& thrusters)
    : thrusters_(thrusters), command_(Eigen::VectorXd::Zero(thrusters.size())) {}

void ThrusterDynamics::Step(const Eigen::VectorXd& target, double dt) {
  for (std::size_t i = 0; i < thrusters_.size(); ++i) {
    const double limit = thrusters_[i].rate_limit;
    double change = target(i) - command_(i);
    if (limit > 0.0) change = std::clamp(change, -limit * dt, limit * dt);
    command_(i) += change;
  }
}

Eigen::VectorXd ThrusterDynamics::Derivative(const Eigen::VectorXd& delivered) const {
  Eigen::VectorXd d(thrusters_.size());
  for (std::size_t i = 0; i < thrusters_.size(); ++i) {
    d(i) = (command_(i) - delivered(i)) / thrusters_[i].time_constant;
  }
  return d;
}

}  // namespace moorsim::vessel
