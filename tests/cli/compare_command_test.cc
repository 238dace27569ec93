// `moorsim compare` end to end: exit 0 within tolerance, 1 for a difference, and every bad
// input as one line naming the file or the flag with exit code 2, nothing on stdout.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/cli/run_cli.h"
#include "tests/support/synthetic_outputs.h"

namespace moorsim::testing {
namespace {

class CompareCommand : public ::testing::Test {
 protected:
  CompareCommand() : dir_(::testing::TempDir()) {
    std::vector<SyntheticTable> changed = SyntheticRun();
    changed[1].values[12] = 20.05;  // x of row 2: 20 in the reference
    WriteTables(a_, changed);
    WriteTables(b_, SyntheticRun());
  }

  CliResult Compare(std::vector<std::string> args) {
    args.insert(args.begin(), "compare");
    return RunCli(args, dir_.path());
  }

  TempDirectory dir_;
  const std::string a_ = (dir_.path() / "a.h5").string();
  const std::string b_ = (dir_.path() / "b.h5").string();
};

TEST_F(CompareCommand, ExitsZeroWithinToleranceAndOneOutside) {
  CliResult r = Compare({a_, b_});
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_EQ(r.out,
            "/vessel/pose_true: row 2 (t = 2 s), column 0 (x): a 20.05, b 20, |a-b| "
            "0.05000000000000071 > allowed 2e-08 (1 of 30 values differ)\n1 of 3 channels "
            "differ\n");
  EXPECT_EQ(r.err, "");

  r = Compare({a_, b_, "--atol", "/vessel/pose_true/x=0.06"});
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.out, "all 3 channels within tolerance\n");

  // Flags before the files, each taking one value; the last matching pattern wins.
  r = Compare({"--atol", "/vessel/*=0.06", "--atol", "/vessel/pose_true/[xyz]=0.01", a_, b_});
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  r = Compare({"--rtol=1e-2", "--show", "0", a_, b_});
  EXPECT_EQ(r.exit_code, 0) << r.Describe();

  r = Compare({"--show", "0", a_, b_});
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_EQ(r.out, "(1 more not shown: --show)\n1 of 3 channels differ\n");

  // A directory means its run.h5.
  std::filesystem::create_directories(dir_.path() / "out");
  std::filesystem::copy_file(b_, dir_.path() / "out" / "run.h5");
  r = Compare({(dir_.path() / "out").string(), b_});
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
}

TEST_F(CompareCommand, EveryBadInputIsOneLineWithExitCode2) {
  const std::filesystem::path& d = dir_.path();
  const auto write = [&](const std::string& name, const std::string& text) {
    WriteWholeFile(d / name, text);
    return (d / name).string();
  };
  const std::string runs = write("runs.csv", "run,status\n0,ok\n");
  const std::string no_run = write("no_run.csv", "index,status\n0,ok\n");
  const std::string twice = write("twice.csv", "run,status\n0,ok\n1,ok\n0,failed\n");
  const std::string ragged = write("ragged.csv", "run,status\n0,ok,7\n");
  const std::string bad_index = write("bad_index.csv", "run,status\n0,ok\nx1,ok\n");
  const std::string unclosed = write("unclosed.csv", "run,status\n0,\"ok\n");
  const std::string notes = write("notes.txt", "run,status\n0,ok\n");
  const std::string truncated = write("truncated.h5", ReadWholeFile(b_).substr(0, 800));
  const std::string zeroed = write("zeroed.h5", std::string(800, '\0'));
  const std::string campaign = (d / "campaign.h5").string();
  {
    output::Hdf5File file(campaign);
    file.WriteDataset("/runs/status", std::vector<std::string>{"ok"});
    file.Close();
  }
  std::filesystem::create_directories(d / "empty");
  const std::string empty = (d / "empty").string();
  const std::string missing = (d / "missing.h5").string();

  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{missing, b_}, missing + ": no such file or directory"},
      {{a_, missing}, missing + ": no such file or directory"},
      {{empty, b_}, empty + ": a directory without run.h5 or runs.csv"},
      {{notes, b_}, notes + ": neither an HDF5 file nor a .csv table"},
      {{truncated, b_}, truncated + ": damaged HDF5 file (HDF5 cannot open it)"},
      {{zeroed, b_}, zeroed + ": damaged or not an HDF5 file (no HDF5 signature)"},
      {{runs, b_},
       runs + " is a CSV table but " + b_ + " is a run (run.h5) (compare like with like)"},
      {{a_, runs},
       a_ + " is a run (run.h5) but " + runs + " is a CSV table (compare like with like)"},
      {{campaign, b_},
       campaign + " is a campaign (campaign.h5) but " + b_ +
           " is a run (run.h5) (compare like with like)"},
      {{no_run, runs}, no_run + ": no 'run' column (not a runs.csv of moorsim batch)"},
      {{runs, twice}, twice + ":4: run 0 again (first on line 2)"},
      {{ragged, runs}, ragged + ":2: 3 fields, the header has 2"},
      {{bad_index, runs}, bad_index + ":3: run 'x1' is not a run index (a whole number >= 0)"},
      {{unclosed, runs}, unclosed + ":2: a quote never closed"},
      {{a_, b_, "--atol", "/x=abc"}, "--atol '/x=abc': 'abc' is not a number"},
      {{a_, b_, "--atol=-1"}, "--atol '-1': -1 is negative (a tolerance is >= 0)"},
      {{a_, b_, "--rtol", "/time=-1e-3"},
       "--rtol '/time=-1e-3': -1e-3 is negative (a tolerance is >= 0)"},
      {{a_, b_, "--rtol", "/time=inf"}, "--rtol '/time=inf': 'inf' is not a finite number"},
      {{a_, b_, "--atol", "=1"}, "--atol '=1': no pattern before '=' (PATTERN=VALUE or VALUE)"},
      {{a_, b_, "--atol", ""}, "--atol '': empty value"},
      {{a_, b_, "--atol", "/moring/*=2e3"},
       "--atol '/moring/*=2e3': matches no channel of " + a_ + " or " + b_},
      {{a_, b_, "--ignore", "/vesel/*"},
       "--ignore '/vesel/*': matches no channel of " + a_ + " or " + b_},
      {{a_, b_, "--show", "many"}, "--show: 'many' in 'many' is not a finite number"},
      {{a_, b_, "--show", "-1"}, "--show: '-1' must be a whole number in 0..1000000"},
  };
  for (const Case& c : cases) {
    const CliResult r = Compare(c.args);
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.err, "moorsim: " + c.message + "\n") << r.Describe();
    EXPECT_EQ(r.out, "") << r.Describe();
  }
}

TEST_F(CompareCommand, AByteOrderMarkBeforeACsvHeaderIsSkipped) {
  // Excel's "CSV UTF-8" starts the file with one; the first column is still 'run'.
  const std::filesystem::path& d = dir_.path();
  WriteWholeFile(d / "plain.csv", "run,status\n0,ok\n");
  WriteWholeFile(d / "excel.csv", "\xEF\xBB\xBFrun,status\n0,ok\n");
  const CliResult r = Compare({(d / "excel.csv").string(), (d / "plain.csv").string()});
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.err, "");
}

}  // namespace
}  // namespace moorsim::testing
