// Extreme-value statistics of a response (a line's tension, the vessel's offset) for the
// design checks: the most probable maximum (MPM) in a storm and a chosen quantile of it,
// with their confidence intervals, from
// * the maxima of independent storms of the same sea state (one per seed), fitted with a
//   Gumbel distribution by maximum likelihood (the method of the standards' "several
//   realisations"); or
// * the peaks of one long record above a threshold, fitted by maximum likelihood with a
//   Weibull distribution from the record's mean (P(X > x) = exp(-((x - mean) / scale)^shape),
//   truncated at the threshold: the peaks of a linear Gaussian response are Rayleigh, shape
//   2), the storm's maximum being the value its expected number of peaks exceeds once.
// The intervals are asymptotic (the inverse of the observed information, the delta method
// for the quantiles), at `confidence` (0.95 unless asked).
#pragma once

#include <cmath>

#include <Eigen/Dense>
#include <span>
#include <string_view>
#include <vector>

#include "core/choice.h"

namespace moorsim::analysis {

/// How a sea state's extremes are estimated: the maxima of several storms (one per seed),
/// Gumbel-fitted; or the peaks of one long record, Weibull-fitted.
enum class ExtremesMethod { kGumbel, kWeibull };
inline constexpr std::string_view kExtremesMethodNames[] = {"gumbel", "weibull"};
constexpr ChoiceInfo ChoicesOf(ExtremesMethod) { return {"extremes method", kExtremesMethodNames}; }

/// A statistic with its confidence interval.
struct Estimate {
  double value = 0.0;
  double lower = 0.0, upper = 0.0;
};

/// Gumbel (maxima) distribution F(x) = exp(-exp(-(x - location) / scale)).
struct GumbelFit {
  double location = 0.0;  ///< mu: the mode, i.e. the MPM of one storm's maximum
  double scale = 0.0;     ///< beta > 0
  /// The estimates' covariance (location, scale): the inverse of the observed information.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  int samples = 0;
  double confidence = 0.95;

  /// The maximum not exceeded with probability p, with its interval.
  Estimate Quantile(double p) const;
  /// The MPM (the mode, the location), with its interval.
  Estimate Mpm() const { return Quantile(std::exp(-1.0)); }
  /// How many maxima would give an MPM interval of +-`fraction` of the MPM (the asymptotic
  /// variance of the location, scaled by sample count).
  int SamplesFor(double fraction) const;
};

/// Fits `maxima` (at least 3, not all equal; finite). Throws std::invalid_argument
/// otherwise.
GumbelFit FitGumbel(std::span<const double> maxima, double confidence = 0.95);

/// The local maxima of `history` above `threshold` (each upcrossing of the threshold's
/// excursion counts its highest value once).
std::vector<double> PeaksOverThreshold(std::span<const double> history, double threshold);

/// Weibull fit of the peaks above `threshold`, measured from `location` (the record's mean):
/// P(X > x | X > threshold) = exp(-((x - location) / scale)^shape + ((threshold -
/// location) / scale)^shape).
struct WeibullFit {
  double threshold = 0.0, location = 0.0;
  double scale = 0.0, shape = 0.0;
  /// Covariance of (log scale, log shape): the inverse of the observed information.
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  int samples = 0;
  double confidence = 0.95;

  /// The largest of `peaks` peaks over the threshold not exceeded with probability p
  /// (P(max <= x) = exp(-peaks P(X > x))), with its interval.
  Estimate Quantile(double peaks, double p) const;
  /// The MPM of the largest of `peaks` peaks over the threshold (the value one peak in
  /// `peaks` exceeds: the quantile at exp(-1)), with its interval.
  Estimate Mpm(double peaks) const { return Quantile(peaks, std::exp(-1.0)); }
};

/// Fits the peaks (values above `threshold`, at least 3; `threshold` not below `location`).
/// Throws std::invalid_argument.
WeibullFit FitWeibull(std::span<const double> peaks, double threshold, double location,
                      double confidence = 0.95);

/// The standard normal's quantile at p in (0, 1).
double NormalQuantile(double p);

}  // namespace moorsim::analysis
