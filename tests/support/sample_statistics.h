// Sample statistics shared by the statistical tests (random streams, sensors).
#pragma once

#include <cmath>
#include <vector>

namespace moorsim::testing {

inline double Mean(const std::vector<double>& x) {
  double sum = 0.0;
  for (const double v : x) sum += v;
  return sum / static_cast<double>(x.size());
}

/// Unbiased sample variance (n - 1 in the denominator).
inline double Variance(const std::vector<double>& x) {
  const double mean = Mean(x);
  double sum = 0.0;
  for (const double v : x) sum += (v - mean) * (v - mean);
  return sum / static_cast<double>(x.size() - 1);
}

/// Pearson correlation of x[i] and y[i + lag] over the overlapping samples.
inline double Correlation(const std::vector<double>& x, const std::vector<double>& y, int lag = 0) {
  const int n = static_cast<int>(x.size()) - lag;
  double mx = 0.0;
  double my = 0.0;
  for (int i = 0; i < n; ++i) {
    mx += x[i];
    my += y[i + lag];
  }
  mx /= n;
  my /= n;
  double sxy = 0.0;
  double sxx = 0.0;
  double syy = 0.0;
  for (int i = 0; i < n; ++i) {
    const double dx = x[i] - mx;
    const double dy = y[i + lag] - my;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  return sxy / std::sqrt(sxx * syy);
}

}  // namespace moorsim::testing
