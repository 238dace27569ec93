#include "core/passive_observer.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/Cholesky>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"

namespace moorsim {
namespace {

/// Throws moorsim::InputError "<key> = <value>: <rule>" for element i of `key`.
[[noreturn]] void ThrowObserverOption(const PassiveObserverKeys& keys,
                                      const PassiveObserverKey& key, int i, double value,
                                      const std::string& rule) {
  std::string field = std::string(keys.prefix) + std::string(key.name);
  if (key.per_dof) field += "[" + std::to_string(i + keys.first_index) + "]";
  throw InputError(field + " = " + FormatNumber(value) + ": " + rule);
}

/// Every element finite and > 0 (>= 0 with `allow_zero`).
void CheckObserverOptionPositive(const PassiveObserverKeys& keys, const PassiveObserverKey& key,
                                 const Vec3& value, bool allow_zero) {
  for (int i = 0; i < 3; ++i) {
    const double v = value(i);
    if (!(std::isfinite(v) && (allow_zero ? v >= 0.0 : v > 0.0))) {
      ThrowObserverOption(keys, key, i, v,
                          allow_zero ? "must be finite and >= 0" : "must be finite and > 0");
    }
  }
}

/// e = y - eta - xi2 at x on the valid channels, heading wrapped; 0 elsewhere.
Vec3 ObserverOutputError(const ObserverStateLayout::State& x, const Vec3& y,
                         const std::array<bool, 3>& valid) {
  using L = ObserverStateLayout;
  const Vec3 eta = x.segment<3>(L::kPose);
  const Vec3 xi2 = x.segment<3>(L::kWave + 3);
  Vec3 e = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    if (valid[i]) e(i) = y(i) - eta(i) - xi2(i);
  }
  if (valid[2]) e(2) = WrapAngle(e(2));
  return e;
}

}  // namespace

void ValidatePassiveObserver(const PassiveNonlinearObserverOptions& options,
                             const PassiveObserverKeys& keys) {
  CheckObserverOptionPositive(keys, keys.wave_frequency, options.wave_frequency, false);
  CheckObserverOptionPositive(keys, keys.wave_damping, options.wave_damping, true);
  CheckObserverOptionPositive(keys, keys.notch_damping, options.notch_damping, false);
  CheckObserverOptionPositive(keys, keys.cutoff_ratio, options.cutoff_ratio, false);
  CheckObserverOptionPositive(keys, keys.bias_time_constant, options.bias_time_constant, false);
  CheckObserverOptionPositive(keys, keys.velocity_gain, options.velocity_gain, false);
  const Vec3 ratio = options.bias_gain.cwiseQuotient(options.velocity_gain);  // K3 / K4
  const Vec3& bias_gain = keys.bias_gain_is_ratio ? ratio : options.bias_gain;
  CheckObserverOptionPositive(keys, keys.bias_gain, bias_gain, false);
  if (!(std::isfinite(options.max_substep) && options.max_substep > 0.0)) {
    ThrowObserverOption(keys, keys.max_substep, 0, options.max_substep, "must be finite and > 0 s");
  }
  // What the ratio's rule quotes when the caller's key names K3 itself.
  const auto ratio_clause = [&](int i) {
    return keys.bias_gain_is_ratio
               ? std::string()
               : std::string(keys.bias_gain.name) + " / " + std::string(keys.velocity_gain.name) +
                     " = " + FormatNumber(ratio(i)) + " 1/s ";
  };
  for (int i = 0; i < 3; ++i) {
    // The notch needs zeta_n > lambda (K1 changes sign otherwise; Fossen 2011 11.4.1).
    if (!(options.notch_damping(i) > options.wave_damping(i))) {
      ThrowObserverOption(keys, keys.notch_damping, i, options.notch_damping(i),
                          "must be > " + std::string(keys.wave_damping.name) +
                              " (the notch needs zeta_n > lambda)");
    }
    // Fossen & Strand (1999): 1/T < K3/K4 < w0 < w_c (the loop transfer is then SPR).
    if (!(options.cutoff_ratio(i) > 1.0)) {
      ThrowObserverOption(keys, keys.cutoff_ratio, i, options.cutoff_ratio(i),
                          "must be > 1 (passivity: omega_c > omega_0)");
    }
    if (!(ratio(i) > 1.0 / options.bias_time_constant(i))) {
      ThrowObserverOption(keys, keys.bias_gain, i, bias_gain(i),
                          ratio_clause(i) + "must be > 1 / " +
                              std::string(keys.bias_time_constant.name) + " (passivity)");
    }
    if (!(ratio(i) < options.wave_frequency(i))) {
      ThrowObserverOption(
          keys, keys.bias_gain, i, bias_gain(i),
          ratio_clause(i) + "must be < " + std::string(keys.wave_frequency.name) + " (passivity)");
    }
  }
}

PassiveObserverGains ComputePassiveObserverGains(const PassiveNonlinearObserverOptions& options,
                                                 const PassiveObserverKeys& keys) {
  ValidatePassiveObserver(options, keys);
  PassiveObserverGains gains;
  for (int i = 0; i < 3; ++i) {
    const double w0 = options.wave_frequency(i);
    const double wc = options.cutoff_ratio(i) * w0;
    const double notch = options.notch_damping(i) - options.wave_damping(i);
    gains.k1_integral(i) = -2.0 * notch * wc / w0;
    gains.k1_wave(i) = 2.0 * w0 * notch;
    gains.k2(i) = wc;
  }
  if (!options.wave_filter) {
    gains.k1_integral.setZero();
    gains.k1_wave.setZero();
  }
  gains.k3 = options.bias_gain;
  gains.k4 = options.velocity_gain;
  return gains;
}

// ---------------------------------------------------------------------------------------

PassiveNonlinearObserver::PassiveNonlinearObserver(const PassiveNonlinearObserverOptions& options,
                                                   const Mat3& mass, const Mat3& damping,
                                                   MooringLoad load,
                                                   const PassiveObserverKeys& keys)
    : options_(options),
      gains_(ComputePassiveObserverGains(options, keys)),
      load_(std::move(load)) {
  if (!mass.allFinite() || !damping.allFinite()) {
    throw InputError("passive observer: the mass and damping matrices must be finite");
  }
  mass_ = 0.5 * (mass + mass.transpose());
  const Eigen::LLT<Mat3> llt(mass_);
  if (llt.info() != Eigen::Success) {
    throw InputError("passive observer: the mass matrix must be positive definite");
  }
  mass_inverse_ = llt.solve(Mat3::Identity());
  damping_ = damping;
  bias_rate_ = options.bias_time_constant.cwiseInverse();
  wave_stiffness_ = options.wave_frequency.cwiseAbs2();
  wave_resistance_ = 2.0 * options.wave_damping.cwiseProduct(options.wave_frequency);
  Reset();
}

void PassiveNonlinearObserver::Reset(const Vec3& eta_initial) {
  started_ = false;
  seen_ = {false, false, false};
  y_.setZero();
  valid_ = {false, false, false};
  x_.setZero();
  x_.segment<3>(kPose) = eta_initial;
  x_(kPose + 2) = WrapAngle(eta_initial.z());
}

Vec3 PassiveNonlinearObserver::OutputError(const Vec3& y, const std::array<bool, 3>& valid) const {
  return ObserverOutputError(x_, y, valid);
}

PassiveNonlinearObserver::State PassiveNonlinearObserver::Derivative(
    const State& x, const Vec3& y, const std::array<bool, 3>& valid, const Vec3& tau) const {
  const Vec3 xi1 = x.segment<3>(kWave);
  const Vec3 xi2 = x.segment<3>(kWave + 3);
  const Vec3 eta = x.segment<3>(kPose);
  const Vec3 b = x.segment<3>(kBias);
  const Vec3 nu = x.segment<3>(kVelocity);
  const Vec3 e = ObserverOutputError(x, y, valid);

  // R(psi_hat), not R(y_psi): see the file comment.
  const Mat3 R = YawRotation(std::cos(eta.z()), std::sin(eta.z()));
  const Vec3 k3e = gains_.k3.cwiseProduct(e);
  const Vec3 k4e = gains_.k4.cwiseProduct(e);
  Vec3 bias_correction, acceleration_correction;
  if (options_.mass_scaled_gains) {
    bias_correction = R * (mass_ * (R.transpose() * k3e));  // M_e K3 e
    acceleration_correction = R.transpose() * k4e;          // M^-1 R^T M_e K4 e
  } else {
    bias_correction = k3e;
    acceleration_correction = mass_inverse_ * (R.transpose() * k4e);
  }
  const Vec3 load_earth = load_(eta) + b;

  State d;
  d.segment<3>(kWave) = xi2 + gains_.k1_integral.cwiseProduct(e);
  d.segment<3>(kWave + 3) = -wave_stiffness_.cwiseProduct(xi1) -
                            wave_resistance_.cwiseProduct(xi2) + gains_.k1_wave.cwiseProduct(e);
  d.segment<3>(kPose) = R * nu + gains_.k2.cwiseProduct(e);
  d.segment<3>(kBias) = -bias_rate_.cwiseProduct(b) + bias_correction;
  d.segment<3>(kVelocity) =
      mass_inverse_ * (-damping_ * nu + R.transpose() * load_earth + tau) + acceleration_correction;
  return d;
}

void PassiveNonlinearObserver::Propagate(double dt, const Vec3& tau, const Vec3& y,
                                         const std::array<bool, 3>& valid) {
  // Zero-order hold: the held sample, on its channels, over the whole interval. First-order
  // hold: the new sample's channels, each on the line from the held sample where that was
  // valid too, else at the new value.
  const bool first_order = options_.hold == Options::Hold::kFirstOrder;
  const std::array<bool, 3>& injected = first_order ? valid : valid_;
  Vec3 end = y_, step = Vec3::Zero();
  if (first_order) {
    for (int i = 0; i < 3; ++i) {
      end(i) = valid[i] ? y(i) : 0.0;
      if (valid[i] && valid_[i]) step(i) = y(i) - y_(i);
    }
    step(2) = WrapAngle(step(2));
  }
  const Vec3 start = end - step;

  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / options_.max_substep - 1e-9)));
  const double h = dt / substeps;
  for (int n = 0; n < substeps; ++n) {
    Vec3 y0 = y_, y_mid = y_, y1 = y_;
    if (first_order) {
      y0 = start + (static_cast<double>(n) / substeps) * step;
      y_mid = start + ((n + 0.5) / substeps) * step;
      y1 = start + (static_cast<double>(n + 1) / substeps) * step;
    }
    const State k1 = Derivative(x_, y0, injected, tau);
    const State k2 = Derivative(x_ + 0.5 * h * k1, y_mid, injected, tau);
    const State k3 = Derivative(x_ + 0.5 * h * k2, y_mid, injected, tau);
    const State k4 = Derivative(x_ + h * k3, y1, injected, tau);
    x_ += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    x_(kPose + 2) = WrapAngle(x_(kPose + 2));
  }
}

void PassiveNonlinearObserver::Update(double dt, const Vec3& tau, const Vec3& y,
                                      const std::array<bool, 3>& valid) {
  if (started_) {
    Propagate(dt, tau, y, valid);
  } else if (options_.start == Options::Start::kAllChannels) {
    if (!(valid[0] && valid[1] && valid[2])) return;  // nothing held until the start
    x_.setZero();
    x_.segment<3>(kPose) = y;
    x_(kPose + 2) = WrapAngle(y.z());
    started_ = true;
  } else {
    started_ = true;
  }
  if (options_.start == Options::Start::kEachChannel) {
    for (int i = 0; i < 3; ++i) {
      if (!valid[i] || seen_[i]) continue;
      x_(kPose + i) = y(i);
      x_(kWave + i) = x_(kWave + 3 + i) = 0.0;
      seen_[i] = true;
    }
    x_(kPose + 2) = WrapAngle(x_(kPose + 2));
  }
  for (int i = 0; i < 3; ++i) y_(i) = valid[i] ? y(i) : 0.0;
  valid_ = valid;
}

}  // namespace moorsim
