// Detection on the coupled plant (its acceptance test): the thesis scenario with waves
// (JONSWAP Hs 2.5 m, Tp 7 s, beam-on), the 0.1 m/s current, the thesis's PI and GNSS/gyro
// noise of variance 0.005 per DOF, each DOF from its own stream, with the library's four
// detectors at their defaults. Everything comes from scenarios/library/
// thesis_line6_current.yaml and thesis_no_failure_current.yaml as shipped, with the failed
// line and the duration overridden, at the files' seed 1.
//
// Required: for every single-line failure (at 400 s, all eight lines) every detector raises
// an alarm within 180 s, names the parted line at its first alarm, and raises none before
// the break; in 3600 s without a failure no detector raises an alarm. Measured at seed 1
// (benchmarks/README.md has the table and the other seeds): DHT 57-93 s, MLE 59-71 s, GLR
// 27-29 s, force deficit 25-32 s after the break; no false alarm.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"

namespace moorsim::simulation {
namespace {

const std::string kLibrary = MOORSIM_SOURCE_DIR "/scenarios/library/";
constexpr double kFailureTime = 400.0;  // the thesis files' failure time
constexpr double kAllowedDelay = 180.0;

/// No alarm before the break; the first alarm after it within kAllowedDelay, naming `line`.
void ExpectEveryDetectorFinds(const Simulation& sim, int line) {
  for (const DetectorRecord& r : sim.detector_records()) {
    SCOPED_TRACE(r.label);
    EXPECT_EQ(r.FalseAlarms(), 0);
    ASSERT_TRUE(r.FirstAlarm().has_value());
    EXPECT_GE(r.FirstAlarm()->time, kFailureTime);
    EXPECT_LE(r.FirstAlarm()->time - kFailureTime, kAllowedDelay);
    EXPECT_EQ(r.FirstAlarm()->hypothesis, line);
  }
}

class SingleLineFailureAcceptance : public ::testing::TestWithParam<int> {};

TEST_P(SingleLineFailureAcceptance, EveryDetectorAlarmsAndNamesTheLineWithin180s) {
  const int line = GetParam();
  const scenarios::Scenario scenario =
      scenarios::LoadScenario(kLibrary + "thesis_line6_current.yaml",
                              {"failure.line=" + std::to_string(line),
                               "simulation.duration=" + std::to_string(kFailureTime + 200.0)});
  ASSERT_EQ(scenario.detectors.size(), 4u);
  ASSERT_EQ(scenario.failure.time, kFailureTime);
  Simulation sim(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  sim.AdvanceTo(scenario.simulation.duration);
  ExpectEveryDetectorFinds(sim, line);
}

INSTANTIATE_TEST_SUITE_P(AllEightLines, SingleLineFailureAcceptance, ::testing::Range(1, 9));

// detection.observer: passive (the TAPM thesis's observers with covariances from training runs of
// their own models) on the thesis's line-6 case: every detector names line 6 within 180 s
// (the DHT, MLE and GLR: the force deficit needs the EKF bank's bias).
// Measured at seed 1: DHT 83 s, MLE 57 s, GLR 52 s. Over all eight lines the MLE and GLR
// isolate every one (37-57 s); the DHT misses lines 3, 4, 7 and names line 1 for line 8
// (benchmarks/README.md), so the EKF bank stays the default.
TEST(CoupledDetectionAcceptance, PassiveObserversFindLineSix) {
  const scenarios::Scenario scenario =
      scenarios::LoadScenario(kLibrary + "thesis_line6_current.yaml",
                              {"detection.observer=passive", "simulation.duration=600",
                               "detectors=[{type: dht}, {type: mle}, {type: glr}]"});
  Simulation sim(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  sim.AdvanceTo(scenario.simulation.duration);
  ExpectEveryDetectorFinds(sim, 6);
}

TEST(CoupledDetectionAcceptance, NoAlarmInAnHourWithoutFailure) {
  const scenarios::Scenario scenario = scenarios::LoadScenario(
      kLibrary + "thesis_no_failure_current.yaml", {"simulation.duration=3600"});
  ASSERT_EQ(scenario.detectors.size(), 4u);
  Simulation sim(scenarios::ToPlantModel(scenario), scenario.simulation.seed);
  sim.AdvanceTo(3600.0);
  for (const DetectorRecord& r : sim.detector_records()) {
    SCOPED_TRACE(r.label);
    EXPECT_EQ(r.FalseAlarms(), 0);
    EXPECT_FALSE(r.FirstAlarm().has_value());
  }
}

}  // namespace
}  // namespace moorsim::simulation
