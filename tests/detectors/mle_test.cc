// The MLE's forgetting recursion and alarm rule on hand-made evidence (the synthetic-truth
// tests are in detectors_test.cc).
#include "detectors/mle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "tests/detectors/evidence_support.h"

namespace moorsim::detectors {
namespace {

// The TAPM thesis's MLE (forgetting 0.999, and the hold and margin these tests were written
// for); MleOptions' defaults are tuned for the coupled plant instead (detectors/mle.h).
constexpr MleOptions kSeedMle{.forgetting_factor = 0.999, .hold = 30.0, .margin = 10.0};

using testing::WithLogLikelihoods;

TEST(MleTest, ForgettingGivesAGeometricSumWithMemoryOneOverOneMinusLambda) {
  // A constant log-likelihood l gives J_n = -l (1 - lambda^n) / (1 - lambda) -> -l / (1 -
  // lambda): the steady-state window is 1 / (1 - lambda) = 1000 samples at 0.999.
  Mle mle(kSeedMle);
  mle.Reset(2);
  const int n = 5000;
  for (int i = 0; i < n; ++i) mle.Step(WithLogLikelihoods(i, {-1.0, -3.0}));
  const double window = (1.0 - std::pow(0.999, n)) / (1.0 - 0.999);
  EXPECT_NEAR(mle.negative_log_likelihood()[0], window, 1e-9 * window);
  EXPECT_NEAR(mle.negative_log_likelihood()[1], 3.0 * window, 3e-9 * window);
  EXPECT_NEAR(window, 1000.0, 7.0);  // 1000 (1 - e^-5)
}

TEST(MleTest, LambdaOneIsThePlainSum) {
  Mle mle(MleOptions{.forgetting_factor = 1.0});
  mle.Reset(2);
  for (int i = 0; i < 100; ++i) mle.Step(WithLogLikelihoods(i, {-0.5, -0.25}));
  EXPECT_DOUBLE_EQ(mle.negative_log_likelihood()[0], 50.0);
  EXPECT_DOUBLE_EQ(mle.negative_log_likelihood()[1], 25.0);
}

TEST(MleTest, AlarmNeedsTheHoldAndTheMargin) {
  // forgetting 1: J_0 - J_1 grows by 1 nat a sample while hypothesis 1 leads.
  Mle mle(MleOptions{.forgetting_factor = 1.0, .hold = 2.0, .margin = 4.5});
  mle.Reset(3);
  std::vector<bool> alarms;
  std::vector<int> hypotheses;
  for (int i = 0; i < 8; ++i) {
    const Verdict& v = mle.Step(WithLogLikelihoods(i, {-1.0, 0.0, -1.5}));
    alarms.push_back(v.alarm);
    hypotheses.push_back(v.hypothesis);
  }
  // Hypothesis 1 is the argmin from t = 0; the hold is met at t = 2 but the lead J_0 - J_1 =
  // t + 1 first exceeds 4.5 at t = 4.
  EXPECT_EQ(hypotheses, std::vector<int>(8, 1));
  EXPECT_EQ(alarms, (std::vector<bool>{false, false, false, false, true, true, true, true}));
  // The intact hypothesis takes the lead back: no alarm.
  for (int i = 8; i < 30; ++i) mle.Step(WithLogLikelihoods(i, {0.0, -2.0, -2.0}));
  EXPECT_EQ(mle.Step(WithLogLikelihoods(30, {0.0, -2.0, -2.0})).hypothesis, 0);
}

TEST(MleTest, ANewLeaderRestartsTheHold) {
  Mle mle(MleOptions{.forgetting_factor = 1.0, .hold = 1.0, .margin = 0.0});
  mle.Reset(3);
  EXPECT_FALSE(mle.Step(WithLogLikelihoods(0.0, {-5.0, 0.0, -5.0})).alarm);
  EXPECT_TRUE(mle.Step(WithLogLikelihoods(1.0, {-5.0, 0.0, -5.0})).alarm);
  const Verdict& v = mle.Step(WithLogLikelihoods(2.0, {-5.0, -30.0, 0.0}));
  EXPECT_EQ(v.hypothesis, 2);
  EXPECT_FALSE(v.alarm);
  EXPECT_TRUE(mle.Step(WithLogLikelihoods(3.0, {-5.0, -5.0, 0.0})).alarm);
}

TEST(MleTest, NonFiniteLogLikelihoodIsASolverError) {
  Mle mle(kSeedMle);
  mle.Reset(2);
  try {
    mle.Update(WithLogLikelihoods(3.0, {0.0, std::log(0.0)}));
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    EXPECT_STREQ(e.what(), "mle: log-likelihood of hypothesis 1 is -inf at t = 3 s");
  }
}

}  // namespace
}  // namespace moorsim::detectors
