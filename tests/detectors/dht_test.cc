// The DHT's recursion, floor rule and alarm rule on hand-made evidence (the synthetic-truth
// tests are in detectors_test.cc).
#include "detectors/dht.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/detectors/evidence_support.h"

namespace moorsim::detectors {
namespace {

using testing::WithLogLikelihoods;

DhtOptions Options(double floor, double threshold, double hold) {
  DhtOptions options;
  options.floor = floor;
  options.threshold = threshold;
  options.hold = hold;
  return options;
}

double Sum(const std::vector<double>& x) {
  double sum = 0.0;
  for (const double v : x) sum += v;
  return sum;
}

TEST(ProbabilityFloorTest, RaisesToTheFloorAndKeepsTheOtherRatios) {
  std::vector<double> p = {0.6, 0.4 - 3e-10, 1e-10, 2e-10};
  std::vector<char> scratch(p.size());
  internal::ApplyProbabilityFloor(1e-9, p, scratch);
  EXPECT_EQ(p[2], 1e-9);
  EXPECT_EQ(p[3], 1e-9);
  EXPECT_NEAR(p[0] / p[1], 0.6 / (0.4 - 3e-10), 1e-15);
  EXPECT_NEAR(Sum(p), 1.0, 1e-15);
}

TEST(ProbabilityFloorTest, CascadesWhenTheScalingTakesAnotherBelowTheFloor) {
  // Floor 0.2: flooring the last two leaves 0.6 for {0.79, 0.2}, which scales 0.2 to
  // 0.121 < 0.2, so it is floored too and 0.79 gets the remaining 0.4.
  std::vector<double> p = {0.79, 0.2, 0.01, 0.0};
  std::vector<char> scratch(p.size());
  internal::ApplyProbabilityFloor(0.2, p, scratch);
  EXPECT_DOUBLE_EQ(p[0], 0.4);
  EXPECT_EQ(p[1], 0.2);
  EXPECT_EQ(p[2], 0.2);
  EXPECT_EQ(p[3], 0.2);
}

TEST(ProbabilityFloorTest, LeavesADistributionAboveTheFloorAlone) {
  std::vector<double> p = {0.25, 0.25, 0.5};
  std::vector<char> scratch(p.size());
  internal::ApplyProbabilityFloor(1e-9, p, scratch);
  EXPECT_EQ(p, (std::vector<double>{0.25, 0.25, 0.5}));
}

TEST(DhtTest, OneStepIsBayesRule) {
  // Hassani et al. 2018, eq. 47: h_k' = L_k h_k / sum_i L_i h_i, here with the prior
  // 0.7 / 0.15 / 0.15.
  Dht dht(DhtOptions{.prior_intact = 0.7});
  dht.Reset(3);
  EXPECT_DOUBLE_EQ(dht.posterior()[0], 0.7);
  EXPECT_DOUBLE_EQ(dht.posterior()[1], 0.15);
  const std::vector<double> log_l = {std::log(0.1), std::log(0.5), std::log(0.2)};
  const Verdict v = dht.Update(WithLogLikelihoods(0.0, log_l));
  const double z = 0.7 * 0.1 + 0.15 * 0.5 + 0.15 * 0.2;
  EXPECT_NEAR(v.score[0], 0.07 / z, 1e-15);
  EXPECT_NEAR(v.score[1], 0.075 / z, 1e-15);
  EXPECT_NEAR(v.score[2], 0.03 / z, 1e-15);
  EXPECT_EQ(v.hypothesis, 1);
}

TEST(DhtTest, EqualLikelihoodsLeaveThePosterior) {
  Dht dht;
  dht.Reset(4);
  const Verdict v = dht.Update(WithLogLikelihoods(0.0, {-7.0, -7.0, -7.0, -7.0}));
  for (const double h : v.score) EXPECT_DOUBLE_EQ(h, 0.25);
}

TEST(DhtTest, AFlooredHypothesisRecovers) {
  // 100 samples of 50 nats per sample for hypothesis 0 push hypothesis 1 to the floor; from
  // log odds ln(1e-9) = -20.7 it then needs ceil((20.7 + ln 99) / 5) = 6 samples of 5 nats
  // to pass 0.99. Without the floor it would need ceil((100 * 50 + ln 99) / 5) = 1001.
  Dht dht(Options(1e-9, 0.99, 0.0));
  dht.Reset(2);
  for (int i = 0; i < 100; ++i) dht.Step(WithLogLikelihoods(i, {0.0, -50.0}));
  EXPECT_EQ(dht.posterior()[1], 1e-9);
  int samples = 0;
  while (!dht.Step(WithLogLikelihoods(100 + samples, {-5.0, 0.0})).alarm) ++samples;
  EXPECT_EQ(samples + 1, 6);
}

TEST(DhtTest, AlarmNeedsTheSameHypothesisForTheHoldAndIsALevel) {
  Dht dht(Options(1e-9, 0.9, 1.0));
  dht.Reset(3);
  // 100 nats per sample: enough to lift a floored hypothesis (log odds -20.7) to the top
  // in one sample.
  const std::vector<double> favour_2 = {-100.0, -100.0, 0.0};
  const std::vector<double> favour_1 = {-100.0, 0.0, -100.0};
  const std::vector<double> favour_0 = {0.0, -100.0, -100.0};
  // t = 0: h_2 > 0.9 at once; the alarm waits until t - 0 >= 1.
  EXPECT_FALSE(dht.Step(WithLogLikelihoods(0.0, favour_2)).alarm);
  EXPECT_FALSE(dht.Step(WithLogLikelihoods(0.5, favour_2)).alarm);
  EXPECT_TRUE(dht.Step(WithLogLikelihoods(1.0, favour_2)).alarm);
  // Another failure hypothesis takes over: its own hold starts.
  const Verdict& v = dht.Step(WithLogLikelihoods(1.5, favour_1));
  EXPECT_EQ(v.hypothesis, 1);
  EXPECT_FALSE(v.alarm);
  EXPECT_FALSE(dht.Step(WithLogLikelihoods(2.0, favour_1)).alarm);
  EXPECT_TRUE(dht.Step(WithLogLikelihoods(2.5, favour_1)).alarm);
  // The intact hypothesis wins back: the alarm drops.
  EXPECT_FALSE(dht.Step(WithLogLikelihoods(3.0, favour_0)).alarm);
}

TEST(DhtTest, IntactNeverAlarms) {
  Dht dht(Options(1e-9, 0.99, 0.0));
  dht.Reset(2);
  const Verdict& v = dht.Step(WithLogLikelihoods(0.0, {0.0, -30.0}));
  EXPECT_EQ(v.hypothesis, 0);
  EXPECT_FALSE(v.alarm);
}

TEST(DhtTest, TooLargeAFloorForTheBankIsAnInputError) {
  Dht dht(Options(0.2, 0.99, 10.0));
  EXPECT_NO_THROW(dht.Reset(4));
  try {
    dht.Reset(5);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "dht: floor 0.2 is too large for 5 hypotheses (floor times hypotheses must be "
                 "< 1)");
  }
}

TEST(DhtTest, NonFiniteLogLikelihoodIsASolverError) {
  Dht dht;
  dht.Reset(3);
  try {
    dht.Update(WithLogLikelihoods(12.5, {0.0, std::nan(""), 0.0}));
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    EXPECT_STREQ(e.what(), "dht: log-likelihood of hypothesis 1 is nan at t = 12.5 s");
  }
  EXPECT_THROW(
      dht.Update(WithLogLikelihoods(13.0, {0.0, 0.0, -std::numeric_limits<double>::infinity()})),
      SolverError);
}

TEST(DhtTest, WrongHypothesisCountIsAContractErrorNotAnAbort) {
  Dht dht;
  dht.Reset(3);
  try {
    dht.Update(WithLogLikelihoods(0.0, {0.0, 0.0}));
    FAIL() << "no ContractError";
  } catch (const ContractError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("dht: contract violated"));
  }
}

}  // namespace
}  // namespace moorsim::detectors
