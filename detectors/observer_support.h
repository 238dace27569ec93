// What the hypothesis observers (detectors/ekf_observer.cc, detectors/passive_observer.cc)
// and the own-model simulator of detectors/innovation_covariance.cc share: the heading
// wrap, the yaw rotation, the checks of options and observations (with the error messages
// they throw) and the mass and mooring-damping set-up. Internal to the detectors library.
#pragma once

#include <string>
#include <string_view>

#include "core/angles.h"
#include "core/observer_state.h"
#include "core/types.h"
#include "detectors/detector.h"
#include "detectors/hypothesis_bank.h"

namespace moorsim::detectors::internal {

inline constexpr double kLogTwoPi = 1.8378770664093453;  // log(2 pi)

using ::moorsim::WrapAngle;  // (-pi, pi]

using ::moorsim::YawRotation;  // core/observer_state.h

/// Throws moorsim::InputError "<field> = <value>: <rule>" (value to 10 digits).
[[noreturn]] void ThrowField(std::string_view field, double value, std::string_view rule);

/// "name[i + 1]", the 1-based element of a Vec3 option.
std::string Element(std::string_view name, int i);

/// Every element of `value` finite and > 0 (>= 0 with `allow_zero`), else ThrowField with
/// the field "<prefix><name>[i + 1]" (prefix e.g. "ekf.").
void CheckVector(std::string_view prefix, std::string_view name, const Vec3& value,
                 bool allow_zero);
/// `value` finite and > 0, else ThrowField with the field "<prefix><name>".
void CheckScalar(std::string_view prefix, std::string_view name, double value);

/// A finite time and command and finite poses on the valid channels, else
/// moorsim::InputError naming the field and the time.
void CheckObservation(const Observation& observation);
/// dt = t - previous in (0, max_interval], else moorsim::InputError. Returns dt.
double CheckInterval(double t, double previous, double max_interval);

struct MassMatrices {
  Mat3 mass = Mat3::Zero();     ///< M symmetrised, (M + M^T) / 2
  Mat3 inverse = Mat3::Zero();  ///< its inverse
};
/// The model's mass matrix and its inverse. Throws moorsim::InputError "<owner>: ..." if
/// the mass, damping or mooring damping matrices are not finite or M is not positive
/// definite.
MassMatrices CheckedMass(std::string_view owner, const LowFrequencyModel& model,
                         const Mat3& mooring_damping);

/// D_mo of hypothesis h: bank.MooringDamping(h, mass, ratio) if any ratio is > 0, else 0.
Mat3 MooringDampingFor(const HypothesisBank& bank, int h, const Mat3& mass, const Vec3& ratio);

}  // namespace moorsim::detectors::internal
