// Detector plugins end to end (detectors/plugin/moorsim_detector_plugin.h): a plugin named
// in a scenario's `detectors:` runs in `moorsim run` beside a built-in detector and its
// verdicts land in run.h5 and summary.json; a plugin that cannot be used is one located line
// and exit 2; a plugin that breaks the contract fails its runs in a campaign, which goes on.
#include <gtest/gtest.h>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kPluginScenario =
    MOORSIM_SOURCE_DIR "/scenarios/library/thesis_no_failure_current.yaml";

std::vector<double> ReadDetectorTable(hid_t file, const char* path, std::size_t& columns) {
  const hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  if (d < 0) return {};
  const hid_t space = H5Dget_space(d);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  columns = dims.size() > 1 ? dims[1] : 1;
  std::vector<double> values(dims[0] * columns);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(d);
  return values;
}

TEST(PluginCommand, APluginRunsBesideTheBuiltInDetectors) {
  // The bank CUSUM in plain C with a low threshold, so that it alarms on the intact run's
  // likelihood ratios: every row of its table must follow its rule (score[0] = 0, the sums
  // >= 0, alarm exactly when the largest sum exceeds 3, then naming that line).
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "plugin").string();
  const CliResult r =
      RunCli({"run", kPluginScenario, "--out", out, "--duration", "120", "--quiet", "--set",
              std::string("detectors=[{type: dht}, {plugin: ") + MOORSIM_TEST_CUSUM_PLUGIN +
                  ", type: bank_cusum, label: cusum, threshold: 3}]"},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::size_t columns = 0, one = 0;
  const std::vector<double> score = ReadDetectorTable(file, "/detectors/cusum/score", columns);
  const std::vector<double> alarm = ReadDetectorTable(file, "/detectors/cusum/alarm", one);
  const std::vector<double> decision = ReadDetectorTable(file, "/detectors/cusum/decision", one);
  std::size_t dht_columns = 0;
  EXPECT_FALSE(ReadDetectorTable(file, "/detectors/dht/score", dht_columns).empty());
  H5Fclose(file);
  ASSERT_EQ(columns, 9u);
  const std::size_t rows = alarm.size();
  ASSERT_EQ(score.size(), rows * columns);
  int alarms = 0;
  for (std::size_t k = 0; k < rows; ++k) {
    const double* s = &score[k * columns];
    EXPECT_EQ(s[0], 0.0);
    const double* best = std::max_element(s + 1, s + columns);
    EXPECT_TRUE(std::all_of(s, s + columns, [](double v) { return std::isfinite(v) && v >= 0; }));
    EXPECT_EQ(alarm[k] != 0.0, *best > 3.0) << "row " << k;
    if (alarm[k] != 0.0) {
      EXPECT_EQ(decision[k], static_cast<double>(best - s)) << "row " << k;
      ++alarms;
    }
  }
  EXPECT_GT(alarms, 0) << "the low threshold should alarm on the intact run";
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  EXPECT_EQ(summary["detectors"]["cusum"]["type"], "bank_cusum");
  EXPECT_FALSE(summary["detectors"]["cusum"]["history"].empty());
}

TEST(PluginCommand, APluginThatCannotBeUsedIsOneLocatedLine) {
  TempDirectory dir(::testing::TempDir());
  const std::string plugin = MOORSIM_TEST_CUSUM_PLUGIN;
  const struct {
    std::string entry;
    std::string expected;
  } cases[] = {
      {"{plugin: /nonexistent/libnone.so, type: bank_cusum}",
       "detectors[1].plugin: plugin /nonexistent/libnone.so: cannot load"},
      {"{plugin: " + plugin + ", type: bank_cusum, gain: 3}",
       "detectors[1]: unknown parameter 'gain' for bank_cusum (known: drift, threshold)"},
      {"{plugin: " + plugin + ", type: cusum}",
       "detectors[1].type: plugin " + plugin + " has no detector 'cusum' (it has: bank_cusum)"},
      {std::string("{plugin: ") + MOORSIM_TEST_OLD_ABI_PLUGIN + ", type: nan_score}",
       "built for detector plugin ABI version 0"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.entry);
    const CliResult r =
        RunCli({"run", kPluginScenario, "--out", (dir.path() / "bad").string(), "--duration", "5",
                "--quiet", "--set", "detectors=[" + c.entry + "]"},
               dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST(PluginCommand, APluginThatBreaksTheContractFailsItsRunsAndTheCampaignGoesOn) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path campaign = dir.path() / "faulty.yaml";
  std::ofstream(campaign) << "scenario: " << kPluginScenario
                          << "\nseed: 3\nset:\n  simulation.duration: 5\n  detectors: [{type: "
                             "dht}, {plugin: "
                          << MOORSIM_TEST_FAULTY_PLUGIN
                          << ", type: nan_score}]\nblocks:\n  - name: intact\n    seeds: 2\n";
  const std::string out = (dir.path() / "out").string();
  const CliResult r =
      RunCli({"batch", campaign.string(), "--out", out, "--quiet", "--threads", "2"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  int failed = 0;
  for (const auto& row : std::filesystem::directory_iterator(std::filesystem::path(out) / "rows")) {
    const nlohmann::json j = nlohmann::json::parse(ReadWholeFile(row.path()));
    EXPECT_NE(j["status"], "ok");
    const std::string error = j["error"].get<std::string>();
    EXPECT_NE(
        error.find(std::string("plugin ") + MOORSIM_TEST_FAULTY_PLUGIN + " detector 'nan_score'"),
        std::string::npos)
        << error;
    ++failed;
  }
  EXPECT_EQ(failed, 2);
}

// The SHA-256 of `path` as coreutils' sha256sum computes it.
std::string Sha256Sum(const std::string& path, const std::filesystem::path& scratch) {
  const CliResult r = RunProgram("/usr/bin/sha256sum", {path}, scratch);
  return r.out.substr(0, r.out.find(' '));
}

TEST(PluginCommand, WithPluginOnTheCommandLineItsTypesAreNamedAloneListedAndRecorded) {
  TempDirectory dir(::testing::TempDir());
  const std::string plugin = MOORSIM_TEST_CUSUM_PLUGIN;
  const std::string sha256 = Sha256Sum(plugin, dir.path());
  ASSERT_EQ(sha256.size(), 64u);
  // The run's help lists the plugin's types with their parameter tables.
  CliResult r = RunCli({"run", "--plugin", plugin, "--help"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NE(r.out.find("From plugin " + plugin + ":\n  bank_cusum: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("    threshold                default 10 nats; > 0;"), std::string::npos);
  // `type:` alone names it; summary.json records the library and its checksum.
  const std::string out = (dir.path() / "run").string();
  r = RunCli({"run", kPluginScenario, "--plugin", plugin, "--out", out, "--duration", "20",
              "--quiet", "--set", "detectors=[{type: bank_cusum, label: cusum}]"},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  EXPECT_EQ(summary["detectors"]["cusum"]["type"], "bank_cusum");
  EXPECT_EQ(summary["plugins"], nlohmann::json::parse(R"([{"path": ")" + plugin +
                                                      R"(", "sha256": ")" + sha256 + R"("}])"));
  // A library that cannot be loaded: one line, exit 2, before anything else.
  r = RunCli({"validate", "--plugin", "/nonexistent/libnone.so", kPluginScenario}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err.rfind("moorsim: --plugin: plugin /nonexistent/libnone.so: cannot load", 0), 0u)
      << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  // A campaign: every row's command carries --plugin, campaign.json the library's identity.
  const std::filesystem::path campaign = dir.path() / "cusum.yaml";
  std::ofstream(campaign) << "scenario: " << kPluginScenario
                          << "\nseed: 3\nset:\n  simulation.duration: 5\n  detectors: [{type: "
                             "bank_cusum}]\nblocks:\n  - name: intact\n    seeds: 2\n";
  const std::string campaign_out = (dir.path() / "campaign").string();
  r = RunCli({"batch", campaign.string(), "--plugin", plugin, "--out", campaign_out, "--quiet"},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json meta = nlohmann::json::parse(ReadWholeFile(campaign_out + "/campaign.json"));
  EXPECT_EQ(meta["plugins"], summary["plugins"]);
  int rows = 0;
  for (const auto& row :
       std::filesystem::directory_iterator(std::filesystem::path(campaign_out) / "rows")) {
    const std::string command = nlohmann::json::parse(ReadWholeFile(row.path()))["command"];
    EXPECT_NE(command.find(" --plugin " + plugin), std::string::npos) << command;
    ++rows;
  }
  EXPECT_EQ(rows, 2);
  r = RunCli({"batch", campaign.string(), "--out", (dir.path() / "none").string(), "--quiet"},
             dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(
      r.err.find("unknown detector 'bank_cusum' (known: cells, deficit, dht, fused, glr, mle)"),
      std::string::npos)
      << r.err;
}

TEST(PluginCommand, ACampaignResumesOnlyWithTheSamePluginLibraries) {
  // A plugin library is an input of a campaign (its identity, campaign.json): a resume with
  // another library, one more, or the same file changed is refused, naming the library.
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path plugin = dir.path() / "libcopy.so";
  std::filesystem::copy_file(MOORSIM_TEST_CUSUM_PLUGIN, plugin);
  const std::filesystem::path campaign = dir.path() / "short.yaml";
  std::ofstream(campaign) << "scenario: " << kPluginScenario
                          << "\nseed: 3\nset: {simulation.duration: 1, detectors: []}\n"
                             "blocks:\n  - name: intact\n    seeds: 1\n";
  const std::string out = (dir.path() / "out").string();
  const std::vector<std::string> batch = {"batch", campaign.string(), "--out", out, "--quiet"};
  std::vector<std::string> with_plugin = batch;
  with_plugin.insert(with_plugin.end(), {"--plugin", plugin.string()});
  CliResult r = RunCli(batch, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  r = RunCli(with_plugin, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: --out " + out +
                       ": holds the results of another campaign: this campaign reads the plugin " +
                       plugin.string() + ", which " + out +
                       " was not started with; choose another directory or remove this one\n");
  std::filesystem::remove_all(out);
  r = RunCli(with_plugin, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  std::ofstream(plugin, std::ios::app) << "rebuilt";  // still loads: bytes past the ELF's end
  r = RunCli(with_plugin, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_NE(r.err.find("the plugin " + plugin.string() + " changed since " + out + " was started"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace moorsim::testing
