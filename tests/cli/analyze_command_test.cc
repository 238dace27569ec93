// `moorsim analyze` end to end: the JSON object on the thesis scenario, the text tables, and
// bad input as one line on stderr with exit code 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/version.h"
#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kThesis = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6_current.yaml";

class AnalyzeCommandTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunCli(args, dir_.path()); }

  TempDirectory dir_{::testing::TempDir()};
};

// Exit code 2, nothing on stdout, one line on stderr that contains every one of `parts`.
void ExpectOneLineInputError(const CliResult& r, const std::vector<std::string>& parts) {
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_TRUE(r.out.empty()) << r.Describe();
  ASSERT_FALSE(r.err.empty()) << r.Describe();
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.Describe();
  EXPECT_EQ(r.err.back(), '\n');
  for (const std::string& part : parts) {
    EXPECT_NE(r.err.find(part), std::string::npos) << "missing '" << part << "'\n" << r.Describe();
  }
}

// The thesis scenario has no detectors section: its bank is still intact plus one
// hypothesis per line (9), the rate matrix 9 x 9 with a zero diagonal and positive entries
// elsewhere, sampled at the sensors' 1 Hz.
TEST_F(AnalyzeCommandTest, JsonOnTheThesisScenario) {
  const CliResult r = Run({"analyze", kThesis, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json out = nlohmann::json::parse(r.out);
  EXPECT_EQ(out["version"], std::string(moorsim::kVersion));
  EXPECT_EQ(out["scenario"], kThesis);
  EXPECT_EQ(out["sample_interval"], 1.0);
  ASSERT_EQ(out["hypotheses"].size(), 9u);
  EXPECT_EQ(out["hypotheses"][0], "intact");
  EXPECT_EQ(out["hypotheses"][6], "line 6");
  const nlohmann::json& rate = out["rate"];
  ASSERT_EQ(rate.size(), 9u);
  for (int i = 0; i < 9; ++i) {
    ASSERT_EQ(rate[i].size(), 9u);
    EXPECT_EQ(rate[i][i].get<double>(), 0.0) << i;
    for (int j = 0; j < 9; ++j) {
      if (j != i) {
        EXPECT_GT(rate[i][j].get<double>(), 0.0) << i << " " << j;
      }
    }
  }
  ASSERT_TRUE(out["hard_pairs"].is_array());
  for (const nlohmann::json& pair : out["hard_pairs"]) {
    ASSERT_EQ(pair["hypotheses"].size(), 2u);
    EXPECT_LT(pair["rate"][0].get<double>(), out["min_rate"].get<double>());
    EXPECT_LT(pair["rate"][1].get<double>(), out["min_rate"].get<double>());
  }
  const nlohmann::json& transient = out["transient"];
  EXPECT_EQ(transient["duration"], 60.0);
  ASSERT_EQ(transient["lines"].size(), 8u);
  for (int k = 1; k <= 8; ++k) {
    const nlohmann::json& line = transient["lines"][k - 1];
    EXPECT_EQ(line["line"], k);
    EXPECT_GT(line["against_intact"].get<double>(), 0.0);
    EXPECT_LT(std::abs(line["against_intact_heading"].get<double>()),
              line["against_intact"].get<double>());
    EXPECT_TRUE(line["rival"].is_string());
  }
  EXPECT_EQ(out["controller"], "pi (closed, linearised)");
}

// The library's turret is free (the heading loop holds the hull); locked, the mooring
// holds the heading too, and every line's break still gives evidence.
using AnalyzeCommandSlow = AnalyzeCommandTest;

TEST_F(AnalyzeCommandSlow, ALockedTurret) {
  const CliResult r = Run({"analyze", kThesis, "--json", "--set", "vessel.turret.bearing=locked"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json out = nlohmann::json::parse(r.out);
  ASSERT_EQ(out["transient"]["lines"].size(), 8u);
  for (const nlohmann::json& line : out["transient"]["lines"]) {
    EXPECT_GT(line["against_intact"].get<double>(), 0.0) << line.dump();
  }
}

TEST_F(AnalyzeCommandTest, TextTablesAndOptions) {
  const CliResult r = Run({"analyze", kThesis, "--min-rate", "0.001", "--window", "30"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NE(r.out.find("D(row || column)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 8"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("first 30 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("below 0.001 nats/sample"), std::string::npos) << r.out;
}

TEST_F(AnalyzeCommandTest, BadInputIsOneLineAndExitCodeTwo) {
  ExpectOneLineInputError(Run({"analyze", kThesis, "--min-rate", "fast"}), {"--min-rate", "fast"});
  ExpectOneLineInputError(Run({"analyze", kThesis, "--window", "-5"}), {"--window", "-5"});
  ExpectOneLineInputError(Run({"analyze", kThesis, "--bogus"}), {"--bogus"});
  ExpectOneLineInputError(Run({"analyze", kThesis, "--set", "sensors.gnss.rate_hz=0"}),
                          {"sensors.gnss.rate_hz"});
  ExpectOneLineInputError(Run({"analyze", "/nonexistent/scenario.yaml"}), {"scenario.yaml"});
  // On its bearing the turret leaves the heading to the controller, which the analysis
  // models only for 'pi', and only at the sensors' rate.
  ExpectOneLineInputError(Run({"analyze", kThesis, "--set", "controller.type=none"}),
                          {"controller.type", "none", "pi"});
  ExpectOneLineInputError(Run({"analyze", kThesis, "--set", "controller.rate_hz=2"}),
                          {"controller.rate_hz", "2", "1 Hz"});
}

// A mooring with free points (a bridle): the detectors' quasi-static model solves the
// apex's balance, and every line is a hypothesis, the bridle's legs too.
TEST_F(AnalyzeCommandTest, AMooringWithFreePointsIsAnalyzed) {
  const auto r = Run({"analyze", MOORSIM_SOURCE_DIR "/scenarios/library/seed_bridled.yaml"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("11 hypotheses"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("line 10"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace moorsim::testing
