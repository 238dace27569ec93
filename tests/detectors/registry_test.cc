// The detector registry: lookup, parameter checks and their exact messages, --help text.
#include "detectors/registry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "detectors/dht.h"
#include "detectors/glr.h"
#include "detectors/mle.h"

namespace moorsim::detectors {
namespace {

DetectorSpec Spec(const std::string& type, std::map<std::string, double> parameters = {}) {
  DetectorSpec spec;
  spec.type = type;
  spec.label = type;
  spec.parameters = std::move(parameters);
  return spec;
}

std::string MessageOf(const DetectorSpec& spec) {
  try {
    MakeDetector(spec, "detectors[2]");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

TEST(RegistryTest, TypesAreSortedAndEveryOneBuildsWithDefaults) {
  EXPECT_EQ(DetectorTypes(),
            (std::vector<std::string_view>{"cells", "deficit", "dht", "fused", "glr", "mle"}));
  for (const std::string_view type : DetectorTypes()) {
    const std::unique_ptr<Detector> detector = MakeDetector(Spec(std::string(type)), "d");
    ASSERT_NE(detector, nullptr);
    EXPECT_EQ(detector->type(), type);
    detector->Reset(9);
  }
}

TEST(RegistryTest, DefaultsAreTheReferenceSheetValues) {
  // reference/README.md: DHT floor 1e-9, GLR window 50. MLE, GLR threshold and hold: tuned
  // on the coupled thesis plant (detectors/mle.h, detectors/registry.cc).
  const auto dht = MakeDetector(Spec("dht"), "d");
  EXPECT_EQ(dynamic_cast<const Dht&>(*dht).options().floor, 1e-9);
  EXPECT_EQ(dynamic_cast<const Dht&>(*dht).options().threshold, 0.99);
  EXPECT_EQ(dynamic_cast<const Dht&>(*dht).options().hold, 10.0);
  EXPECT_FALSE(dynamic_cast<const Dht&>(*dht).options().prior_intact.has_value());
  const auto mle = MakeDetector(Spec("mle"), "d");
  EXPECT_EQ(dynamic_cast<const Mle&>(*mle).options().forgetting_factor, 0.99);
  EXPECT_EQ(dynamic_cast<const Mle&>(*mle).options().hold, 10.0);
  EXPECT_EQ(dynamic_cast<const Mle&>(*mle).options().margin, 5.0);
  const auto glr = MakeDetector(Spec("glr"), "d");
  EXPECT_EQ(dynamic_cast<const Glr&>(*glr).options().window, 50);
  EXPECT_EQ(dynamic_cast<const Glr&>(*glr).threshold(), 120.0);
  EXPECT_EQ(dynamic_cast<const Glr&>(*glr).options().hold, 15.0);
}

TEST(RegistryTest, GlrThresholdOrFalseAlarmProbabilityNotBoth) {
  EXPECT_EQ(MessageOf(Spec("glr", {{"threshold", 50}, {"false_alarm_probability", 1e-3}})),
            "detectors[2]: give threshold or false_alarm_probability, not both");
}

TEST(RegistryTest, GivenParametersReachTheDetector) {
  const auto dht =
      MakeDetector(Spec("dht", {{"floor", 1e-6}, {"hold", 0.0}, {"prior_intact", 0.5}}), "d");
  EXPECT_EQ(dynamic_cast<const Dht&>(*dht).options().floor, 1e-6);
  EXPECT_EQ(dynamic_cast<const Dht&>(*dht).options().hold, 0.0);
  EXPECT_EQ(dynamic_cast<const Dht&>(*dht).options().prior_intact, 0.5);
  const auto mle = MakeDetector(Spec("mle", {{"forgetting_factor", 1.0}}), "d");
  EXPECT_EQ(dynamic_cast<const Mle&>(*mle).options().forgetting_factor, 1.0);
  // The GLR's default threshold follows the window and the false-alarm probability...
  const auto glr =
      MakeDetector(Spec("glr", {{"window", 20}, {"false_alarm_probability", 1e-3}}), "d");
  EXPECT_DOUBLE_EQ(dynamic_cast<const Glr&>(*glr).threshold(), GlrDefaultThreshold(1e-3, 20));
  // ...unless the threshold is given.
  const auto fixed = MakeDetector(Spec("glr", {{"window", 20}, {"threshold", 25.0}}), "d");
  EXPECT_EQ(dynamic_cast<const Glr&>(*fixed).threshold(), 25.0);
}

TEST(RegistryTest, UnknownTypeNamesTheKnownOnes) {
  EXPECT_EQ(
      MessageOf(Spec("glrx")),
      "detectors[2].type: unknown detector 'glrx' (known: cells, deficit, dht, fused, glr, mle)");
}

TEST(RegistryTest, UnknownParameterNamesTheKnownOnes) {
  EXPECT_EQ(MessageOf(Spec("dht", {{"flor", 1e-9}})),
            "detectors[2]: unknown parameter 'flor' for dht (known: floor, hold, prior_intact, "
            "threshold)");
  EXPECT_EQ(MessageOf(Spec("mle", {{"lambda", 0.99}})),
            "detectors[2]: unknown parameter 'lambda' for mle (known: forgetting_factor, hold, "
            "margin)");
  EXPECT_EQ(MessageOf(Spec("glr", {{"M", 50}})),
            "detectors[2]: unknown parameter 'M' for glr (known: false_alarm_probability, "
            "hold, threshold, window)");
}

TEST(RegistryTest, OutOfRangeValuesGiveTheRule) {
  EXPECT_EQ(MessageOf(Spec("dht", {{"floor", 2}})), "detectors[2].floor: 2 must be in (0, 1)");
  EXPECT_EQ(MessageOf(Spec("dht", {{"floor", 0}})), "detectors[2].floor: 0 must be in (0, 1)");
  EXPECT_EQ(MessageOf(Spec("dht", {{"threshold", 1}})),
            "detectors[2].threshold: 1 must be in (0, 1)");
  EXPECT_EQ(MessageOf(Spec("dht", {{"hold", -1}})), "detectors[2].hold: -1 must be >= 0");
  EXPECT_EQ(MessageOf(Spec("mle", {{"forgetting_factor", 1.5}})),
            "detectors[2].forgetting_factor: 1.5 must be in (0, 1]");
  EXPECT_EQ(MessageOf(Spec("mle", {{"forgetting_factor", 0}})),
            "detectors[2].forgetting_factor: 0 must be in (0, 1]");
  EXPECT_EQ(MessageOf(Spec("mle", {{"margin", -0.5}})), "detectors[2].margin: -0.5 must be >= 0");
  EXPECT_EQ(MessageOf(Spec("glr", {{"window", 1}})),
            "detectors[2].window: 1 must be an integer in [2, 10000]");
  EXPECT_EQ(MessageOf(Spec("glr", {{"window", 20.5}})),
            "detectors[2].window: 20.5 must be an integer in [2, 10000]");
  EXPECT_EQ(MessageOf(Spec("glr", {{"threshold", 0}})), "detectors[2].threshold: 0 must be > 0");
  EXPECT_EQ(MessageOf(Spec("glr", {{"false_alarm_probability", 1}})),
            "detectors[2].false_alarm_probability: 1 must be in (0, 1)");
}

// Each type's ROC statistic reads its score the way its alarm rule does: DHT the largest
// failure posterior, MLE the best failure hypothesis's lead over intact, GLR its g; cells,
// deficit, plugins and unknown names have none. Grids increase. And the scores' units.
TEST(RegistryTest, StatisticsReadEachDetectorsScoreTheWayItsAlarmRuleDoes) {
  const auto value = [](std::string_view type, std::vector<double> score) {
    return StatisticOf(type)->value(score);
  };
  EXPECT_EQ(value("dht", {0.1, 0.7, 0.2}), 0.7);
  EXPECT_EQ(value("mle", {10.0, 4.0, 12.0}), 6.0);
  EXPECT_EQ(value("glr", {42.0, 1.0, 2.0}), 42.0);
  EXPECT_TRUE(std::isnan(value("glr", {})));
  EXPECT_TRUE(std::isnan(value("dht", {1.0})));
  for (std::string_view type : {"cells", "deficit", "nope"}) {
    EXPECT_EQ(StatisticOf(type), nullptr) << type;
    EXPECT_EQ(ScoreUnitsOf(type), "score") << type;
  }
  EXPECT_EQ(ScoreUnitsOf("dht"), "probability");
  EXPECT_EQ(ScoreUnitsOf("mle"), "nats (negative log-likelihood)");
  EXPECT_EQ(ScoreUnitsOf("glr"), "chi-square statistic");
  for (std::string_view type : {"dht", "glr", "mle"}) {
    const DetectorStatistic* statistic = StatisticOf(type);
    ASSERT_NE(statistic, nullptr) << type;
    EXPECT_FALSE(statistic->description.empty()) << type;
    EXPECT_TRUE(std::is_sorted(statistic->thresholds.begin(), statistic->thresholds.end()));
    EXPECT_GT(statistic->thresholds.size(), 10u) << type;
  }
}

TEST(RegistryTest, HelpListsEveryTypeAndParameter) {
  const std::string help = DetectorHelp();
  for (const DetectorType& type : DetectorTable()) {
    EXPECT_NE(help.find("  " + std::string(type.name) + ": "), std::string::npos) << type.name;
    for (const DetectorParameter& p : type.parameters) {
      EXPECT_NE(help.find("    " + std::string(p.name) + " "), std::string::npos) << p.name;
    }
  }
  EXPECT_NE(help.find("floor                    default 1e-09; in (0, 1);"), std::string::npos)
      << help;
  EXPECT_NE(help.find("hold                     default 15 s; >= 0;"), std::string::npos);
}

TEST(RegistryTest, EveryDefaultLiesInItsRange) {
  for (const DetectorType& type : DetectorTable()) {
    for (const DetectorParameter& p : type.parameters) {
      if (p.default_value) {
        EXPECT_TRUE(p.range.Contains(*p.default_value)) << type.name << "." << p.name;
      } else {
        EXPECT_FALSE(p.default_note.empty()) << type.name << "." << p.name;
      }
    }
  }
}

}  // namespace
}  // namespace moorsim::detectors
