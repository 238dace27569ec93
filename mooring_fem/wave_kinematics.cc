#include "mooring_fem/wave_kinematics.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/sincos.h"

namespace moorsim::mooring_fem {

namespace {

// A component's velocity and acceleration below this are left out [m/s, m/s^2]: a
// hundredth of a millimetre per second, against currents of 0.1-1 m/s.
constexpr double kNegligible = 1e-5;

[[noreturn]] void Refuse(const std::string& what, double value) {
  std::ostringstream out;
  out << "wave kinematics: " << what << " " << value;
  throw InputError(out.str());
}

// Per-call scratch for the components' phases (one per thread: campaigns run simulations
// on several).
struct PhaseScratch {
  std::vector<double> chi, sine, cosine;
  void Resize(std::size_t n) {
    if (chi.size() < n) {
      chi.resize(n);
      sine.resize(n);
      cosine.resize(n);
    }
  }
};

}  // namespace

double WaveKinematics::WaveNumber(double omega, double depth, double gravity) {
  const double deep = omega * omega / gravity;
  if (std::tanh(deep * depth) == 1.0) return deep;
  // Newton on f(k) = g k tanh(k h) - omega^2 from above the root (f is convex in k).
  double k = std::max(deep, omega / std::sqrt(gravity * depth));
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double th = std::tanh(k * depth);
    const double f = gravity * k * th - omega * omega;
    const double slope = gravity * (th + k * depth * (1.0 - th * th));
    const double step = f / slope;
    k -= step;
    if (std::abs(step) <= 1e-15 * k) break;
  }
  return k;
}

WaveKinematics::WaveKinematics(const std::vector<WaveTrain>& trains, double depth, double gravity,
                               WaveStretching stretching)
    : depth_(depth), stretching_(stretching) {
  if (!(depth > 0.0 && std::isfinite(depth))) Refuse("depth must be > 0 m, not", depth);
  if (!(gravity > 0.0 && std::isfinite(gravity))) Refuse("gravity must be > 0, not", gravity);
  for (const WaveTrain& w : trains) {
    if (!(w.omega > 0.0 && std::isfinite(w.omega))) Refuse("frequency must be > 0, not", w.omega);
    if (!(w.amplitude >= 0.0 && std::isfinite(w.amplitude))) {
      Refuse("amplitude must be >= 0 m, not", w.amplitude);
    }
    if (!std::isfinite(w.phase) || !std::isfinite(w.direction)) {
      Refuse("phase and direction must be finite, not", w.phase + w.direction);
    }
  }
  // The components that reach deepest first, so those that reach a point are a prefix.
  // Velocity a omega C and acceleration a omega^2 C with C <= 2 exp(k zeta) / (1 -
  // exp(-2 k h)): below `reach` both are under kNegligible.
  struct Sorted {
    WaveTrain w;
    double k, decay, reach;
  };
  std::vector<Sorted> sorted;
  for (const WaveTrain& w : trains) {
    const double k = WaveNumber(w.omega, depth, gravity);
    const double decay = 1.0 / -std::expm1(-2.0 * k * depth);
    const double size = 2.0 * w.amplitude * w.omega * std::max(1.0, w.omega) * decay;
    sorted.push_back({w, k, decay, size > kNegligible ? std::log(size / kNegligible) / k : 0.0});
  }
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Sorted& a, const Sorted& b) { return a.reach > b.reach; });
  for (const Sorted& c : sorted) {
    omega_.push_back(c.w.omega);
    amplitude_.push_back(c.w.amplitude);
    phase_.push_back(c.w.phase);
    k_.push_back(c.k);
    cos_dir_.push_back(std::cos(c.w.direction));
    sin_dir_.push_back(std::sin(c.w.direction));
    kx_.push_back(c.k * cos_dir_.back());
    ky_.push_back(c.k * sin_dir_.back());
    decay_.push_back(c.decay);
    reach_.push_back(c.reach);
    highest_crest_ += c.w.amplitude;
  }
  deepest_reach_ = reach_.empty() ? 0.0 : reach_.front();
}

double WaveKinematics::Elevation(double t, double x, double y) const {
  double eta = 0.0;
  for (std::size_t i = 0; i < omega_.size(); ++i) {
    eta += amplitude_[i] * std::cos(omega_[i] * t - (kx_[i] * x + ky_[i] * y) + phase_[i]);
  }
  return eta;
}

WaterMotion WaveKinematics::At(double t, const Vec3& r, bool with_gradient) const {
  WaterMotion out;
  const double zeta = -r.z();
  const double h = depth_;
  // Out of every crest's reach, or too deep for any component.
  if (zeta > highest_crest_) return out;
  // The highest the stretched height can be.
  double zeta_bound = std::min(zeta, 0.0);
  if (stretching_ == WaveStretching::kWheeler) {
    zeta_bound = highest_crest_ < h ? h * (zeta + highest_crest_) / (h - highest_crest_) : 0.0;
  }
  if (zeta_bound < -deepest_reach_ || omega_.empty()) return out;

  // The components that reach the point at its highest: a prefix (the constructor's order).
  const auto reaching = [&](double height) {
    return static_cast<std::size_t>(
        std::partition_point(reach_.begin(), reach_.end(), [&](double d) { return height >= -d; }) -
        reach_.begin());
  };
  // Wheeler's stretched height needs the surface above the point (every component), and
  // so does a point that may be above a trough; deeper points with no stretching need only
  // the components that reach them.
  const bool surface_needed = stretching_ == WaveStretching::kWheeler || zeta > -highest_crest_;
  const std::size_t n = surface_needed ? omega_.size() : reaching(zeta_bound);
  thread_local PhaseScratch scratch;
  scratch.Resize(n);
  double* chi = scratch.chi.data();
  for (std::size_t i = 0; i < n; ++i) {
    chi[i] = omega_[i] * t - (kx_[i] * r.x() + ky_[i] * r.y()) + phase_[i];
  }
  moorsim::internal::SinCos(chi, scratch.sine.data(), scratch.cosine.data(), static_cast<int>(n));
  const double* s = scratch.sine.data();
  const double* c = scratch.cosine.data();

  // The surface above the point and its slope; the stretched height and its gradient.
  double eta = 0.0, eta_x = 0.0, eta_y = 0.0;
  if (surface_needed) {
    for (std::size_t i = 0; i < n; ++i) {
      eta += amplitude_[i] * c[i];
      eta_x += amplitude_[i] * kx_[i] * s[i];
      eta_y += amplitude_[i] * ky_[i] * s[i];
    }
    if (zeta > eta) return out;  // out of the water
  }
  double zs = 0.0;
  Vec3 dzs = Vec3::Zero();  // d zeta_s / d r
  if (stretching_ == WaveStretching::kWheeler) {
    zs = h * (zeta - eta) / (h + eta);
    const double d_eta = -h * (h + zeta) / ((h + eta) * (h + eta));
    dzs = Vec3(d_eta * eta_x, d_eta * eta_y, -h / (h + eta));
  } else {
    zs = std::min(zeta, 0.0);
    dzs.z() = zeta < 0.0 ? -1.0 : 0.0;
  }

  const std::size_t active = std::min(n, reaching(zs));
  for (std::size_t i = 0; i < active; ++i) {
    const double k = k_[i];
    const double q = std::exp(k * zs);
    // The seabed's image, exp(-k (zs + 2 h)) = q exp(-2 k (zs + h)): below 1e-16 of q
    // where k (zs + h) > 18.5 (deep water for this component at this point).
    const double p = k * (zs + h) > 18.5 ? 0.0 : std::exp(-k * (zs + 2.0 * h));
    const double C = (q + p) * decay_[i];
    const double S = (q - p) * decay_[i];
    const double av = amplitude_[i] * omega_[i];
    const double aa = av * omega_[i];
    const double uh = av * C * c[i];
    const double w = -av * S * s[i];
    const double ah = -aa * C * s[i];
    const double aw = -aa * S * c[i];
    out.velocity += Vec3(uh * cos_dir_[i], uh * sin_dir_[i], -w);
    out.acceleration += Vec3(ah * cos_dir_[i], ah * sin_dir_[i], -aw);
    if (!with_gradient) continue;
    const Vec3 dchi(-kx_[i], -ky_[i], 0.0);
    const Eigen::RowVector3d duh = (av * (k * S * c[i] * dzs - C * s[i] * dchi)).transpose();
    const Eigen::RowVector3d dw = (-av * (k * C * s[i] * dzs + S * c[i] * dchi)).transpose();
    const Eigen::RowVector3d dah = (-aa * (k * S * s[i] * dzs + C * c[i] * dchi)).transpose();
    const Eigen::RowVector3d daw = (-aa * (k * C * c[i] * dzs - S * s[i] * dchi)).transpose();
    out.d_velocity.row(0) += cos_dir_[i] * duh;
    out.d_velocity.row(1) += sin_dir_[i] * duh;
    out.d_velocity.row(2) -= dw;
    out.d_acceleration.row(0) += cos_dir_[i] * dah;
    out.d_acceleration.row(1) += sin_dir_[i] * dah;
    out.d_acceleration.row(2) -= daw;
  }
  return out;
}

}  // namespace moorsim::mooring_fem
