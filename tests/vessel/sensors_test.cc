// Tests of the pose sensors and tension cells (vessel/sensors.h).
//
// Statistical bounds. For N independent samples a sample correlation, proportion or mean
// is Gaussian to a very good approximation with a known standard error (SE), and for
// normal data (N - 1) s^2 / sigma^2 is chi-square with N - 1 degrees of freedom, so
// s^2 / sigma^2 - 1 has SE sqrt(2 / (N - 1)) (the normal approximation of chi-square is
// accurate to well under 1 % of the bound at these N). Every bound is 4.5 SE: a correct
// implementation fails a given check with probability about 7e-6 (two-sided), so the few
// dozen checks here together would fail by chance less than once in 10^3 seed choices,
// while the faults they guard against (one seed for every DOF: correlation 1; an Euler
// Gauss-Markov step: variance 33 % off; q dt for q sqrt(dt): a factor 4) miss by tens or
// hundreds of SE. The seeds are fixed, so a pass repeats.
#include "vessel/sensors.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "tests/support/sample_statistics.h"

namespace moorsim::vessel {
namespace {

using moorsim::testing::Correlation;
using moorsim::testing::Mean;
using moorsim::testing::Variance;

constexpr double kSigmas = 4.5;
constexpr double kThreeHours = 3.0 * 3600.0;

/// Sensors with white noise only, of the given standard deviations.
PoseSensorSpec WhiteNoiseSpec(double north = 0.1, double east = 0.2, double heading = 0.01) {
  PoseSensorSpec spec;
  spec.north = ChannelNoise{.std_dev = north};
  spec.east = ChannelNoise{.std_dev = east};
  spec.heading = ChannelNoise{.std_dev = heading};
  return spec;
}

/// Everything switched on: walk and Gauss-Markov biases, outliers, both kinds of dropout.
PoseSensorSpec FullSpec() {
  PoseSensorSpec spec;
  spec.gnss_rate = 2.0;
  spec.gyro_rate = 5.0;
  spec.north = {.std_dev = 0.1,
                .bias_walk = 0.01,
                .initial_bias = 0.5,
                .outlier_probability = 0.03,
                .outlier_std_dev = 3.0};
  spec.east = {.std_dev = 0.2,
               .bias_walk = 0.02,
               .bias_time_constant = 100.0,
               .outlier_probability = 0.01,
               .outlier_std_dev = 5.0};
  spec.heading = {.std_dev = 0.01,
                  .bias_walk = 0.001,
                  .bias_time_constant = 600.0,
                  .initial_bias = -0.02,
                  .outlier_probability = 0.02,
                  .outlier_std_dev = 0.2};
  spec.gnss_dropout_probability = 0.05;
  spec.gnss_dropout_mean_duration = 3.0;
  spec.gyro_dropout_probability = 0.1;
  return spec;
}

/// One channel's record: value and validity per instant.
struct ChannelRecord {
  std::vector<double> value;
  std::vector<bool> valid;
};

/// x, y and psi of `samples` consecutive instants of equal-rate sensors at a fixed true
/// pose.
std::array<ChannelRecord, 3> Record(PoseSensors& sensors, int samples,
                                    const Vec3& pose = Vec3::Zero()) {
  std::array<ChannelRecord, 3> record;
  for (ChannelRecord& c : record) {
    c.value.reserve(samples);
    c.valid.reserve(samples);
  }
  for (int k = 0; k < samples; ++k) {
    const PoseMeasurement m = sensors.Sample(sensors.gnss_clock().Instant(k), pose);
    for (int i = 0; i < 3; ++i) {
      record[i].value.push_back(m.value[i]);
      record[i].valid.push_back(m.valid[i]);
    }
  }
  return record;
}

std::array<ChannelRecord, 3> Record(const PoseSensorSpec& spec, std::uint64_t seed, int samples,
                                    const Vec3& pose = Vec3::Zero()) {
  PoseSensors sensors(spec, seed);
  return Record(sensors, samples, pose);
}

/// 4.5 SE of a sample variance ratio s^2 / sigma^2 from n normal samples.
double VarianceRatioBound(double n) { return kSigmas * std::sqrt(2.0 / (n - 1.0)); }

/// 4.5 SE of a proportion p estimated from n trials.
double ProportionBound(double p, double n) { return kSigmas * std::sqrt(p * (1.0 - p) / n); }

bool SameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

void ExpectInputError(const std::function<void()>& make, const std::string& message) {
  try {
    make();
    ADD_FAILURE() << "no InputError; expected \"" << message << "\"";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

// --- specification ---------------------------------------------------------------------

TEST(SensorSpecTest, SeedSensorsAreTheReferenceSheets) {
  const PoseSensorSpec seed = SeedPoseSensors();
  EXPECT_EQ(seed.gnss_rate, 1.0);
  EXPECT_EQ(seed.gyro_rate, 1.0);
  for (const ChannelNoise& c : {seed.north, seed.east, seed.heading}) {
    // Measurement variance 0.005 m^2 / rad^2 per DOF (TAPM thesis; docs/design.md section 9).
    EXPECT_DOUBLE_EQ(c.std_dev * c.std_dev, 0.005);
    EXPECT_EQ(c.std_dev, std::sqrt(0.005));
    EXPECT_EQ(c.bias_walk, 0.0);
    EXPECT_EQ(c.outlier_probability, 0.0);
  }
  EXPECT_EQ(seed.gnss_dropout_probability, 0.0);
  EXPECT_EQ(seed.gyro_dropout_probability, 0.0);
}

TEST(SensorSpecTest, BadSpecsThrowNamingKeyAndValue) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  struct Case {
    std::function<void(PoseSensorSpec&)> edit;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[](PoseSensorSpec& s) { s.gnss_rate = -1.0; }, "sensors.gnss.rate_hz: -1 must be > 0"},
      {[](PoseSensorSpec& s) { s.gyro_rate = 0.0; }, "sensors.gyro.rate_hz: 0 must be > 0"},
      {[&](PoseSensorSpec& s) { s.gnss_rate = inf; }, "sensors.gnss.rate_hz: inf must be finite"},
      {[&](PoseSensorSpec& s) { s.gyro_rate = nan; }, "sensors.gyro.rate_hz: nan must be finite"},
      {[](PoseSensorSpec& s) { s.north.std_dev = -0.1; },
       "sensors.gnss.north.std_dev: -0.1 must be >= 0"},
      {[&](PoseSensorSpec& s) { s.heading.bias_walk = nan; },
       "sensors.gyro.heading.bias_walk: nan must be finite"},
      {[](PoseSensorSpec& s) { s.east.bias_time_constant = -5.0; },
       "sensors.gnss.east.bias_time_constant_s: -5 must be >= 0"},
      {[&](PoseSensorSpec& s) { s.north.initial_bias = inf; },
       "sensors.gnss.north.initial_bias: inf must be finite"},
      {[](PoseSensorSpec& s) { s.heading.outlier_probability = 1.5; },
       "sensors.gyro.heading.outlier_probability: 1.5 must be in [0, 1]"},
      {[](PoseSensorSpec& s) { s.east.outlier_std_dev = -2.0; },
       "sensors.gnss.east.outlier_std_dev: -2 must be >= 0"},
      {[](PoseSensorSpec& s) { s.gnss_dropout_probability = -0.1; },
       "sensors.gnss.dropout_probability: -0.1 must be in [0, 1]"},
      {[&](PoseSensorSpec& s) { s.gyro_dropout_probability = nan; },
       "sensors.gyro.dropout_probability: nan must be in [0, 1]"},
      {[](PoseSensorSpec& s) { s.gnss_dropout_mean_duration = -2.0; },
       "sensors.gnss.dropout_mean_duration_s: -2 must be >= 0"},
  };
  for (const Case& c : cases) {
    PoseSensorSpec spec;
    c.edit(spec);
    ExpectInputError([&] { PoseSensors(spec, 1); }, c.message);
    ExpectInputError([&] { ValidatePoseSensorSpec(spec); }, c.message);
  }
  ExpectInputError([] { ValidatePoseSensorSpec(PoseSensorSpec{.gnss_rate = 0.0}, "run.sensors"); },
                   "run.sensors.gnss.rate_hz: 0 must be > 0");

  ExpectInputError([] { TensionCells(0, ChannelNoise{}, 1.0, 1); },
                   "sensors.tension_cells.lines: 0 must be >= 1");
  ExpectInputError([] { TensionCells(8, ChannelNoise{}, -1.0, 1); },
                   "sensors.tension_cells.rate_hz: -1 must be > 0");
  ExpectInputError([] { TensionCells(8, ChannelNoise{.std_dev = -1.0}, 1.0, 1); },
                   "sensors.tension_cells.noise.std_dev: -1 must be >= 0");
  // Limits are allowed.
  EXPECT_NO_THROW(PoseSensors(PoseSensorSpec{.gnss_dropout_probability = 1.0}, 1));
  EXPECT_NO_THROW(TensionCells(1, ChannelNoise{.outlier_probability = 1.0}, 1.0, 1));
}

// --- streams ---------------------------------------------------------------------------

TEST(PoseSensorsTest, StreamsAreTheDocumentedNames) {
  // Pins the naming contract: other tools (and later versions) can regenerate or
  // cross-check a channel's noise from the run seed and its documented name.
  const std::uint64_t seed = 20240611;
  PoseSensors sensors(WhiteNoiseSpec(0.1, 0.2, 0.01), seed);
  RandomStream north = RandomStream::Derive(seed, "gnss.north.noise");
  RandomStream east = RandomStream::Derive(seed, "gnss.east.noise");
  RandomStream heading = RandomStream::Derive(seed, "gyro.heading.noise");
  for (int k = 0; k < 10; ++k) {
    const PoseMeasurement m = sensors.Sample(k, Vec3(100.0, -50.0, 0.5));
    EXPECT_EQ(m.value.x(), 100.0 + 0.1 * north.Normal());
    EXPECT_EQ(m.value.y(), -50.0 + 0.2 * east.Normal());
    EXPECT_EQ(m.value.z(), 0.5 + 0.01 * heading.Normal());
  }

  // Bias: b_1 = b_0 + q sqrt(dt) v_0 from "<instrument>.<channel>.bias", dt = 1/4 s.
  PoseSensorSpec walk;
  walk.gnss_rate = walk.gyro_rate = 4.0;
  walk.north = {.bias_walk = 0.3, .initial_bias = 1.0};
  walk.east = {};
  walk.heading = {};
  PoseSensors walking(walk, seed);
  RandomStream bias = RandomStream::Derive(seed, "gnss.north.bias");
  EXPECT_EQ(walking.Sample(0.0, Vec3::Zero()).value.x(), 1.0);
  EXPECT_EQ(walking.Sample(0.25, Vec3::Zero()).value.x(), 1.0 + 0.3 * 0.5 * bias.Normal());

  TensionCells cells(3, ChannelNoise{.std_dev = 1000.0}, 1.0, seed);
  RandomStream cell3 = RandomStream::Derive(seed, "tension_cell.3.noise");
  const std::vector<double> tensions = {1e6, 2e6, 3e6};
  EXPECT_EQ(cells.Sample(0.0, tensions)[2], 3e6 + 1000.0 * cell3.Normal());
}

TEST(PoseSensorsTest, NoiseIsIndependentAcrossDegreesOfFreedom) {
  // The thesis's fault: one seed for every DOF gives correlation 1 between x, y and psi.
  // For independent channels sqrt(N) rho is asymptotically N(0, 1), so |rho| < 4.5 /
  // sqrt(N) fails by chance with probability ~7e-6 per pair.
  constexpr int kSamples = 100'000;
  const PoseSensorSpec spec = SeedPoseSensors();
  const std::array<ChannelRecord, 3> r = Record(spec, 7, kSamples);
  const double bound = kSigmas / std::sqrt(static_cast<double>(kSamples));
  const double rho_xy = Correlation(r[0].value, r[1].value);
  const double rho_xpsi = Correlation(r[0].value, r[2].value);
  const double rho_ypsi = Correlation(r[1].value, r[2].value);
  RecordProperty("rho_x_y", std::to_string(rho_xy));
  RecordProperty("rho_x_psi", std::to_string(rho_xpsi));
  RecordProperty("rho_y_psi", std::to_string(rho_ypsi));
  EXPECT_LT(std::abs(rho_xy), bound);
  EXPECT_LT(std::abs(rho_xpsi), bound);
  EXPECT_LT(std::abs(rho_ypsi), bound);

  // Each channel has the configured variance 0.005 (chi-square bound, 2.0 %).
  const char* names[] = {"x", "y", "psi"};
  for (int i = 0; i < 3; ++i) {
    const double ratio = Variance(r[i].value) / 0.005;
    RecordProperty(std::string("variance_ratio_") + names[i], std::to_string(ratio));
    EXPECT_LT(std::abs(ratio - 1.0), VarianceRatioBound(kSamples)) << names[i];
    EXPECT_LT(std::abs(Mean(r[i].value)), kSigmas * std::sqrt(0.005 / kSamples)) << names[i];
  }
  // And each is white: lag-one autocorrelation within the same bound.
  for (int i = 0; i < 3; ++i) {
    const std::vector<double> head(r[i].value.begin(), r[i].value.end() - 1);
    const std::vector<double> tail(r[i].value.begin() + 1, r[i].value.end());
    EXPECT_LT(std::abs(Correlation(head, tail)), bound) << names[i];
  }
}

TEST(PoseSensorsTest, SameSeedGivesBitIdenticalSequences) {
  const PoseSensorSpec spec = FullSpec();
  PoseSensors a(spec, 99);
  PoseSensors b(spec, 99);
  int compared = 0;
  for (double t = 0.0; t <= 2000.0; t = a.NextSampleTime(t)) {
    const Vec3 pose(10.0 * std::sin(0.01 * t), 5.0 * std::cos(0.02 * t), 0.001 * t);
    const PoseMeasurement ma = a.Sample(t, pose);
    const PoseMeasurement mb = b.Sample(t, pose);
    for (int i = 0; i < 3; ++i) {
      ASSERT_EQ(ma.valid[i], mb.valid[i]) << "t = " << t;
      ASSERT_TRUE(SameBits(ma.value[i], mb.value[i])) << "t = " << t;
    }
    ++compared;
  }
  // The gyro's 5 Hz instants in [0, 2000] s (10001) and the GNSS's at x.5 s (2000).
  EXPECT_EQ(compared, 12001);
}

TEST(PoseSensorsTest, DifferentSeedsDiffer) {
  const std::array<ChannelRecord, 3> a = Record(FullSpec(), 1, 1000);
  const std::array<ChannelRecord, 3> b = Record(FullSpec(), 2, 1000);
  for (int i = 0; i < 3; ++i) {
    int equal = 0;
    for (int k = 0; k < 1000; ++k) equal += a[i].value[k] == b[i].value[k];
    EXPECT_EQ(equal, 0) << "channel " << i;
  }
}

TEST(PoseSensorsTest, InstrumentNameSelectsTheStreams) {
  const PoseSensorSpec spec = WhiteNoiseSpec();
  PoseSensors reference(spec, 5);
  PoseSensors other_gnss(spec, 5, "gnss_aft");
  PoseSensors other_gyro(spec, 5, "gnss", "gyro_2");
  const std::array<ChannelRecord, 3> r = Record(reference, 1000);
  const std::array<ChannelRecord, 3> g = Record(other_gnss, 1000);
  const std::array<ChannelRecord, 3> h = Record(other_gyro, 1000);
  int north_equal = 0;
  int heading_equal = 0;
  for (int k = 0; k < 1000; ++k) {
    north_equal += r[0].value[k] == g[0].value[k];
    heading_equal += r[2].value[k] == h[2].value[k];
  }
  EXPECT_EQ(north_equal, 0);
  EXPECT_EQ(heading_equal, 0);
  // Renaming one instrument leaves the other's numbers alone.
  EXPECT_EQ(r[2].value, g[2].value);
  EXPECT_EQ(r[0].value, h[0].value);
  EXPECT_EQ(r[1].value, h[1].value);
}

// --- outliers and dropouts ---------------------------------------------------------------

TEST(PoseSensorsTest, OutliersLeaveTheWhiteNoiseUnchanged) {
  // With outliers on, each sample is either bit-identical to the run without them or
  // carries an outlier; the count of outliers is binomial(N, p) and their sizes have the
  // configured spread.
  constexpr int kSamples = 100'000;
  const PoseSensorSpec clean = WhiteNoiseSpec();
  PoseSensorSpec spiky = clean;
  spiky.north.outlier_probability = 0.05;
  spiky.north.outlier_std_dev = 5.0;
  spiky.east.outlier_probability = 0.01;
  spiky.east.outlier_std_dev = 2.0;
  spiky.heading.outlier_probability = 0.02;
  spiky.heading.outlier_std_dev = 0.3;
  const std::array<ChannelRecord, 3> a = Record(clean, 11, kSamples);
  const std::array<ChannelRecord, 3> b = Record(spiky, 11, kSamples);
  const ChannelNoise* channels[] = {&spiky.north, &spiky.east, &spiky.heading};
  for (int i = 0; i < 3; ++i) {
    std::vector<double> outliers;
    for (int k = 0; k < kSamples; ++k) {
      if (!SameBits(a[i].value[k], b[i].value[k]))
        outliers.push_back(b[i].value[k] - a[i].value[k]);
    }
    const double p = channels[i]->outlier_probability;
    const double fraction = static_cast<double>(outliers.size()) / kSamples;
    RecordProperty("outlier_fraction_" + std::to_string(i), std::to_string(fraction));
    EXPECT_LT(std::abs(fraction - p), ProportionBound(p, kSamples)) << "channel " << i;
    // The heading's outliers of 0.3 rad around psi = 0 never wrap, so the difference is the
    // outlier itself (to rounding).
    const double s = channels[i]->outlier_std_dev;
    const double ratio = Variance(outliers) / (s * s);
    EXPECT_LT(std::abs(ratio - 1.0), VarianceRatioBound(static_cast<double>(outliers.size())))
        << "channel " << i;
  }
}

TEST(PoseSensorsTest, DropoutsLeaveDeliveredSamplesUnchanged) {
  constexpr int kSamples = 20'000;
  PoseSensorSpec base = FullSpec();
  base.gnss_dropout_probability = 0.0;
  base.gyro_dropout_probability = 0.0;
  base.gyro_rate = base.gnss_rate;  // Record samples equal-rate sensors
  PoseSensorSpec lossy = base;
  lossy.gnss_dropout_probability = 0.1;
  lossy.gnss_dropout_mean_duration = 3.0;
  lossy.gyro_dropout_probability = 0.2;
  const std::array<ChannelRecord, 3> a = Record(base, 3, kSamples);
  const std::array<ChannelRecord, 3> b = Record(lossy, 3, kSamples);
  int lost[3] = {0, 0, 0};
  for (int k = 0; k < kSamples; ++k) {
    ASSERT_EQ(b[0].valid[k], b[1].valid[k]) << "GNSS lost x and y separately at sample " << k;
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(a[i].valid[k]);
      if (b[i].valid[k]) {
        ASSERT_TRUE(SameBits(a[i].value[k], b[i].value[k])) << "sample " << k;
      } else {
        ASSERT_TRUE(std::isnan(b[i].value[k]));
        ++lost[i];
      }
    }
  }
  EXPECT_GT(lost[0], 1000);
  EXPECT_GT(lost[2], 1000);
}

TEST(PoseSensorsTest, DropoutFractionMatchesProbability) {
  constexpr int kSamples = 100'000;
  PoseSensorSpec spec = WhiteNoiseSpec();
  spec.gnss_dropout_probability = 0.1;
  spec.gyro_dropout_probability = 0.25;
  const std::array<ChannelRecord, 3> r = Record(spec, 13, kSamples);
  int gnss_lost = 0;
  int gyro_lost = 0;
  int both_lost = 0;
  for (int k = 0; k < kSamples; ++k) {
    gnss_lost += !r[0].valid[k];
    gyro_lost += !r[2].valid[k];
    both_lost += !r[0].valid[k] && !r[2].valid[k];
  }
  const double gnss_fraction = static_cast<double>(gnss_lost) / kSamples;
  const double gyro_fraction = static_cast<double>(gyro_lost) / kSamples;
  const double both_fraction = static_cast<double>(both_lost) / kSamples;
  RecordProperty("gnss_lost_fraction", std::to_string(gnss_fraction));
  RecordProperty("gyro_lost_fraction", std::to_string(gyro_fraction));
  RecordProperty("both_lost_fraction", std::to_string(both_fraction));
  EXPECT_LT(std::abs(gnss_fraction - 0.1), ProportionBound(0.1, kSamples));
  EXPECT_LT(std::abs(gyro_fraction - 0.25), ProportionBound(0.25, kSamples));
  // The two instruments fail independently: P(both) = 0.1 * 0.25.
  EXPECT_LT(std::abs(both_fraction - 0.025), ProportionBound(0.025, kSamples));
}

TEST(PoseSensorsTest, DropoutDurationsAreGeometricInSamples) {
  // A dropout lasting Exp(mean) loses further samples with probability r = exp(-dt/mean)
  // each; a new dropout may start right after one ends, so runs of lost samples continue
  // with probability r' = r + (1 - r) p: mean 1 / (1 - r'), SE sqrt(r') / (1 - r') /
  // sqrt(n). Runs of delivered samples end with probability p: mean 1 / p, SE
  // sqrt(1 - p) / p / sqrt(n).
  constexpr int kSamples = 300'000;
  const double p = 0.02;
  const double mean_duration = 5.0;
  PoseSensorSpec spec = WhiteNoiseSpec();
  spec.gnss_dropout_probability = p;
  spec.gnss_dropout_mean_duration = mean_duration;
  const std::array<ChannelRecord, 3> r = Record(spec, 17, kSamples);
  std::vector<double> lost_runs;
  std::vector<double> delivered_runs;
  int run = 1;
  for (int k = 1; k < kSamples; ++k) {
    if (r[0].valid[k] == r[0].valid[k - 1]) {
      ++run;
      continue;
    }
    (r[0].valid[k - 1] ? delivered_runs : lost_runs).push_back(run);
    run = 1;
  }  // the last, unfinished run is left out
  const double continuation = std::exp(-1.0 / mean_duration);
  const double r_lost = continuation + (1.0 - continuation) * p;
  const double lost_mean = Mean(lost_runs);
  const double delivered_mean = Mean(delivered_runs);
  RecordProperty("dropouts", std::to_string(lost_runs.size()));
  RecordProperty("mean_lost_run", std::to_string(lost_mean));
  RecordProperty("mean_delivered_run", std::to_string(delivered_mean));
  const double n_lost = static_cast<double>(lost_runs.size());
  const double n_delivered = static_cast<double>(delivered_runs.size());
  EXPECT_GT(n_lost, 4000.0);
  EXPECT_NEAR(lost_mean, 1.0 / (1.0 - r_lost),
              kSigmas * std::sqrt(r_lost) / (1.0 - r_lost) / std::sqrt(n_lost));
  EXPECT_NEAR(delivered_mean, 1.0 / p, kSigmas * std::sqrt(1.0 - p) / p / std::sqrt(n_delivered));
  // The header's long-run lost fraction L / (L + (1 - p) / p), L = 1 / (1 - r). Samples
  // are correlated, so no binomial bound: propagated from the two run means' SEs (1.2 %
  // and 1.3 %) the fraction's SE is about 1.6 % of it; 8 % is 5 SE.
  const double L = 1.0 / (1.0 - continuation);
  const double expected_fraction = L / (L + (1.0 - p) / p);
  int lost = 0;
  for (int k = 0; k < kSamples; ++k) lost += !r[0].valid[k];
  EXPECT_NEAR(static_cast<double>(lost) / kSamples, expected_fraction, 0.08 * expected_fraction);
}

// --- biases ------------------------------------------------------------------------------

TEST(PoseSensorsTest, RandomWalkBiasVarianceIsIntensitySquaredTimesTime) {
  // Over many seeds the bias at T has mean b_0 and variance q^2 T. Rate 4 Hz, so a
  // q dt step (instead of q sqrt(dt)) would give a variance 4 times too small. The three
  // channels are independent; each is normalised by its own q^2 T and pooled.
  constexpr int kSeeds = 6000;
  constexpr double kRate = 4.0;
  constexpr double kDuration = 20.0;
  constexpr int kLast = static_cast<int>(kDuration * kRate);
  PoseSensorSpec spec;
  spec.gnss_rate = spec.gyro_rate = kRate;
  spec.north = {.bias_walk = 0.01, .initial_bias = 0.3};
  spec.east = {.bias_walk = 0.02};
  spec.heading = {.bias_walk = 0.001};
  const double q[] = {0.01, 0.02, 0.001};
  const double b0[] = {0.3, 0.0, 0.0};
  std::vector<double> at_end;  // (b(T) - b_0) / (q sqrt(T))
  std::vector<double> at_half;
  for (int seed = 0; seed < kSeeds; ++seed) {
    PoseSensors sensors(spec, 1000 + seed);
    for (int k = 0; k <= kLast; ++k) {
      const PoseMeasurement m = sensors.Sample(sensors.gnss_clock().Instant(k), Vec3::Zero());
      if (k == kLast / 2 || k == kLast) {
        const double t = k / kRate;
        for (int i = 0; i < 3; ++i) {
          (k == kLast ? at_end : at_half).push_back((m.value[i] - b0[i]) / (q[i] * std::sqrt(t)));
        }
      }
    }
  }
  for (const std::vector<double>* z : {&at_half, &at_end}) {
    double sum = 0.0;
    double sum_sq = 0.0;
    for (const double v : *z) {
      sum += v;
      sum_sq += v * v;
    }
    const double n = static_cast<double>(z->size());
    const double ratio = sum_sq / n;  // mean known (0): chi-square with n dof over n
    RecordProperty(z == &at_end ? "variance_ratio_T" : "variance_ratio_T_half",
                   std::to_string(ratio));
    EXPECT_LT(std::abs(ratio - 1.0), kSigmas * std::sqrt(2.0 / n));
    EXPECT_LT(std::abs(sum / n), kSigmas / std::sqrt(n));
  }
}

TEST(PoseSensorsTest, GaussMarkovBiasReachesItsStationaryVariance) {
  // db = -b/tau dt + q dW from b_0 = 0: Var b(t) = q^2 tau / 2 (1 - exp(-2 t / tau)),
  // corr(b(t), b(t - dt)) = exp(-dt / tau) at stationarity. Sampled at dt = tau / 2,
  // where an Euler step would give q^2 tau / (2 - dt / tau), 33 % high; the exact
  // discretisation must not care about the rate.
  constexpr int kSeeds = 10'000;
  constexpr double kTau = 20.0;
  constexpr double kRate = 0.1;  // dt = 10 s
  constexpr int kLast = 20;      // T = 200 s = 10 tau
  PoseSensorSpec spec;
  spec.gnss_rate = spec.gyro_rate = kRate;
  spec.north = {.bias_walk = 0.01, .bias_time_constant = kTau};
  spec.east = {.bias_walk = 0.05, .bias_time_constant = kTau};
  spec.heading = {.bias_walk = 0.002, .bias_time_constant = kTau};
  const double q[] = {0.01, 0.05, 0.002};
  const double T = kLast / kRate;
  double sum_sq = 0.0;
  double sum_prev_sq = 0.0;
  double sum_product = 0.0;
  int n = 0;
  for (int seed = 0; seed < kSeeds; ++seed) {
    PoseSensors sensors(spec, 50'000 + seed);
    Vec3 previous = Vec3::Zero();
    for (int k = 0; k <= kLast; ++k) {
      const PoseMeasurement m = sensors.Sample(sensors.gnss_clock().Instant(k), Vec3::Zero());
      if (k == kLast) {
        for (int i = 0; i < 3; ++i) {
          const double scale = q[i] * std::sqrt(kTau / 2.0);
          sum_sq += (m.value[i] / scale) * (m.value[i] / scale);
          sum_prev_sq += (previous[i] / scale) * (previous[i] / scale);
          sum_product += (m.value[i] / scale) * (previous[i] / scale);
          ++n;
        }
      }
      previous = m.value;
    }
  }
  const double expected = -std::expm1(-2.0 * T / kTau);
  const double ratio = sum_sq / n / expected;
  const double correlation = sum_product / std::sqrt(sum_sq * sum_prev_sq);
  const double phi = std::exp(-1.0 / (kRate * kTau));
  RecordProperty("stationary_variance_ratio", std::to_string(ratio));
  RecordProperty("lag_one_correlation", std::to_string(correlation));
  EXPECT_LT(std::abs(ratio - 1.0), kSigmas * std::sqrt(2.0 / n));
  // SE of a correlation coefficient near rho: (1 - rho^2) / sqrt(n).
  EXPECT_NEAR(correlation, phi, kSigmas * (1.0 - phi * phi) / std::sqrt(n));
}

// --- timing --------------------------------------------------------------------------------

TEST(SensorClockTest, InstantsAreExactMultiplesOverThreeHours) {
  for (const double rate : {1.0, 10.0, 3.0, 0.3, 7.3}) {
    const SensorClock clock(rate);
    EXPECT_EQ(clock.NextSampleTime(-1.0), 0.0);
    EXPECT_TRUE(clock.Due(0.0));
    std::int64_t k = 0;
    int mismatches = 0;
    double t = 0.0;
    double accumulated = 0.0;
    for (; t <= kThreeHours; t = clock.NextSampleTime(t), ++k) {
      mismatches += t != static_cast<double>(k) / rate;
      mismatches += clock.Index(t) != k;
      // Off by a millionth of an interval, or half-way: not an instant.
      mismatches += clock.Due(t + 1e-6 / rate) || clock.Due(t + 0.5 / rate);
      if (k > 0) accumulated += 1.0 / rate;
    }
    EXPECT_EQ(mismatches, 0) << "rate " << rate;
    const auto expected_count =
        static_cast<std::int64_t>(std::floor(kThreeHours * rate + 1e-9)) + 1;
    EXPECT_EQ(k, expected_count) << "rate " << rate;
    const double last = static_cast<double>(k - 1) / rate;
    char drift[32];
    std::snprintf(drift, sizeof drift, "%.3g", accumulated - last);
    RecordProperty("accumulation_drift_s_at_" + std::to_string(rate), drift);
    if (rate == 10.0 || rate == 3.0) {
      EXPECT_EQ(last, kThreeHours);  // exactly, where an integer number of intervals fits
      // The accumulated sum this design avoids does drift.
      EXPECT_NE(accumulated, kThreeHours);
    }
  }
}

TEST(PoseSensorsTest, CoincidingInstantsGiveOneMeasurement) {
  struct Rates {
    double gnss;
    double gyro;
    int instants;  // distinct instants in [0, 3 h]
    int gnss_samples;
    int gyro_samples;
  };
  for (const Rates& rates :
       {Rates{1.0, 1.0, 10801, 10801, 10801}, Rates{1.0, 10.0, 108001, 10801, 108001},
        Rates{0.1, 0.3, 3241, 1081, 3241}, Rates{2.0, 3.0, 43201, 21601, 32401}}) {
    PoseSensorSpec spec = WhiteNoiseSpec();
    spec.gnss_rate = rates.gnss;
    spec.gyro_rate = rates.gyro;
    PoseSensors sensors(spec, 23);
    int instants = 0;
    int gnss = 0;
    int gyro = 0;
    double previous = -1.0;
    double closest = std::numeric_limits<double>::infinity();
    for (double t = 0.0; t <= kThreeHours; t = sensors.NextSampleTime(t)) {
      ASSERT_TRUE(sensors.Due(t));
      const PoseMeasurement m = sensors.Sample(t, Vec3::Zero());
      ASSERT_EQ(m.valid[0], m.valid[1]);
      gnss += m.valid[0];
      gyro += m.valid[2];
      ++instants;
      closest = std::min(closest, t - previous);
      previous = t;
    }
    EXPECT_EQ(instants, rates.instants) << rates.gnss << " / " << rates.gyro << " Hz";
    EXPECT_EQ(gnss, rates.gnss_samples) << rates.gnss << " / " << rates.gyro << " Hz";
    EXPECT_EQ(gyro, rates.gyro_samples) << rates.gnss << " / " << rates.gyro << " Hz";
    // No instant is reported twice with a rounding-sized gap (the true closest is 0.1 s).
    EXPECT_GT(closest, 0.05) << rates.gnss << " / " << rates.gyro << " Hz";
  }
}

TEST(PoseSensorsTest, SkippedInstantsAreDrawnAndDiscarded) {
  PoseSensorSpec spec = FullSpec();
  spec.gyro_rate = spec.gnss_rate;
  const std::array<ChannelRecord, 3> every = Record(spec, 31, 400);
  PoseSensors sparse(spec, 31);
  for (int k = 0; k < 400; k += 7) {
    const PoseMeasurement m = sparse.Sample(sparse.gnss_clock().Instant(k), Vec3::Zero());
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(m.valid[i], every[i].valid[k]) << "sample " << k;
      EXPECT_TRUE(SameBits(m.value[i], every[i].value[k])) << "sample " << k;
    }
  }
}

TEST(PoseSensorsTest, EachInstantIsMeasuredOnce) {
  PoseSensors sensors(SeedPoseSensors(), 1);
  sensors.Sample(5.0, Vec3::Zero());
  EXPECT_THROW(sensors.Sample(5.0, Vec3::Zero()), std::logic_error);
  EXPECT_THROW(sensors.Sample(3.0, Vec3::Zero()), std::logic_error);
  // Between instants nothing is due: all invalid, NaN.
  const PoseMeasurement between = sensors.Sample(5.5, Vec3::Zero());
  EXPECT_EQ(between.time, 5.5);
  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(between.valid[i]);
    EXPECT_TRUE(std::isnan(between.value[i]));
  }
  EXPECT_NO_THROW(sensors.Sample(6.0, Vec3::Zero()));
}

TEST(PoseSensorsTest, HeadingIsWrapped) {
  PoseSensorSpec exact = WhiteNoiseSpec(0.0, 0.0, 0.0);
  PoseSensors sensors(exact, 1);
  const double cases[][2] = {{kPi, kPi},           {-kPi, kPi},           {1.5 * kPi, -0.5 * kPi},
                             {7.0, 7.0 - 2 * kPi}, {-7.0, 2 * kPi - 7.0}, {0.25, 0.25}};
  int k = 0;
  for (const auto& c : cases) {
    EXPECT_NEAR(sensors.Sample(k++, Vec3(0.0, 0.0, c[0])).value.z(), c[1], 1e-15) << c[0];
  }

  // Noisy heading next to +pi: every value in (-pi, pi], about half wrapped to near -pi,
  // and the wrapped error stays the noise.
  PoseSensors noisy(SeedPoseSensors(), 3);
  int wrapped = 0;
  constexpr int kSamples = 10'000;
  for (int j = 0; j < kSamples; ++j) {
    const double truth = kPi - 0.01 + 4.0 * kPi;  // unwrapped input
    const double psi = noisy.Sample(j, Vec3(0.0, 0.0, truth)).value.z();
    ASSERT_GT(psi, -kPi);
    ASSERT_LE(psi, kPi);
    wrapped += psi < 0.0;
    EXPECT_LT(std::abs(std::remainder(psi - truth, 2.0 * kPi)), 0.5);
  }
  // P(noise > 0.01) with sigma 0.0707 is 0.444.
  EXPECT_NEAR(static_cast<double>(wrapped) / kSamples, 0.444, ProportionBound(0.444, kSamples));
}

// --- tension cells ---------------------------------------------------------------------------

TEST(TensionCellsTest, CellsAreIndependentWithTheirNoise) {
  constexpr int kLines = 8;
  constexpr int kSamples = 20'000;
  constexpr double kStd = 5000.0;
  TensionCells cells(kLines, ChannelNoise{.std_dev = kStd}, 2.0, 41);
  const std::vector<double> truth(kLines, 1.2e6);
  std::vector<std::vector<double>> error(kLines);
  for (int k = 0; k < kSamples; ++k) {
    const std::vector<double> measured = cells.Sample(cells.clock().Instant(k), truth);
    for (int i = 0; i < kLines; ++i) error[i].push_back(measured[i] - truth[i]);
  }
  double worst_rho = 0.0;
  for (int i = 0; i < kLines; ++i) {
    EXPECT_LT(std::abs(Variance(error[i]) / (kStd * kStd) - 1.0), VarianceRatioBound(kSamples));
    for (int j = i + 1; j < kLines; ++j) {
      worst_rho = std::max(worst_rho, std::abs(Correlation(error[i], error[j])));
    }
  }
  RecordProperty("worst_rho_between_cells", std::to_string(worst_rho));
  EXPECT_LT(worst_rho, kSigmas / std::sqrt(static_cast<double>(kSamples)));
}

TEST(TensionCellsTest, ReproducibleAndChecked) {
  const ChannelNoise noise{
      .std_dev = 100.0, .bias_walk = 10.0, .outlier_probability = 0.1, .outlier_std_dev = 1e4};
  TensionCells a(3, noise, 1.0, 8);
  TensionCells b(3, noise, 1.0, 8);
  TensionCells c(3, noise, 1.0, 9);
  const std::vector<double> truth = {1e6, 1.1e6, 0.9e6};
  for (int k = 0; k < 100; ++k) {
    const std::vector<double> ma = a.Sample(k, truth);
    const std::vector<double> mb = b.Sample(k, truth);
    const std::vector<double> mc = c.Sample(k, truth);
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(SameBits(ma[i], mb[i]));
      EXPECT_NE(ma[i], mc[i]);
    }
  }
  EXPECT_THROW(a.Sample(100.0, std::vector<double>(2, 1e6)), std::invalid_argument);
  EXPECT_THROW(a.Sample(50.0, truth), std::logic_error);
  for (const double v : a.Sample(100.5, truth)) EXPECT_TRUE(std::isnan(v));
  EXPECT_EQ(a.NextSampleTime(100.5), 101.0);
  EXPECT_EQ(a.lines(), 3);
}

TEST(TensionCellsTest, StuckDriftingAndDeadCellsReadAsTheyShould) {
  const ChannelNoise noise{.std_dev = 100.0};
  TensionCells healthy(4, noise, 1.0, 12);
  TensionCells faulty(4, noise, 1.0, 12);
  using Mode = SensorFault::Mode;
  faulty.AddFault({.line = 0, .fault = {.mode = Mode::kStuck, .from = 10.0}});
  faulty.AddFault({.line = 2, .fault = {.mode = Mode::kDrift, .from = 20.0, .size = -500.0}});
  faulty.AddFault({.line = 3, .fault = {.mode = Mode::kDead, .from = 30.0}});
  double stuck = 0.0;
  for (int k = 0; k < 40; ++k) {
    const std::vector<double> truth = {1e6 + 1e3 * k, 1.1e6, 0.9e6, 1.2e6};
    const std::vector<double> h = healthy.Sample(k, truth);
    const std::vector<double> f = faulty.Sample(k, truth);
    if (k < 10) {
      EXPECT_EQ(f[0], h[0]);
      stuck = f[0];
    } else {
      EXPECT_EQ(f[0], stuck) << k;  // the reading at 9 s, while the truth climbs
    }
    EXPECT_EQ(f[1], h[1]);  // the other cells are untouched, noise included
    EXPECT_DOUBLE_EQ(f[2], h[2] - (k >= 20 ? 500.0 * (k - 20) : 0.0)) << k;
    EXPECT_DOUBLE_EQ(f[3], k >= 30 ? h[3] - truth[3] : h[3]) << k;  // its noise alone
  }
}

TEST(TensionCellsTest, StepGainAndDegradedCellsForAPeriod) {
  using Mode = SensorFault::Mode;
  const ChannelNoise noise{.std_dev = 100.0};
  TensionCells healthy(3, noise, 1.0, 5);
  TensionCells faulty(3, noise, 1.0, 5);
  faulty.AddFault(
      {.line = 0, .fault = {.mode = Mode::kStep, .from = 5.0, .until = 15.0, .size = 2e4}});
  faulty.AddFault({.line = 1, .fault = {.mode = Mode::kGain, .from = 5.0, .size = 1.1}});
  faulty.AddFault(
      {.line = 2, .fault = {.mode = Mode::kDegraded, .from = 5.0, .until = 10.0, .size = 8.0}});
  const std::vector<double> truth = {1e6, 1.1e6, 0.9e6};
  for (int k = 0; k < 20; ++k) {
    const std::vector<double> h = healthy.Sample(k, truth);
    const std::vector<double> f = faulty.Sample(k, truth);
    const bool step = k >= 5 && k < 15;
    EXPECT_DOUBLE_EQ(f[0], h[0] + (step ? 2e4 : 0.0)) << k;
    // The gain scales the truth, not the error.
    EXPECT_NEAR(f[1], k >= 5 ? 1.1 * truth[1] + (h[1] - truth[1]) : h[1], 1e-6) << k;
    const double error = f[2] - truth[2], healthy_error = h[2] - truth[2];
    EXPECT_NEAR(error, (k >= 5 && k < 10 ? 8.0 : 1.0) * healthy_error, 1e-6) << k;
  }
}

TEST(TensionCellsTest, AFaultOutsideTheMooringOrOutOfRangeIsNamed) {
  using Mode = SensorFault::Mode;
  TensionCells cells(3, ChannelNoise{}, 1.0, 1);
  ExpectInputError([&] { cells.AddFault({.line = 3, .fault = {.mode = Mode::kDead}}); },
                   "sensors.tension_cells.faults.line: 4 is not a line of the mooring (1..3)");
  ExpectInputError(
      [&] { cells.AddFault({.line = 0, .fault = {.mode = Mode::kGain, .size = 0.0}}); },
      "sensors.tension_cells.faults.gain: 0 must be > 0");
  ExpectInputError(
      [&] {
        cells.AddFault({.line = 0, .fault = {.mode = Mode::kStep, .from = 10.0, .until = 5.0}});
      },
      "sensors.tension_cells.faults.end: 5 must be after the fault's time");
}

TEST(PoseSensorsTest, EachFaultActsOnItsChannelAlone) {
  using Mode = SensorFault::Mode;
  PoseSensorSpec spec;
  spec.north.bias_walk = 0.01;  // a bias, which the faults leave as it is
  PoseSensors healthy(spec, 21);
  PoseSensors faulty(spec, 21);
  faulty.AddFault(PoseChannel::kNorth, {.mode = Mode::kStep, .from = 10.0, .size = 2.0});
  faulty.AddFault(PoseChannel::kEast, {.mode = Mode::kStuck, .from = 20.0, .until = 30.0});
  faulty.AddFault(PoseChannel::kHeading, {.mode = Mode::kDrift, .from = 5.0, .size = 1e-3});
  faulty.AddFault(PoseChannel::kNorth, {.mode = Mode::kDead, .from = 40.0, .until = 45.0});
  double frozen = 0.0;
  for (int k = 0; k < 50; ++k) {
    const Vec3 truth(10.0 + 0.1 * k, -5.0 + 0.05 * k, 0.2);
    const PoseMeasurement h = healthy.Sample(k, truth);
    const PoseMeasurement f = faulty.Sample(k, truth);
    SCOPED_TRACE("t = " + std::to_string(k));
    if (k >= 40 && k < 45) {
      EXPECT_FALSE(f.valid[0]);  // dead: no reading, the east channel still has one
    } else {
      EXPECT_TRUE(f.valid[0]);
      EXPECT_DOUBLE_EQ(f.value.x(), h.value.x() + (k >= 10 ? 2.0 : 0.0));
    }
    EXPECT_TRUE(f.valid[1]);
    if (k < 20) frozen = f.value.y();
    EXPECT_EQ(f.value.y(), k >= 20 && k < 30 ? frozen : h.value.y());
    EXPECT_NEAR(f.value.z(), WrapAngle(h.value.z() + (k >= 5 ? 1e-3 * (k - 5) : 0.0)), 1e-12);
  }
}

TEST(PoseSensorsTest, ADegradedGnssIsNoisierOnlyWhileItLasts) {
  using Mode = SensorFault::Mode;
  PoseSensors healthy(PoseSensorSpec{}, 3);
  PoseSensors faulty(PoseSensorSpec{}, 3);
  faulty.AddFault(PoseChannel::kNorth,
                  {.mode = Mode::kDegraded, .from = 100.0, .until = 200.0, .size = 10.0});
  faulty.AddFault(PoseChannel::kEast,
                  {.mode = Mode::kDegraded, .from = 100.0, .until = 200.0, .size = 10.0});
  const Vec3 truth(1.0, 2.0, 0.0);
  for (int k = 0; k < 300; ++k) {
    const PoseMeasurement h = healthy.Sample(k, truth);
    const PoseMeasurement f = faulty.Sample(k, truth);
    const double factor = k >= 100 && k < 200 ? 10.0 : 1.0;
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(f.value(i) - truth(i), factor * (h.value(i) - truth(i)), 1e-12) << k;
    }
    EXPECT_EQ(f.value.z(), h.value.z());
  }
}

}  // namespace
}  // namespace moorsim::vessel
