#include "analysis/extremes.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

namespace moorsim::analysis {
namespace {

void RequireSamples(std::span<const double> x, const char* what) {
  if (x.size() < 3) {
    throw std::invalid_argument(std::string(what) + ": at least 3 values to fit, got " +
                                std::to_string(x.size()));
  }
  for (double v : x) {
    if (!std::isfinite(v)) {
      throw std::invalid_argument(std::string(what) + ": a value that is not finite");
    }
  }
}

// Bisection for the root of an increasing function on [lo, hi] (f(lo) < 0 < f(hi)).
template <typename F>
double Root(F f, double lo, double hi) {
  for (int i = 0; i < 200 && hi - lo > 1e-14 * std::abs(hi); ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Estimate Interval(double value, double variance, double confidence) {
  const double half = NormalQuantile(0.5 + confidence / 2.0) * std::sqrt(std::max(variance, 0.0));
  return {value, value - half, value + half};
}

}  // namespace

double NormalQuantile(double p) {
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("normal quantile: p outside (0, 1)");
  // Phi(x) = erfc(-x / sqrt 2) / 2 increases with x.
  return Root([p](double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)) - p; }, -40.0, 40.0);
}

GumbelFit FitGumbel(std::span<const double> maxima, double confidence) {
  RequireSamples(maxima, "Gumbel fit");
  const double n = static_cast<double>(maxima.size());
  const double lowest = *std::min_element(maxima.begin(), maxima.end());
  const double mean = std::accumulate(maxima.begin(), maxima.end(), 0.0) / n;
  double spread = 0.0;
  for (double x : maxima) spread += (x - mean) * (x - mean);
  spread = std::sqrt(spread / (n - 1.0));
  if (!(spread > 0.0)) throw std::invalid_argument("Gumbel fit: every value is the same");
  // The likelihood equation for the scale: beta = mean - sum x w / sum w, w = e^(-x/beta)
  // (x measured from the lowest value, so that no weight overflows).
  const auto weights = [&](double beta, double* sum_w, double* sum_xw) {
    *sum_w = *sum_xw = 0.0;
    for (double x : maxima) {
      const double w = std::exp(-(x - lowest) / beta);
      *sum_w += w;
      *sum_xw += (x - lowest) * w;
    }
  };
  const double guess = spread * std::sqrt(6.0) / std::numbers::pi;
  const double beta = Root(
      [&](double b) {
        double sw, sxw;
        weights(b, &sw, &sxw);
        return b - (mean - lowest) + sxw / sw;
      },
      guess * 1e-3, guess * 1e3);
  double sw, sxw;
  weights(beta, &sw, &sxw);
  GumbelFit fit;
  fit.scale = beta;
  fit.location = lowest - beta * std::log(sw / n);
  fit.samples = static_cast<int>(maxima.size());
  fit.confidence = confidence;
  // The observed information: minus the log-likelihood's Hessian in (mu, beta).
  double s_e = 0.0, s_z = 0.0, s_ze = 0.0, s_zze = 0.0;
  for (double x : maxima) {
    const double z = (x - fit.location) / beta;
    const double e = std::exp(-z);
    s_e += e;
    s_z += z;
    s_ze += z * e;
    s_zze += z * z * e;
  }
  Eigen::Matrix2d information;
  information(0, 0) = s_e;
  information(0, 1) = information(1, 0) = n - s_e + s_ze;
  information(1, 1) = -(n - 2.0 * s_z + 2.0 * s_ze - s_zze);
  information /= beta * beta;
  fit.covariance = information.inverse();
  return fit;
}

Estimate GumbelFit::Quantile(double p) const {
  const double y = -std::log(-std::log(p));
  const Eigen::Vector2d gradient(1.0, y);
  return Interval(location + scale * y, gradient.dot(covariance * gradient), confidence);
}

int GumbelFit::SamplesFor(double fraction) const {
  const double z = NormalQuantile(0.5 + confidence / 2.0);
  const double per_sample = covariance(0, 0) * samples;
  return static_cast<int>(std::ceil(z * z * per_sample / std::pow(fraction * location, 2)));
}

std::vector<double> PeaksOverThreshold(std::span<const double> history, double threshold) {
  std::vector<double> peaks;
  bool above = false;
  for (double x : history) {
    if (x > threshold) {
      if (!above) peaks.push_back(x);
      peaks.back() = std::max(peaks.back(), x);
      above = true;
    } else {
      above = false;
    }
  }
  return peaks;
}

WeibullFit FitWeibull(std::span<const double> peaks, double threshold, double location,
                      double confidence) {
  RequireSamples(peaks, "Weibull fit");
  if (!(threshold >= location)) {
    throw std::invalid_argument("Weibull fit: the threshold lies below the location");
  }
  std::vector<double> y;
  for (double p : peaks) {
    if (!(p > threshold)) {
      throw std::invalid_argument("Weibull fit: a peak at or below the threshold");
    }
    y.push_back(p - location);
  }
  const double n = static_cast<double>(y.size());
  // Measured in units of the largest: no power overflows.
  const double unit = *std::max_element(y.begin(), y.end());
  double sum_log = 0.0;
  for (double& v : y) {
    v /= unit;
    sum_log += std::log(v);
  }
  const double t = (threshold - location) / unit;
  // For a shape k the scale's likelihood equation gives sigma^k = mean(y^k - t^k); the
  // profile log-likelihood in log k is then maximised (golden section).
  const auto scale_power = [&](double k) {
    double s = 0.0;
    for (double v : y) s += std::pow(v, k) - std::pow(t, k);
    return s / n;
  };
  const auto profile = [&](double log_k) {
    const double k = std::exp(log_k);
    return n * log_k - n * std::log(scale_power(k)) + (k - 1.0) * sum_log - n;
  };
  double lo = std::log(0.05), hi = std::log(50.0);
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double a = hi - golden * (hi - lo), b = lo + golden * (hi - lo);
    (profile(a) < profile(b) ? lo : hi) = (profile(a) < profile(b) ? a : b);
  }
  const double k = std::exp(0.5 * (lo + hi));
  WeibullFit fit;
  fit.threshold = threshold;
  fit.location = location;
  fit.shape = k;
  fit.scale = unit * std::pow(scale_power(k), 1.0 / k);
  fit.samples = static_cast<int>(y.size());
  fit.confidence = confidence;
  // The observed information in (log scale, log shape), by central differences of the
  // log-likelihood (in the scaled unit: the same curvature).
  const auto log_likelihood = [&](double a, double b) {
    const double sigma = std::exp(a) / unit, shape = std::exp(b);
    double l = n * (b - shape * std::log(sigma)) + n * std::pow(t / sigma, shape);
    for (double v : y) l += (shape - 1.0) * std::log(v) - std::pow(v / sigma, shape);
    return l;
  };
  const double a = std::log(fit.scale), b = std::log(k), h = 1e-4;
  const double l0 = log_likelihood(a, b);
  Eigen::Matrix2d information;
  information(0, 0) = -(log_likelihood(a + h, b) - 2.0 * l0 + log_likelihood(a - h, b)) / (h * h);
  information(1, 1) = -(log_likelihood(a, b + h) - 2.0 * l0 + log_likelihood(a, b - h)) / (h * h);
  information(0, 1) = information(1, 0) =
      -(log_likelihood(a + h, b + h) - log_likelihood(a + h, b - h) - log_likelihood(a - h, b + h) +
        log_likelihood(a - h, b - h)) /
      (4.0 * h * h);
  fit.covariance = information.inverse();
  return fit;
}

Estimate WeibullFit::Quantile(double peaks, double p) const {
  if (!(peaks > 1.0)) throw std::invalid_argument("Weibull quantile: fewer than 2 peaks");
  if (!(p > 0.0 && p < 1.0)) throw std::invalid_argument("Weibull quantile: p outside (0, 1)");
  // peaks P(X > x) = -ln p: ((x - c) / sigma)^k = ((u - c) / sigma)^k + ln N - ln(-ln p),
  // so x - c = sigma q^(1/k), with q that sum and t = u - c.
  const double t = threshold - location;
  const double tail = std::log(peaks) - std::log(-std::log(p));
  const auto at = [&](double a, double b) {
    const double sigma = std::exp(a), k = std::exp(b);
    return sigma * std::pow(std::pow(t / sigma, k) + tail, 1.0 / k);
  };
  // Derivatives of the excess in log sigma (a) and log k (b), by central differences.
  const double a = std::log(scale), b = std::log(shape), h = 1e-6;
  const Eigen::Vector2d gradient((at(a + h, b) - at(a - h, b)) / (2.0 * h),
                                 (at(a, b + h) - at(a, b - h)) / (2.0 * h));
  return Interval(location + at(a, b), gradient.dot(covariance * gradient), confidence);
}

}  // namespace moorsim::analysis
