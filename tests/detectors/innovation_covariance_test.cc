// Tests of the offline innovation covariance (detectors/innovation_covariance.h): the
// streaming estimator against a known covariance, the own-model simulator's stationary
// statistics, the trained Sigma_h's consistency on fresh data from the same model, and a
// DHT-style check that the passive observers with their trained covariances prefer the
// true hypothesis.
#include "detectors/innovation_covariance.h"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/random.h"
#include "detectors/hypothesis_bank.h"
#include "detectors/passive_observer.h"
#include "tests/detectors/observer_test_support.h"

namespace moorsim::detectors {
namespace {

using State = HypothesisPassiveObserver::State;
using testing::SeedBank;

/// Sigma_h of every hypothesis, trained once with the defaults (10000 s, seed 1).
const std::vector<Mat3>& SeedCovariances() {
  static const std::vector<Mat3> covariances =
      TrainPassiveCovariances(SeedBank(), SeedLowFrequencyModel(), {}, {});
  return covariances;
}

// Gaussian samples with a known covariance: the estimate is within 4 standard errors of
// it, entry by entry (the standard error of a sample covariance entry is
// sqrt((S_ii S_jj + S_ij^2) / n)), and agrees with the two-pass formula to rounding.
// Samples with an invalid channel are skipped, even if the invalid value is NaN.
TEST(InnovationCovarianceEstimatorTest, MatchesAKnownCovariance) {
  Mat3 L;
  L << 0.2, 0.0, 0.0, 0.05, 0.15, 0.0, -0.01, 0.02, 0.08;
  const Mat3 sigma = L * L.transpose();
  const Vec3 mean(0.1, -0.2, 0.01);
  RandomStream stream = RandomStream::Derive(7, "test.gaussian");
  constexpr int kSamples = 40000;
  std::vector<Vec3> samples;
  InnovationCovarianceEstimator estimator;
  for (int k = 0; k < kSamples; ++k) {
    const Vec3 n(stream.Normal(), stream.Normal(), stream.Normal());
    samples.push_back(mean + L * n);
    EXPECT_TRUE(estimator.Add(samples.back()));
    if (k % 100 == 0) {
      EXPECT_FALSE(estimator.Add(Vec3(std::nan(""), 1.0, 1.0), {false, true, true}));
      HypothesisEvidence partial;
      partial.dimension = 2;
      EXPECT_FALSE(estimator.Add(partial));
    }
  }
  EXPECT_EQ(estimator.count(), kSamples);
  const Mat3 estimate = estimator.Covariance();
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(estimator.mean()(i), mean(i), 4.0 * std::sqrt(sigma(i, i) / kSamples));
    for (int j = 0; j < 3; ++j) {
      const double standard_error =
          std::sqrt((sigma(i, i) * sigma(j, j) + sigma(i, j) * sigma(i, j)) / kSamples);
      EXPECT_NEAR(estimate(i, j), sigma(i, j), 4.0 * standard_error) << i << "," << j;
    }
  }
  Vec3 two_pass_mean = Vec3::Zero();
  for (const Vec3& s : samples) two_pass_mean += s;
  two_pass_mean /= kSamples;
  Mat3 two_pass = Mat3::Zero();
  for (const Vec3& s : samples) two_pass += (s - two_pass_mean) * (s - two_pass_mean).transpose();
  two_pass /= kSamples - 1;
  EXPECT_TRUE(estimate.isApprox(two_pass, 1e-10));
  EXPECT_EQ(estimate, estimate.transpose());

  estimator.Reset();
  EXPECT_EQ(estimator.count(), 0);
}

TEST(InnovationCovarianceEstimatorTest, RefusesTooFewSamplesOrASingularCovariance) {
  auto message = [](const InnovationCovarianceEstimator& estimator) -> std::string {
    try {
      estimator.Covariance();
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  RandomStream stream = RandomStream::Derive(8, "test.gaussian");
  InnovationCovarianceEstimator estimator(100);
  for (int k = 0; k < 50; ++k) estimator.Add(Vec3(stream.Normal(), stream.Normal(), 0.1));
  EXPECT_NE(message(estimator).find("50 samples with all channels valid, need at least 100"),
            std::string::npos)
      << message(estimator);
  for (int k = 0; k < 50; ++k) estimator.Add(Vec3(stream.Normal(), stream.Normal(), 0.1));
  EXPECT_NE(message(estimator).find("not positive definite"), std::string::npos)
      << message(estimator);  // the heading channel never varies

  try {
    InnovationCovarianceEstimator too_small(3);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("innovation_covariance.min_samples = 3"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(estimator.Add(Vec3(0.0, std::nan(""), 0.0)), InputError);
}

// The simulator's exactly discretised linear parts have the stationary statistics they
// are built for. 20000 samples at 1 s: the wave motion's correlation time 1/(lambda w0)
// = 11 s leaves ~900 independent samples, a 5 % standard error on a variance; the bias,
// with T shortened to 10 s, 2.2 %; the measurement noise, 1 %. Bounds 15 %, 10 %, 5 %.
TEST(HypothesisModelSimulatorTest, StationaryStatistics) {
  EkfOptions noise;
  noise.force_noise.setZero();
  noise.bias_time_constant = Vec3::Constant(10.0);
  const QuasiStaticMooring no_lines;
  HypothesisModelSimulator simulator(no_lines, SeedLowFrequencyModel(), Mat3::Zero(), noise,
                                     Vec3::Zero(), 3);
  Vec3 wave_square = Vec3::Zero(), integral_square = Vec3::Zero(), bias_square = Vec3::Zero(),
       noise_square = Vec3::Zero();
  constexpr int kSamples = 20000;
  for (int k = 1; k <= kSamples; ++k) {
    simulator.Advance(1.0, Vec3::Zero());
    const State& x = simulator.state();
    const Observation obs = simulator.Measure(k, Vec3::Zero());
    const Vec3 v = obs.pose - x.segment<3>(HypothesisPassiveObserver::kPose) -
                   x.segment<3>(HypothesisPassiveObserver::kWave + 3);
    wave_square += x.segment<3>(HypothesisPassiveObserver::kWave + 3).cwiseAbs2();
    integral_square += x.segment<3>(HypothesisPassiveObserver::kWave).cwiseAbs2();
    bias_square += x.segment<3>(HypothesisPassiveObserver::kBias).cwiseAbs2();
    noise_square += Vec3(v.x(), v.y(), std::remainder(v.z(), 2.0 * std::numbers::pi)).cwiseAbs2();
  }
  for (int i = 0; i < 3; ++i) {
    const double wave_variance = noise.wave_motion_std(i) * noise.wave_motion_std(i);
    const double w0 = noise.wave_frequency(i);
    EXPECT_NEAR(wave_square(i) / kSamples / wave_variance, 1.0, 0.15) << i;
    EXPECT_NEAR(integral_square(i) / kSamples / (wave_variance / (w0 * w0)), 1.0, 0.15) << i;
    EXPECT_NEAR(bias_square(i) / kSamples / (noise.bias_std(i) * noise.bias_std(i)), 1.0, 0.1) << i;
    EXPECT_NEAR(noise_square(i) / kSamples / noise.measurement_variance(i), 1.0, 0.05) << i;
  }
}

/// Mean e^T Sigma^-1 e of passive observer h over `samples` seconds of fresh own-model
/// data (streams "own_model", not the training's), after a 500 s settle.
double MeanNis(int h, std::uint64_t seed, int samples) {
  const QuasiStaticMooring& mooring = SeedBank().mooring(h);
  const LowFrequencyModel model = SeedLowFrequencyModel();
  HypothesisModelSimulator plant(mooring, model, Mat3::Zero(), EkfOptions{}, Vec3::Zero(), seed);
  HypothesisPassiveObserver observer(mooring, model, Mat3::Zero(), SeedCovariances()[h]);
  const Vec3 tau = HoldingThrust(mooring, Vec3::Zero());
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k <= 500 + samples; ++k) {
    if (k > 0) plant.Advance(1.0, tau);
    observer.Update(plant.Measure(k, tau));
    if (k > 500) {
      sum += observer.normalised_innovation_squared();
      ++count;
    }
  }
  return sum / count;
}

// The trained Sigma_h is symmetric positive definite and consistent: on 10000 s of fresh
// data from the same model the mean normalised innovation squared is 3 within 10 %. (The
// innovations are autocorrelated - the wave motion - so both Sigma_h and the mean carry a
// few % of Monte-Carlo error: over 10 replay seeds the means were 2.98-3.10 for the
// intact and 2.89-3.01 for the line-6 observer.)
TEST(PassiveCovarianceTrainingSlow, TrainedCovarianceIsConsistent) {
  for (int h : {0, 6}) {
    const Mat3& sigma = SeedCovariances()[h];
    EXPECT_EQ(sigma, sigma.transpose());
    EXPECT_EQ(Eigen::LLT<Mat3>(sigma).info(), Eigen::Success);
    // Larger than the measurement noise plus wave motion (0.005 + 0.0225 m^2): a 1 s
    // prediction through a 1.1 rad/s loop does not remove them.
    EXPECT_GT(sigma(0, 0), 0.0275);
    const double nis = MeanNis(h, 2 + h, 10000);
    EXPECT_GT(nis, 2.7) << "hypothesis " << h;
    EXPECT_LT(nis, 3.3) << "hypothesis " << h;
  }
}

// The recorded-run overload on the same data as the simulated training gives the same
// Sigma, bit for bit: the training is observer h on a HypothesisModelSimulator with the
// streams "training", held by HoldingThrust.
TEST(PassiveCovarianceTrainingSlow, RecordedRunAndSimulatedTrainingAgree) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  CovarianceTrainingOptions training;
  training.duration = 1000.0;
  training.settle_time = 200.0;
  training.seed = 17;
  training.pose = Vec3(3.0, -2.0, 0.1);
  const int h = 7;
  const Mat3 simulated = TrainPassiveCovariance(bank, h, model, {}, EkfOptions{}, training);

  HypothesisModelSimulator plant(bank.mooring(h), model, Mat3::Zero(), EkfOptions{}, training.pose,
                                 training.seed, "training");
  const Vec3 tau = HoldingThrust(bank.mooring(h), training.pose);
  std::vector<Observation> run;
  for (int k = 0; k <= 1200; ++k) {
    if (k > 0) plant.Advance(1.0, tau);
    run.push_back(plant.Measure(k, tau));
  }
  EXPECT_EQ(TrainPassiveCovariance(bank, h, model, {}, run, 200.0), simulated);

  // Too short a run for the minimum sample count.
  const std::vector<Observation> short_run(run.begin(), run.begin() + 250);
  EXPECT_THROW(TrainPassiveCovariance(bank, h, model, {}, short_run, 200.0), InputError);
}

// DHT-style: on data from hypothesis k (line k absent) the summed log-likelihood of
// passive observer k, with its trained Sigma_k, beats the intact observer over 2000 s. The
// vessel starts at rest, held at the origin by the true model's holding thrust, with zero
// bias (which then wanders with its 1 MN spread). The evidence is the transient: a wrong
// observer must take up the parted line's 3.5 MN in its bias, which its K3/K4 loop does in
// 20-40 s with innovations of decimetres. Afterwards the observers' innovations on the
// same data are nearly equal (their steady-state log-likelihoods differ by ~0.003 nats
// per sample, and not always in favour of the true model: a passive observer is no
// optimal predictor), so the margin barely grows. Over 6 seeds x 8 lines the margin over
// the intact observer was 5-19 nats at 2000 s, all positive. (Started with a random 1 MN
// bias that every observer must learn, it was positive in only 40 of 48: an unknown
// starting load looks like part of a line's.) On intact data the intact observer beats
// the line-6 one over the first 200 s (2.6-13 nats over 10 seeds), but over 2000 s only
// in 6 of 10: that check is on the transient.
TEST(PassiveCovarianceTrainingSlow, TrueHypothesisBeatsTheAlternative) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  PassiveObserverBank observers(bank, model, {}, SeedCovariances());
  struct Case {
    int truth, other;
    std::uint64_t seed;
    int duration;
  };
  for (const Case& c :
       {Case{6, 0, 31, 2000}, Case{7, 0, 32, 2000}, Case{8, 0, 33, 2000}, Case{0, 6, 34, 200}}) {
    const QuasiStaticMooring& mooring = bank.mooring(c.truth);
    HypothesisModelSimulator plant(mooring, model, Mat3::Zero(), EkfOptions{}, Vec3::Zero(),
                                   c.seed);
    State x = plant.state();
    x.segment<3>(HypothesisPassiveObserver::kBias).setZero();
    plant.set_state(x);
    observers.Reset();
    const Vec3 tau = HoldingThrust(mooring, Vec3::Zero());
    std::vector<double> sum(bank.size(), 0.0);
    for (int k = 0; k <= c.duration; ++k) {
      if (k > 0) plant.Advance(1.0, tau);
      const Evidence& evidence = observers.Update(plant.Measure(k, tau));
      for (int h = 0; h < bank.size(); ++h) sum[h] += evidence.hypotheses[h].log_likelihood;
    }
    EXPECT_GT(sum[c.truth] - sum[c.other], 2.0) << "truth " << c.truth << " vs " << c.other;
  }
}

TEST(PassiveCovarianceTrainingSlow, BadOptionsNameTheField) {
  const HypothesisBank& bank = SeedBank();
  const LowFrequencyModel model = SeedLowFrequencyModel();
  auto message = [&](const CovarianceTrainingOptions& training, int h) -> std::string {
    try {
      TrainPassiveCovariance(bank, h, model, {}, EkfOptions{}, training);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  CovarianceTrainingOptions training;
  training.duration = -1.0;
  EXPECT_NE(message(training, 0).find("training.duration = -1"), std::string::npos)
      << message(training, 0);
  training = {};
  training.settle_time = std::nan("");
  EXPECT_NE(message(training, 0).find("training.settle_time = nan"), std::string::npos)
      << message(training, 0);
  training = {};
  training.min_samples = 2;
  EXPECT_NE(message(training, 0).find("training.min_samples = 2"), std::string::npos)
      << message(training, 0);
  EXPECT_NE(message({}, 9).find("training hypothesis = 9"), std::string::npos) << message({}, 9);
  EkfOptions noise;
  noise.bias_std.y() = -1.0;
  EXPECT_THROW(TrainPassiveCovariance(bank, 0, model, {}, noise), InputError);
}

}  // namespace
}  // namespace moorsim::detectors
