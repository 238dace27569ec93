// Campaigns as a library call (campaign/batch.h): threads give the rows of one
// thread, a run repeated alone gives its row, a diverging run is a failed row while the
// rest finish, an interrupted campaign resumes to the table of an uninterrupted one,
// shards merge to the whole, a locked or foreign directory is refused, a run past its
// wall-clock limit is a timeout row, each listed value is checked before the first run and
// a drawn one in its own run.
#include "campaign/batch.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "core/error.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::simulation {
namespace {

using runner::RunRequest;
using runner::RunResult;
using runner::RunScenario;
using runner::RunStatus;

// The signal that stopped a batch (0: it was not interrupted).
int Interruption(const BatchResult& r) {
  return r.status == BatchStatus::kInterrupted ? r.signal : 0;
}

namespace fs = std::filesystem;

using moorsim::testing::FreshDirectory;

// Seven short runs of the thesis plant with its four detectors: lines 2 and 6 parting at
// a drawn time, two seeds each; two intact runs; one run with a step limit CVODE cannot
// meet within its step budget (it fails at once with CV_TOO_MUCH_WORK).
std::string CampaignText() {
  return "name: small\n"
         "scenario: " MOORSIM_SOURCE_DIR
         "/scenarios/library/thesis_no_failure_current.yaml\n"
         "seed: 99\n"
         "set: {simulation.duration: 40}\n"
         "blocks:\n"
         "  - name: failures\n"
         "    set: {failure.mode: fairlead}\n"
         "    factors:\n"
         "      - {key: failure.line, values: [2, 6]}\n"
         "      - {key: failure.time, uniform: [15, 25]}\n"
         "    seeds: 2\n"
         "  - name: intact\n"
         "    seeds: {from: 1, to: 2}\n"
         "  - name: diverging\n"
         "    set: {solver.max_step: 1.0e-6, solver.max_steps: 500}\n"
         "    seeds: 1\n";
}

fs::path WriteCampaign(const fs::path& dir, const std::string& text) {
  const fs::path path = dir / "campaign.yaml";
  std::ofstream(path) << text;
  return path;
}

// A row without what differs from run to run of the same computation: wall times.
nlohmann::json Comparable(nlohmann::json row) {
  row.erase("wall_time");
  if (row.contains("integrator")) {
    for (const char* key :
         {"rhs_seconds", "jacobian_seconds", "linear_setup_seconds", "linear_solve_seconds"}) {
      row["integrator"].erase(key);
    }
  }
  return row;
}

std::map<std::int64_t, nlohmann::json> RowsOf(const fs::path& dir) {
  std::map<std::int64_t, nlohmann::json> rows;
  for (const nlohmann::json& row : ReadRows(dir))
    rows[row.at("run").get<std::int64_t>()] = Comparable(row);
  return rows;
}

BatchOptions Options(const fs::path& campaign, const fs::path& out, int threads) {
  BatchOptions o;
  o.campaign_path = campaign.string();
  o.out = out;
  o.threads = threads;
  o.progress = false;
  o.command_line = "test";
  return o;
}

class BatchTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = new fs::path(FreshDirectory("batch_suite"));
    campaign_ = new fs::path(WriteCampaign(*root_, CampaignText()));
  }
  // The reference, built by the tests that compare with it (each test runs in a process of
  // its own under ctest): every run one after another on one thread.
  static const BatchResult& Reference() {
    if (reference_ == nullptr) {
      reference_ = new BatchResult(RunBatch(Options(*campaign_, *root_ / "sequential", 1)));
    }
    return *reference_;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*root_);
    delete root_;
    delete campaign_;
    delete reference_;
  }
  static fs::path* root_;
  static fs::path* campaign_;
  static BatchResult* reference_;
};
fs::path* BatchTest::root_ = nullptr;
fs::path* BatchTest::campaign_ = nullptr;
BatchResult* BatchTest::reference_ = nullptr;

// Whole campaigns of coupled runs: labelled acceptance by the suite name.
using BatchAcceptance = BatchTest;

TEST_F(BatchAcceptance, ADivergingRunIsAFailedRowAndTheRestFinish) {
  const BatchResult& reference = Reference();
  EXPECT_EQ(reference.status, BatchStatus::kRunsFailed) << reference.message;
  EXPECT_EQ(reference.runs, 7);
  EXPECT_EQ(reference.done, 7);
  EXPECT_EQ(reference.failed, 1);
  const auto rows = RowsOf(*root_ / "sequential");
  ASSERT_EQ(rows.size(), 7u);
  for (const auto& [run, row] : rows) {
    SCOPED_TRACE(run);
    if (row.at("block") == "diverging") {
      EXPECT_EQ(row.at("status"), "failed");
      EXPECT_NE(row.at("error").get<std::string>().find("CV_TOO_MUCH_WORK"), std::string::npos);
    } else {
      EXPECT_EQ(row.at("status"), "ok");
      EXPECT_EQ(row.at("simulated_time"), 40.0);
    }
  }
  // The failure runs carry their truth; every detector has a ROC record.
  const nlohmann::json& first = rows.at(0);
  EXPECT_EQ(first.at("failure").at("line"), 2);
  EXPECT_EQ(first.at("lines"), 8);
  for (const char* d : {"dht", "mle", "glr"}) {
    const nlohmann::json& r = first.at("detectors").at(d);
    EXPECT_EQ(r.at("thresholds").size(), r.at("false_crossings").size());
    EXPECT_EQ(r.at("thresholds").size(), r.at("first_crossing").size());
  }
  EXPECT_TRUE(fs::exists(*root_ / "sequential" / "runs.csv"));
  EXPECT_TRUE(fs::exists(*root_ / "sequential" / "campaign.h5"));
}

TEST_F(BatchTest, FourThreadsGiveTheRowsOfOne) {
  const BatchResult threaded = RunBatch(Options(*campaign_, *root_ / "threads", 4));
  EXPECT_EQ(threaded.status, BatchStatus::kRunsFailed) << threaded.message;
  Reference();
  EXPECT_EQ(RowsOf(*root_ / "threads"), RowsOf(*root_ / "sequential"));
}

TEST_F(BatchAcceptance, ARunRepeatedAloneGivesItsRow) {
  Reference();
  const PreparedCampaign p = PrepareCampaign(campaign_->string());
  const auto rows = RowsOf(*root_ / "sequential");
  for (const std::int64_t index : {2, 4}) {  // a failure run and an intact one
    SCOPED_TRACE(index);
    RunRequest request;
    request.scenario_path = p.campaign.scenario_path;
    request.overrides = scenarios::MakeCampaignRun(p.campaign, index).overrides;
    request.out = *root_ / ("alone" + std::to_string(index));
    const RunResult alone = RunScenario(request);
    ASSERT_EQ(alone.status, RunStatus::kOk) << alone.message;
    const nlohmann::json& row = rows.at(index);
    EXPECT_EQ(alone.summary.at("seed"), row.at("seed"));
    for (const auto& [label, d] : alone.summary.at("detectors").items()) {
      for (const char* key : {"alarm_time", "isolated_line", "delay", "false_alarms"}) {
        EXPECT_EQ(d.at(key), row.at("detectors").at(label).at(key)) << label << " " << key;
      }
    }
    EXPECT_EQ(alone.summary.at("integrator").at("steps"), row.at("integrator").at("steps"));
    // The row's command is that run: the same overrides in the same order.
    const std::string command = row.at("command").get<std::string>();
    EXPECT_NE(command.find("--seed " + row.at("seed").dump()), std::string::npos) << command;
  }
}

TEST_F(BatchAcceptance, AnInterruptedCampaignResumesToTheSameTable) {
  const fs::path out = *root_ / "interrupted";
  BatchOptions o = Options(*campaign_, out, 2);
  std::atomic<long> calls{0};
  // SIGINT after 100 output rows: the first two runs (41 rows each) have finished, the
  // next two are under way.
  o.stop_requested = [&calls] { return ++calls > 100 ? SIGINT : 0; };
  const BatchResult first = RunBatch(o);
  EXPECT_EQ(Interruption(first), SIGINT) << first.message;
  const std::size_t kept = RowsOf(out).size();
  EXPECT_GT(kept, 0u);
  EXPECT_LT(kept, 7u);
  EXPECT_TRUE(fs::exists(out / "runs.csv"));  // the table of what finished

  const BatchResult resumed = RunBatch(Options(*campaign_, out, 2));
  EXPECT_EQ(resumed.status, BatchStatus::kRunsFailed) << resumed.message;  // the diverging run
  EXPECT_EQ(resumed.skipped, static_cast<std::int64_t>(kept));
  EXPECT_EQ(resumed.done, 7 - static_cast<std::int64_t>(kept));
  Reference();
  EXPECT_EQ(RowsOf(out), RowsOf(*root_ / "sequential"));
}

TEST_F(BatchAcceptance, ShardsMergeToTheWholeCampaign) {
  std::vector<fs::path> shards;
  for (int k = 0; k < 3; ++k) {
    BatchOptions o = Options(*campaign_, *root_ / ("shard" + std::to_string(k)), 1);
    o.shard_index = k;
    o.shard_count = 3;
    const BatchResult r = RunBatch(o);
    EXPECT_EQ(r.runs, k == 0 ? 3 : 2);
    shards.push_back(o.out);
  }
  MergeCampaigns(shards, *root_ / "merged", "test");
  Reference();
  EXPECT_EQ(RowsOf(*root_ / "merged"), RowsOf(*root_ / "sequential"));
  EXPECT_TRUE(fs::exists(*root_ / "merged" / "campaign.h5"));
  // Shards of another campaign do not merge.
  const fs::path other = FreshDirectory("batch_other");
  const fs::path other_campaign =
      WriteCampaign(other, CampaignText() + "  - name: more\n    seeds: 1\n");
  BatchOptions o = Options(other_campaign, other / "out", 1);
  o.shard_index = 1;
  o.shard_count = 100;  // one run only
  RunBatch(o);
  EXPECT_THROW(MergeCampaigns({shards[0], other / "out"}, other / "merged", "test"), InputError);
  fs::remove_all(other);
}

TEST_F(BatchTest, ALockedOrForeignDirectoryIsRefused) {
  const fs::path out = *root_ / "locked";
  fs::create_directories(out);
  const int fd = ::open((out / "moorsim.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const BatchResult locked = RunBatch(Options(*campaign_, out, 1));
  ::close(fd);
  EXPECT_EQ(locked.status, BatchStatus::kRejected);
  EXPECT_NE(locked.message.find("in use by another moorsim"), std::string::npos) << locked.message;

  const fs::path foreign = FreshDirectory("batch_foreign");
  const fs::path campaign = WriteCampaign(foreign, CampaignText() + "# another text\n");
  const fs::path recorded = *root_ / "recorded";  // a directory of this suite's campaign
  fs::create_directories(recorded);
  fs::copy_file(*campaign_, recorded / "campaign.yaml");
  const BatchResult refused = RunBatch(Options(campaign, recorded, 1));
  EXPECT_EQ(refused.status, BatchStatus::kRejected);
  EXPECT_NE(refused.message.find("holds the results of another campaign"), std::string::npos)
      << refused.message;
  fs::remove_all(foreign);
}

TEST_F(BatchTest, ARunPastItsWallClockLimitIsATimeoutRow) {
  BatchOptions o = Options(*campaign_, *root_ / "timeout", 1);
  o.shard_index = 4;  // runs 4 (intact)
  o.shard_count = 100;
  o.run_timeout = 1e-3;  // passed before the first output row
  const BatchResult r = RunBatch(o);
  EXPECT_EQ(r.status, BatchStatus::kRunsFailed);
  const auto rows = RowsOf(o.out);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows.at(4).at("status"), "timeout");
  EXPECT_LT(rows.at(4).at("simulated_time").get<double>(), 40.0);
}

TEST_F(BatchTest, BadInputNamesTheRun) {
  const fs::path dir = FreshDirectory("batch_bad");
  const fs::path campaign =
      WriteCampaign(dir, "scenario: " MOORSIM_SOURCE_DIR
                         "/scenarios/library/thesis_no_failure.yaml\n"
                         "seed: 1\n"
                         "blocks:\n"
                         "  - name: lines\n"
                         "    factors: [{key: failure.line, values: [8, 9]}]\n"
                         "    set: {failure.time: 100}\n"
                         "    seeds: 1\n");
  const BatchResult r = RunBatch(Options(campaign, dir / "out", 1));
  EXPECT_EQ(r.status, BatchStatus::kRejected);
  EXPECT_EQ(r.message.rfind(campaign.string() + ":4:5: blocks.lines: run 1 (failure.line=9): ", 0),
            0u)
      << r.message;
  EXPECT_NE(r.message.find("failure.line"), std::string::npos) << r.message;
  EXPECT_FALSE(fs::exists(dir / "out" / "rows"));  // nothing ran, nothing written
  fs::remove_all(dir);
}

// Before the first run, each listed value is loaded and checked once, in the first run
// that has it, not every run: a grid of 3 x 4 values with 5 seeds each (60 runs) loads 6,
// and a choice between two modes drawn over 10 runs loads one run per mode.
TEST(CampaignPreparation, ChecksEachListedValueInItsFirstRunNotEveryRun) {
  const fs::path dir = FreshDirectory("batch_preparation");
  const fs::path campaign =
      WriteCampaign(dir, "scenario: " MOORSIM_SOURCE_DIR
                         "/scenarios/library/thesis_no_failure_current.yaml\n"
                         "seed: 3\n"
                         "blocks:\n"
                         "  - name: grid\n"
                         "    set: {failure.mode: fairlead}\n"
                         "    factors:\n"
                         "      - {key: failure.line, values: [1, 2, 3]}\n"
                         "      - {key: failure.time, values: [100, 200, 300, 400]}\n"
                         "      - {key: environment.waves.hs, uniform: [1, 3]}\n"
                         "    seeds: 5\n"
                         "  - name: modes\n"
                         "    set: {failure.line: 4, failure.time: 100}\n"
                         "    factors: [{key: failure.mode, choice: [fairlead, anchor]}]\n"
                         "    seeds: 10\n");
  const PreparedCampaign p = PrepareCampaign(campaign.string());
  // Grid points are numbered with the last listed factor fastest: line value v is point
  // 4 v, time value v point v; each point's first run is 5 x its point.
  const std::vector<std::int64_t> grid = {0, 20, 40, 5, 10, 15};
  ASSERT_EQ(p.checked_runs.size(), grid.size() + 2);
  EXPECT_TRUE(std::equal(grid.begin(), grid.end(), p.checked_runs.begin()));
  std::set<std::string> modes;
  for (std::size_t k = grid.size(); k < p.checked_runs.size(); ++k) {
    const scenarios::CampaignRun run = scenarios::MakeCampaignRun(p.campaign, p.checked_runs[k]);
    EXPECT_EQ(run.block, 1);
    modes.insert(run.factors.at(0).second);
  }
  EXPECT_EQ(modes, (std::set<std::string>{"fairlead", "anchor"}));
  EXPECT_EQ(p.EstimatedDuration(0), p.EstimatedDuration(59));
  fs::remove_all(dir);
}

// A value drawn per run (uniform, normal, follows) is loaded by the thread that runs it: a
// draw the scenario refuses is that run's "rejected" row naming the run, and the others run.
TEST(CampaignPreparation, ADrawnValueTheScenarioRefusesIsThatRunsRejectedRow) {
  const fs::path dir = FreshDirectory("batch_drawn_refused");
  const fs::path campaign =
      WriteCampaign(dir, "scenario: " MOORSIM_SOURCE_DIR
                         "/scenarios/library/thesis_no_failure_current.yaml\n"
                         "seed: 11\n"
                         "set: {simulation.duration: 6, failure.line: 2}\n"
                         "blocks:\n"
                         "  - name: late\n"
                         "    factors: [{key: failure.time, uniform: [2, 10]}]\n"
                         "    seeds: 8\n");
  const BatchResult r = RunBatch(Options(campaign, dir / "out", 2));
  EXPECT_EQ(r.status, BatchStatus::kRunsFailed) << r.message;
  const std::map<std::int64_t, nlohmann::json> rows = RowsOf(dir / "out");
  ASSERT_EQ(rows.size(), 8u);
  int rejected = 0;
  for (const auto& [index, row] : rows) {
    const scenarios::CampaignRun run =
        scenarios::MakeCampaignRun(scenarios::LoadCampaign(campaign.string()), index);
    const double time = std::stod(run.factors.at(0).second);
    if (time < 6.0) {
      EXPECT_EQ(row.at("status"), "ok") << row.dump();
      EXPECT_EQ(row.at("failure").at("time").get<double>(), time);
      continue;
    }
    ++rejected;
    EXPECT_EQ(row.at("status"), "rejected");
    const std::string error = row.at("error").get<std::string>();
    const std::string where =
        campaign.string() + ":5:5: blocks.late: run " + std::to_string(index) + " (failure.time=";
    EXPECT_EQ(error.rfind(where, 0), 0u) << error;
    EXPECT_NE(error.find("failure.time"), std::string::npos) << error;
    EXPECT_TRUE(row.at("failure").is_null());
  }
  EXPECT_GT(rejected, 0);  // with this campaign seed, some of the 8 draws are past 6 s
  EXPECT_LT(rejected, 8);
  fs::remove_all(dir);
}

// ---------------------------------------------------------------------------------------
// A results directory belongs to one campaign: what determines its runs, not its text.

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// `text` with its one `from` replaced by `to`.
std::string Replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Copies of the thesis scenario and its base in `dir` (its WAMIT files where the library
// has them, or in `wamit` when given), and a campaign of two 1-second runs without
// detectors on them.
struct CopiedCampaign {
  fs::path campaign, scenario, base;
};
CopiedCampaign CopyThesisCampaign(const fs::path& dir, const std::string& seed = "3",
                                  const fs::path& wamit = {}) {
  const fs::path library = MOORSIM_SOURCE_DIR "/scenarios/library";
  CopiedCampaign c{dir / "campaign.yaml", dir / "scenario.yaml", dir / "thesis_no_failure.yaml"};
  fs::copy_file(library / "thesis_no_failure_current.yaml", c.scenario);
  const fs::path stem = wamit.empty() ? fs::path(MOORSIM_SOURCE_DIR "/data/fpso_wamit") : wamit;
  WriteText(c.base, Replaced(ReadText(library / "thesis_no_failure.yaml"),
                             "hydrodynamics: ../../data/fpso_wamit/fpso",
                             "hydrodynamics: " + (stem / "fpso").string()));
  WriteText(c.campaign, "scenario: scenario.yaml\nseed: " + seed +
                            "\nset: {simulation.duration: 1, detectors: []}\n"
                            "blocks:\n  - name: intact\n    seeds: 2\n");
  return c;
}

// Two copies of that campaign, in DIR/a and DIR/b.
std::pair<CopiedCampaign, CopiedCampaign> TwoCopies(const fs::path& dir) {
  fs::create_directories(dir / "a");
  fs::create_directories(dir / "b");
  return {CopyThesisCampaign(dir / "a"), CopyThesisCampaign(dir / "b")};
}

// A batch stopped before its first run: it records the campaign in `out` (or refuses the
// directory) and runs nothing.
BatchResult RecordOnly(const fs::path& campaign, const fs::path& out) {
  BatchOptions o = Options(campaign, out, 1);
  // Preparing asks once per run (the campaigns here have two); the next ask, before the
  // first run starts, stops the batch.
  o.stop_requested = [asks = 0]() mutable { return ++asks > 2 ? SIGINT : 0; };
  return RunBatch(o);
}

// A fresh directory `name` with a copy of the campaign, recorded in its out/.
struct RecordedCampaign {
  fs::path dir;
  CopiedCampaign copy;
  fs::path out;
};
RecordedCampaign Recorded(const std::string& name) {
  RecordedCampaign r;
  r.dir = FreshDirectory(name);
  r.copy = CopyThesisCampaign(r.dir);
  r.out = r.dir / "out";
  EXPECT_EQ(Interruption(RecordOnly(r.copy.campaign, r.out)), SIGINT);
  return r;
}

// The one-line refusal of a results directory that holds another campaign.
void ExpectRefused(const BatchResult& r, const fs::path& out, const std::string& what) {
  EXPECT_EQ(r.status, BatchStatus::kRejected) << r.message;
  EXPECT_EQ(r.message.rfind("out " + out.string() + ": holds the results of another campaign: ", 0),
            0u)
      << r.message;
  EXPECT_NE(r.message.find(what), std::string::npos) << r.message;
  EXPECT_EQ(r.message.find('\n'), std::string::npos) << r.message;
}

TEST(CampaignIdentity, AChangedBaseScenarioIsRefusedOnResume) {
  const auto [dir, c, out] = Recorded("identity_base");
  // Unchanged (a comment added to the campaign would change it): the same command resumes.
  EXPECT_EQ(Interruption(RecordOnly(c.campaign, out)), SIGINT);
  // A heavier hull in the base scenario: the campaign's text is the same, its runs are not.
  WriteText(c.base, Replaced(ReadText(c.base), "mass: 1.0041e8", "mass: 1.1e8"));
  ExpectRefused(
      RecordOnly(c.campaign, out), out,
      "the base scenario " + c.base.string() + " changed since " + out.string() + " was started");
  fs::remove_all(dir);
}

TEST(CampaignIdentity, AnotherReleasesDirectoryIsRefused) {
  const auto [dir, c, out] = Recorded("identity_release");
  nlohmann::json record = nlohmann::json::parse(ReadText(out / "campaign.json"));
  nlohmann::json& identity = record.at("identity");
  ASSERT_EQ(identity.at("inputs")[0].at("what"), "moorsim release");
  identity.at("inputs")[0]["path"] = "0.0.1";
  identity.at("inputs")[0]["sha256"] = std::string(64, '0');
  identity["sha256"] = std::string(64, '1');
  WriteText(out / "campaign.json", record.dump());
  ExpectRefused(RecordOnly(c.campaign, out), out,
                out.string() + " was started by moorsim 0.0.1, this is moorsim ");
  // A directory of a moorsim that recorded no identity cannot be told apart: refused too.
  record.erase("identity");
  WriteText(out / "campaign.json", record.dump());
  const BatchResult r = RecordOnly(c.campaign, out);
  EXPECT_EQ(r.status, BatchStatus::kRejected);
  EXPECT_EQ(r.message, "out " + out.string() +
                           ": was started by an earlier moorsim, which did not record its "
                           "campaign's identity; finish it with that moorsim or choose another "
                           "directory");
  fs::remove_all(dir);
}

TEST(CampaignIdentity, TheSameCampaignTextBesideAnotherScenarioIsRefused) {
  const fs::path dir = FreshDirectory("identity_tree");
  const auto [a, b] = TwoCopies(dir);
  const fs::path out = dir / "out";
  ASSERT_EQ(Interruption(RecordOnly(a.campaign, out)), SIGINT);
  // The same files elsewhere are the same campaign.
  EXPECT_EQ(Interruption(RecordOnly(b.campaign, out)), SIGINT);
  WriteText(b.scenario, Replaced(ReadText(b.scenario), "speed: 0.1}", "speed: 0.3}"));
  ExpectRefused(RecordOnly(b.campaign, out), out, "the scenario " + b.scenario.string());
  fs::remove_all(dir);
}

TEST(CampaignIdentity, AChangedHydrodynamicsFileIsRefusedOnResume) {
  const fs::path dir = FreshDirectory("identity_wamit");
  const fs::path wamit = dir / "wamit";
  fs::create_directories(wamit);
  for (const char* extension : {".1", ".hst", ".3", ".4", ".9"}) {
    fs::copy_file(MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso" + std::string(extension),
                  wamit / ("fpso" + std::string(extension)));
  }
  const CopiedCampaign c = CopyThesisCampaign(dir, "3", wamit);
  const fs::path out = dir / "out";
  ASSERT_EQ(Interruption(RecordOnly(c.campaign, out)), SIGINT);
  const fs::path hst = wamit / "fpso.hst";
  WriteText(hst, ReadText(hst) + "     6     6   1.000000E+00\n");
  ExpectRefused(
      RecordOnly(c.campaign, out), out,
      "the hydrodynamics file " + hst.string() + " changed since " + out.string() + " was started");
  fs::remove_all(dir);
}

TEST(CampaignIdentity, ARowThatIsNotOneOfTheCampaignsRunsIsAnError) {
  const auto [dir, c, out] = Recorded("identity_rows");
  const nlohmann::json recorded = nlohmann::json::parse(ReadText(out / "campaign.json"));
  const std::string identity =
      recorded.value("identity", nlohmann::json::object()).value("sha256", "");
  // A row as the batch writes it, of run `run` of the campaign `campaign`.
  const auto row = [](int run, const std::string& campaign) {
    return nlohmann::json{{"run", run},
                          {"block", "intact"},
                          {"seed", 1},
                          {"status", "ok"},
                          {"factors", nlohmann::json::object()},
                          {"failure", nullptr},
                          {"detectors", nlohmann::json::object()},
                          {"error", ""},
                          {"command", ""},
                          {"campaign", campaign}}
        .dump();
  };
  const struct {
    std::string name, text, message;
  } cases[] = {
      {"00000099.json", row(99, identity), "run 99 is not one of the campaign's 2 runs (0..1)"},
      {"00000001.json", "{\"run\": 1, \"sta", "not a row of moorsim batch (damaged:"},
      {"00000001.json", row(0, identity), "holds run 0, not run 1"},
      {"00000001.json", row(1, std::string(64, 'a')), "a row of another campaign"},
      {"notes.json", "{}", "not a row of moorsim batch (rows are files named NNNNNNNN.json)"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.name + ": " + k.text);
    const fs::path file = out / "rows" / k.name;
    WriteText(file, k.text);
    const BatchResult r = RecordOnly(c.campaign, out);
    EXPECT_EQ(r.status, BatchStatus::kRejected) << r.message;
    EXPECT_EQ(r.message.rfind(file.string() + ": ", 0), 0u) << r.message;
    EXPECT_NE(r.message.find(k.message), std::string::npos) << r.message;
    const std::string table = ReadText(out / "runs.csv");
    EXPECT_EQ(table.find("\n99,"), std::string::npos) << table;
    fs::remove(file);
  }
  // A row that a killed batch left half written (under its temporary name) is no row.
  WriteText(out / "rows" / "00000001.json.partial", "{\"run\": 1, \"sta");
  EXPECT_EQ(Interruption(RecordOnly(c.campaign, out)), SIGINT);
  // Nor does it reach a merge's table.
  WriteText(out / "rows" / "00000099.json", row(99, identity));
  EXPECT_THROW(MergeCampaigns({out}, dir / "merged", "test"), InputError);
  EXPECT_FALSE(fs::exists(dir / "merged" / "runs.csv"));
  fs::remove_all(dir);
}

TEST(CampaignMerge, AnOutOfAnotherCampaignIsRefused) {
  const auto [dir, c, mine] = Recorded("merge_foreign");
  fs::create_directories(dir / "other");
  const CopiedCampaign other = CopyThesisCampaign(dir / "other", "4");
  const fs::path foreign = dir / "foreign";
  ASSERT_EQ(Interruption(RecordOnly(other.campaign, foreign)), SIGINT);
  const std::string recorded = ReadText(foreign / "campaign.json");
  try {
    MergeCampaigns({mine}, foreign, "test");
    ADD_FAILURE() << "merged into another campaign's directory";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("out " + foreign.string() +
                                ": holds the results of another campaign: the campaign file " +
                                c.campaign.string() + " differs from " + other.campaign.string() +
                                ", which " + foreign.string() + " was started with",
                            0),
              0u)
        << message;
  }
  EXPECT_EQ(ReadText(foreign / "campaign.json"), recorded);  // untouched
  // Nor into a directory with rows but no record of their campaign.
  const fs::path unrecorded = dir / "unrecorded";
  fs::create_directories(unrecorded / "rows");
  WriteText(unrecorded / "rows" / "00000000.json", "{}");
  EXPECT_THROW(MergeCampaigns({mine}, unrecorded, "test"), InputError);
  EXPECT_FALSE(fs::exists(unrecorded / "campaign.json"));
  // Into a directory of the same campaign (a shard, an earlier merge) it goes.
  MergeCampaigns({mine}, dir / "merged", "test");
  MergeCampaigns({mine}, dir / "merged", "test");
  MergeCampaigns({dir / "merged"}, mine, "test");
  fs::remove_all(dir);
}

TEST(CampaignMerge, ShardsOfTheSameTextOnAnotherScenarioDoNotMerge) {
  const fs::path dir = FreshDirectory("merge_shards");
  const auto [a, b] = TwoCopies(dir);
  WriteText(b.base, Replaced(ReadText(b.base), "mass: 1.0041e8", "mass: 1.1e8"));
  ASSERT_EQ(Interruption(RecordOnly(a.campaign, dir / "shard_a")), SIGINT);
  ASSERT_EQ(Interruption(RecordOnly(b.campaign, dir / "shard_b")), SIGINT);
  try {
    MergeCampaigns({dir / "shard_a", dir / "shard_b"}, dir / "merged", "test");
    ADD_FAILURE() << "merged shards of two campaigns";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("merge " + (dir / "shard_b").string() +
                                ": holds another campaign "
                                "than " +
                                (dir / "shard_a").string() + ": the base scenario ",
                            0),
              0u)
        << message;
  }
  EXPECT_FALSE(fs::exists(dir / "merged" / "campaign.json"));
  fs::remove_all(dir);
}

TEST(DetectorStatistic, ATraceCountsUpcrossingsBeforeTheFailureAndFirstCrossingsAfter) {
  StatisticTrace trace("glr", 10.0);
  for (int t = 0; t < 20; ++t) {
    const double g = t < 10 ? (t % 4 == 1 ? 40.0 : 5.0) : 100.0 + t;
    trace.Add(t, {g, 0.0});
  }
  const nlohmann::json j = trace.ToJson();
  const std::vector<double> grid = j.at("thresholds").get<std::vector<double>>();
  for (std::size_t k = 0; k < grid.size(); ++k) {
    SCOPED_TRACE(grid[k]);
    EXPECT_EQ(j.at("false_crossings")[k], grid[k] <= 40.0 ? 3 : 0);  // t = 1, 5, 9
    if (grid[k] <= 110.0) {
      EXPECT_EQ(j.at("first_crossing")[k], 10.0);
    } else if (grid[k] <= 119.0) {
      EXPECT_EQ(j.at("first_crossing")[k], std::ceil(grid[k] - 100.0));
    } else {
      EXPECT_TRUE(j.at("first_crossing")[k].is_null());
    }
  }
  EXPECT_EQ(j.at("max_before_failure"), 40.0);
}

}  // namespace
}  // namespace moorsim::simulation
