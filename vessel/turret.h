// An FPSO's turret: the body that carries the mooring lines' fairleads and turns on a bearing
// about the hull's vertical axis, so that the hull can weathervane around it (Ren and
// Skjetne's line model, section 3.4: the turret rotates under the moment of the lines'
// horizontal forces, its friction against the hull negligible).
//
// The turret centre c sits at body (x, y); the fairleads are body points at turret angle 0
// and turn with the turret angle alpha (relative to the hull, positive clockwise seen from
// above, like the heading): r(alpha) = c + Rz(alpha) (r - c). The lines load the hull
// through the bearing: their net force acts at the turret centre (its roll and pitch
// moments pass through the bearing), and about the vertical axis the hull feels only the
// bearing moment. The turret itself obeys
//
//   alpha' = Omega - r,   I_t Omega' = M_lines - M_bearing(alpha', F),
//
// with Omega the turret's own rate of turn about its axis (the hull's yaw rate r plus the
// relative rate), M_lines the lines' moment about the turret axis and M_bearing the
// bearing's moment resisting the relative rate:
//   free:      M = d alpha'
//   friction:  M = mu r_b (|F_z| + |F_h|) tanh(alpha' / w_s) + d alpha'
// a Coulomb moment regularised over the slip rate w_s (Coulomb's friction with the bearing's
// vertical and horizontal reactions as the normal loads, each on the bearing radius r_b),
// plus viscous damping d. `locked` is the turret fixed to the hull (no turret states): the
// lines' whole moment acts on the hull.
#pragma once

#include <string>
#include <string_view>

#include "core/choice.h"
#include "core/types.h"

namespace moorsim::vessel {

enum class TurretBearing { kLocked, kFree, kFriction };

inline constexpr std::string_view kTurretBearingNames[] = {"locked", "free", "friction"};
constexpr ChoiceInfo ChoicesOf(TurretBearing) { return {"turret bearing", kTurretBearingNames}; }

struct TurretParameters {
  TurretBearing bearing = TurretBearing::kLocked;
  double x = 0.0, y = 0.0;            ///< turret centre, body frame [m]
  double inertia = 6.0e8;             ///< I_t about its axis [kg m^2]
  double friction_coefficient = 0.0;  ///< mu [-] (friction)
  double bearing_radius = 20.0;       ///< r_b [m] (friction)
  double damping = 0.0;               ///< d [N m s/rad]
  double slip_rate = 1.0e-5;          ///< w_s [rad/s] (friction)
};

/// The bearing's moment on the hull (and, negated, on the turret) [N m] at relative rate
/// `rate` [rad/s] under the lines' net force on the turret F (body frame) [N], with its
/// derivatives with respect to the rate and F if asked for. Zero for kLocked.
double BearingMoment(const TurretParameters& turret, double rate, const Vec3& F,
                     double* d_rate = nullptr, Vec3* d_force = nullptr);

/// The moment about the vertical axis through the turret centre of a load tau (body frame,
/// about the body origin: force, then moment) [N m]: tau_N - (c x F)_z.
double MomentAboutTurret(const TurretParameters& turret, const Vec6& tau);

}  // namespace moorsim::vessel
