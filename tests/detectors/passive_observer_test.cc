// Tests of the passive observers (detectors/passive_observer.h): the gains against the TAPM
// thesis's numbers, the loop's poles, convergence on noise-free data from the observer's own model
// (HypothesisModelSimulator with every noise source off), heading wrap, missing channels,
// the bank and bad input. The statistical checks with the offline covariance are in
// innovation_covariance_test.cc.
#include "detectors/passive_observer.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "detectors/hypothesis_bank.h"
#include "detectors/innovation_covariance.h"
#include "tests/detectors/observer_test_support.h"

namespace moorsim::detectors {
namespace {

using State = HypothesisPassiveObserver::State;
using testing::SeedBank;

/// A plausible innovation covariance (the trained one is about diag(0.031, 0.031, 0.010)).
Mat3 TypicalCovariance() { return Vec3(0.03, 0.03, 0.01).asDiagonal(); }

// TAPM thesis eq. 4.5-4.8 with zeta_n = 1, lambda = 0.1, w0 = 2 pi / 7, w_c = 1.2255 w0:
// the numbers of MSS's ExPassiveObs.m (w0 = 0.8976, w_c = 1.1).
TEST(PassiveObserverGainsTest, MatchTheSeed) {
  const PassiveObserverGains gains = ComputePassiveObserverGains({});
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(gains.k2(i), 1.1, 1e-4);                                // w_c = 1.2255 * 0.8976
    EXPECT_NEAR(gains.k1_integral(i), -2.0 * 0.9 * 1.2255, 1e-12);      // -2.2059
    EXPECT_NEAR(gains.k1_wave(i), 2.0 * 0.9 * 2.0 * kPi / 7.0, 1e-12);  // 1.6158
  }
  EXPECT_EQ(gains.k4, Vec3(0.1, 0.1, 0.01));
  EXPECT_TRUE(gains.k3.isApprox(0.1 * gains.k4, 1e-15));

  // The wave/position loop (Fossen 2011 section 11.4.1; ExPassiveObs.m's h0 denominator)
  //   s^3 + (K1_{i+3} + K2 + 2 lambda w0) s^2 + (w0^2 + 2 lambda w0 K2 - K1_i w0^2) s
  //   + w0^2 K2
  // is (s^2 + 2 zeta_n w0 s + w0^2)(s + w_c): a notch at w0 and a cut-off at w_c.
  const double w0 = 2.0 * kPi / 7.0, wc = 1.2255 * w0, lambda = 0.1;
  EXPECT_NEAR(gains.k1_wave(0) + gains.k2(0) + 2.0 * lambda * w0, wc + 2.0 * w0, 1e-12);
  EXPECT_NEAR(w0 * w0 + 2.0 * lambda * w0 * gains.k2(0) - gains.k1_integral(0) * w0 * w0,
              2.0 * w0 * wc + w0 * w0, 1e-12);
}

/// d(observer rate)/d(state) by central differences at a state at rest at `pose`, with the
/// bias rows and columns scaled by 1/M so that the eigenvalue problem is well balanced.
Eigen::VectorXcd ObserverPoles(const HypothesisPassiveObserver& observer,
                               const QuasiStaticMooring& mooring, const Vec3& pose) {
  State x = State::Zero();
  x.segment<3>(HypothesisPassiveObserver::kPose) = pose;
  const Vec3 tau = HoldingThrust(mooring, pose);
  const double steps[15] = {1e-4, 1e-4, 1e-6, 1e-4, 1e-4, 1e-6, 1e-4, 1e-4,
                            1e-6, 1.0,  1.0,  100., 1e-5, 1e-5, 1e-7};
  Eigen::Matrix<double, 15, 15> A;
  for (int j = 0; j < 15; ++j) {
    State plus = x, minus = x;
    plus(j) += steps[j];
    minus(j) -= steps[j];
    A.col(j) = (observer.Derivative(plus, pose, {true, true, true}, tau) -
                observer.Derivative(minus, pose, {true, true, true}, tau)) /
               (2.0 * steps[j]);
  }
  Eigen::Matrix<double, 15, 1> scale = Eigen::Matrix<double, 15, 1>::Ones();
  scale.segment<3>(HypothesisPassiveObserver::kBias) = Vec3(1e-8, 1e-8, 1e-11);
  const Eigen::Matrix<double, 15, 15> balanced =
      scale.asDiagonal() * A * scale.cwiseInverse().asDiagonal();
  return Eigen::EigenSolver<Eigen::Matrix<double, 15, 15>>(balanced, false).eigenvalues();
}

// The linearised observer on the seed FPSO (intact, at the thesis heading -135 deg): all
// poles stable; the fastest |lambda| ~ 1.3 rad/s, so the 0.5 s RK4 substep has
// |lambda h| ~ 0.65 (stable to 2.78); with the mass-scaled gains the slowest mode decays
// in about 36 s (1/0.028). With the literal SI gains the slowest modes are the bias's own
// 1/T = 0.001 1/s: nothing corrects it.
TEST(PassiveObserverGainsTest, LoopPolesOnTheSeedModel) {
  const QuasiStaticMooring& mooring = SeedBank().mooring(0);
  const Vec3 pose(0.0, 0.0, -0.75 * kPi);
  const HypothesisPassiveObserver scaled(mooring, SeedLowFrequencyModel(), Mat3::Zero(),
                                         TypicalCovariance());
  const Eigen::VectorXcd poles = ObserverPoles(scaled, mooring, pose);
  double fastest = 0.0, slowest = 1e9;
  for (const std::complex<double>& p : poles) {
    EXPECT_LT(p.real(), 0.0) << p;
    fastest = std::max(fastest, std::abs(p));
    slowest = std::min(slowest, -p.real());
  }
  EXPECT_LT(fastest, 1.4);
  EXPECT_GT(slowest, 0.02);

  PassiveObserverOptions literal;
  literal.mass_scaled_gains = false;
  const HypothesisPassiveObserver open_loop(mooring, SeedLowFrequencyModel(), Mat3::Zero(),
                                            TypicalCovariance(), literal);
  slowest = 1e9;
  for (const std::complex<double>& p : ObserverPoles(open_loop, mooring, pose)) {
    slowest = std::min(slowest, -p.real());
  }
  EXPECT_NEAR(slowest, 1e-3, 1e-5);
}

/// Noise off: no wave motion, bias and force noise, measurement noise 1e-24 (must be > 0).
EkfOptions NoiseFree() {
  EkfOptions noise;
  noise.wave_motion_std.setZero();
  noise.bias_std.setZero();
  noise.force_noise.setZero();
  noise.measurement_variance = Vec3::Constant(1e-24);
  return noise;
}

struct ConvergenceResult {
  Vec3 pose_error;
  Vec3 bias_error;
  Vec3 bias;
};

/// The observer of line-6-failed on noise-free own-model data: the vessel is held at the
/// thesis heading with the holding thrust, starts 3 m off with a 0.6 MN bias and some
/// speed; the observer starts from a first sample that is 1 m, 1 m, 3 deg off and with
/// b = nu = 0.
ConvergenceResult RunNoiseFree(const PassiveObserverOptions& options, double duration) {
  const QuasiStaticMooring& mooring = SeedBank().mooring(6);
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const Vec3 pose(0.0, 0.0, -0.75 * kPi);
  HypothesisModelSimulator truth(mooring, model, Mat3::Zero(), NoiseFree(), pose, 1);
  State x = State::Zero();
  x.segment<3>(HypothesisPassiveObserver::kPose) = pose + Vec3(2.0, -2.0, 0.02);
  x.segment<3>(HypothesisPassiveObserver::kBias) = Vec3(4e5, -4.5e5, 2e7);
  x.segment<3>(HypothesisPassiveObserver::kVelocity) = Vec3(0.05, -0.03, 1e-3);
  truth.set_state(x);
  HypothesisPassiveObserver observer(mooring, model, Mat3::Zero(), TypicalCovariance(), options);
  const Vec3 tau = HoldingThrust(mooring, pose);
  for (int k = 0; k <= duration; ++k) {
    if (k > 0) truth.Advance(1.0, tau);
    Observation obs = truth.Measure(k, tau);
    if (k == 0) obs.pose += Vec3(1.0, 1.0, 0.05);
    observer.Update(obs);
  }
  const State& t = truth.state();
  ConvergenceResult r;
  r.pose_error = observer.pose() - t.segment<3>(HypothesisPassiveObserver::kPose);
  r.bias = t.segment<3>(HypothesisPassiveObserver::kBias);
  r.bias_error = observer.bias() - r.bias;
  return r;
}

// With its own model and no noise the observer's error decays to what the 1 s hold of y
// leaves while the truth drifts with its decaying bias: after 2000 s (60 times the
// slowest error time constant) the position is within 1.2 mm (bound 1 cm), the heading
// within 5e-6 rad (bound 1e-3) and the bias within 0.3 % (bound 3 %) of the truth, whose
// own bias has decayed to e^-2 of its start (T = 1000 s), about 0.06 MN.
TEST(PassiveObserverConvergenceTest, NoiseFreeOwnModelFromAWrongStart) {
  const ConvergenceResult r = RunNoiseFree({}, 2000.0);
  EXPECT_LT(r.pose_error.head<2>().norm(), 0.01) << r.pose_error.transpose();
  EXPECT_LT(std::abs(r.pose_error.z()), 1e-3) << r.pose_error.transpose();
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(r.bias_error(i)), 0.03 * std::abs(r.bias(i)))
        << i << ": bias " << r.bias.transpose() << " error " << r.bias_error.transpose();
  }
}

// The literal SI reading of K3, K4 (file comment of core/passive_observer.h) does not estimate
// the bias: after the same 2000 s its bias estimate is still ~0 (error 100 % of the bias),
// and the open-loop velocity model leaves the position estimate 0.1 m off (up to 0.8 m
// in the first minutes).
TEST(PassiveObserverConvergenceTest, LiteralGainsDoNotEstimateTheBias) {
  PassiveObserverOptions literal;
  literal.mass_scaled_gains = false;
  const ConvergenceResult r = RunNoiseFree(literal, 2000.0);
  EXPECT_GT(r.bias_error.head<2>().norm(), 0.5 * r.bias.head<2>().norm())
      << r.bias_error.transpose();
  EXPECT_GT(r.pose_error.head<2>().norm(), 0.02) << r.pose_error.transpose();
}

/// An observer already running for 20 s on a still vessel at `eta`.
HypothesisPassiveObserver WarmObserver(const QuasiStaticMooring& mooring, const Vec3& eta) {
  return testing::Warm(HypothesisPassiveObserver(mooring, SeedLowFrequencyModel(), Mat3::Zero(),
                                                 TypicalCovariance()),
                       eta);
}

// Heading across +-pi: a vessel at heading 180 deg whose gyro reports values on both sides
// of the branch cut. The innovation is wrapped, so it stays small, and the estimate stays
// in (-pi, pi]. No mooring (a free vessel), as in the EKF's test.
TEST(PassiveObserverHeadingWrapTest, InnovationWrapsAcrossPi) {
  const QuasiStaticMooring no_lines;
  HypothesisPassiveObserver observer = WarmObserver(no_lines, Vec3(0.0, 0.0, kPi - 0.01));
  testing::ExpectHeadingWrapsAcrossPi(observer, [](const HypothesisPassiveObserver& o, int k) {
    EXPECT_LT(std::abs(std::remainder(o.pose().z() - kPi, 2.0 * kPi)), 0.03) << "t " << k;
  });
}

// A missing channel drops out of the likelihood (dimension 2, the 2-D Gaussian under the
// valid block of Sigma) and out of the correction: a garbage value there moves nothing.
TEST(PassiveObserverMissingChannelTest, DimensionLikelihoodAndCorrection) {
  const QuasiStaticMooring& mooring = SeedBank().mooring(0);
  Mat3 sigma;
  sigma << 0.03, 0.004, -0.001, 0.004, 0.032, 0.002, -0.001, 0.002, 0.01;
  HypothesisPassiveObserver observer(mooring, SeedLowFrequencyModel(), Mat3::Zero(), sigma);
  for (int k = 0; k <= 20; ++k) {
    Observation obs;
    obs.t = k;
    observer.Update(obs);
  }
  Observation obs;
  obs.t = 21.0;
  obs.pose = Vec3(0.3, 9.0, -0.05);  // y is garbage and flagged invalid
  obs.valid = {true, false, true};
  const HypothesisEvidence e = observer.Update(obs);
  EXPECT_EQ(e.dimension, 2);
  EXPECT_EQ(e.innovation.y(), 0.0);
  EXPECT_EQ(e.covariance, sigma);
  Eigen::Matrix2d S;
  S << sigma(0, 0), sigma(0, 2), sigma(2, 0), sigma(2, 2);
  const Eigen::Vector2d v(e.innovation.x(), e.innovation.z());
  const double expected =
      -0.5 * (v.dot(S.inverse() * v) + std::log(S.determinant()) + 2.0 * std::log(2.0 * kPi));
  EXPECT_NEAR(e.log_likelihood, expected, 1e-12 * std::abs(expected));
  EXPECT_NEAR(observer.normalised_innovation_squared(), v.dot(S.inverse() * v), 1e-12);

  // The next interval is integrated without a y correction. Had the garbage 9 m been
  // used, K2 = 1.1 1/s alone would have pulled the estimate metres toward it.
  obs.t = 22.0;
  obs.pose = Vec3(0.3, 0.0, -0.05);
  obs.valid = {true, true, true};
  observer.Update(obs);
  EXPECT_LT(std::abs(observer.pose().y()), 0.01);

  // Nothing valid: dimension 0, likelihood 0 (the log of an empty product).
  obs.t = 23.0;
  obs.valid = {false, false, false};
  const HypothesisEvidence none = observer.Update(obs);
  EXPECT_EQ(none.dimension, 0);
  EXPECT_EQ(none.log_likelihood, 0.0);
  EXPECT_EQ(none.innovation, Vec3::Zero());
  EXPECT_DOUBLE_EQ(observer.time(), 23.0);

  // The first observation only initialises, and only once all channels are there.
  testing::ExpectInitialisesOnACompleteObservation(
      HypothesisPassiveObserver(mooring, SeedLowFrequencyModel(), Mat3::Zero(), sigma));
}

// The full-channel log-likelihood is the 3-D Gaussian of the innovation under Sigma.
TEST(PassiveObserverEvidenceTest, FullLikelihood) {
  Mat3 sigma;
  sigma << 0.03, 0.004, -0.001, 0.004, 0.032, 0.002, -0.001, 0.002, 0.01;
  HypothesisPassiveObserver observer(SeedBank().mooring(0), SeedLowFrequencyModel(), Mat3::Zero(),
                                     sigma);
  Observation obs;
  observer.Update(obs);
  obs.t = 1.0;
  obs.pose = Vec3(0.2, -0.1, 0.03);
  const HypothesisEvidence e = observer.Update(obs);
  EXPECT_EQ(e.dimension, 3);
  // One second after a start at rest at the origin the prediction is still the origin.
  EXPECT_TRUE(e.innovation.isApprox(obs.pose, 1e-6)) << e.innovation.transpose();
  const double expected = -0.5 * (e.innovation.dot(sigma.inverse() * e.innovation) +
                                  std::log(sigma.determinant()) + 3.0 * std::log(2.0 * kPi));
  EXPECT_NEAR(e.log_likelihood, expected, 1e-12 * std::abs(expected));
}

// With use_thrust_command = false the command is ignored.
TEST(PassiveObserverThrustTest, CommandCanBeIgnored) {
  PassiveObserverOptions options;
  options.use_thrust_command = false;
  const LowFrequencyModel model = SeedLowFrequencyModel();
  const QuasiStaticMooring& mooring = SeedBank().mooring(0);
  HypothesisPassiveObserver a(mooring, model, Mat3::Zero(), TypicalCovariance(), options);
  HypothesisPassiveObserver b(mooring, model, Mat3::Zero(), TypicalCovariance(), options);
  HypothesisPassiveObserver used(mooring, model, Mat3::Zero(), TypicalCovariance());
  testing::FeedDifferentCommands(a, b, used);
  EXPECT_GT(used.velocity().head<2>().norm() - a.velocity().head<2>().norm(), 1e-3);
}

TEST(PassiveObserverInputTest, BadOptionsNameTheField) {
  auto message = [](const PassiveObserverOptions& options) -> std::string {
    try {
      Validate(options);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  PassiveObserverOptions options;
  options.velocity_gain = Vec3(0.1, 0.1, -1.0);
  EXPECT_NE(message(options).find("passive.velocity_gain[3] = -1"), std::string::npos)
      << message(options);
  options = {};
  options.notch_damping.y() = 0.05;  // below lambda = 0.1
  EXPECT_NE(message(options).find("passive.notch_damping[2] = 0.05"), std::string::npos)
      << message(options);
  options = {};
  options.bias_gain.x() = 0.5;  // K3/K4 = 5 1/s > w0
  EXPECT_NE(message(options).find("passive.bias_gain[1] = 0.5"), std::string::npos)
      << message(options);
  options = {};
  options.cutoff_ratio.z() = 0.9;
  EXPECT_NE(message(options).find("passive.cutoff_ratio[3] = 0.9"), std::string::npos)
      << message(options);
  options = {};
  options.max_substep = 0.0;
  EXPECT_NE(message(options).find("passive.max_substep = 0"), std::string::npos)
      << message(options);
  options = {};
  options.mooring_damping_ratio.x() = std::nan("");
  EXPECT_NE(message(options).find("passive.mooring_damping_ratio[1] = nan"), std::string::npos)
      << message(options);
  EXPECT_THROW(HypothesisPassiveObserver(QuasiStaticMooring(), SeedLowFrequencyModel(),
                                         Mat3::Zero(), TypicalCovariance(), options),
               InputError);

  // The covariance must be symmetric positive definite.
  Mat3 singular = TypicalCovariance();
  singular(2, 2) = 0.0;
  EXPECT_THROW(HypothesisPassiveObserver(QuasiStaticMooring(), SeedLowFrequencyModel(),
                                         Mat3::Zero(), singular),
               InputError);
  Mat3 asymmetric = TypicalCovariance();
  asymmetric(0, 1) = 0.001;
  EXPECT_THROW(HypothesisPassiveObserver(QuasiStaticMooring(), SeedLowFrequencyModel(),
                                         Mat3::Zero(), asymmetric),
               InputError);
  LowFrequencyModel bad_mass = SeedLowFrequencyModel();
  bad_mass.mass(2, 2) = 0.0;
  EXPECT_THROW(
      HypothesisPassiveObserver(QuasiStaticMooring(), bad_mass, Mat3::Zero(), TypicalCovariance()),
      InputError);

  // Time must advance; a valid channel must be finite.
  testing::ExpectBadObservationsThrow(WarmObserver(QuasiStaticMooring(), Vec3::Zero()));
}

// The bank runs one observer per hypothesis and hands back evidence for each; it needs one
// covariance per hypothesis; Reset starts every observer over.
TEST(PassiveObserverBankTest, OneObserverPerHypothesis) {
  const HypothesisBank& bank = SeedBank();
  PassiveObserverOptions options;
  options.mooring_damping_ratio = Vec3(0.1, 0.1, 0.1);
  const std::vector<Mat3> covariances(bank.size(), TypicalCovariance());
  PassiveObserverBank observers(bank, SeedLowFrequencyModel(), options, covariances);
  testing::ExpectEvidenceForEachHypothesis(observers, 30);
  observers.Reset();
  EXPECT_FALSE(observers.observer(3).initialised());

  const std::vector<Mat3> too_few(bank.size() - 1, TypicalCovariance());
  try {
    PassiveObserverBank(bank, SeedLowFrequencyModel(), {}, too_few);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("8 innovation covariances for 9 hypotheses"),
              std::string::npos)
        << error.what();
  }
  std::vector<Mat3> one_bad = covariances;
  one_bad[4](1, 1) = -1.0;
  try {
    PassiveObserverBank(bank, SeedLowFrequencyModel(), {}, one_bad);
    FAIL() << "expected InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("hypothesis 4 (line 4)"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace moorsim::detectors
