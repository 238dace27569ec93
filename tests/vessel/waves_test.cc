// Tests of the wave spectrum, spreading and realisations (vessel/waves.h).
//
// References independent of the implementation: the closed-form Pierson-Moskowitz
// cumulative (gamma = 1), DNV-RP-C205's published fits of Tz/Tp and T1/Tp, the analytic
// cos-2s normalisation and trigonometric moments, and the random-phase model's own
// statistics. Monte-Carlo bounds are 4.5 standard errors (two-sided false-failure
// probability ~7e-6 for a correct implementation); the seeds are fixed so a pass repeats.
#include "vessel/waves.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "core/random.h"

namespace moorsim::vessel {
namespace {

constexpr double kGravity = 9.81;
constexpr double kSigmas = 4.5;

/// The seed sea state (TAPM thesis table 4.3; docs/design.md section 9).
JonswapParameters SeedSeaState(double gamma = 3.3) {
  JonswapParameters sea;
  sea.significant_height = 2.5;
  sea.peak_period = 7.0;
  sea.peak_enhancement = gamma;
  return sea;
}

WaveRealisation Realise(const WaveSpectrum& spectrum, const WaveRealisationOptions& options,
                        std::uint64_t seed) {
  RandomStream stream = RandomStream::Derive(seed, "waves");
  return WaveRealisation(spectrum, options, stream);
}

double SampleVariance(const Eigen::VectorXd& x) {
  return (x.array() - x.mean()).square().sum() / static_cast<double>(x.size() - 1);
}

/// Sample autocorrelation of x at a lag of `lag` samples (means removed, normalised by the
/// overlapping part's variances).
double Autocorrelation(const Eigen::VectorXd& x, Eigen::Index lag) {
  const Eigen::Index n = x.size() - lag;
  const Eigen::ArrayXd a = x.head(n).array() - x.head(n).mean();
  const Eigen::ArrayXd b = x.tail(n).array() - x.tail(n).mean();
  return (a * b).sum() / std::sqrt(a.square().sum() * b.square().sum());
}

// --- spectrum ------------------------------------------------------------------------

TEST(JonswapSpectrumTest, VarianceIsHsSquaredOverSixteen) {
  // DNV's A_gamma = 1 - 0.287 ln(gamma) is a fit, so the integral is Hs^2/16 only
  // approximately. Measured over (0, 60 omega_p] (the PM tail beyond holds
  // 1 - exp(-1.25/60^4) = 1e-7 of the energy): gamma 1: -1e-7 (exact form),
  // 3.3: +0.24 %, 5: +0.0003 %. The 1 % bound is the brief's; it holds with room.
  for (const double gamma : {1.0, 3.3, 5.0}) {
    const JonswapSpectrum spectrum(SeedSeaState(gamma));
    const double wp = spectrum.PeakFrequency();
    const double m0 = SpectralMoment(spectrum, 0, 0.0, 60.0 * wp, 200000);
    const double target = 2.5 * 2.5 / 16.0;
    const double relative_error = m0 / target - 1.0;
    RecordProperty("relative_error_gamma_" + std::to_string(gamma), std::to_string(relative_error));
    EXPECT_LT(std::abs(relative_error), 0.01) << "gamma = " << gamma;
    if (gamma == 1.0) {
      EXPECT_LT(std::abs(relative_error), 1e-6);
    }
  }
}

TEST(JonswapSpectrumTest, NormalisationErrorAtGammaSevenIsDnvs) {
  // Documents the approximation at the edge of DNV's range (the class comment quotes it):
  // m0 is 1.75 % low at gamma = 7, so Hs is 0.88 % low.
  const JonswapSpectrum spectrum(SeedSeaState(7.0));
  const double m0 = SpectralMoment(spectrum, 0, 0.0, 60.0 * spectrum.PeakFrequency(), 200000);
  EXPECT_NEAR(m0 / (2.5 * 2.5 / 16.0) - 1.0, -0.0175, 0.0005);
}

TEST(JonswapSpectrumTest, PiersonMoskowitzCumulativeMatchesClosedForm) {
  // gamma = 1 is Pierson-Moskowitz, whose integral from omega to infinity is
  // Hs^2/16 (1 - exp(-5/4 (omega_p/omega)^4)) (substitute u = 5/4 (omega_p/omega)^4).
  // Checks SpectralMoment and the spectrum's form together; Simpson on 2e5 panels is
  // accurate to well below 1e-7 relative.
  const JonswapSpectrum spectrum(SeedSeaState(1.0));
  const double wp = spectrum.PeakFrequency();
  const double upper = 60.0 * wp;
  const auto tail = [&](double omega) {
    return 2.5 * 2.5 / 16.0 * (1.0 - std::exp(-1.25 * std::pow(wp / omega, 4)));
  };
  for (const double lower : {0.7 * wp, wp, 1.5 * wp, 3.0 * wp}) {
    const double expected = tail(lower) - tail(upper);
    EXPECT_NEAR(SpectralMoment(spectrum, 0, lower, upper, 200000), expected, 1e-7 * expected)
        << "from " << lower / wp << " omega_p";
  }
}

TEST(JonswapSpectrumTest, PeriodsMatchDnvFits) {
  // DNV-RP-C205 (2010) 3.5.5.4 gives cubic fits in gamma of the mean zero-crossing period
  // Tz = 2 pi sqrt(m0/m2) and the mean period T1 = 2 pi m0/m1 relative to Tp. They test
  // the spectrum's shape, not only its area. The fits are approximations themselves
  // (measured deviation <= 0.22 %); 0.5 % is their stated-to-the-digit precision.
  for (const double gamma : {1.0, 3.3, 5.0}) {
    const JonswapSpectrum spectrum(SeedSeaState(gamma));
    const double wp = spectrum.PeakFrequency();
    // m2's integrand falls only as omega^-3; stopping at 60 omega_p loses 1.4e-4 of it.
    const double upper = 60.0 * wp;
    const double m0 = SpectralMoment(spectrum, 0, 0.0, upper, 200000);
    const double m1 = SpectralMoment(spectrum, 1, 0.0, upper, 200000);
    const double m2 = SpectralMoment(spectrum, 2, 0.0, upper, 200000);
    const double tz_over_tp = 2.0 * kPi * std::sqrt(m0 / m2) / 7.0;
    const double t1_over_tp = 2.0 * kPi * m0 / m1 / 7.0;
    const double g = gamma;
    EXPECT_NEAR(tz_over_tp, 0.6673 + 0.05037 * g - 0.006230 * g * g + 0.0003341 * g * g * g,
                0.005 * tz_over_tp)
        << "gamma = " << gamma;
    EXPECT_NEAR(t1_over_tp, 0.7303 + 0.04936 * g - 0.006556 * g * g + 0.0003610 * g * g * g,
                0.005 * t1_over_tp)
        << "gamma = " << gamma;
  }
}

TEST(JonswapSpectrumTest, PeaksAtPeakFrequencyWithEnhancedHeight) {
  for (const double gamma : {1.0, 3.3, 5.0, 7.0}) {
    const JonswapSpectrum spectrum(SeedSeaState(gamma));
    const double wp = spectrum.PeakFrequency();
    EXPECT_DOUBLE_EQ(wp, 2.0 * kPi / 7.0);
    // Scan +-30 % around omega_p in steps of 1e-5 omega_p: the maximum is at omega_p to
    // within one step (both the PM factor and the enhancement peak exactly there).
    double best_omega = 0.0;
    double best_density = -1.0;
    for (int j = -30000; j <= 30000; ++j) {
      const double omega = wp * (1.0 + 1e-5 * j);
      const double density = spectrum.Density(omega);
      if (density > best_density) {
        best_density = density;
        best_omega = omega;
      }
    }
    EXPECT_NEAR(best_omega, wp, 1.01e-5 * wp) << "gamma = " << gamma;
    // At the peak the enhancement is exactly gamma: S(wp) = A_gamma gamma 5/16 Hs^2 e^-1.25 / wp.
    const double pm_peak = 5.0 / 16.0 * 2.5 * 2.5 * std::exp(-1.25) / wp;
    EXPECT_NEAR(spectrum.Density(wp), (1.0 - 0.287 * std::log(gamma)) * gamma * pm_peak,
                1e-12 * pm_peak * gamma);
  }
}

TEST(JonswapSpectrumTest, IsZeroAndFiniteAwayFromTheSea) {
  const JonswapSpectrum spectrum(SeedSeaState());
  EXPECT_EQ(spectrum.Density(0.0), 0.0);
  EXPECT_EQ(spectrum.Density(-1.0), 0.0);
  EXPECT_EQ(spectrum.Density(1e-80), 0.0);  // omega^-5 alone would overflow here
  EXPECT_EQ(spectrum.Density(0.05), 0.0);
  EXPECT_GT(spectrum.Density(100.0), 0.0);
  EXPECT_TRUE(std::isfinite(spectrum.Density(1e-3)));
}

// --- spreading -----------------------------------------------------------------------

TEST(CosineSpreadingTest, IntegratesToOneOverATurn) {
  // Simpson on 20000 panels of a smooth periodic function: error far below 1e-9.
  for (const double s : {0.0, 0.5, 1.0, 2.0, 10.0, 75.0, 400.0}) {
    const CosineSpreading spreading(0.3, s);
    double integral = 0.0;
    const int panels = 20000;
    const double h = 2.0 * kPi / panels;
    for (int j = 0; j <= panels; ++j) {
      const double weight = (j == 0 || j == panels) ? 1.0 : (j % 2 == 1 ? 4.0 : 2.0);
      integral += weight * spreading.Density(0.3 - kPi + j * h);
    }
    EXPECT_NEAR(integral * h / 3.0, 1.0, 1e-9) << "s = " << s;
  }
  // Closed forms: s = 0 is uniform, 1/(2 pi); s = 1 is (1 + cos(theta - theta_0)) / (2 pi).
  EXPECT_NEAR(CosineSpreading(0.3, 0.0).Density(2.0), 1.0 / (2.0 * kPi), 1e-15);
  EXPECT_NEAR(CosineSpreading(0.3, 1.0).Density(0.3), 1.0 / kPi, 1e-15);
  EXPECT_NEAR(CosineSpreading(0.3, 1.0).Density(0.3 + kPi), 0.0, 1e-15);
  EXPECT_NEAR(CosineSpreading(0.3, 10.0).Density(1.0),
              CosineSpreading(0.3, 10.0).Density(1.0 + 2.0 * kPi), 1e-14);
}

TEST(CosineSpreadingTest, QuantileInvertsTheDistribution) {
  for (const double s : {0.0, 1.0, 10.0, 400.0}) {
    const CosineSpreading spreading(-2.5, s);
    // Symmetric about theta_0, so the median is theta_0.
    EXPECT_NEAR(spreading.Quantile(0.5), -2.5, 1e-9) << "s = " << s;
    // The probability between the quantiles q(p1) and q(p2) is p2 - p1: integrate D
    // between them with Simpson (independent of the table: analytic normalisation).
    for (const auto& [p1, p2] : {std::pair{0.1, 0.9}, std::pair{0.25, 0.5}, std::pair{0.02, 0.3}}) {
      double a = spreading.Quantile(p1);
      double b = spreading.Quantile(p2);
      if (b < a) b += 2.0 * kPi;  // the interval may wrap through +-pi
      const int panels = 20000;
      const double h = (b - a) / panels;
      double integral = 0.0;
      for (int j = 0; j <= panels; ++j) {
        const double weight = (j == 0 || j == panels) ? 1.0 : (j % 2 == 1 ? 4.0 : 2.0);
        integral += weight * spreading.Density(a + j * h);
      }
      EXPECT_NEAR(integral * h / 3.0, p2 - p1, 1e-6) << "s = " << s << ", p = " << p1 << ".." << p2;
    }
  }
}

TEST(WaveRealisationTest, RealisedDirectionsFollowTheSpreading) {
  // 20000 components give 20000 independent directions. For cos-2s the offset
  // u = theta - theta_0 has E[cos u] = s/(s+1), E[sin u] = 0 and
  // E[cos 2u] = s(s-1)/((s+1)(s+2)), which give the variances of the sample means.
  // theta_0 near pi makes the directions wrap through +-pi.
  const JonswapSpectrum spectrum(SeedSeaState());
  for (const double mean_direction : {3.0 * kPi / 4.0, kPi - 0.1, -1.0}) {
    const double s = 10.0;
    WaveRealisationOptions options;
    options.mean_direction = mean_direction;
    options.spreading_exponent = s;
    options.components = 20000;
    const WaveRealisation sea = Realise(spectrum, options, 11);
    double sum_cos = 0.0;
    double sum_sin = 0.0;
    for (const WaveComponent& c : sea.components()) {
      EXPECT_GT(c.direction, -kPi);
      EXPECT_LE(c.direction, kPi);
      sum_cos += std::cos(c.direction - mean_direction);
      sum_sin += std::sin(c.direction - mean_direction);
    }
    const double n = options.components;
    const double mean_cos = s / (s + 1.0);
    const double mean_cos2 = s * (s - 1.0) / ((s + 1.0) * (s + 2.0));
    const double var_cos = 0.5 * (1.0 + mean_cos2) - mean_cos * mean_cos;
    const double var_sin = 0.5 * (1.0 - mean_cos2);
    EXPECT_NEAR(sum_cos / n, mean_cos, kSigmas * std::sqrt(var_cos / n));
    EXPECT_NEAR(sum_sin / n, 0.0, kSigmas * std::sqrt(var_sin / n));
    // Circular mean direction: within ~0.3 deg of theta_0.
    EXPECT_NEAR(std::remainder(std::atan2(sum_sin, sum_cos), 2.0 * kPi), 0.0,
                kSigmas * std::sqrt(var_sin / n) / mean_cos);
  }
}

TEST(WaveRealisationTest, LongCrestedComponentsShareTheMeanDirection) {
  const JonswapSpectrum spectrum(SeedSeaState());
  WaveRealisationOptions options;
  options.mean_direction = 7.0;  // wrapped to 7 - 2 pi
  const WaveRealisation sea = Realise(spectrum, options, 3);
  for (const WaveComponent& c : sea.components()) EXPECT_DOUBLE_EQ(c.direction, 7.0 - 2.0 * kPi);
}

// --- realisation ----------------------------------------------------------------------

TEST(WaveRealisationTest, ComponentsFollowTheConstruction) {
  const JonswapSpectrum spectrum(SeedSeaState());
  const WaveRealisationOptions options;
  const WaveRealisation sea = Realise(spectrum, options, 1);
  const double wp = 2.0 * kPi / 7.0;
  EXPECT_DOUBLE_EQ(sea.omega_min(), 0.5 * wp);
  EXPECT_DOUBLE_EQ(sea.omega_max(), 4.0 * wp);
  ASSERT_EQ(sea.components().size(), 200u);
  EXPECT_NEAR(sea.bin_width(), 3.5 * wp / 200.0, 1e-15);
  for (std::size_t i = 0; i < sea.components().size(); ++i) {
    const WaveComponent& c = sea.components()[i];
    const double bin_start = sea.omega_min() + i * sea.bin_width();
    EXPECT_GE(c.omega, bin_start);
    EXPECT_LT(c.omega, bin_start + sea.bin_width());
    EXPECT_NEAR(c.amplitude, std::sqrt(2.0 * spectrum.Density(c.omega) * sea.bin_width()), 1e-15);
    EXPECT_GE(c.phase, 0.0);
    EXPECT_LT(c.phase, 2.0 * kPi);
  }
}

TEST(WaveRealisationTest, RealisedSignificantHeightMatchesTarget) {
  // Hs = 4 sqrt(m0) of the realised record within 2 % of the requested 2.5 m.
  // Two estimates of m0 for ten seeds: the realisation's sum a_i^2/2, and the sample
  // variance of a 3-hour record sampled at 0.5 s (what a wave probe would report). Expected
  // deviations: the default range drops 0.32 % of m0 and DNV's A_gamma adds 0.24 % (Hs
  // -0.04 % net); random frequencies make sum a_i^2/2 a stratified estimate of m0 whose Hs
  // has a standard deviation of 0.30 % over seeds (worst 1.03 % in 10^4 seeds, measured);
  // the 3-hour record's variance differs from sum a_i^2/2 by cross terms that the record
  // length averages to a few tenths of a percent. Measured here: worst 0.88 % (seed 7).
  const JonswapSpectrum spectrum(SeedSeaState());
  const WaveRealisationOptions options;
  double worst_sum = 0.0;
  double worst_record = 0.0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const WaveRealisation sea = Realise(spectrum, options, seed);
    const double hs_sum = sea.RealisedSignificantHeight();
    const Eigen::VectorXd record = sea.ElevationSeries(0.0, 0.5, 21600);
    const double hs_record = 4.0 * std::sqrt(SampleVariance(record));
    worst_sum = std::max(worst_sum, std::abs(hs_sum / 2.5 - 1.0));
    worst_record = std::max(worst_record, std::abs(hs_record / 2.5 - 1.0));
    EXPECT_NEAR(hs_sum, 2.5, 0.02 * 2.5) << "seed " << seed;
    EXPECT_NEAR(hs_record, 2.5, 0.02 * 2.5) << "seed " << seed;
    EXPECT_NEAR(std::abs(record.mean()), 0.0, 0.01);  // zero-mean sea, 1 cm
  }
  RecordProperty("worst_hs_error_sum", std::to_string(worst_sum));
  RecordProperty("worst_hs_error_record", std::to_string(worst_record));
}

TEST(WaveRealisationTest, RecordDoesNotRepeat) {
  // A grid whose frequencies are all integer multiples of d_omega repeats exactly after
  // T = 2 pi / d_omega: choose omega_min = 28.5 d_omega so the bin centres are
  // (29 + i) d_omega. Bin centres (the control) then give a record that repeats to
  // rounding; random frequencies in the same bins must not.
  const JonswapSpectrum spectrum(SeedSeaState());
  WaveRealisationOptions options;
  options.components = 200;
  const double d_omega = 0.45 / 28.5;
  options.omega_min = 0.45;
  options.omega_max = 0.45 + 200 * d_omega;
  const double dt = 0.5;
  const double period = 2.0 * kPi / d_omega;  // 398 s
  const double lag_time = std::round(period / dt) * dt;
  const Eigen::Index lag = static_cast<Eigen::Index>(std::lround(period / dt));

  options.frequency_sampling = FrequencySampling::kBinCentre;
  const WaveRealisation grid = Realise(spectrum, options, 5);
  // Exact repetition, checked on the exact period rather than the sampled lag.
  for (const double t : {0.0, 123.4, 5000.0}) {
    EXPECT_NEAR(grid.Elevation(t + period, 0.0, 0.0), grid.Elevation(t, 0.0, 0.0), 1e-9);
  }
  const Eigen::VectorXd grid_record = grid.ElevationSeries(0.0, dt, 21600);
  EXPECT_GT(Autocorrelation(grid_record, lag), 0.99);

  // Random frequencies: omega_i T = 2 pi (29 + i + U_i), so the record's autocorrelation
  // at lag T is sum_i w_i cos(2 pi U_i + ...), w_i = a_i^2 / sum a^2: zero mean, variance
  // sum w_i^2 / 2 over seeds. Check each seed against 4.5 of those standard deviations
  // and the RMS over 20 seeds against the prediction (factor 0.6..1.5 covers the RMS's own
  // sampling spread for 20 seeds).
  options.frequency_sampling = FrequencySampling::kRandomInBin;
  double sum_r2 = 0.0;
  double sum_predicted = 0.0;
  const int seeds = 20;
  for (int seed = 1; seed <= seeds; ++seed) {
    const WaveRealisation sea = Realise(spectrum, options, seed);
    double total = 0.0;
    double total_sq = 0.0;
    for (const WaveComponent& c : sea.components()) total += c.amplitude * c.amplitude;
    for (const WaveComponent& c : sea.components()) {
      const double w = c.amplitude * c.amplitude / total;
      total_sq += w * w;
    }
    const double predicted_variance = 0.5 * total_sq;
    const Eigen::VectorXd record = sea.ElevationSeries(0.0, dt, 21600);
    const double r = Autocorrelation(record, lag);
    EXPECT_LT(std::abs(r), kSigmas * std::sqrt(predicted_variance)) << "seed " << seed;
    EXPECT_LT(std::abs(r), 0.5) << "seed " << seed;
    sum_r2 += r * r;
    sum_predicted += predicted_variance;
    if (seed == 1) {
      RecordProperty("lag_T_autocorrelation_seed1", std::to_string(r));
      EXPECT_GT(std::abs(sea.Elevation(100.0 + lag_time, 0.0, 0.0) - sea.Elevation(100.0, 0, 0)),
                0.0);
    }
  }
  const double rms_ratio = std::sqrt(sum_r2 / sum_predicted);
  RecordProperty("lag_T_rms_over_prediction", std::to_string(rms_ratio));
  EXPECT_GT(rms_ratio, 0.6);
  EXPECT_LT(rms_ratio, 1.5);
}

TEST(WaveRealisationTest, SeriesMatchesPointwiseElevation) {
  // The phasor recurrence against direct cosines over 3 hours, at the origin and at a
  // point off it in a short-crested sea. Rounding over 512 rotations of 200 unit phasors
  // is ~1e-13 m; 1e-9 m leaves room.
  const JonswapSpectrum spectrum(SeedSeaState());
  WaveRealisationOptions options;
  options.spreading_exponent = 4.0;
  options.mean_direction = 2.0;
  const WaveRealisation sea = Realise(spectrum, options, 8);
  for (const auto& [x, y] : {std::pair{0.0, 0.0}, std::pair{150.0, -80.0}}) {
    const Eigen::VectorXd series = sea.ElevationSeries(10.0, 0.5, 21600, x, y);
    double worst = 0.0;
    for (Eigen::Index j = 0; j < series.size(); ++j) {
      worst = std::max(worst, std::abs(series[j] - sea.Elevation(10.0 + 0.5 * j, x, y)));
    }
    EXPECT_LT(worst, 1e-9) << "at (" << x << ", " << y << ")";
  }
  EXPECT_EQ(sea.ElevationSeries(0.0, 0.5, 0).size(), 0);
}

TEST(WaveRealisationTest, WavesTravelTowardTheirDirection) {
  // One component travelling to theta_0 = 60 deg (north-east-ish): the crest seen at the
  // origin at t arrives a distance d downstream at t + d / c, c = g / omega (deep water).
  const JonswapSpectrum spectrum(SeedSeaState());
  WaveRealisationOptions options;
  options.components = 1;
  options.mean_direction = kPi / 3.0;
  const WaveRealisation sea = Realise(spectrum, options, 2);
  const double omega = sea.components()[0].omega;
  const double celerity = kGravity / omega;
  const double d = 37.0;
  const double x = d * std::cos(kPi / 3.0);
  const double y = d * std::sin(kPi / 3.0);
  for (const double t : {0.0, 3.3, 40.0}) {
    EXPECT_NEAR(sea.Elevation(t + d / celerity, x, y), sea.Elevation(t, 0.0, 0.0), 1e-12);
  }
  // Long-crested: the crests are lines perpendicular to theta_0, so a full realisation
  // is the same anywhere along one.
  options.components = 200;
  const WaveRealisation long_crested = Realise(spectrum, options, 2);
  for (const double t : {0.0, 3.3, 40.0}) {
    EXPECT_NEAR(long_crested.Elevation(t, -d * std::sin(kPi / 3.0), d * std::cos(kPi / 3.0)),
                long_crested.Elevation(t, 0.0, 0.0), 1e-12);
  }
}

TEST(WaveRealisationTest, SameSeedRepeatsAndDifferentSeedDiffers) {
  const JonswapSpectrum spectrum(SeedSeaState());
  WaveRealisationOptions options;
  options.spreading_exponent = 10.0;
  const WaveRealisation a = Realise(spectrum, options, 42);
  const WaveRealisation b = Realise(spectrum, options, 42);
  const WaveRealisation c = Realise(spectrum, options, 43);
  ASSERT_EQ(a.components().size(), b.components().size());
  for (std::size_t i = 0; i < a.components().size(); ++i) {
    EXPECT_EQ(a.components()[i].omega, b.components()[i].omega);
    EXPECT_EQ(a.components()[i].phase, b.components()[i].phase);
    EXPECT_EQ(a.components()[i].direction, b.components()[i].direction);
    EXPECT_NE(a.components()[i].phase, c.components()[i].phase);
  }
  const Eigen::VectorXd record_a = a.ElevationSeries(0.0, 0.5, 21600);
  const Eigen::VectorXd record_b = b.ElevationSeries(0.0, 0.5, 21600);
  const Eigen::VectorXd record_c = c.ElevationSeries(0.0, 0.5, 21600);
  EXPECT_EQ(record_a, record_b);  // bit for bit
  // Two independent realisations: the records' correlation is a random-phase sum like
  // the one in RecordDoesNotRepeat; 0.5 is beyond 4 of its standard deviations.
  const Eigen::ArrayXd da = record_a.array() - record_a.mean();
  const Eigen::ArrayXd dc = record_c.array() - record_c.mean();
  const double r = (da * dc).sum() / std::sqrt(da.square().sum() * dc.square().sum());
  RecordProperty("seed_42_vs_43_correlation", std::to_string(r));
  EXPECT_LT(std::abs(r), 0.5);
}

TEST(WaveRealisationTest, SpreadingDoesNotChangeFrequenciesOrPhases) {
  // Each component takes three draws whatever the options, so switching spreading on
  // keeps the sea's frequencies and phases: only the directions change.
  const JonswapSpectrum spectrum(SeedSeaState());
  WaveRealisationOptions options;
  const WaveRealisation long_crested = Realise(spectrum, options, 9);
  options.spreading_exponent = 2.0;
  const WaveRealisation short_crested = Realise(spectrum, options, 9);
  for (std::size_t i = 0; i < long_crested.components().size(); ++i) {
    EXPECT_EQ(long_crested.components()[i].omega, short_crested.components()[i].omega);
    EXPECT_EQ(long_crested.components()[i].phase, short_crested.components()[i].phase);
  }
}

// --- bad input ------------------------------------------------------------------------

struct BadInputCase {
  const char* name;
  std::function<void()> build;
  const char* message;  // expected substring: field, value and constraint
};

void BuildSea(const JonswapParameters& sea, const WaveRealisationOptions& options) {
  const JonswapSpectrum spectrum(sea);
  RandomStream stream = RandomStream::Derive(1, "waves");
  const WaveRealisation realisation(spectrum, options, stream);
}

JonswapParameters WithSea(const std::function<void(JonswapParameters&)>& change) {
  JonswapParameters sea = SeedSeaState();
  change(sea);
  return sea;
}

WaveRealisationOptions WithOptions(const std::function<void(WaveRealisationOptions&)>& change) {
  WaveRealisationOptions options;
  change(options);
  return options;
}

// A given sea: the components as they are, the deep-water wave number for the hull;
// nothing drawn. A bad component is refused naming it.
TEST(WaveRealisationTest, AGivenSeaIsItsComponents) {
  const std::vector<WaveComponent> given = {{0.5, 1.2, 0.3, 0.7}, {1.1, 0.4, -2.0, -1.9}};
  const WaveRealisation sea(given, 9.81);
  ASSERT_EQ(sea.components().size(), 2u);
  EXPECT_EQ(sea.bin_width(), 0.0);
  EXPECT_EQ(sea.omega_min(), 0.5);
  EXPECT_EQ(sea.omega_max(), 1.1);
  for (const auto& [t, x, y] : {std::tuple{0.0, 0.0, 0.0}, std::tuple{12.5, 80.0, -30.0}}) {
    double expected = 0.0;
    for (const WaveComponent& c : given) {
      const double k = c.omega * c.omega / 9.81;
      expected += c.amplitude *
                  std::cos(c.omega * t -
                           k * (x * std::cos(c.direction) + y * std::sin(c.direction)) + c.phase);
    }
    EXPECT_NEAR(sea.Elevation(t, x, y), expected, 1e-12);
  }
  const auto message = [](std::vector<WaveComponent> bad) {
    try {
      WaveRealisation(std::move(bad), 9.81);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(message({{0.5, 1.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}}).find("waves.trains[2].omega"),
            std::string::npos);
  EXPECT_NE(message({{0.5, -1.0, 0.0, 0.0}}).find("waves.trains[1].amplitude"), std::string::npos);
  EXPECT_NE(message({}).find("waves.trains"), std::string::npos);
}

TEST(WavesBadInputTest, EveryBadValueIsNamed) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::vector<BadInputCase> cases = {
      {"HsZero", [] { BuildSea(WithSea([](auto& s) { s.significant_height = 0.0; }), {}); },
       "waves.significant_height: 0 m must be > 0"},
      {"HsNegative", [] { BuildSea(WithSea([](auto& s) { s.significant_height = -1.5; }), {}); },
       "waves.significant_height: -1.5 m must be > 0"},
      {"HsNaN", [] { BuildSea(WithSea([](auto& s) { s.significant_height = kNaN; }), {}); },
       "waves.significant_height: nan m"},
      {"TpZero", [] { BuildSea(WithSea([](auto& s) { s.peak_period = 0.0; }), {}); },
       "waves.peak_period: 0 s must be > 0"},
      {"TpInfinite", [] { BuildSea(WithSea([](auto& s) { s.peak_period = kInf; }), {}); },
       "waves.peak_period: inf s"},
      {"GammaBelowOne", [] { BuildSea(WithSea([](auto& s) { s.peak_enhancement = 0.5; }), {}); },
       "waves.peak_enhancement: 0.5 must be in [1, 7]"},
      {"GammaAboveSeven", [] { BuildSea(WithSea([](auto& s) { s.peak_enhancement = 8.0; }), {}); },
       "waves.peak_enhancement: 8 must be in [1, 7]"},
      {"NoComponents",
       [] { BuildSea(SeedSeaState(), WithOptions([](auto& o) { o.components = 0; })); },
       "waves.components: 0 must be >= 1"},
      {"OmegaMinZero",
       [] { BuildSea(SeedSeaState(), WithOptions([](auto& o) { o.omega_min = 0.0; })); },
       "waves.omega_min: 0 rad/s must be > 0"},
      {"OmegaMaxBelowMin",
       [] {
         BuildSea(SeedSeaState(), WithOptions([](auto& o) {
                    o.omega_min = 0.5;
                    o.omega_max = 0.3;
                  }));
       },
       "waves.omega_max: 0.3 rad/s must be finite and > waves.omega_min = 0.5 rad/s"},
      {"OmegaMaxBelowDefaultMin",
       [] { BuildSea(SeedSeaState(), WithOptions([](auto& o) { o.omega_max = 0.2; })); },
       "waves.omega_max: 0.2 rad/s must be finite and > waves.omega_min = 0.448"},
      {"SpreadingNegative",
       [] { BuildSea(SeedSeaState(), WithOptions([](auto& o) { o.spreading_exponent = -1.0; })); },
       "waves.spreading_exponent: -1 must be >= 0"},
      {"GravityZero",
       [] { BuildSea(SeedSeaState(), WithOptions([](auto& o) { o.gravity = 0.0; })); },
       "waves.gravity: 0 m/s^2 must be > 0"},
      {"DirectionInfinite",
       [] { BuildSea(SeedSeaState(), WithOptions([](auto& o) { o.mean_direction = kInf; })); },
       "waves.mean_direction: inf rad must be finite"},
      {"MomentRangeInverted", [] { SpectralMoment(JonswapSpectrum(SeedSeaState()), 0, 2.0, 1.0); },
       "spectral moment omega_max: 1 rad/s"},
      {"NegativeMomentFromZero",
       [] { SpectralMoment(JonswapSpectrum(SeedSeaState()), -1, 0.0, 1.0); },
       "must be > 0 for a negative order -1"},
  };
  for (const BadInputCase& c : cases) {
    SCOPED_TRACE(c.name);
    try {
      c.build();
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos)
          << "message: " << e.what() << "\nexpected to contain: " << c.message;
    }
  }
}

}  // namespace
}  // namespace moorsim::vessel
