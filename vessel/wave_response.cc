#include "vessel/wave_response.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "core/sincos.h"
#include "core/types.h"
#include "vessel/checks.h"

namespace moorsim::vessel {
namespace {

// Heading grid limits. Above 45° the grid would blur HydroData's 10° table; below 0.1° the
// table of 200 components outgrows 80 MB and gains nothing over data tabulated every 10°.
constexpr double kMaxHeadingStep = 45.0 * kDegree;
constexpr double kMinHeadingStep = 0.1 * kDegree;

// Drift modes kept by default: surge, sway, yaw (WaveResponseOptions::drift_all_modes).
constexpr int kHorizontalModes[] = {0, 1, 5};

void CheckOptions(const WaveResponseOptions& options) {
  const double step = options.heading_step;
  // The relative slack lets 45 * pi / 180 through whichever way it was rounded.
  if (!std::isfinite(step) || step < kMinHeadingStep * (1.0 - 1e-12) ||
      step > kMaxHeadingStep * (1.0 + 1e-12)) {
    throw InputError("WaveResponseOptions.heading_step = " + FormatNumber(step) + " rad (" +
                     FormatNumber(step / kDegree) + " deg): must be finite and in [0.1, 45] deg");
  }
  if (!std::isfinite(options.gravity) || !(options.gravity > 0.0)) {
    throw InputError("WaveResponseOptions.gravity = " + FormatNumber(options.gravity) +
                     " m/s^2: must be finite and > 0");
  }
}

// Components are taken in blocks of this many for the vectorised phase and sincos passes
// (three stack arrays of 512 bytes).
constexpr int kBlock = 64;

/// Where β = θ − ψ falls on the heading grid of n cells from −π: the cell and the weight
/// of its upper node. θ + π and ψ come as fractions of a turn in [0, 1), so β + π is their
/// difference, wrapped once. (The branch is the same for a component from call to call
/// while ψ changes slowly, so it predicts well; a branch-free form measured 8 % slower.)
struct HeadingCell {
  int cell = 0;
  double weight = 0.0;
};

inline HeadingCell LocateHeading(double direction_turns, double psi_turns, int n) {
  double turns = direction_turns - psi_turns;  // (−1, 1)
  if (turns < 0.0) turns += 1.0;               // [0, 1]; 1 only by rounding, at node n
  const double position = turns * n;
  const int cell = std::min(static_cast<int>(position), n - 1);
  return {cell, position - cell};
}

/// ψ as a fraction of a turn, in [0, 1).
inline double PsiTurns(double psi) {
  const double turns = psi / kTwoPi;
  const double fraction = turns - std::floor(turns);
  return fraction < 1.0 ? fraction : 0.0;
}

}  // namespace

WaveResponse::WaveResponse(const HydroData& hydro, const WaveRealisation& waves,
                           const WaveResponseOptions& options) {
  CheckOptions(options);
  if (hydro.motion_rao.empty()) {
    throw InputError("WaveResponse: no motion RAOs: '" + hydro.source + ".4' was not read");
  }
  if (hydro.mean_drift.empty()) {
    throw InputError("WaveResponse: no mean drift coefficients: '" + hydro.source +
                     ".9' was not read");
  }

  if (options.drift_all_modes) {
    drift_modes_ = {0, 1, 2, 3, 4, 5};
  } else {
    drift_modes_.assign(std::begin(kHorizontalModes), std::end(kHorizontalModes));
  }
  // Three drift modes take four columns (the fourth zero) so that pairs of modes fill SSE2
  // registers.
  drift_columns_ = options.drift_all_modes ? 6 : 4;
  row_size_ = 12 + drift_columns_;
  // 1e-12 keeps a step that divides the turn up to rounding (2 deg) from gaining a cell.
  heading_cells_ = static_cast<int>(std::ceil(kTwoPi / options.heading_step * (1.0 - 1e-12)));
  const int n = heading_cells_;
  const double step = kTwoPi / n;

  const std::vector<WaveComponent>& components = waves.components();
  const std::size_t count = components.size();
  omega_.resize(count);
  amplitude_.resize(count);
  phase_.resize(count);
  wave_number_north_.resize(count);
  wave_number_east_.resize(count);
  direction_turns_.resize(count);
  table_.assign(count * static_cast<std::size_t>(n + 1) * row_size_, 0.0);

  for (std::size_t i = 0; i < count; ++i) {
    const WaveComponent& c = components[i];
    // The same expressions as WaveRealisation, so χ_i matches its Elevation to round-off.
    const double k = DeepWaterWaveNumber(c.omega, options.gravity);
    omega_[i] = c.omega;
    amplitude_[i] = c.amplitude;
    phase_[i] = c.phase;
    wave_number_north_[i] = k * std::cos(c.direction);
    wave_number_east_[i] = k * std::sin(c.direction);
    const double turns = (c.direction + kPi) / kTwoPi;
    direction_turns_[i] = turns - std::floor(turns);
    if (direction_turns_[i] >= 1.0) direction_turns_[i] = 0.0;

    double* rows = &table_[i * static_cast<std::size_t>(n + 1) * row_size_];
    for (int g = 0; g < n; ++g) {
      const double beta = -kPi + g * step;
      const ComplexVec6 rao = hydro.Rao(c.omega, beta);
      const Vec6 drift = hydro.Drift(c.omega, beta);
      double* row = rows + static_cast<std::size_t>(g) * row_size_;
      for (int j = 0; j < 6; ++j) {
        row[j] = rao[j].real();
        row[6 + j] = rao[j].imag();
      }
      for (std::size_t m = 0; m < drift_modes_.size(); ++m) row[12 + m] = drift[drift_modes_[m]];
    }
    // Node n (β = +π) is node 0 (β = −π): the same head seas, bit for bit.
    std::copy(rows, rows + row_size_, rows + static_cast<std::size_t>(n) * row_size_);
  }
}

double WaveResponse::heading_step() const { return kTwoPi / heading_cells_; }

template <bool kMotion, int kDriftColumns>
void WaveResponse::Accumulate(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot,
                              Vec6* drift) const {
  // Fixed-size Eigen arrays over the modes so that the blends, square roots and sums run
  // two modes per SSE2 instruction; the drift columns are padded to an even count.
  using Modes = Eigen::Array<double, 6, 1>;
  using DriftModes = Eigen::Array<double, (kDriftColumns > 0 ? kDriftColumns : 2), 1>;
  Modes xi_sum = Modes::Zero();
  Modes xi_dot_sum = Modes::Zero();
  // Re and Im of z₊ and z₋ per drift mode.
  DriftModes plus_re = DriftModes::Zero();
  DriftModes plus_im = DriftModes::Zero();
  DriftModes minus_re = DriftModes::Zero();
  DriftModes minus_im = DriftModes::Zero();

  const int n = heading_cells_;
  const std::size_t stride = static_cast<std::size_t>(n + 1) * row_size_;
  const double psi_turns = PsiTurns(psi);
  const double* table = table_.data();
  const std::size_t count = omega_.size();

  double chi[kBlock];
  double sin_chi[kBlock];
  double cos_chi[kBlock];
  for (std::size_t begin = 0; begin < count; begin += kBlock) {
    const int block = static_cast<int>(std::min<std::size_t>(kBlock, count - begin));
    const double* omega = &omega_[begin];
    const double* north = &wave_number_north_[begin];
    const double* east = &wave_number_east_[begin];
    const double* phase = &phase_[begin];
    // χ_i exactly as WaveRealisation::Elevation writes it.
    for (int l = 0; l < block; ++l) chi[l] = omega[l] * t - (north[l] * x + east[l] * y) + phase[l];
    moorsim::internal::SinCos(chi, sin_chi, cos_chi, block);

    for (int l = 0; l < block; ++l) {
      const std::size_t i = begin + l;
      const HeadingCell h = LocateHeading(direction_turns_[i], psi_turns, n);
      const double w = h.weight;
      const double* low = table + i * stride + static_cast<std::size_t>(h.cell) * row_size_;
      const double* high = low + row_size_;
      const double a = amplitude_[i];
      const double c = cos_chi[l];
      const double s = sin_chi[l];

      if constexpr (kMotion) {
        // a Re{(R + i I) e^{iχ}} = a (R cos χ − I sin χ); d/dt multiplies by iω.
        const Eigen::Map<const Modes> re_low(low);
        const Eigen::Map<const Modes> im_low(low + 6);
        const Eigen::Map<const Modes> re_high(high);
        const Eigen::Map<const Modes> im_high(high + 6);
        const Modes re = re_low + w * (re_high - re_low);
        const Modes im = im_low + w * (im_high - im_low);
        const double a_cos = a * c;
        const double a_sin = a * s;
        xi_sum += re * a_cos - im * a_sin;
        xi_dot_sum -= omega[l] * (re * a_sin + im * a_cos);
      }
      if constexpr (kDriftColumns > 0) {
        const Eigen::Map<const DriftModes> d_low(low + 12);
        const Eigen::Map<const DriftModes> d_high(high + 12);
        const DriftModes d = d_low + w * (d_high - d_low);
        const DriftModes q = a * d.abs().sqrt();
        // Each component joins z₊ or z₋ by the sign of its D: a select, not a branch.
        const DriftModes q_plus = (d > 0.0).select(q, 0.0);
        const DriftModes q_minus = q - q_plus;
        plus_re += q_plus * c;
        plus_im += q_plus * s;
        minus_re += q_minus * c;
        minus_im += q_minus * s;
      }
    }
  }

  if constexpr (kMotion) {
    if (xi != nullptr) *xi = xi_sum.matrix();
    if (xi_dot != nullptr) *xi_dot = xi_dot_sum.matrix();
  }
  if constexpr (kDriftColumns > 0) {
    const DriftModes load =
        (plus_re.square() + plus_im.square()) - (minus_re.square() + minus_im.square());
    drift->setZero();
    for (std::size_t m = 0; m < drift_modes_.size(); ++m) (*drift)[drift_modes_[m]] = load[m];
  }
}

void WaveResponse::Evaluate(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot,
                            Vec6* drift) const {
  if (!std::isfinite(t) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(psi)) {
    // No exception on the RHS path: NaN tells the ODE adapter to cut the step.
    for (Vec6* out : {xi, xi_dot, drift}) {
      if (out != nullptr) out->setConstant(kNaN);
    }
    return;
  }
  const bool motion = xi != nullptr || xi_dot != nullptr;
  // The drift column count as a template argument gives fixed-size, vectorised arrays.
  const bool six = drift_columns_ == 6;
  if (drift == nullptr) {
    if (motion) Accumulate<true, 0>(t, x, y, psi, xi, xi_dot, nullptr);
  } else if (motion) {
    if (six) {
      Accumulate<true, 6>(t, x, y, psi, xi, xi_dot, drift);
    } else {
      Accumulate<true, 4>(t, x, y, psi, xi, xi_dot, drift);
    }
  } else {
    if (six) {
      Accumulate<false, 6>(t, x, y, psi, nullptr, nullptr, drift);
    } else {
      Accumulate<false, 4>(t, x, y, psi, nullptr, nullptr, drift);
    }
  }
}

void WaveResponse::Motion(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot) const {
  Evaluate(t, x, y, psi, xi, xi_dot, nullptr);
}

Vec6 WaveResponse::DriftLoad(double t, double x, double y, double psi) const {
  Vec6 drift;
  Evaluate(t, x, y, psi, nullptr, nullptr, &drift);
  return drift;
}

Vec6 WaveResponse::MeanDrift(double psi) const {
  // The time average of |z₊|² − |z₋|² keeps only the i = k terms: Σ_i a_i² D_ij.
  Vec6 mean = Vec6::Zero();
  if (!std::isfinite(psi)) {
    mean.setConstant(kNaN);
    return mean;
  }
  const int n = heading_cells_;
  const std::size_t stride = static_cast<std::size_t>(n + 1) * row_size_;
  const double psi_turns = PsiTurns(psi);
  for (std::size_t i = 0; i < omega_.size(); ++i) {
    const HeadingCell h = LocateHeading(direction_turns_[i], psi_turns, n);
    const double w = h.weight;
    const double* low = &table_[i * stride + static_cast<std::size_t>(h.cell) * row_size_];
    const double* high = low + row_size_;
    const double a_squared = amplitude_[i] * amplitude_[i];
    for (std::size_t m = 0; m < drift_modes_.size(); ++m) {
      mean[drift_modes_[m]] += a_squared * (low[12 + m] + w * (high[12 + m] - low[12 + m]));
    }
  }
  return mean;
}

}  // namespace moorsim::vessel
