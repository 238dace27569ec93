// Sample clocks by integer index and the event loop built on them: every instant is
// reached exactly, clocks with no common period all fire, and a loop that cannot advance
// is an error instead of a hang.
#include "core/sample_clock.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/integrator.h"

namespace moorsim {
namespace {

const std::vector<double> kRates = {0.5, 1.0, 2.0, 3.0, 5.0, 7.0, 10.0, 20.0, 1.0 / 3.0};

TEST(SampleClockTest, WalksEveryInstantExactlyOnceInOrder) {
  for (double rate : kRates) {
    SCOPED_TRACE(rate);
    const SampleClock clock(rate);
    double t = 0.0;
    for (std::int64_t k = 1; k <= 2000; ++k) {
      const double next = clock.NextSampleTime(t);
      ASSERT_EQ(next, clock.Instant(k));
      ASSERT_GT(next, t);
      ASSERT_EQ(clock.LastIndex(next), k);
      ASSERT_EQ(clock.Index(next), k);
      t = next;
    }
  }
}

TEST(SampleClockTest, ProductAndQuotientOfTheSameInstantAgree) {
  // The hang of a 10 Hz controller: 3 / 10 < 3 * 0.1 in the last bit. Both name instant 3.
  const SampleClock clock(10.0);
  ASSERT_LT(3.0 / 10.0, 3.0 * (1.0 / 10.0));
  EXPECT_EQ(clock.LastIndex(3.0 / 10.0), 3);
  EXPECT_EQ(clock.LastIndex(3.0 * (1.0 / 10.0)), 3);
  EXPECT_EQ(clock.NextSampleTime(3.0 * (1.0 / 10.0)), clock.Instant(4));
  EXPECT_EQ(clock.LastIndex(-1.0), -1);
  EXPECT_EQ(clock.NextSampleTime(-1.0), 0.0);
}

TEST(SampleClockTest, RejectsRatesThatAreNotPositiveAndFinite) {
  for (double rate : {0.0, -1.0, std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_THROW(SampleClock(rate, "controller.rate_hz"), InputError) << rate;
  }
  try {
    SampleClock(0.0, "controller.rate_hz");
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "controller.rate_hz: 0 must be > 0");
  }
}

// x' = -x: one state, diagonal Jacobian.
class Decay : public OdeSystem {
 public:
  Decay() {
    pattern_.size = 1;
    pattern_.row_start = {0, 1};
    pattern_.column = {0};
  }
  int StateSize() const override { return 1; }
  void Derivatives(double, const double* x, double* xdot) override { xdot[0] = -x[0]; }
  const SparsityPattern& JacobianPattern() const override { return pattern_; }
  void Jacobian(double, const double*, const double*, double* values) override { values[0] = -1.0; }

 private:
  SparsityPattern pattern_;
};

IntegratorOptions Options() {
  IntegratorOptions options;
  options.atol = {1e-10};
  options.rtol = 1e-8;
  return options;
}

TEST(AdvanceThroughEventsTest, ClocksWithNoCommonPeriodEachFireAtEveryInstant) {
  // Sensors 1 Hz, controller 3 Hz, output 7 Hz over 20 s, each clock asked by index.
  Decay system;
  const double x0 = 1.0;
  Integrator integrator(system, 0.0, &x0, Options());
  std::vector<SampleClock> clocks = {SampleClock(1.0), SampleClock(3.0), SampleClock(7.0)};
  std::vector<std::int64_t> next(clocks.size(), 0);
  std::vector<std::vector<double>> fired(clocks.size());
  AdvanceThroughEvents(
      20.0, [&]() -> Integrator& { return integrator; },
      [&](double) {
        double t = std::numeric_limits<double>::infinity();
        for (std::size_t c = 0; c < clocks.size(); ++c) t = std::min(t, clocks[c].Instant(next[c]));
        return t;
      },
      [&](double now) {
        for (std::size_t c = 0; c < clocks.size(); ++c) {
          if (const std::int64_t k = clocks[c].LastIndex(now); k >= next[c]) {
            fired[c].push_back(now);
            next[c] = k + 1;
          }
        }
      });
  EXPECT_EQ(integrator.time(), 20.0);
  EXPECT_NEAR(integrator.state()[0], std::exp(-20.0), 1e-6 * std::exp(-20.0) + 1e-9);
  for (std::size_t c = 0; c < clocks.size(); ++c) {
    const auto expected = static_cast<std::size_t>(20.0 * clocks[c].rate()) + 1;
    ASSERT_EQ(fired[c].size(), expected) << "clock " << clocks[c].rate() << " Hz";
    for (std::size_t k = 0; k < fired[c].size(); ++k) {
      EXPECT_EQ(fired[c][k], clocks[c].Instant(static_cast<std::int64_t>(k)));
    }
  }
}

TEST(AdvanceThroughEventsTest, AnEventThatDoesNotMoveIsAnErrorNotAHang) {
  Decay system;
  const double x0 = 1.0;
  Integrator integrator(system, 0.0, &x0, Options());
  int passes = 0;
  try {
    AdvanceThroughEvents(
        10.0, [&]() -> Integrator& { return integrator; },
        [&](double now) { return now < 0.5 ? 0.5 : now; },  // stuck at 0.5
        [&](double) { ++passes; });
    FAIL() << "no error";
  } catch (const SolverError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("t = 0.5 s: the event loop made no progress"));
  }
  EXPECT_EQ(passes, 2);  // at the start and at 0.5
}

}  // namespace
}  // namespace moorsim
