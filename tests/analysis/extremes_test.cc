// Extreme-value fits (analysis/extremes.h): the Gumbel fit of storm maxima recovers a known
// distribution's MPM within its interval, and its intervals cover the truth as often as
// they say; the Weibull fit of one record's peaks and the Gumbel fit of many storms' maxima
// both give the MPM of a linear Gaussian response's maximum, sigma sqrt(2 ln N) for N
// Rayleigh peaks (its mode, exactly computed here).
#include "analysis/extremes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace moorsim::analysis {
namespace {

std::vector<double> GumbelSample(double mu, double beta, int n, std::mt19937_64& random) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x(static_cast<std::size_t>(n));
  for (double& v : x) v = mu - beta * std::log(-std::log(u(random)));
  return x;
}

TEST(Gumbel, RecoversAKnownDistributionsMpmAndQuantileWithinTheirIntervals) {
  std::mt19937_64 random(7);
  const double mu = 8.0e6, beta = 4.0e5;
  const GumbelFit fit = FitGumbel(GumbelSample(mu, beta, 200, random));
  const Estimate mpm = fit.Mpm();
  EXPECT_LT(mpm.lower, mu);
  EXPECT_GT(mpm.upper, mu);
  EXPECT_NEAR(mpm.value, fit.location, 1e-9 * mu);
  const double p90 = mu - beta * std::log(-std::log(0.9));
  const Estimate q = fit.Quantile(0.9);
  EXPECT_LT(q.lower, p90);
  EXPECT_GT(q.upper, p90);
  EXPECT_NEAR(fit.scale, beta, 0.15 * beta);
}

TEST(Gumbel, NinetyFivePercentIntervalsCoverTheTruthNinetyFivePercentOfTheTime) {
  // 1000 fits of 40 maxima each: the MPM's and the 90 % quantile's intervals hold the true
  // values 95 % of the time, to within the binomial spread of 1000 trials (+-1.4 %) and
  // the asymptotic intervals' small-sample shortfall (40 maxima).
  std::mt19937_64 random(11);
  const double mu = 100.0, beta = 10.0;
  const double p90 = mu - beta * std::log(-std::log(0.9));
  int mpm_in = 0, q_in = 0;
  const int trials = 1000;
  for (int t = 0; t < trials; ++t) {
    const GumbelFit fit = FitGumbel(GumbelSample(mu, beta, 40, random));
    const Estimate m = fit.Mpm(), q = fit.Quantile(0.9);
    mpm_in += (m.lower < mu && mu < m.upper) ? 1 : 0;
    q_in += (q.lower < p90 && p90 < q.upper) ? 1 : 0;
  }
  EXPECT_NEAR(mpm_in / double(trials), 0.95, 0.025);
  EXPECT_NEAR(q_in / double(trials), 0.95, 0.03);
}

TEST(Gumbel, SamplesForAToleranceShrinkTheIntervalAsSaid) {
  std::mt19937_64 random(5);
  const GumbelFit fit = FitGumbel(GumbelSample(50.0, 5.0, 30, random));
  const int needed = fit.SamplesFor(0.02);
  const Estimate m = fit.Mpm();
  // The interval's half-width scales as 1/sqrt(n).
  const double half = (m.upper - m.lower) / 2.0 * std::sqrt(30.0 / needed);
  EXPECT_LE(half, 0.02 * fit.location * 1.0001);
  EXPECT_GT(half * std::sqrt(double(needed) / (needed - 1)), 0.02 * fit.location * 0.98);
  EXPECT_THROW(FitGumbel(std::vector<double>{1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(FitGumbel(std::vector<double>{3.0, 3.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(FitGumbel(std::vector<double>{1.0, NAN, 2.0}), std::invalid_argument);
}

// The exact mode of the largest of n Rayleigh peaks of scale sigma: the root of the
// derivative of log(n f F^(n-1)), with f and F the Rayleigh density and distribution.
double RayleighMaximumMode(double sigma, double n) {
  double lo = sigma, hi = 20.0 * sigma;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.5 * (lo + hi);
    const double e = std::exp(-x * x / (2.0 * sigma * sigma));
    // d/dx log: 1/x - x/sigma^2 + (n - 1) (x/sigma^2) e / (1 - e).
    const double slope =
        1.0 / x - x / (sigma * sigma) + (n - 1.0) * x / (sigma * sigma) * e / (1.0 - e);
    (slope > 0.0 ? lo : hi) = x;
  }
  return 0.5 * (lo + hi);
}

TEST(LinearResponse, TheMpmOfRayleighPeaksIsTheClosedFormByBothFits) {
  // A linear Gaussian response of standard deviation sigma: narrow-band, its peaks are
  // Rayleigh. A 3-hour storm with a 10 s mean period has N = 1080 of them, the largest's
  // mode near sigma sqrt(2 ln N) = 3.74 sigma.
  const double sigma = 2.0e5, n = 1080.0;
  const double mode = RayleighMaximumMode(sigma, n);
  EXPECT_NEAR(mode / (sigma * std::sqrt(2.0 * std::log(n))), 1.0, 0.01);
  std::mt19937_64 random(2);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto peak = [&] { return sigma * std::sqrt(-2.0 * std::log(1.0 - u(random))); };
  // 60 storms' maxima, Gumbel-fitted.
  std::vector<double> maxima;
  for (int s = 0; s < 60; ++s) {
    double largest = 0.0;
    for (int i = 0; i < n; ++i) largest = std::max(largest, peak());
    maxima.push_back(largest);
  }
  const Estimate gumbel = FitGumbel(maxima).Mpm();
  EXPECT_LT(gumbel.lower, mode);
  EXPECT_GT(gumbel.upper, mode);
  EXPECT_NEAR(gumbel.value / mode, 1.0, 0.03);
  // One long record's peaks above sigma (20 storms' worth), Weibull-fitted from the
  // response's mean: shape 2.
  std::vector<double> peaks;
  int total = 0;
  for (int i = 0; i < 20 * n; ++i, ++total) {
    const double p = peak();
    if (p > sigma) peaks.push_back(p);
  }
  const WeibullFit weibull = FitWeibull(peaks, sigma, 0.0);
  EXPECT_NEAR(weibull.shape, 2.0, 0.1);
  // Peaks over the threshold expected in one storm.
  const double over = n * static_cast<double>(peaks.size()) / total;
  const Estimate w = weibull.Mpm(over);
  // The value exceeded by one peak in N is sigma sqrt(2 ln N), the mode's leading term.
  const double exceeded_once = sigma * std::sqrt(2.0 * std::log(n));
  EXPECT_LT(w.lower, exceeded_once);
  EXPECT_GT(w.upper, exceeded_once);
  EXPECT_NEAR(w.value / exceeded_once, 1.0, 0.02);
  // The storm maximum's 90 % quantile: exp(-N exp(-x^2 / (2 sigma^2))) = 0.9.
  const double q90 = sigma * std::sqrt(2.0 * (std::log(n) - std::log(-std::log(0.9))));
  const Estimate wq = weibull.Quantile(over, 0.9);
  EXPECT_LT(wq.lower, q90);
  EXPECT_GT(wq.upper, q90);
  EXPECT_NEAR(wq.value / q90, 1.0, 0.02);
  EXPECT_GT(wq.value, w.value);
  EXPECT_THROW(weibull.Quantile(over, 1.0), std::invalid_argument);
}

TEST(PeaksOverThreshold, EachExcursionCountsItsHighestValueOnce) {
  const std::vector<double> x = {0, 2, 3, 2, 0, 5, 0, 1, 4, 4, 1};
  EXPECT_EQ(PeaksOverThreshold(x, 1.5), (std::vector<double>{3, 5, 4}));
  EXPECT_THROW(FitWeibull(std::vector<double>{2.0, 3.0, 1.0}, 1.5, 0.0), std::invalid_argument);
  EXPECT_THROW(FitWeibull(std::vector<double>{2.0, 3.0, 4.0}, 1.5, 2.0), std::invalid_argument);
}

}  // namespace
}  // namespace moorsim::analysis
