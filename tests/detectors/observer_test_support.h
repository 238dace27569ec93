// What the tests of the hypothesis observers share (ekf_observer_test.cc,
// passive_observer_test.cc, innovation_covariance_test.cc): the seed case's hypothesis bank and
// the checks both observers (HypothesisEkf, HypothesisPassiveObserver) and both banks
// (ObserverBank, PassiveObserverBank) must pass alike.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.h"
#include "core/types.h"
#include "detectors/detector.h"
#include "detectors/hypothesis_bank.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace moorsim::detectors::testing {

/// The mooring of the seed scenario (scenarios/library/seed_tapm.yaml).
inline mooring_fem::MooringParameters SeedMooring() {
  return scenarios::ToMooringParameters(
      scenarios::LoadScenario(std::string(MOORSIM_SOURCE_DIR) + "/scenarios/library/seed_tapm.yaml")
          .mooring);
}

/// The seed case's hypothesis bank (intact and each line failed), built once.
inline const HypothesisBank& SeedBank() {
  static const HypothesisBank bank(SeedMooring());
  return bank;
}

/// `observer` after 21 samples (t = 0 ... 20 s) of a still vessel at `eta`.
template <class Observer>
Observer Warm(Observer observer, const Vec3& eta) {
  for (int k = 0; k <= 20; ++k) {
    Observation obs;
    obs.t = k;
    obs.pose = eta;
    observer.Update(obs);
  }
  return observer;
}

/// Feeds `observer` (warm at heading pi - 0.01) a gyro that reports values on both sides of
/// the branch cut, t = 21 ... 59 s: the innovation is wrapped, so it stays small, and the
/// estimate stays in (-pi, pi]. `check(observer, t)` adds the caller's checks per sample.
template <class Observer, class Check>
void ExpectHeadingWrapsAcrossPi(Observer& observer, Check check) {
  constexpr double kPi = std::numbers::pi;
  for (int k = 21; k < 60; ++k) {
    Observation obs;
    obs.t = k;
    // Alternately just below +pi and just above -pi: 0.02 rad apart on the circle.
    obs.pose = Vec3(0.0, 0.0, k % 2 == 0 ? kPi - 0.01 : -kPi + 0.01);
    const HypothesisEvidence e = observer.Update(obs);
    EXPECT_LT(std::abs(e.innovation.z()), 0.05) << "t " << k;
    EXPECT_GT(observer.pose().z(), -kPi);
    EXPECT_LE(observer.pose().z(), kPi);
    check(observer, k);
  }
}

/// The first observation only initialises `fresh`, and only once all channels are there;
/// the pose estimate is then the measured pose.
template <class Observer>
void ExpectInitialisesOnACompleteObservation(Observer fresh) {
  Observation obs;
  obs.t = 0.0;
  obs.pose = Vec3(0.3, 0.0, -0.05);
  obs.valid = {true, true, false};
  EXPECT_EQ(fresh.Update(obs).dimension, 0);
  EXPECT_FALSE(fresh.initialised());
  obs.valid = {true, true, true};
  EXPECT_EQ(fresh.Update(obs).dimension, 0);
  EXPECT_TRUE(fresh.initialised());
  EXPECT_EQ(fresh.pose(), obs.pose);
}

/// Feeds the same poses to `a` and `b` with different commands (0 to `a`) and to `used`
/// with b's commands, t = 0 ... 9 s. With use_thrust_command = false in `a` and `b` they
/// must agree exactly.
template <class Observer>
void FeedDifferentCommands(Observer& a, Observer& b, Observer& used) {
  Observation obs;
  for (int k = 0; k < 10; ++k) {
    obs.t = k;
    obs.pose = Vec3(0.01 * k, -0.02 * k, 0.001 * k);
    obs.tau_command = Vec3::Zero();
    a.Update(obs);
    obs.tau_command = Vec3(5e6, -3e6, 1e8);
    b.Update(obs);
    used.Update(obs);
  }
  EXPECT_EQ(a.state(), b.state());
}

/// `observer`, warm at t = 20 s: a time that does not advance, and a valid channel that
/// is not finite, are moorsim::InputError.
template <class Observer>
void ExpectBadObservationsThrow(Observer observer) {
  Observation obs;
  obs.t = 20.0;  // the last sample's time again
  EXPECT_THROW(observer.Update(obs), InputError);
  obs.t = 21.0;
  obs.pose.x() = std::nan("");
  EXPECT_THROW(observer.Update(obs), InputError);
}

/// Runs `observers` (a bank of the seed case's 9 hypotheses) on `samples` samples of a still
/// vessel at the origin: evidence for each hypothesis at each sample, dimension 0 at the
/// first (initialisation) and 3 after. At the origin the intact model is at rest and the
/// line-k models are pushed, so the intact observer explains a still vessel best.
template <class Bank>
void ExpectEvidenceForEachHypothesis(Bank& observers, int samples) {
  EXPECT_EQ(observers.size(), 9);
  Observation obs;
  for (int k = 0; k < samples; ++k) {
    obs.t = k;
    const Evidence& e = observers.Update(obs);
    EXPECT_EQ(e.t, obs.t);
    ASSERT_EQ(e.hypotheses.size(), 9u);
    EXPECT_EQ(e.hypotheses[0].dimension, k == 0 ? 0 : 3);
  }
  const Evidence& e = observers.evidence();
  for (int h = 1; h < 9; ++h) {
    EXPECT_GT(e.hypotheses[0].log_likelihood, e.hypotheses[h].log_likelihood) << h;
  }
}

}  // namespace moorsim::detectors::testing
