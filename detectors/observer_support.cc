#include "detectors/observer_support.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/Cholesky>

#include "core/error.h"

namespace moorsim::detectors::internal {

void ThrowField(std::string_view field, double value, std::string_view rule) {
  std::ostringstream out;
  out.precision(10);
  out << field << " = " << value << ": " << rule;
  throw InputError(out.str());
}

std::string Element(std::string_view name, int i) {
  std::ostringstream out;
  out << name << "[" << i + 1 << "]";
  return out.str();
}

void CheckVector(std::string_view prefix, std::string_view name, const Vec3& value,
                 bool allow_zero) {
  for (int i = 0; i < 3; ++i) {
    const double v = value(i);
    if (!(std::isfinite(v) && (allow_zero ? v >= 0.0 : v > 0.0))) {
      ThrowField(std::string(prefix) + Element(name, i), v,
                 allow_zero ? "must be finite and >= 0" : "must be finite and > 0");
    }
  }
}

void CheckScalar(std::string_view prefix, std::string_view name, double value) {
  if (!(std::isfinite(value) && value > 0.0)) {
    ThrowField(std::string(prefix) + std::string(name), value, "must be finite and > 0");
  }
}

void CheckObservation(const Observation& observation) {
  if (!std::isfinite(observation.t)) {
    std::ostringstream out;
    out << "observation.t = " << observation.t << ": must be finite";
    throw InputError(out.str());
  }
  if (!observation.tau_command.allFinite()) {
    std::ostringstream out;
    out << "observation.tau_command at t = " << observation.t << " s is not finite";
    throw InputError(out.str());
  }
  for (int i = 0; i < 3; ++i) {
    if (observation.valid[i] && !std::isfinite(observation.pose(i))) {
      std::ostringstream out;
      out << "observation.pose[" << i + 1 << "] = " << observation.pose(i)
          << " at t = " << observation.t << " s: a valid channel must be finite";
      throw InputError(out.str());
    }
  }
}

double CheckInterval(double t, double previous, double max_interval) {
  const double dt = t - previous;
  if (!(dt > 0.0) || dt > max_interval) {
    std::ostringstream out;
    out << "observation.t = " << t << " s: must advance from the previous " << previous
        << " s by (0, " << max_interval << "] s";
    throw InputError(out.str());
  }
  return dt;
}

MassMatrices CheckedMass(std::string_view owner, const LowFrequencyModel& model,
                         const Mat3& mooring_damping) {
  if (!model.mass.allFinite() || !model.damping.allFinite() || !mooring_damping.allFinite()) {
    throw InputError(std::string(owner) +
                     ": the mass, damping and mooring damping matrices must be finite");
  }
  MassMatrices m;
  m.mass = 0.5 * (model.mass + model.mass.transpose());
  const Eigen::LLT<Mat3> llt(m.mass);
  if (llt.info() != Eigen::Success) {
    throw InputError(std::string(owner) +
                     ": the mass matrix M = M_RB + A(0) must be positive definite");
  }
  m.inverse = llt.solve(Mat3::Identity());
  return m;
}

Mat3 MooringDampingFor(const HypothesisBank& bank, int h, const Mat3& mass, const Vec3& ratio) {
  return (ratio.array() > 0.0).any() ? bank.MooringDamping(h, mass, ratio) : Mat3::Zero();
}

}  // namespace moorsim::detectors::internal
