// What the water and the seabed do to a line: current velocity vs depth, and the
// regularised seabed contact law. Both are smooth (C1) so the implicit integrator's
// Newton iteration sees no kinks (docs/design.md section 8.3).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/types.h"
#include "mooring_fem/parameters.h"
#include "mooring_fem/seabed.h"

namespace moorsim::mooring_fem {

/// The current where the lines are: a horizontal velocity whose speed is piecewise linear
/// in depth (constant beyond the ends), or a table over position and time (CurrentTable).
class CurrentField {
 public:
  CurrentField() = default;
  explicit CurrentField(const CurrentProfile& profile);

  bool empty() const { return depth_.empty() && table_ == nullptr; }
  /// Water velocity at `r` (NED) and time t [m/s], Earth frame.
  Vec3 VelocityAt(double t, const Vec3& r) const {
    if (table_ != nullptr) return TableVelocity(t, r, nullptr);
    return ProfileVelocity(r.z());
  }
  /// d(velocity)/dr at `r` and t [1/s] (columns: x, y, z).
  Mat3 GradientAt(double t, const Vec3& r) const;

 private:
  Vec3 ProfileVelocity(double z) const;
  Vec3 TableVelocity(double t, const Vec3& r, Mat3* gradient) const;

  Vec3 direction_ = Vec3::Zero();  // unit horizontal vector the water flows toward
  std::vector<double> depth_;
  std::vector<double> speed_;
  std::shared_ptr<const CurrentTable> table_;
};

/// The strongest current a table may hold [m/s]: the strongest tidal races (Saltstraumen)
/// run at about 10 m/s.
inline constexpr double kMaxCurrentSpeed = 10.0;

/// "" for a velocity within kMaxCurrentSpeed, else what is wrong with it.
std::string CurrentSpeedProblem(const Vec3& velocity);

/// Throws moorsim::InputError naming the table's source and what is wrong: an axis empty or
/// not strictly increasing or not finite, a velocity count that is not the grid's, a
/// velocity not finite or faster than kMaxCurrentSpeed, a period not longer than the times
/// it repeats.
void CheckCurrentTable(const CurrentTable& table);

/// Where a node touches the seabed: the unit normal into the seabed and the penetration
/// along it (seabed.h).
struct SeabedFrame {
  Vec3 normal = Vec3::UnitZ();
  double penetration = 0.0;  ///< [m]
};

/// For the Jacobian: the frame's derivatives with respect to the node's position.
struct SeabedFrameDerivatives {
  Vec3 d_penetration = Vec3::UnitZ();  ///< d penetration / d r
  Mat3 d_normal = Mat3::Zero();        ///< d normal / d r [1/m]
};

/// The seabed's surface and its contact law. Contact per metre of line: a penalty spring
/// on the penetration delta along the local normal with pressure `stiffness` per metre,
/// smoothed over `regularisation` metres so the force and its slope are continuous at
/// first contact:
///   q(delta) = 0 (delta <= 0), delta^2 / (2 eps) (0 < delta < eps), delta - eps/2 (else)
/// and a damper on the normal velocity blended in by the smoothstep s(delta / eps).
struct SeabedContact {
  SeabedSurface surface;
  double stiffness = 0.0;           ///< [N/m^3] times contact width (diameter)
  double damping = 0.0;             ///< [N s/m^3]
  double friction_velocity = 0.01;  ///< [m/s]
  double regularisation = 0.5;      ///< eps [m]

  /// How far `r` is below the seabed, vertically [m] (> 0: in contact).
  double Below(const Vec3& r) const { return r.z() - surface.DepthAt(r.x(), r.y()); }
  /// The normal and penetration at `r` (in contact), and their derivatives if asked.
  SeabedFrame Frame(const Vec3& r, SeabedFrameDerivatives* derivatives = nullptr) const {
    if (surface.flat()) {  // the common case, inline: every grounded node
      if (derivatives != nullptr) *derivatives = {};
      return {Vec3::UnitZ(), Below(r)};
    }
    return SlopedFrame(r, derivatives);
  }
  /// Frame() on a seabed that is not flat.
  SeabedFrame SlopedFrame(const Vec3& r, SeabedFrameDerivatives* derivatives) const;
  /// Smoothed penetration q(delta) [m] and dq/ddelta.
  void Penetration(double delta, double* q, double* dq) const;
  /// Smoothstep weight of the damper in [0, 1] and its derivative [1/m].
  void DamperWeight(double delta, double* s, double* ds) const;
  /// Energy stored per unit spring constant: integral of q from 0 to delta [m^2].
  double PenetrationEnergy(double delta) const;
};

}  // namespace moorsim::mooring_fem
