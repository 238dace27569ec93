// The water particle velocity and acceleration of linear (Airy) waves in water of finite
// depth, where the lines are: the same regular components the hull's sea is made of
// (vessel/waves.h: frequency, amplitude, travel-to direction, phase), each with the wave
// number of the finite-depth dispersion relation omega^2 = g k tanh(k h).
//
// With zeta = -z the height above the mean surface (NED z down), the phase
// chi = omega t - k (x cos(theta) + y sin(theta)) + phi, and the depth profiles
//   C(zeta) = cosh(k (zeta + h)) / sinh(k h),   S(zeta) = sinh(k (zeta + h)) / sinh(k h)
// (Faltinsen 1990, table 2.1; DNV-RP-C205 section 3.2), each component moves the water by
//   horizontal velocity      a omega C cos(chi)       along (cos(theta), sin(theta))
//   vertical velocity (up)  -a omega S sin(chi)
//   horizontal acceleration -a omega^2 C sin(chi)
//   vertical acceleration   -a omega^2 S cos(chi)     (the local acceleration, d/dt)
// summed over the components. Linear theory holds up to the mean surface; under a crest the
// profiles are evaluated at a stretched height (Wheeler 1970): zeta_s = h (zeta - eta) /
// (h + eta), which maps the instantaneous surface eta to 0 and keeps the seabed, or, with
// stretching off, at min(zeta, 0) (linear theory held constant above the mean surface).
// Above the instantaneous surface the water does not move (the point is out of it).
//
// A component whose velocity and acceleration at a point are below 1e-5 m/s and m/s^2 is
// skipped there (its profile decays as exp(k zeta)): a line's deep nodes cost nothing.
#pragma once

#include <vector>

#include "core/choice.h"
#include "core/types.h"

namespace moorsim::mooring_fem {

/// One regular wave, as the hull's sea has it (vessel::WaveComponent).
struct WaveTrain {
  double omega = 0.0;      ///< [rad/s], > 0
  double amplitude = 0.0;  ///< elevation amplitude [m], >= 0
  double phase = 0.0;      ///< [rad]
  double direction = 0.0;  ///< travel-to, from north toward east [rad]
};

enum class WaveStretching {
  kWheeler,  ///< the profiles stretched between the seabed and the instantaneous surface
  kNone,     ///< linear theory to the mean surface, held constant up to the crest
};

inline constexpr std::string_view kWaveStretchingNames[] = {"wheeler", "none"};
constexpr ChoiceInfo ChoicesOf(WaveStretching) { return {"stretching rule", kWaveStretchingNames}; }

/// The water's motion at a point: velocity and acceleration (Earth NED) and, if asked,
/// their gradients d/dr (columns: x, y, z).
struct WaterMotion {
  Vec3 velocity = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero();
  Mat3 d_velocity = Mat3::Zero();
  Mat3 d_acceleration = Mat3::Zero();
};

class WaveKinematics {
 public:
  /// Throws moorsim::InputError for a non-positive frequency, depth or gravity, or a
  /// negative or non-finite amplitude.
  WaveKinematics(const std::vector<WaveTrain>& trains, double depth, double gravity,
                 WaveStretching stretching);

  /// The water's motion at `r` (NED) and time `t`; its gradients too if `with_gradient`.
  WaterMotion At(double t, const Vec3& r, bool with_gradient) const;
  /// Surface elevation eta [m], positive up, at (x, y).
  double Elevation(double t, double x, double y) const;

  /// The finite-depth wave number k [rad/m]: omega^2 = g k tanh(k h). Where tanh(k h)
  /// rounds to 1 it is omega^2 / g exactly, the hull's deep-water wave number.
  static double WaveNumber(double omega, double depth, double gravity);

  int size() const { return static_cast<int>(omega_.size()); }

 private:
  // Structure of arrays, one entry per component, the deepest reaching first.
  std::vector<double> omega_, amplitude_, phase_, k_, kx_, ky_, cos_dir_, sin_dir_;
  std::vector<double> decay_;  // 1 / (1 - exp(-2 k h))
  std::vector<double> reach_;  // depth below which the component is skipped [m]
  double depth_ = 0.0;
  WaveStretching stretching_ = WaveStretching::kWheeler;
  double highest_crest_ = 0.0;  // sum of amplitudes: no surface rises higher [m]
  double deepest_reach_ = 0.0;  // no component reaches below this [m]
};

}  // namespace moorsim::mooring_fem
