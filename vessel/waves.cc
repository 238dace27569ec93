#include "vessel/waves.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <string_view>

#include "core/angles.h"
#include "core/error.h"
#include "core/format.h"
#include "vessel/checks.h"

namespace moorsim::vessel {
namespace {

// DNV-RP-C205 (2010) 3.5.5: the range of gamma over which A_gamma was fitted.
constexpr double kMinPeakEnhancement = 1.0;
constexpr double kMaxPeakEnhancement = 7.0;

// Default frequency range as multiples of omega_p (see WaveRealisationOptions).
constexpr double kDefaultOmegaMinOverPeak = 0.5;
constexpr double kDefaultOmegaMaxOverPeak = 4.0;

// Cells of the tabulated spreading CDF. The table spans only where D is above 1e-16 of its
// peak, so its resolution follows the width of D: ~2000 cells across +-2 circular standard
// deviations for large s; the quantiles agree with direct integration of D to 1e-6 in
// probability (tests/vessel/waves_test.cc).
constexpr int kSpreadingCells = 8192;
constexpr double kSpreadingTailRatio = 1e-16;

// ElevationSeries recomputes exact cosines this often; between anchors each sample costs
// one complex multiplication per component, whose rounding grows ~linearly with the count.
constexpr int kSeriesReanchorSamples = 512;

using internal::ThrowBadValue;

/// Composite Simpson's rule of f over [a, b] on an even number of panels >= 2.
template <typename Integrand>
double Simpson(const Integrand& f, double a, double b, int panels) {
  panels = std::max(2, panels + (panels % 2));
  const double h = (b - a) / panels;
  double sum = f(a) + f(b);
  for (int j = 1; j < panels; ++j) sum += (j % 2 == 1 ? 4.0 : 2.0) * f(a + j * h);
  return sum * h / 3.0;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// JONSWAP

JonswapSpectrum::JonswapSpectrum(const JonswapParameters& parameters) : parameters_(parameters) {
  const double hs = parameters.significant_height;
  const double tp = parameters.peak_period;
  const double gamma = parameters.peak_enhancement;
  if (!(hs > 0.0) || !std::isfinite(hs)) {
    ThrowBadValue("waves.significant_height", hs, "m", "must be > 0 and finite");
  }
  if (!(tp > 0.0) || !std::isfinite(tp)) {
    ThrowBadValue("waves.peak_period", tp, "s", "must be > 0 and finite");
  }
  if (!(gamma >= kMinPeakEnhancement && gamma <= kMaxPeakEnhancement)) {
    ThrowBadValue("waves.peak_enhancement", gamma, "",
                  "must be in [1, 7] (JONSWAP gamma; DNV-RP-C205 3.5.5 fits A_gamma there)");
  }
  peak_frequency_ = kTwoPi / tp;
  normalising_factor_ = 1.0 - 0.287 * std::log(gamma);
}

double JonswapSpectrum::Density(double omega) const {
  if (!(omega > 0.0)) return 0.0;
  const double hs = parameters_.significant_height;
  const double ratio = peak_frequency_ / omega;  // omega_p / omega
  const double ratio4 = ratio * ratio * ratio * ratio;
  // Far below the peak exp() underflows to 0 while ratio^5 may overflow; return the limit
  // instead of inf * 0.
  if (1.25 * ratio4 > 745.0) return 0.0;
  const double pierson_moskowitz =
      5.0 / 16.0 * hs * hs * ratio4 * ratio / peak_frequency_ * std::exp(-1.25 * ratio4);
  const double sigma = omega <= peak_frequency_ ? 0.07 : 0.09;
  const double offset = (omega - peak_frequency_) / (sigma * peak_frequency_);
  const double enhancement =
      std::exp(std::exp(-0.5 * offset * offset) * std::log(parameters_.peak_enhancement));
  return normalising_factor_ * pierson_moskowitz * enhancement;
}

double SpectralMoment(const WaveSpectrum& spectrum, int order, double omega_min, double omega_max,
                      int intervals) {
  if (!(omega_min >= 0.0) || !std::isfinite(omega_min)) {
    ThrowBadValue("spectral moment omega_min", omega_min, "rad/s", "must be >= 0 and finite");
  }
  if (order < 0 && !(omega_min > 0.0)) {
    ThrowBadValue("spectral moment omega_min", omega_min, "rad/s",
                  "must be > 0 for a negative order " + std::to_string(order));
  }
  if (!(omega_max > omega_min) || !std::isfinite(omega_max)) {
    ThrowBadValue("spectral moment omega_max", omega_max, "rad/s",
                  "must be finite and > omega_min = " + FormatNumber(omega_min) + " rad/s");
  }
  if (intervals < 2) {
    ThrowBadValue("spectral moment intervals", intervals, "", "must be >= 2");
  }
  const auto integrand = [&](double omega) {
    const double density = spectrum.Density(omega);
    return density == 0.0 ? 0.0 : std::pow(omega, order) * density;
  };
  const double peak = spectrum.PeakFrequency();
  if (!(peak > omega_min && peak < omega_max)) {
    return Simpson(integrand, omega_min, omega_max, intervals);
  }
  const int below =
      static_cast<int>(std::lround(intervals * (peak - omega_min) / (omega_max - omega_min)));
  return Simpson(integrand, omega_min, peak, below) +
         Simpson(integrand, peak, omega_max, intervals - below);
}

// ---------------------------------------------------------------------------------------
// cos-2s spreading

CosineSpreading::CosineSpreading(double mean_direction, double exponent)
    : mean_direction_(mean_direction), exponent_(exponent) {
  if (!std::isfinite(mean_direction)) {
    ThrowBadValue("waves.mean_direction", mean_direction, "rad", "must be finite");
  }
  if (!(exponent >= 0.0) || !std::isfinite(exponent)) {
    ThrowBadValue("waves.spreading_exponent", exponent, "",
                  "must be >= 0 and finite (cos-2s exponent s; omit it for long-crested waves)");
  }
  normalisation_ =
      std::exp(std::lgamma(exponent + 1.0) - std::lgamma(exponent + 0.5)) / (2.0 * std::sqrt(kPi));

  // Half-width of the table: where cos^(2s)(u/2) falls to kSpreadingTailRatio (the whole
  // turn when s is small). The probability outside is below 1e-16 * 2 pi * peak density.
  table_half_width_ = kPi;
  if (exponent > 0.0) {
    const double cos_edge = std::exp(std::log(kSpreadingTailRatio) / (2.0 * exponent));
    table_half_width_ = std::min(kPi, 2.0 * std::acos(cos_edge));
  }
  offset_cdf_.assign(kSpreadingCells + 1, 0.0);
  const double cell = 2.0 * table_half_width_ / kSpreadingCells;
  const auto shape = [&](double offset) {
    return std::pow(std::cos(0.5 * offset), 2.0 * exponent);
  };
  for (int j = 0; j < kSpreadingCells; ++j) {
    const double left = -table_half_width_ + j * cell;
    offset_cdf_[j + 1] = offset_cdf_[j] + Simpson(shape, left, left + cell, 2);
  }
  const double total = offset_cdf_.back();
  for (double& value : offset_cdf_) value /= total;
  offset_cdf_.back() = 1.0;
}

double CosineSpreading::Density(double direction) const {
  const double offset = WrapAngle(direction - mean_direction_);
  return normalisation_ * std::pow(std::cos(0.5 * offset), 2.0 * exponent_);
}

double CosineSpreading::Quantile(double probability) const {
  if (!(probability >= 0.0 && probability <= 1.0)) {
    ThrowBadValue("spreading quantile probability", probability, "", "must be in [0, 1]");
  }
  const int cells = static_cast<int>(offset_cdf_.size()) - 1;
  // First node with cdf > probability; the cell to its left holds the quantile.
  const auto upper = std::upper_bound(offset_cdf_.begin(), offset_cdf_.end(), probability);
  const int j = std::clamp(static_cast<int>(upper - offset_cdf_.begin()) - 1, 0, cells - 1);
  const double mass = offset_cdf_[j + 1] - offset_cdf_[j];
  const double fraction = mass > 0.0 ? (probability - offset_cdf_[j]) / mass : 0.5;
  // The table spans [-half_width, half_width] in `cells` equal cells.
  const double cell = 2.0 * table_half_width_ / cells;
  return WrapAngle(mean_direction_ - table_half_width_ + (j + fraction) * cell);
}

// ---------------------------------------------------------------------------------------
// Realisation

WaveRealisation::WaveRealisation(const WaveSpectrum& spectrum,
                                 const WaveRealisationOptions& options, RandomStream& stream) {
  if (options.components < 1) {
    ThrowBadValue("waves.components", options.components, "", "must be >= 1");
  }
  if (!(options.gravity > 0.0) || !std::isfinite(options.gravity)) {
    ThrowBadValue("waves.gravity", options.gravity, "m/s^2", "must be > 0 and finite");
  }
  if (!std::isfinite(options.mean_direction)) {
    ThrowBadValue("waves.mean_direction", options.mean_direction, "rad", "must be finite");
  }
  const double peak = spectrum.PeakFrequency();
  omega_min_ = options.omega_min.value_or(kDefaultOmegaMinOverPeak * peak);
  omega_max_ = options.omega_max.value_or(kDefaultOmegaMaxOverPeak * peak);
  if (!(omega_min_ > 0.0) || !std::isfinite(omega_min_)) {
    ThrowBadValue("waves.omega_min", omega_min_, "rad/s", "must be > 0 and finite");
  }
  if (!(omega_max_ > omega_min_) || !std::isfinite(omega_max_)) {
    ThrowBadValue("waves.omega_max", omega_max_, "rad/s",
                  "must be finite and > waves.omega_min = " + FormatNumber(omega_min_) + " rad/s");
  }
  std::optional<CosineSpreading> spreading;
  if (options.spreading_exponent) {
    spreading.emplace(options.mean_direction, *options.spreading_exponent);
  }

  const int n = options.components;
  bin_width_ = (omega_max_ - omega_min_) / n;
  components_.resize(n);
  for (int i = 0; i < n; ++i) {
    // Always three draws per component, in this order (see the class comment).
    const double frequency_draw = stream.Uniform();
    const double phase_draw = stream.Uniform();
    const double direction_draw = stream.Uniform();
    const double in_bin =
        options.frequency_sampling == FrequencySampling::kRandomInBin ? frequency_draw : 0.5;
    WaveComponent& c = components_[i];
    c.omega = omega_min_ + (i + in_bin) * bin_width_;
    c.amplitude = std::sqrt(2.0 * spectrum.Density(c.omega) * bin_width_);
    c.phase = kTwoPi * phase_draw;
    c.direction =
        spreading ? spreading->Quantile(direction_draw) : WrapAngle(options.mean_direction);
  }

  FillSums(options.gravity);
}

WaveRealisation::WaveRealisation(std::vector<WaveComponent> given, double gravity)
    : components_(std::move(given)) {
  if (components_.empty()) ThrowBadValue("waves.trains", 0, "", "must hold at least one wave");
  if (!(gravity > 0.0) || !std::isfinite(gravity)) {
    ThrowBadValue("waves.gravity", gravity, "m/s^2", "must be > 0 and finite");
  }
  omega_min_ = omega_max_ = components_.front().omega;
  for (std::size_t i = 0; i < components_.size(); ++i) {
    const WaveComponent& c = components_[i];
    const std::string name = "waves.trains[" + std::to_string(i + 1) + "]";
    if (!(c.omega > 0.0) || !std::isfinite(c.omega)) {
      ThrowBadValue(name + ".omega", c.omega, "rad/s", "must be > 0 and finite");
    }
    if (!(c.amplitude >= 0.0) || !std::isfinite(c.amplitude)) {
      ThrowBadValue(name + ".amplitude", c.amplitude, "m", "must be >= 0 and finite");
    }
    if (!std::isfinite(c.phase) || !std::isfinite(c.direction)) {
      ThrowBadValue(name + ".phase", c.phase, "rad", "and its direction must be finite");
    }
    omega_min_ = std::min(omega_min_, c.omega);
    omega_max_ = std::max(omega_max_, c.omega);
  }
  FillSums(gravity);
}

void WaveRealisation::FillSums(double gravity) {
  const Eigen::Index n = static_cast<Eigen::Index>(components_.size());
  omega_.resize(n);
  amplitude_.resize(n);
  phase_.resize(n);
  wave_number_north_.resize(n);
  wave_number_east_.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const WaveComponent& c = components_[i];
    const double k = DeepWaterWaveNumber(c.omega, gravity);
    omega_[i] = c.omega;
    amplitude_[i] = c.amplitude;
    phase_[i] = c.phase;
    wave_number_north_[i] = k * std::cos(c.direction);
    wave_number_east_[i] = k * std::sin(c.direction);
  }
}

double WaveRealisation::Elevation(double t, double x, double y) const {
  double elevation = 0.0;
  for (Eigen::Index i = 0; i < omega_.size(); ++i) {
    elevation += amplitude_[i] *
                 std::cos(omega_[i] * t - (wave_number_north_[i] * x + wave_number_east_[i] * y) +
                          phase_[i]);
  }
  return elevation;
}

Eigen::VectorXd WaveRealisation::ElevationSeries(double t_start, double dt, int samples, double x,
                                                 double y) const {
  if (samples < 0) ThrowBadValue("elevation series samples", samples, "", "must be >= 0");
  Eigen::VectorXd elevation(samples);
  const Eigen::Index n = omega_.size();
  const Eigen::ArrayXd local_phase = phase_ - (wave_number_north_ * x + wave_number_east_ * y);
  const Eigen::ArrayXd step_cos = (omega_ * dt).cos();
  const Eigen::ArrayXd step_sin = (omega_ * dt).sin();
  // (re, im) = exp(i (omega_i t + local_phase_i)), advanced by exp(i omega_i dt) per sample.
  Eigen::ArrayXd re(n);
  Eigen::ArrayXd im(n);
  Eigen::ArrayXd next_re(n);
  for (int j = 0; j < samples; ++j) {
    if (j % kSeriesReanchorSamples == 0) {
      const double t = t_start + j * dt;
      re = (omega_ * t + local_phase).cos();
      im = (omega_ * t + local_phase).sin();
    }
    elevation[j] = (amplitude_ * re).sum();
    next_re = re * step_cos - im * step_sin;
    im = re * step_sin + im * step_cos;
    re.swap(next_re);
  }
  return elevation;
}

double WaveRealisation::RealisedVariance() const { return 0.5 * amplitude_.square().sum(); }

double WaveRealisation::RealisedSignificantHeight() const {
  return 4.0 * std::sqrt(RealisedVariance());
}

}  // namespace moorsim::vessel
