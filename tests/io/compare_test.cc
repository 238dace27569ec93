// Tests of the channel-by-channel comparison (io/compare.h) on synthetic HDF5
// files and campaign tables: equal, within and outside tolerance, which pattern wins,
// shapes, missing channels and rows, NaN, integers and text. The one-line errors of bad
// input are checked through the program (tests/cli/compare_command_test.cc).
#include "io/compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/scratch_directory.h"
#include "tests/support/synthetic_outputs.h"

namespace moorsim::output {
namespace {

using moorsim::testing::SyntheticRun;
using moorsim::testing::SyntheticTable;
using moorsim::testing::WriteTables;
using Kind = ChannelDifference::Kind;

class CompareTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = moorsim::testing::FreshDirectory("compare_test"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  /// Writes `a` and `b` and compares them.
  Comparison Run(const std::vector<SyntheticTable>& a, const std::vector<SyntheticTable>& b,
                 const CompareOptions& options = {}) {
    WriteTables(dir_ / "a.h5", a);
    WriteTables(dir_ / "b.h5", b);
    return CompareOutputs((dir_ / "a.h5").string(), (dir_ / "b.h5").string(), options);
  }

  /// Writes two campaign tables and compares them.
  Comparison RunCsv(const std::string& a, const std::string& b,
                    const CompareOptions& options = {}) {
    std::ofstream(dir_ / "a.csv") << a;
    std::ofstream(dir_ / "b.csv") << b;
    return CompareOutputs((dir_ / "a.csv").string(), (dir_ / "b.csv").string(), options);
  }

  std::filesystem::path dir_;
};

/// The synthetic run with one value of a table changed.
std::vector<SyntheticTable> Changed(const std::string& table, std::size_t index, double value) {
  std::vector<SyntheticTable> run = SyntheticRun();
  for (SyntheticTable& t : run) {
    if (t.path == table) t.values.at(index) = value;
  }
  return run;
}

CompareOptions Tolerances(const std::vector<std::string>& atol,
                          const std::vector<std::string>& rtol = {}) {
  CompareOptions options;
  for (const std::string& text : atol) AddTolerance(options, ToleranceRule::Kind::kAbsolute, text);
  for (const std::string& text : rtol) AddTolerance(options, ToleranceRule::Kind::kRelative, text);
  return options;
}

std::string Printed(const Comparison& comparison, std::size_t show = 20) {
  std::ostringstream out;
  PrintComparison(comparison, show, out);
  return out.str();
}

TEST_F(CompareTest, EqualRunsHaveNoDifference) {
  const Comparison c = Run(SyntheticRun(), SyntheticRun());
  EXPECT_EQ(c.channels, 3u);
  EXPECT_TRUE(c.differences.empty());
  EXPECT_EQ(Printed(c), "all 3 channels within tolerance\n");
}

TEST_F(CompareTest, AFloatPassesWithinAtolPlusRtolTimesTheReference) {
  // Row 2, column x: 20 in the reference, 20.05 in A: |a - b| = 0.05 (to round-off).
  const std::vector<SyntheticTable> a = Changed("/vessel/pose_true", 12, 20.05);
  const Comparison strict = Run(a, SyntheticRun());
  ASSERT_EQ(strict.differences.size(), 1u);
  const ChannelDifference& d = strict.differences[0];
  EXPECT_EQ(d.channel, "/vessel/pose_true");
  EXPECT_EQ(d.kind, Kind::kValues);
  EXPECT_EQ(d.row, 2u);
  EXPECT_EQ(d.column, 0u);
  EXPECT_DOUBLE_EQ(d.a, 20.05);
  EXPECT_DOUBLE_EQ(d.b, 20.0);
  EXPECT_NEAR(d.difference, 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(d.allowed, 20.0 * 1e-9);  // the default: rtol 1e-9, atol 0
  EXPECT_EQ(d.detail,
            "row 2 (t = 2 s), column 0 (x): a 20.05, b 20, |a-b| 0.05000000000000071 > allowed "
            "2e-08 (1 of 30 values differ)");
  EXPECT_EQ(Printed(strict), "/vessel/pose_true: " + d.detail + "\n1 of 3 channels differ\n");

  EXPECT_TRUE(Run(a, SyntheticRun(), Tolerances({"0.06"})).differences.empty());
  EXPECT_EQ(Run(a, SyntheticRun(), Tolerances({"0.04"})).differences.size(), 1u);
  // rtol 2.6e-3 of 20 allows 0.052, 2.4e-3 allows 0.048.
  EXPECT_TRUE(Run(a, SyntheticRun(), Tolerances({}, {"2.6e-3"})).differences.empty());
  EXPECT_EQ(Run(a, SyntheticRun(), Tolerances({}, {"2.4e-3"})).differences.size(), 1u);
  // atol and rtol add up: 0.03 + 1.1e-3 x 20 = 0.052, 0.03 + 0.9e-3 x 20 = 0.048.
  EXPECT_TRUE(Run(a, SyntheticRun(), Tolerances({"0.03"}, {"1.1e-3"})).differences.empty());
  EXPECT_EQ(Run(a, SyntheticRun(), Tolerances({"0.03"}, {"0.9e-3"})).differences.size(), 1u);
}

TEST_F(CompareTest, TheLastMatchingPatternOfAKindWins) {
  const std::vector<SyntheticTable> a = Changed("/vessel/pose_true", 12, 20.05);
  EXPECT_EQ(Run(a, SyntheticRun(), Tolerances({"*=1", "/vessel/pose_true=0"})).differences.size(),
            1u);
  EXPECT_TRUE(
      Run(a, SyntheticRun(), Tolerances({"/vessel/pose_true=0", "*=1"})).differences.empty());
  // A later --rtol rule does not undo an --atol rule.
  EXPECT_TRUE(Run(a, SyntheticRun(), Tolerances({"*=1"}, {"/vessel/*=0"})).differences.empty());
  // A column by its name: the positions' rule covers x, the angles' rule does not.
  EXPECT_TRUE(
      Run(a, SyntheticRun(), Tolerances({"/vessel/pose_true=1e-9", "/vessel/pose_true/[xyz]=0.1"}))
          .differences.empty());
  const Comparison angles =
      Run(a, SyntheticRun(), Tolerances({"/vessel/pose_true=0.1", "/vessel/pose_true/p*=1e-9"}));
  EXPECT_TRUE(angles.differences.empty());
  const Comparison x_only =
      Run(a, SyntheticRun(), Tolerances({"/vessel/pose_true=0.1", "/vessel/pose_true/x=1e-9"}));
  ASSERT_EQ(x_only.differences.size(), 1u);
  EXPECT_DOUBLE_EQ(x_only.differences[0].allowed, 1e-9 + 20.0 * 1e-9);
}

TEST_F(CompareTest, IntegersCompareExactlyUnlessAPatternGivesThemATolerance) {
  const std::vector<SyntheticTable> a = Changed("/detectors/glr/decision", 3, 2);
  CompareOptions loose;
  loose.atol = 10;  // the default is for floats
  const Comparison c = Run(a, SyntheticRun(), loose);
  ASSERT_EQ(c.differences.size(), 1u);
  EXPECT_EQ(c.differences[0].detail,
            "row 3 (t = 3 s): a 2, b 1 (compared exactly) (1 of 5 values differ)");
  EXPECT_TRUE(std::isinf(c.differences[0].excess));
  EXPECT_TRUE(Run(a, SyntheticRun(), Tolerances({"/detectors/*=1"})).differences.empty());
  EXPECT_EQ(Run(a, SyntheticRun(), Tolerances({"/detectors/*=0.5"})).differences.size(), 1u);
}

TEST_F(CompareTest, SixtyFourBitIntegersCompareExactlyBeyondWhatADoubleHolds) {
  // 2^64 - 1 and 2^64 - 2 are the same double.
  const auto write = [&](const std::string& name, std::uint64_t seed) {
    Hdf5File file((dir_ / name).string());
    const std::vector<std::uint64_t> seeds = {1, seed};
    file.WriteDataset("/runs/seed", {2}, std::span<const std::uint64_t>(seeds));
    file.Close();
  };
  write("a.h5", std::numeric_limits<std::uint64_t>::max() - 1);
  write("b.h5", std::numeric_limits<std::uint64_t>::max());
  const Comparison c =
      CompareOutputs((dir_ / "a.h5").string(), (dir_ / "b.h5").string(), CompareOptions{});
  ASSERT_EQ(c.differences.size(), 1u);
  EXPECT_EQ(c.differences[0].detail,
            "row 1: a 18446744073709551614, b 18446744073709551615 (compared exactly) (1 of 2 "
            "values differ)");
}

TEST_F(CompareTest, ShapesAndChannelsOfOneFileOnlyDifferBeforeAnyValue) {
  std::vector<SyntheticTable> a = Changed("/time", 4, 4.5);  // a value: listed last
  a[1].columns = 3;                                          // 10 x 3 instead of 5 x 6
  a[1].column_names = {"x", "y", "z"};
  a[2].path = "/detectors/cusum/decision";
  const Comparison c = Run(a, SyntheticRun());
  ASSERT_EQ(c.channels, 4u);
  ASSERT_EQ(c.differences.size(), 4u);
  EXPECT_EQ(c.differences[0].channel, "/detectors/cusum/decision");
  EXPECT_EQ(c.differences[0].kind, Kind::kOnlyInA);
  EXPECT_EQ(c.differences[1].channel, "/detectors/glr/decision");
  EXPECT_EQ(c.differences[1].kind, Kind::kOnlyInB);
  EXPECT_EQ(c.differences[2].channel, "/vessel/pose_true");
  EXPECT_EQ(c.differences[2].detail, "shape 10x3 in A, 5x6 in B");
  EXPECT_EQ(c.differences[3].channel, "/time");
  EXPECT_EQ(Printed(c, 2),
            "/detectors/cusum/decision: only in A\n/detectors/glr/decision: only in B\n"
            "(2 more not shown)\n4 of 4 channels differ\n");
}

TEST_F(CompareTest, TheWorstChannelIsListedFirst) {
  // x of row 2 off by 0.05 (allowed 0.01: 5 times), time of row 4 off by 0.5 (allowed 0.01:
  // 50 times), though the pose's difference in absolute terms is the smaller one.
  std::vector<SyntheticTable> a = Changed("/vessel/pose_true", 12, 20.05);
  a[0].values[4] = 4.5;
  const Comparison c = Run(a, SyntheticRun(), Tolerances({"0.01"}, {"0"}));
  ASSERT_EQ(c.differences.size(), 2u);
  EXPECT_EQ(c.differences[0].channel, "/time");
  EXPECT_NEAR(c.differences[0].excess, 50.0, 1e-9);
  EXPECT_EQ(c.differences[0].detail,
            "row 4: a 4.5, b 4, |a-b| 0.5 > allowed 0.01 (1 of 5 values differ)");
  EXPECT_EQ(c.differences[1].channel, "/vessel/pose_true");
  EXPECT_NEAR(c.differences[1].excess, 5.0, 1e-9);
}

TEST_F(CompareTest, NanEqualsNanOnly) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<SyntheticTable> b = Changed("/vessel/pose_true", 7, nan);
  b[1].values[8] = inf;
  std::vector<SyntheticTable> a = b;
  EXPECT_TRUE(Run(a, b).differences.empty());  // NaN and NaN, inf and inf

  a[1].values[7] = 11;
  const Comparison one_nan = Run(a, b, Tolerances({"1e6"}));
  ASSERT_EQ(one_nan.differences.size(), 1u);
  EXPECT_EQ(one_nan.differences[0].detail,
            "row 1 (t = 1 s), column 1 (y): a 11, b nan (NaN in one only) (1 of 30 values "
            "differ)");
  const Comparison other_nan = Run(b, a, Tolerances({"1e6"}));
  ASSERT_EQ(other_nan.differences.size(), 1u);
  EXPECT_TRUE(std::isnan(other_nan.differences[0].a));
  EXPECT_EQ(other_nan.differences[0].b, 11.0);

  a = b;
  a[1].values[8] = -inf;
  EXPECT_EQ(Run(a, b, Tolerances({"1e300"})).differences.size(), 1u);
}

TEST_F(CompareTest, StringDatasetsCompareExactly) {
  const auto write = [&](const std::string& name, const std::string& status) {
    Hdf5File file((dir_ / name).string());
    file.WriteDataset("/runs/status", std::vector<std::string>{"ok", status});
    file.Close();
  };
  write("a.h5", "ok");
  write("b.h5", "ok");
  const std::string a = (dir_ / "a.h5").string(), b = (dir_ / "b.h5").string();
  EXPECT_TRUE(CompareOutputs(a, b, Tolerances({"1"})).differences.empty());
  write("a.h5", "failed");
  const Comparison c = CompareOutputs(a, b, Tolerances({"1"}));
  ASSERT_EQ(c.differences.size(), 1u);
  EXPECT_EQ(c.differences[0].detail, "row 1: a \"failed\", b \"ok\" (1 of 2 values differ)");
}

TEST_F(CompareTest, IgnoredChannelsAreLeftOut) {
  CompareOptions options;
  options.ignore = {"/vessel/*"};
  const Comparison c = Run(Changed("/vessel/pose_true", 12, 20.05), SyntheticRun(), options);
  EXPECT_TRUE(c.differences.empty());
  EXPECT_EQ(c.channels, 2u);
  EXPECT_EQ(Printed(c), "all 2 channels within tolerance (1 ignored)\n");
}

TEST_F(CompareTest, ADirectoryMeansItsRunH5) {
  std::filesystem::create_directories(dir_ / "out");
  WriteTables(dir_ / "out" / "run.h5", Changed("/time", 0, 0.5));
  WriteTables(dir_ / "b.h5", SyntheticRun());
  const Comparison c =
      CompareOutputs((dir_ / "out").string(), (dir_ / "b.h5").string(), CompareOptions{});
  EXPECT_EQ(c.a, (dir_ / "out" / "run.h5").string());
  ASSERT_EQ(c.differences.size(), 1u);
}

// runs.csv of moorsim batch, cut down: rows matched by the run index, whatever their order.
const std::string kTable =
    "run,status,seed,dht.delay,command\n"
    "0,ok,18446744073709551615,10.5,\"moorsim batch \"\"c.yaml\"\", --threads 2\"\n"
    "1,ok,7,,moorsim\n";

TEST_F(CompareTest, CampaignTablesMatchRowsByRunIndex) {
  const std::string reordered =
      "run,status,seed,dht.delay,command\n"
      "1,ok,7,,moorsim\n"
      "0,ok,18446744073709551615,10.5,\"moorsim batch \"\"c.yaml\"\", --threads 2\"\n";
  const Comparison c = RunCsv(reordered, kTable);
  EXPECT_EQ(c.channels, 5u);
  EXPECT_TRUE(c.differences.empty()) << Printed(c);
}

TEST_F(CompareTest, CampaignTableColumnsAreNumbersWithToleranceOrTextExactly) {
  const std::string a =
      "run,status,seed,dht.delay,command\n"
      "0,failed,18446744073709551614,10.6,\"moorsim batch \"\"c.yaml\"\", --threads 2\"\n"
      "1,ok,7,3,moorsim\n";
  const Comparison c = RunCsv(a, kTable, Tolerances({"0.2"}));
  ASSERT_EQ(c.differences.size(), 3u) << Printed(c);
  // All three were allowed nothing (text, an exact integer, a NaN): the largest |a-b| first.
  EXPECT_EQ(Printed(c),
            "dht.delay: run 1: a 3, b nan (NaN in one only) (1 of 2 values differ)\n"
            "status: run 0: a \"failed\", b \"ok\" (1 of 2 values differ)\n"
            "seed: run 0: a 18446744073709551614, b 18446744073709551615 (compared exactly) (1 "
            "of 2 values differ)\n"
            "3 of 5 channels differ\n");
  // dht.delay's 10.6 against 10.5 is within 0.2, outside 0.05.
  const std::string delay_only =
      "run,status,seed,dht.delay,command\n"
      "0,ok,18446744073709551615,10.6,\"moorsim batch \"\"c.yaml\"\", "
      "--threads 2\"\n1,ok,7,,moorsim\n";
  EXPECT_TRUE(RunCsv(delay_only, kTable, Tolerances({"0.2"})).differences.empty());
  EXPECT_EQ(RunCsv(delay_only, kTable, Tolerances({"dht.*=0.05"})).differences.size(), 1u);
}

TEST_F(CompareTest, CampaignTableRowsAndColumnsOfOneTableOnlyDiffer) {
  const std::string a =
      "run,status,seed,dht.delay\n"
      "0,ok,18446744073709551615,10.5\n"
      "1,ok,7,\n"
      "2,ok,8,\n";
  const Comparison c = RunCsv(a, kTable);
  ASSERT_EQ(c.differences.size(), 2u) << Printed(c);
  EXPECT_EQ(Printed(c), "command: only in B\nrun: run 2 only in A\n2 of 5 channels differ\n");
}

}  // namespace
}  // namespace moorsim::output
