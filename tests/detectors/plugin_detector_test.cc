// Detectors from shared libraries through the C ABI (detectors/plugin_detector.h): a CUSUM
// written in plain C against an independent computation, the registry's parameter checks
// applied to a plugin's table, and every way a library or a plugin can break the contract,
// each a clear error naming the plugin.
#include "detectors/plugin_detector.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"

namespace moorsim::detectors {
namespace {

// Evidence for `n` hypotheses whose log-likelihoods are `ll`.
Evidence PluginEvidence(double t, const std::vector<double>& ll) {
  Evidence evidence;
  evidence.t = t;
  evidence.hypotheses.resize(ll.size());
  for (std::size_t h = 0; h < ll.size(); ++h) evidence.hypotheses[h].log_likelihood = ll[h];
  return evidence;
}

DetectorSpec PluginSpec(const std::string& type, std::map<std::string, double> parameters = {}) {
  return DetectorSpec{type, type, std::move(parameters), ""};
}

// The message of the InputError that `make` throws ("" if none).
template <typename F>
std::string PluginInputError(F make) {
  try {
    make();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(PluginDetector, ACusumWrittenInCMatchesItsDefinition) {
  // Three hypotheses; line 1 is less likely than intact by 1 nat a sample, line 2 more
  // likely by 0.5 minus a drift of 0.1: S_2 = 0.4 t crosses 5 at the 13th sample.
  const auto detector = MakePluginDetector(
      MOORSIM_TEST_CUSUM_PLUGIN, PluginSpec("bank_cusum", {{"drift", 0.1}, {"threshold", 5}}),
      "detectors[0]");
  EXPECT_EQ(detector->type(), "bank_cusum");
  EXPECT_FALSE(detector->NeedsLoadEvidence());
  detector->Reset(3);
  double s1 = 0.0, s2 = 0.0;
  for (int t = 1; t <= 20; ++t) {
    const Verdict v = detector->Update(PluginEvidence(t, {-3.0, -4.0, -2.5}));
    s1 = std::max(0.0, s1 - 1.0 - 0.1);
    s2 = std::max(0.0, s2 + 0.5 - 0.1);
    ASSERT_EQ(v.score.size(), 3u);
    EXPECT_DOUBLE_EQ(v.score[1], s1);
    EXPECT_NEAR(v.score[2], s2, 1e-12);
    EXPECT_EQ(v.alarm, s2 > 5.0) << "t = " << t;
    EXPECT_EQ(v.hypothesis, s2 > 5.0 ? 2 : 0);
    EXPECT_EQ(v.alarm, t >= 13);
  }
  // Reset starts over.
  detector->Reset(3);
  EXPECT_FALSE(detector->Update(PluginEvidence(21, {-3.0, -4.0, -2.5})).alarm);
}

TEST(PluginDetector, TheDefaultsAndTheRegistrysChecksApplyToAPluginsTable) {
  const auto detector =
      MakePluginDetector(MOORSIM_TEST_CUSUM_PLUGIN, PluginSpec("bank_cusum"), "d");
  detector->Reset(2);
  int first = 0;  // default threshold 10, drift 0: 1 nat a sample alarms at the 11th
  for (int t = 1; t <= 12 && first == 0; ++t) {
    if (detector->Update(PluginEvidence(t, {0.0, 1.0})).alarm) first = t;
  }
  EXPECT_EQ(first, 11);
  EXPECT_EQ(PluginInputError([] {
              MakePluginDetector(MOORSIM_TEST_CUSUM_PLUGIN, PluginSpec("bank_cusum", {{"gain", 1}}),
                                 "detectors[2]");
            }),
            "detectors[2]: unknown parameter 'gain' for bank_cusum (known: drift, threshold)");
  EXPECT_EQ(PluginInputError([] {
              MakePluginDetector(MOORSIM_TEST_CUSUM_PLUGIN,
                                 PluginSpec("bank_cusum", {{"threshold", 0}}), "detectors[2]");
            }),
            "detectors[2].threshold: 0 must be > 0");
  EXPECT_EQ(PluginInputError([] {
              MakePluginDetector(MOORSIM_TEST_FAULTY_PLUGIN, PluginSpec("needs_gain"),
                                 "detectors[1]");
            }),
            "detectors[1]: needs_gain needs parameter 'gain' (no default)");
}

TEST(PluginDetector, ALibraryThatIsNoPluginOrAnotherVersionIsRefusedByName) {
  const std::string missing = PluginInputError(
      [] { MakePluginDetector("/nonexistent/libnothing.so", PluginSpec("x"), "detectors[0]"); });
  EXPECT_NE(missing.find("detectors[0].plugin: plugin /nonexistent/libnothing.so: cannot load"),
            std::string::npos)
      << missing;
  const std::string no_entry = PluginInputError(
      [] { MakePluginDetector(MOORSIM_TEST_NO_ENTRY_PLUGIN, PluginSpec("x"), "detectors[0]"); });
  EXPECT_NE(no_entry.find("no entry point moorsim_plugin_abi_version"), std::string::npos)
      << no_entry;
  const std::string old_abi = PluginInputError([] {
    MakePluginDetector(MOORSIM_TEST_OLD_ABI_PLUGIN, PluginSpec("nan_score"), "detectors[0]");
  });
  EXPECT_NE(old_abi.find("built for detector plugin ABI version 0, this moorsim loads version " +
                         std::to_string(MOORSIM_DETECTOR_ABI_VERSION)),
            std::string::npos)
      << old_abi;
  EXPECT_EQ(PluginInputError([] {
              MakePluginDetector(MOORSIM_TEST_FAULTY_PLUGIN, PluginSpec("cusum"), "detectors[3]");
            }),
            std::string("detectors[3].type: plugin ") + MOORSIM_TEST_FAULTY_PLUGIN +
                " has no detector 'cusum' (it has: nan_score, wrong_hypothesis, refuses, "
                "needs_gain, lines_map)");
  EXPECT_EQ(PluginInputError([] {
              MakePluginDetector(MOORSIM_TEST_FAULTY_PLUGIN, PluginSpec("refuses"), "detectors[0]");
            }),
            std::string("detectors[0]: plugin ") + MOORSIM_TEST_FAULTY_PLUGIN +
                " detector 'refuses' refused its parameters: this detector accepts no "
                "configuration");
}

TEST(PluginDetector, AVerdictThatBreaksTheContractNamesThePlugin) {
  for (const std::string type : {"nan_score", "wrong_hypothesis"}) {
    SCOPED_TRACE(type);
    const auto detector = MakePluginDetector(MOORSIM_TEST_FAULTY_PLUGIN, PluginSpec(type), "d");
    detector->Reset(3);
    try {
      detector->Update(PluginEvidence(7.0, {0.0, 0.0, 0.0}));
      FAIL() << "no ContractError";
    } catch (const ContractError& error) {
      const std::string message = error.what();
      EXPECT_NE(message.find(std::string("plugin ") + MOORSIM_TEST_FAULTY_PLUGIN + " detector '" +
                             type + "'"),
                std::string::npos)
          << message;
      EXPECT_NE(message.find(type == "nan_score" ? "score of hypothesis 2 is nan at t = 7 s"
                                                 : "verdict hypothesis 3 (of 3), alarm 1"),
                std::string::npos)
          << message;
    }
  }
}

TEST(PluginDetector, ResetTellsWhichLinesEachHypothesisFails) {
  const auto detector =
      MakePluginDetector(MOORSIM_TEST_FAULTY_PLUGIN, PluginSpec("lines_map"), "d");
  // Without a map: moorsim's numbering without pairs, hypothesis h = line h.
  detector->Reset(4);
  EXPECT_EQ(detector->Update(PluginEvidence(0.0, {0, 0, 0, 0})).score,
            (std::vector<double>{0, 100, 200, 300}));
  // With the bank's map, pairs included (the lines 100 a + b as the plugin reads them).
  SetPluginHypotheses(*detector, {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {1, 2}, {1, 3}, {2, 3}});
  detector->Reset(7);
  EXPECT_EQ(detector->Update(PluginEvidence(1.0, {0, 0, 0, 0, 0, 0, 0})).score,
            (std::vector<double>{0, 100, 200, 300, 102, 103, 203}));
  // A map for another number of hypotheses is moorsim's own mistake, never the plugin's.
  EXPECT_THROW(detector->Reset(5), ContractError);
}

}  // namespace
}  // namespace moorsim::detectors
