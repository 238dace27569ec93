// Thrusters and thrust allocation for station keeping in the horizontal plane.
//
// Allocation: the generalised force tau = [X, Y, N] (body frame: surge, sway, yaw) is
// distributed over the thrusters by the weighted pseudo-inverse (Fossen 2011 section
// 12.3.2, unconstrained case) f = W^-1 B^T (B W^-1 B^T)^-1 tau, with B's column for a
// thruster at (x, y) pushing along alpha (from the bow toward starboard)
// [cos alpha, sin alpha, x sin alpha - y cos alpha]. An azimuth thruster enters as two
// orthogonal forces (the extended thrust formulation, Fossen 2011 eq. 12.253) and comes
// back as a magnitude and a direction. If any thruster would exceed its rating, every
// thruster's force is scaled down by one common factor until none does: the delivered
// tau keeps the commanded direction and shrinks (`Allocation::achieved` says what
// remains). Per-thruster clipping would keep more of the total force but turn, e.g., a
// saturated sway command into a large unintended yaw moment. Rate limits and first-order thrust
// dynamics act on the commanded force in ThrusterDynamics.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/types.h"

namespace moorsim::vessel {

struct ThrusterSpec {
  std::string name;
  double x = 0.0;              ///< body-frame position [m], forward
  double y = 0.0;              ///< body-frame position [m], starboard
  double angle = 0.0;          ///< fixed thrust direction [rad] from the bow toward starboard
  bool azimuth = false;        ///< if true, `angle` is free and chosen by the allocation
  double max_thrust = 0.0;     ///< [N], > 0: largest force in the thrust direction
  double min_thrust = 0.0;     ///< [N], <= 0: largest force backwards (fixed thrusters)
  double weight = 1.0;         ///< allocation cost weight, > 0 (larger = used less)
  double time_constant = 1.0;  ///< first-order thrust response [s], > 0
  double rate_limit = 0.0;     ///< [N/s] on the command; 0 = none
};

/// The seed vessel's layout (docs/design.md section 9: two fixed aft thrusters, one bow tunnel;
/// positions and ratings are not given by the TAPM thesis, these are the project's choice):
/// aft at x = -90 m, y = +-8 m, 1 MN ahead / 0.6 MN astern; bow tunnel at x = +90 m,
/// 0.6 MN either way; time constant 5 s; rate limit 0.2 MN/s.
std::vector<ThrusterSpec> SeedThrusters();

/// [X, Y, N] (body frame) of a unit force along alpha [rad, from the bow toward starboard]
/// at (x, y) [m]: a column of the allocation's B.
Vec3 ThrustColumn(double x, double y, double alpha);

struct Allocation {
  Eigen::VectorXd thrust;        ///< per thruster [N] (magnitude for azimuths)
  Eigen::VectorXd direction;     ///< per thruster [rad] (azimuths: chosen; fixed: their angle)
  Vec3 achieved = Vec3::Zero();  ///< tau actually produced after saturation
  bool saturated = false;
};

class ThrustAllocator {
 public:
  /// Throws moorsim::InputError if a thruster's data is invalid or the layout cannot
  /// produce all three of surge, sway and yaw.
  explicit ThrustAllocator(std::vector<ThrusterSpec> thrusters);

  /// Each DOF of tau is first clamped to what the layout can deliver in that DOF alone
  /// (Capacity), then allocated, then scaled down as a whole if a thruster still saturates.
  Allocation Allocate(const Vec3& tau) const;
  /// s * direction for the largest s whose allocation stays within every rating.
  Vec3 Capacity(const Vec3& direction) const;
  /// tau produced by thrust magnitudes and directions.
  Vec3 Force(const Eigen::VectorXd& thrust, const Eigen::VectorXd& direction) const;
  const std::vector<ThrusterSpec>& thrusters() const { return thrusters_; }

 private:
  std::vector<ThrusterSpec> thrusters_;
  std::vector<int> first_column_;          // thruster i's first column in B
  Eigen::MatrixXd pseudo_inverse_;         // W^-1 B^T (B W^-1 B^T)^-1
  Vec3 capacity_positive_ = Vec3::Zero();  // per DOF alone [N, N, N m]
  Vec3 capacity_negative_ = Vec3::Zero();
};

/// First-order thrust response with rate-limited commands: the delivered force f obeys
/// f' = (f_cmd - f) / T, f_cmd moving toward the allocation at no more than the rate limit
/// per second. `Step` advances the command by dt; `Derivative` is the continuous part that
/// the integrator sees (so the right-hand side stays smooth between controller samples).
class ThrusterDynamics {
 public:
  explicit ThrusterDynamics(const std::vector<ThrusterSpec>& thrusters);
  /// Moves each held command toward `target` over dt seconds within the rate limits.
  void Step(const Eigen::VectorXd& target, double dt);
  /// d(delivered)/dt for the delivered thrust `delivered`.
  Eigen::VectorXd Derivative(const Eigen::VectorXd& delivered) const;
  const Eigen::VectorXd& command() const { return command_; }

 private:
  std::vector<ThrusterSpec> thrusters_;
  Eigen::VectorXd command_;
};

}  // namespace moorsim::vessel
