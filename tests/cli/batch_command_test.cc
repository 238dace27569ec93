// `moorsim batch` end to end: the dry run's listing, bad flags as one line with exit 2, a
// small campaign's table and the report built on it (tools/report.py, checked against the
// table by tests/tools/report_test.py), a SIGTERM that stops the batch with exit 143.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kScenario =
    MOORSIM_SOURCE_DIR "/scenarios/library/thesis_no_failure_current.yaml";

std::string WriteCampaign(const std::filesystem::path& dir, double duration) {
  const std::filesystem::path path = dir / "small.yaml";
  std::ofstream(path) << "scenario: " << kScenario
                      << "\nseed: 5\nset: {simulation.duration: " << duration
                      << "}\nblocks:\n"
                         "  - name: failures\n"
                         "    set: {failure.mode: fairlead, failure.time: 50}\n"
                         "    factors: [{key: failure.line, values: [3, 7]}]\n"
                         "    seeds: 1\n"
                         "  - name: intact\n"
                         "    seeds: 2\n";
  return path.string();
}

TEST(BatchCommand, DryRunListsEveryRunAndTheEstimate) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteCampaign(dir.path(), 100);
  const CliResult r = RunCli({"batch", campaign, "--dry-run", "--threads", "2"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NE(r.out.find("4 runs of " + kScenario), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("block failures: 2 points x 1 seeds = 2 runs"), std::string::npos);
  EXPECT_NE(r.out.find("\n1\tfailures\t"), std::string::npos) << r.out;  // run 1's row
  EXPECT_NE(r.out.find("line 7 at 50 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("estimated wall time"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out"));  // nothing written
}

TEST(BatchCommand, BadFlagsExitWithCode2AndOneLine) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteCampaign(dir.path(), 100);
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"batch", campaign, "--shard", "3"},
       "moorsim: --shard 3: expected K/N (e.g. 3/10: the third of ten shards)\n"},
      {{"batch", campaign, "--shard", "0/2"},
       "moorsim: --shard: '0' must be a whole number in 1..2\n"},
      {{"batch", campaign, "--threads", "0"},
       "moorsim: --threads: '0' must be a whole number in 1..4096\n"},
      {{"batch", campaign, "--run-timeout", "-1"},
       "moorsim: --run-timeout -1: must be in (0, 1e7] seconds\n"},
      {{"batch"}, "moorsim: batch: give a campaign file (or --merge DIR...)\n"},
      {{"batch", "--merge", "a", "b"}, "moorsim: --merge needs --out DIR for the joined results\n"},
      {{"batch", (dir.path() / "none.yaml").string()},
       "moorsim: " + (dir.path() / "none.yaml").string() +
           ": cannot open the campaign file: No such file or directory\n"},
  };
  for (const auto& c : cases) {
    const CliResult r = RunCli(c.args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.err, c.message);
  }
}

TEST(BatchCommand, MergeOfADirectoryWithoutItsCampaignRecordIsOneLineAndExit2) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path shard = dir.path() / "shard";
  const std::string merged = (dir.path() / "merged").string();
  std::filesystem::create_directories(shard / "rows");
  std::ofstream(shard / "campaign.yaml") << "seed: 1\n";
  const struct {
    std::string json;  // campaign.json's text; empty: no file
    std::string message;
  } cases[] = {
      {"", ": no campaign.json (not a results directory of moorsim batch)\n"},
      {"{\"name\": ", ": campaign.json is damaged (not the JSON moorsim batch writes)\n"},
      {"[]", ": campaign.json is damaged (not the JSON moorsim batch writes)\n"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.json);
    if (!c.json.empty()) std::ofstream(shard / "campaign.json") << c.json;
    const CliResult r = RunCli({"batch", "--merge", shard.string(), "--out", merged}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.err, "moorsim: --merge " + shard.string() + c.message);
  }
  EXPECT_FALSE(std::filesystem::exists(merged));
}

// Merging some of a campaign's shards is a merge, said to be incomplete with the runs that
// have no row; the campaign run into the merged directory then finishes it.
TEST(BatchCommand, AMergeOfSomeShardsSaysWhichRunsAreMissing) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteCampaign(dir.path(), 60);
  const std::string shard = (dir.path() / "shard1").string();
  const CliResult first =
      RunCli({"batch", campaign, "--shard", "1/2", "--out", shard, "--quiet"}, dir.path());
  ASSERT_EQ(first.exit_code, 0) << first.Describe();
  const std::string merged = (dir.path() / "merged").string();
  const CliResult r = RunCli({"batch", "--merge", shard, "--out", merged}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.err, "moorsim batch: merged 1 directory -> " + merged +
                       ": 2 of 4 runs\nmoorsim batch: warning: the campaign is incomplete: 2 "
                       "runs have no row (runs 1, 3); merge the other shards, or run the "
                       "campaign with --out " +
                       merged + " to finish it\n");
  const CliResult rest = RunCli({"batch", campaign, "--out", merged, "--quiet"}, dir.path());
  ASSERT_EQ(rest.exit_code, 0) << rest.Describe();
  std::ifstream table(std::filesystem::path(merged) / "runs.csv");
  std::string line;
  int rows = 0;
  while (std::getline(table, line)) rows += !line.empty() && line[0] != '#' ? 1 : 0;
  EXPECT_EQ(rows, 1 + 4);  // the header and every run
}

TEST(BatchCommandAcceptance, WritesTheTableAndTheReportMatchesIt) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteCampaign(dir.path(), 80);
  const std::string out = (dir.path() / "results").string();
  const CliResult r =
      RunCli({"batch", campaign, "--out", out, "--quiet"}, dir.path(), std::chrono::seconds(600));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const std::string csv = ReadWholeFile(std::filesystem::path(out) / "runs.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);  // header + 4 runs
  EXPECT_EQ(csv.rfind("run,block,seed,status,failure.line,failure_line,", 0), 0u) << csv;
  EXPECT_NE(csv.find(",wall_time,thrust_saturated_share,heading_error_max_deg,"), std::string::npos)
      << csv;
  EXPECT_EQ(r.err.find("left their setpoint heading"), std::string::npos) << r.err;
  // The report, checked number by number against campaign.h5.
  const CliResult report =
      RunProgram("/usr/bin/python3", {MOORSIM_SOURCE_DIR "/tests/tools/report_test.py", out},
                 dir.path(), std::chrono::seconds(300));
  EXPECT_EQ(report.exit_code, 0) << report.Describe();
  EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out) / "report.html"));
  // A run repeated alone in its own process (nothing shared with the batch: WAMIT data,
  // bank and GLR signatures built afresh) gives its row's detector results.
  for (const char* name : {"00000001.json", "00000003.json"}) {
    const nlohmann::json row =
        nlohmann::json::parse(ReadWholeFile(std::filesystem::path(out) / "rows" / name));
    std::istringstream words(row.at("command").get<std::string>());
    std::vector<std::string> args;
    for (std::string w; words >> w;) args.push_back(w);
    ASSERT_EQ(args.front(), "moorsim");
    args.erase(args.begin());  // the program itself
    const std::string alone = (dir.path() / "alone").string();
    args.insert(args.end(), {"--out", alone, "--quiet"});
    const CliResult run = RunCli(args, dir.path());
    ASSERT_EQ(run.exit_code, 0) << run.Describe();
    const nlohmann::json summary =
        nlohmann::json::parse(ReadWholeFile(std::filesystem::path(alone) / "summary.json"));
    for (const auto& [label, d] : summary.at("detectors").items()) {
      for (const char* key : {"alarm_time", "isolated_line", "delay", "false_alarms"}) {
        EXPECT_EQ(d.at(key), row.at("detectors").at(label).at(key)) << name << " " << label;
      }
    }
    EXPECT_EQ(summary.at("integrator").at("steps"), row.at("integrator").at("steps"));
    EXPECT_EQ(summary.at("station_keeping"), row.at("station_keeping"));
  }
  // Run again: every run has its row, nothing is done twice.
  const CliResult again = RunCli({"batch", campaign, "--out", out}, dir.path());
  ASSERT_EQ(again.exit_code, 0) << again.Describe();
  EXPECT_NE(again.err.find("0 done now, 4 already done"), std::string::npos) << again.err;
}

TEST(BatchCommand, WarnsWhenARunLostItsHeading) {
  // A hull started 30 deg off its setpoint heading has left it by more than 10 deg: the
  // batch finishes as usual (exit 0) and says so on stderr, even with --quiet.
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path campaign = dir.path() / "turned.yaml";
  std::ofstream(campaign) << "scenario: " << kScenario
                          << "\nseed: 5\nset: {simulation.duration: 5, detectors: []}\n"
                             "blocks:\n"
                             "  - name: turned\n"
                             "    factors: [{key: vessel.initial_pose.heading_deg, values: "
                             "[-135, -105]}]\n"
                             "    seeds: 1\n";
  const std::string out = (dir.path() / "results").string();
  const CliResult r = RunCli({"batch", campaign.string(), "--out", out, "--quiet"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NE(r.err.find("warning: 1 runs left their setpoint heading by more than 10 deg"),
            std::string::npos)
      << r.err;
}

TEST(BatchCommand, SigtermStopsTheBatchWithExit143AndKeepsTheFinishedRows) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteCampaign(dir.path(), 2000);
  const std::filesystem::path out = dir.path() / "results";
  pid_t pid = 0;
  const std::string cli = MOORSIM_CLI;
  std::vector<std::string> args = {cli,          "batch",   campaign,    "--out",
                                   out.string(), "--quiet", "--threads", "1"};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  ASSERT_EQ(posix_spawn(&pid, cli.c_str(), nullptr, nullptr, argv.data(), environ), 0);
  // Wait until the first run is under way (the campaign file is recorded before it).
  for (int i = 0; i < 200 && !std::filesystem::exists(out / "campaign.yaml"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  ::kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 143);
  EXPECT_TRUE(std::filesystem::exists(out / "runs.csv"));  // the table of what finished
}

// A campaign of `seeds` runs of one configuration; with `drawn`, a failure time drawn per
// run (every run a configuration of its own) and runs of 4 simulated seconds.
std::string WriteLargeCampaign(const std::filesystem::path& dir, long seeds, bool drawn) {
  const std::filesystem::path path = dir / "large.yaml";
  std::ofstream(path) << "scenario: " << kScenario << "\nseed: 5\nblocks:\n  - name: many\n"
                      << (drawn ? "    set: {failure.line: 3, failure.mode: fairlead, "
                                  "simulation.duration: 4}\n"
                                  "    factors: [{key: failure.time, uniform: [1, 3]}]\n"
                                : "")
                      << "    seeds: " << seeds << "\n";
  return path.string();
}

// Runs that differ only in their seed share one scenario load: the dry run of 100 000 of
// them lists them in seconds (one load per run took minutes).
TEST(BatchCommand, DryRunOfManySeedsLoadsTheScenarioOnce) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteLargeCampaign(dir.path(), 100'000, false);
  const CliResult r = RunCli({"batch", campaign, "--dry-run"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe().substr(0, 2000);
  EXPECT_NE(r.out.find("100000 runs of " + kScenario), std::string::npos);
  EXPECT_NE(r.out.find("\n99999\tmany\t"), std::string::npos);
}

// The documented maximum (10 million runs, each its own configuration) does not wait for
// a preparation that grows with its runs: the first rows are written while the runs are
// still being dealt, and SIGINT stops it with exit 130, the rows kept for the resume.
TEST(BatchCommand, TheLargestCampaignStartsRunningAtOnceAndStopsOnSigint) {
  TempDirectory dir(::testing::TempDir());
  const std::string campaign = WriteLargeCampaign(dir.path(), 10'000'000, true);
  const std::filesystem::path out = dir.path() / "results";
  const pid_t pid =
      StartCli({"batch", campaign, "--out", out.string(), "--quiet", "--threads", "2"}, {});
  // Generous: two runs of 4 simulated seconds take about a second here.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  const auto has_a_row = [&out] {
    std::error_code error;
    for (std::filesystem::directory_iterator it(out / "rows", error), end; !error && it != end;
         it.increment(error)) {
      if (it->path().extension() == ".json") return true;
    }
    return false;
  };
  while (!has_a_row() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const bool started = has_a_row();
  ::kill(pid, SIGINT);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(started) << "no row written within 120 s";
  ASSERT_TRUE(WIFEXITED(status)) << "signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 130);
  const nlohmann::json record = nlohmann::json::parse(ReadWholeFile(out / "campaign.json"));
  EXPECT_EQ(record.at("runs"), 10'000'000);
  // A kept row is a whole run's, with its drawn failure time.
  for (const auto& entry : std::filesystem::directory_iterator(out / "rows")) {
    if (entry.path().extension() != ".json") continue;
    const nlohmann::json row = nlohmann::json::parse(ReadWholeFile(entry.path()));
    EXPECT_EQ(row.at("status"), "ok") << row.dump();
    const double time = row.at("failure").at("time").get<double>();
    EXPECT_GE(time, 1.0);
    EXPECT_LT(time, 3.0);
  }
}

}  // namespace
}  // namespace moorsim::testing

namespace moorsim::testing {
namespace {

// One detector's results in a campaign's rows (rows/*.json, one per run).
struct CampaignRow {
  std::string block, status;
  int failure_line = 0;
  double simulated_time = 0.0;
  double isolation_delay = 0.0;  // NaN: never named after the break
  int final_line = 0;            // 0: no alarm at the end
  int false_alarms = 0;
  double alarm_seconds_before_failure = 0.0;
};

std::vector<CampaignRow> ReadRows(const std::filesystem::path& out, const std::string& label) {
  std::vector<CampaignRow> rows;
  for (const auto& entry : std::filesystem::directory_iterator(out / "rows")) {
    const nlohmann::json j = nlohmann::json::parse(ReadWholeFile(entry.path()));
    CampaignRow row;
    row.block = j.at("block").get<std::string>();
    row.status = j.at("status").get<std::string>();
    if (j.contains("failure") && j.at("failure").is_object()) {
      row.failure_line = j.at("failure").at("line").get<int>();
    }
    row.simulated_time = j.at("simulated_time").get<double>();
    const nlohmann::json& d = j.at("detectors").at(label);
    const nlohmann::json& delay = d.at("isolation_delay");
    row.isolation_delay = delay.is_null() ? std::nan("") : delay.get<double>();
    row.final_line = d.at("final_line").is_null() ? 0 : d.at("final_line").get<int>();
    row.false_alarms = d.at("false_alarms").get<int>();
    row.alarm_seconds_before_failure = d.at("alarm_seconds_before_failure").get<double>();
    rows.push_back(row);
  }
  return rows;
}

// Wilson (1927) 95 % score interval of k successes in n.
std::pair<double, double> Wilson(int k, int n) {
  const double z = 1.959963984540054, p = static_cast<double>(k) / n, z2 = z * z;
  const double centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
  const double half = z / (1.0 + z2 / n) * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n));
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

// The detection acceptance test: not one seed's run but a small held-out campaign
// (scenarios/campaigns/detection_acceptance.yaml: two sea states, wave and current
// directions and seeds that no detector was tuned on; 32 breaks and 6 intact hours), judged
// by its statistics. The force-deficit detector at its defaults must here: name the failed
// line after the break in at least 75 % of the 32 runs (the Wilson interval is printed), in
// at least 14 of the 16 in the thesis sea; keep naming it to the end of the run in at least
// 95 % of those it named (the verdict persists); name a wrong line at the end of at most 2
// runs; name the thesis-sea breaks within kThesisMedianDelay of them (median); raise at
// most kFalseAlarms false alarms in the 6 intact hours, with an alarm on at most 1 % of
// their time.
// kFalseAlarms comes from the rates measured over 100 intact hours per sea state on the
// long campaign (training/detection_long.yaml): 0.03 per hour in the thesis sea and 0.25 per
// hour at Hs 4 m, 0.84 expected in these 3 + 3 hours; more than 3 has a Poisson probability of 1 %,
// so a detector as good as the measured one fails this test by chance about once in 100
// campaigns, and one whose rate at Hs 4 m is five times the measured one about every second
// time.
// Measured at the defaults (threshold 12, min_fraction 0.7): 32/32 named and kept, thesis-sea
// median 27.8 s, 2 false alarms (both at Hs 4 m, 66-68 s each), alarm on 0.62 %. The
// one-stage test (`confirm: 0`) takes 50-56 s on the held-out and fresh campaigns.
constexpr double kThesisMedianDelay = 40.0;  // [s]
constexpr int kFalseAlarms = 3;

TEST(HeldOutAcceptance, TheDeficitDetectorOnASmallHeldOutCampaign) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "acceptance").string();
  const CliResult r =
      RunCli({"batch", MOORSIM_SOURCE_DIR "/scenarios/campaigns/detection_acceptance.yaml", "--out",
              out, "--quiet"},
             dir.path(), std::chrono::seconds(900));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const std::vector<CampaignRow> rows = ReadRows(std::filesystem::path(out), "deficit");
  int breaks = 0, named = 0, kept = 0, wrong = 0, thesis = 0, thesis_named = 0;
  int false_alarms = 0;
  double intact_seconds = 0.0, alarm_seconds = 0.0;
  std::vector<double> thesis_delays;
  for (const CampaignRow& row : rows) {
    ASSERT_EQ(row.status, "ok") << row.block;
    if (row.failure_line == 0) {
      false_alarms += row.false_alarms;
      intact_seconds += row.simulated_time;
      alarm_seconds += row.alarm_seconds_before_failure;
      continue;
    }
    ++breaks;
    const bool in_thesis_sea = row.block.rfind("thesis", 0) == 0;
    thesis += in_thesis_sea ? 1 : 0;
    if (std::isfinite(row.isolation_delay)) {
      ++named;
      thesis_named += in_thesis_sea ? 1 : 0;
      if (in_thesis_sea) thesis_delays.push_back(row.isolation_delay);
      kept += row.final_line == row.failure_line ? 1 : 0;
    }
    wrong += row.final_line != 0 && row.final_line != row.failure_line ? 1 : 0;
  }
  ASSERT_EQ(breaks, 32);
  ASSERT_EQ(thesis, 16);
  ASSERT_EQ(intact_seconds, 6 * 3600.0);
  const auto [low, high] = Wilson(named, breaks);
  // The median of the 16 thesis-sea delays, a break never named counting as the longest.
  thesis_delays.resize(16, std::numeric_limits<double>::infinity());
  std::sort(thesis_delays.begin(), thesis_delays.end());
  const double thesis_median = 0.5 * (thesis_delays[7] + thesis_delays[8]);
  std::printf(
      "deficit: named after the break %d/%d (95 %% interval %.2f-%.2f), %d/16 in the "
      "thesis sea, median delay there %.1f s; kept %d/%d; wrong at the end %d; %d false "
      "alarms in 6 h, alarm on %.2f %%\n",
      named, breaks, low, high, thesis_named, thesis_median, kept, named, wrong, false_alarms,
      100.0 * alarm_seconds / intact_seconds);
  EXPECT_GE(named, 24);
  EXPECT_GE(thesis_named, 14);
  EXPECT_LE(thesis_median, kThesisMedianDelay);
  EXPECT_GE(kept, 0.95 * named);
  EXPECT_LE(wrong, 2);
  EXPECT_LE(false_alarms, kFalseAlarms);
  EXPECT_LE(alarm_seconds, 0.01 * intact_seconds);
}

}  // namespace
}  // namespace moorsim::testing
