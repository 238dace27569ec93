// The passive nonlinear observer shared by the detection observers and the controller
// (core/passive_observer.h): its option checks in both callers' spellings, the gains, the
// bias it reads for an unmodelled load against the closed form, the mass-scaled gains
// against the force-level gains they stand for, and the two holds and two starts against
// each other and against a ramp.
#include "core/passive_observer.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/angles.h"
#include "core/error.h"

namespace moorsim {
namespace {

using ObserverOptions = PassiveNonlinearObserverOptions;
using ObserverStateVector = PassiveNonlinearObserver::State;
constexpr std::array<bool, 3> kEveryChannelValid = {true, true, true};

// The seed FPSO's low-frequency mass and damping (M_RB + A(0); D_ii = M_ii / (50, 100, 20 s)).
const Vec3 kSeedMass(1.0835e8, 1.6484e8, 4.378e11);
Mat3 SeedMass() { return kSeedMass.asDiagonal(); }
Mat3 SeedDamping() { return kSeedMass.cwiseQuotient(Vec3(50.0, 100.0, 20.0)).asDiagonal(); }

PassiveNonlinearObserver::MooringLoad NoMooring() {
  return [](const Vec3&) { return Vec3::Zero().eval(); };
}

std::string ValidationMessageOf(const ObserverOptions& options, const PassiveObserverKeys& keys) {
  try {
    ValidatePassiveObserver(options, keys);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

// The messages name each caller's keys: per DOF from 1 by default (the detection
// observers'), or one value for all DOFs, elements from 0 and K3 set as K3/K4 (the
// controller's).
TEST(PassiveObserverOptionsTest, MessagesNameTheCallersKeys) {
  const PassiveObserverKeys per_dof{.prefix = "passive."};
  const PassiveObserverKeys scalar{.prefix = "controller.observer.",
                                   .first_index = 0,
                                   .wave_frequency = {"wave_peak_frequency"},
                                   .cutoff_ratio = {"cutoff_ratio", false},
                                   .velocity_gain = {"k4_per_mass"},
                                   .bias_gain = {"k3_ratio", false},
                                   .bias_gain_is_ratio = true};
  EXPECT_EQ(ValidationMessageOf({}, per_dof), "no error");
  ObserverOptions options;
  options.velocity_gain.z() = -1.0;
  EXPECT_EQ(ValidationMessageOf(options, per_dof),
            "passive.velocity_gain[3] = -1: must be finite and > 0");
  EXPECT_EQ(ValidationMessageOf(options, scalar),
            "controller.observer.k4_per_mass[2] = -1: must be finite and > 0");
  options = {};
  options.cutoff_ratio.setConstant(0.9);
  EXPECT_EQ(ValidationMessageOf(options, per_dof),
            "passive.cutoff_ratio[1] = 0.9: must be > 1 (passivity: omega_c > omega_0)");
  EXPECT_EQ(ValidationMessageOf(options, scalar),
            "controller.observer.cutoff_ratio = 0.9: must be > 1 (passivity: omega_c > omega_0)");
  options = {};
  options.bias_gain = 2.0 * options.velocity_gain;  // K3/K4 = 2 1/s > w0
  EXPECT_EQ(ValidationMessageOf(options, per_dof),
            "passive.bias_gain[1] = 0.2: bias_gain / velocity_gain = 2 1/s must be < "
            "wave_frequency (passivity)");
  EXPECT_EQ(ValidationMessageOf(options, scalar),
            "controller.observer.k3_ratio = 2: must be < wave_peak_frequency (passivity)");
  options = {};
  options.bias_gain = options.velocity_gain / 2048.0;  // K3/K4 below 1/T
  EXPECT_EQ(ValidationMessageOf(options, scalar),
            "controller.observer.k3_ratio = 0.00048828125: must be > 1 / bias_time_constant "
            "(passivity)");
  options = {};
  options.notch_damping.y() = 0.05;  // below lambda
  EXPECT_EQ(ValidationMessageOf(options, per_dof),
            "passive.notch_damping[2] = 0.05: must be > wave_damping (the notch needs zeta_n > "
            "lambda)");
  options = {};
  options.wave_damping.setZero();  // an undamped wave model is allowed
  options.max_substep = std::nan("");
  EXPECT_EQ(ValidationMessageOf(options, per_dof),
            "passive.max_substep = nan: must be finite and > 0 s");
  EXPECT_THROW(PassiveNonlinearObserver(options, SeedMass(), SeedDamping(), NoMooring()),
               InputError);
  EXPECT_THROW(PassiveNonlinearObserver({}, Mat3::Zero(), SeedDamping(), NoMooring()), InputError);
}

// The wave/position loop (Fossen 2011 section 11.4.1) is (s^2 + 2 zeta_n w0 s + w0^2)(s + w_c)
// (the detection observers' tests check the TAPM thesis's numbers); without the wave model
// K1 = 0.
TEST(PassiveObserverGainsTest, NotchAndCutoffAndNoWaveModel) {
  ObserverOptions options;
  options.wave_frequency = Vec3(0.6, 0.9, 1.2);
  options.notch_damping = Vec3(1.0, 0.8, 0.5);
  const PassiveObserverGains gains = ComputePassiveObserverGains(options);
  for (int i = 0; i < 3; ++i) {
    const double w0 = options.wave_frequency(i), wc = 1.2255 * w0, lambda = 0.1;
    const double zeta = options.notch_damping(i);
    // s^2 and s coefficients of the loop's characteristic polynomial.
    EXPECT_NEAR(gains.k1_wave(i) + gains.k2(i) + 2.0 * lambda * w0, wc + 2.0 * zeta * w0, 1e-12);
    EXPECT_NEAR(w0 * w0 + 2.0 * lambda * w0 * gains.k2(i) - gains.k1_integral(i) * w0 * w0,
                2.0 * zeta * w0 * wc + w0 * w0, 1e-12);
  }
  options.wave_filter = false;
  const PassiveObserverGains off = ComputePassiveObserverGains(options);
  EXPECT_EQ(off.k1_integral, Vec3::Zero());
  EXPECT_EQ(off.k1_wave, Vec3::Zero());
  EXPECT_EQ(off.k2, gains.k2);
}

// A vessel held at rest at heading 0 against a constant Earth-frame load d that the model
// lacks (no mooring, the thrust tau = -d that holds it): the bias settles where the leak
// -b / T balances the injection, b = d / (1 + (D_ii K2_i / M_ii + K4_i) / (T_i K3_i))
// (file comment), 1.2 %, 1.1 % and 6.1 % below d for the seed FPSO. The yaw load is
// applied alone: the heading error that reads it (5e-5 rad) would turn the surge and sway
// loads by 20-40 N.
TEST(PassiveObserverBiasTest, ReadsAnUnmodelledLoadAsTheLeakyClosedForm) {
  Vec3 shortfall = Vec3::Zero();
  for (const Vec3& d : {Vec3(4e5, -3e5, 0.0), Vec3(0.0, 0.0, 2e7)}) {
    PassiveNonlinearObserver observer({}, SeedMass(), SeedDamping(), NoMooring());
    const Vec3 tau = -d;
    for (int k = 0; k <= 4000; ++k)
      observer.Update(1.0, tau, Vec3(1.0, 2.0, 0.0), kEveryChannelValid);
    const PassiveObserverGains& g = observer.gains();
    const Vec3 leak = (SeedDamping().diagonal().cwiseProduct(g.k2).cwiseQuotient(kSeedMass) + g.k4)
                          .cwiseQuotient(observer.options().bias_time_constant.cwiseProduct(g.k3));
    const Vec3 bias = observer.state().segment<3>(PassiveNonlinearObserver::kBias);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(bias(i), d(i) / (1.0 + leak(i)), 1e-9 * d.norm()) << i << ": d " << d.transpose();
      if (d(i) != 0.0) shortfall(i) = 1.0 - bias(i) / d(i);
    }
  }
  EXPECT_NEAR(shortfall.x(), 0.012, 0.0005);
  EXPECT_NEAR(shortfall.y(), 0.011, 0.0005);
  EXPECT_NEAR(shortfall.z(), 0.061, 0.0005);
}

// At heading 0 with a diagonal M, M_e K4 = diag(M) K4: the mass-scaled gains are the
// force-level gains diag(M) K4, diag(M) K3 taken literally, to rounding.
TEST(PassiveObserverGainsTest, MassScaledEqualLiteralForceGainsAtHeadingZero) {
  ObserverOptions literal;
  literal.mass_scaled_gains = false;
  literal.velocity_gain = kSeedMass.cwiseProduct(literal.velocity_gain);
  literal.bias_gain = kSeedMass.cwiseProduct(literal.bias_gain);
  const auto load = [](const Vec3& eta) { return Vec3(-8e4 * eta.x(), -8e4 * eta.y(), 0.0); };
  const PassiveNonlinearObserver scaled({}, SeedMass(), SeedDamping(), load);
  const PassiveNonlinearObserver literal_force(literal, SeedMass(), SeedDamping(), load);
  ObserverStateVector x;
  x << 0.1, -0.2, 0.01, 0.3, 0.1, -0.02, 1.0, -2.0, 0.0, 3e5, -1e5, 2e7, 0.05, -0.02, 1e-4;
  const Vec3 y(1.4, -1.7, 0.03), tau(1e5, 2e5, -3e7);
  const ObserverStateVector a = scaled.Derivative(x, y, kEveryChannelValid, tau);
  const ObserverStateVector b = literal_force.Derivative(x, y, kEveryChannelValid, tau);
  for (int j = 0; j < ObserverStateVector::RowsAtCompileTime; ++j) {
    EXPECT_NEAR(a(j), b(j), 1e-12 * (std::abs(a(j)) + 1e-9)) << j;
  }
}

ObserverOptions WithHold(ObserverOptions::Hold hold, ObserverOptions::Start start) {
  ObserverOptions options;
  options.hold = hold;
  options.start = start;
  return options;
}

// On a measurement that does not change the holds are the same input, and with every
// channel valid from the first sample both starts take the same state: the detection
// observers' mode and the controller's then run the same dynamics, bit for bit, here from
// rest under a thrust and a mooring that move the estimate.
TEST(PassiveObserverHoldTest, ModesAgreeOnAHeldInputBitForBit) {
  const auto load = [](const Vec3& eta) {
    return Vec3(-8e4 * eta.x(), -8e4 * eta.y(), -5e8 * WrapAngle(eta.z()));
  };
  PassiveNonlinearObserver detection(
      WithHold(ObserverOptions::Hold::kZeroOrder, ObserverOptions::Start::kAllChannels), SeedMass(),
      SeedDamping(), load);
  PassiveNonlinearObserver controller(
      WithHold(ObserverOptions::Hold::kFirstOrder, ObserverOptions::Start::kEachChannel),
      SeedMass(), SeedDamping(), load);
  const Vec3 tau(2e5, -1e5, 3e7), y(1.5, -0.5, 0.02);
  for (int k = 0; k < 400; ++k) {
    detection.Update(1.0, tau, y, kEveryChannelValid);
    controller.Update(1.0, tau, y, kEveryChannelValid);
    ASSERT_EQ(detection.state(), controller.state()) << "t " << k;
  }
  EXPECT_GT(detection.state().segment<3>(PassiveNonlinearObserver::kBias).norm(), 1e4);
}

// A measurement that is a ramp between samples is what the first-order hold feeds the
// observer exactly, so at 1 Hz it follows the observer fed at 10 Hz to rounding (the
// substeps are the same); the zero-order hold feeds a staircase that is half a sample
// behind on average and a whole sample just before each new sample, so at the samples its
// pose estimate lags by between half a sample and a sample of the ramp (5-10 cm in x).
TEST(PassiveObserverHoldTest, FirstOrderHoldFollowsARampThatTheZeroOrderHoldLags) {
  const Vec3 v(0.1, -0.05, 0.002);  // [m/s, m/s, rad/s]
  const auto run = [&](ObserverOptions::Hold hold, double dt) {
    ObserverOptions options;
    options.hold = hold;
    options.max_substep = 0.1;
    PassiveNonlinearObserver observer(options, SeedMass(), SeedDamping(), NoMooring());
    const int samples = static_cast<int>(std::lround(600.0 / dt));
    for (int k = 0; k <= samples; ++k)
      observer.Update(dt, Vec3::Zero(), v * (k * dt), kEveryChannelValid);
    return Vec3(observer.state().segment<3>(PassiveNonlinearObserver::kPose));
  };
  const Vec3 reference = run(ObserverOptions::Hold::kFirstOrder, 0.1);
  const Vec3 first_error = run(ObserverOptions::Hold::kFirstOrder, 1.0) - reference;
  const Vec3 zero_error = run(ObserverOptions::Hold::kZeroOrder, 1.0) - reference;
  const Vec3 lag = -zero_error.cwiseQuotient(v);  // [s]
  std::printf("ramp: first-order hold off by %.2e m, zero-order hold by %.2e m in x (%.3f s)\n",
              first_error.x(), zero_error.x(), lag.x());
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(first_error(i)), 1e-9 * std::abs(zero_error(i))) << i;
    EXPECT_GT(lag(i), 0.5) << i;
    EXPECT_LT(lag(i), 1.0) << i;
  }
}

// Start::kAllChannels waits for a complete sample; Start::kEachChannel keeps the guess on a
// channel until its first valid sample and then takes the sample.
TEST(PassiveObserverStartTest, AllChannelsOrEachChannel) {
  PassiveNonlinearObserver all({}, SeedMass(), SeedDamping(), NoMooring());
  all.Update(1.0, Vec3::Zero(), Vec3(1.0, 2.0, 0.0), {true, false, true});
  EXPECT_FALSE(all.started());
  EXPECT_EQ(all.state(), ObserverStateVector::Zero());
  all.Update(1.0, Vec3::Zero(), Vec3(1.0, 2.0, 0.5 + kTwoPi), kEveryChannelValid);
  EXPECT_TRUE(all.started());
  EXPECT_EQ(all.state().segment<3>(PassiveNonlinearObserver::kPose).head<2>(),
            Eigen::Vector2d(1.0, 2.0));
  EXPECT_NEAR(all.state()(PassiveNonlinearObserver::kPose + 2), 0.5, 1e-12);  // wrapped

  PassiveNonlinearObserver each(
      WithHold(ObserverOptions::Hold::kFirstOrder, ObserverOptions::Start::kEachChannel),
      SeedMass(), SeedDamping(), NoMooring());
  each.Reset(Vec3(5.0, 6.0, 0.5));
  each.Update(1.0, Vec3::Zero(), Vec3(1.0, std::nan(""), 0.2), {true, false, true});
  EXPECT_TRUE(each.started());
  EXPECT_EQ(each.state().segment<3>(PassiveNonlinearObserver::kPose), Vec3(1.0, 6.0, 0.2));
  EXPECT_FALSE(each.valid()[1]);
  for (int k = 0; k < 5; ++k) {
    each.Update(1.0, Vec3::Zero(), Vec3(1.0, std::nan(""), 0.2), {true, false, true});
  }
  EXPECT_NEAR(each.state()(PassiveNonlinearObserver::kPose + 1), 6.0, 1e-9);  // open loop, at rest
  each.Update(1.0, Vec3::Zero(), Vec3(1.0, 7.0, 0.2), kEveryChannelValid);
  EXPECT_EQ(each.state()(PassiveNonlinearObserver::kPose + 1), 7.0);
  EXPECT_TRUE(each.state().allFinite());
}

}  // namespace
}  // namespace moorsim
