// The golden run.h5, checked through `moorsim compare` as a user's regression suite would:
// the seed case with line 6 parted at its fairlead at 30 s, the GLR and DHT detectors on,
// 100 s at the scenario's 1 Hz output rate (both detectors alarm and name line 6 within
// it), against tests/data/golden/seed_tapm_line6_run.h5, recorded from an earlier verified
// build. Every dataset of the file is a channel; a missing golden file is a failure.
//
// Tolerances: those of the coupled golden files (tests/simulation/golden_test.cc), far above
// the round-off differences between equivalent builds (the release and the sanitizer builds
// gave bit-identical files here; another CPU or libm may not) and below what a change of
// model moves: 10 % more normal drag on the lines moved the pose by 13 mm, the delivered
// thrust by 47 kN N m, the GLR scores by 0.03 and 8 other channels past these tolerances
// within the 100 s. Per channel:
//  - positions 5 mm, angles 5e-5 rad (0.003 deg), in the true, low-frequency, measured and
//    detection-input poses and the observer's wave-motion estimate;
//  - fairlead tensions 2 kN (of about 5 MN); the anchors exactly (an input);
//  - thrust 5 kN (and 5 kN m), commanded, delivered and as the detection took it;
//  - detector scores 1e-3 relative plus 1e-3 absolute; decisions and alarms exactly (their
//    integer default);
//  - what the golden files above do not record, with the same margins:
//    velocities 1e-3 m/s and 1e-5 rad/s (5 mm and 5e-5 rad over a 5 s wave period),
//    the turret's angle 5e-5 rad, its rate 1e-5 rad/s and its moments 2e3 N m per metre of
//    its 20 m radius (4e4 N m), the loads on the hull (/environment, the observer's bias)
//    5 kN and 5 kN m per metre of the hull's 100 m half-length (5e5 N m), like the thrust.
// Time is compared with the default (1e-9 relative): the sample instants are exact.
//
// Nothing machine-specific is compared: the scenario's absolute path, its text, the
// overrides and the program version are attributes, which compare leaves out, and the
// timings are in summary.json, not in run.h5.
//
// After an intended change of the numbers, rewrite the file with tools/dev/update_golden.sh and
// say why in the commit; this test (and the script) refuse to rewrite under CI=true.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kGolden = MOORSIM_SOURCE_DIR "/tests/data/golden/seed_tapm_line6_run.h5";

// Of the patterns that match, the last one wins: general ones first.
const std::vector<std::pair<std::string, std::string>> kTolerances = {
    {"--atol", "/vessel/pose*=5e-5"},
    {"--atol", "/vessel/pose*/[xyz]=5e-3"},
    {"--atol", "/detection/input/pose_measured=5e-5"},
    {"--atol", "/detection/input/pose_measured/[xy]=5e-3"},
    {"--atol", "/observer/wave_motion=5e-5"},
    {"--atol", "/observer/wave_motion/[xy]=5e-3"},
    {"--atol", "/vessel/velocity_true=1e-5"},
    {"--atol", "/vessel/velocity_true/[uvw]=1e-3"},
    {"--atol", "/vessel/turret=4e4"},
    {"--atol", "/vessel/turret/angle=5e-5"},
    {"--atol", "/vessel/turret/rate=1e-5"},
    {"--atol", "/mooring/fairlead_tension=2e3"},
    {"--atol", "/thrust/*=5e3"},
    {"--atol", "/detection/input/thrust=5e3"},
    {"--atol", "/environment/*=5e5"},
    {"--atol", "/environment/*/[XYZ]=5e3"},
    {"--atol", "/observer/bias=5e3"},
    {"--atol", "/detectors/*/score=1e-3"},
    {"--rtol", "/detectors/*/score=1e-3"},
};

/// Makes the source tree the working directory while it lives, so that the run records the
/// scenario's path relative to it, the same on every machine.
class InSourceTree {
 public:
  InSourceTree() : previous_(std::filesystem::current_path()) {
    std::filesystem::current_path(MOORSIM_SOURCE_DIR);
  }
  ~InSourceTree() { std::filesystem::current_path(previous_); }
  InSourceTree(const InSourceTree&) = delete;
  InSourceTree& operator=(const InSourceTree&) = delete;

 private:
  std::filesystem::path previous_;
};

TEST(CompareGolden, TheSeedCaseWithLine6PartedMatchesTheRecordedRun) {
  TempDirectory dir(std::filesystem::absolute(::testing::TempDir()).string());
  const std::string out = (dir.path() / "run").string();
  const InSourceTree in_source_tree;
  const CliResult run =
      RunCli({"run", "scenarios/library/seed_tapm.yaml", "--out", out, "--duration", "100",
              "--quiet", "--set", "detectors=[{type: glr}, {type: dht}]", "--set",
              "failure.mode=fairlead", "--set", "failure.line=6", "--set", "failure.time=30"},
             dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.Describe();
  if (std::getenv("MOORSIM_UPDATE_GOLDEN") != nullptr) {
    const char* ci = std::getenv("CI");
    ASSERT_FALSE(ci != nullptr && std::string(ci) == "true")
        << "golden files are never rewritten under CI=true";
    std::filesystem::copy_file(out + "/run.h5", kGolden,
                               std::filesystem::copy_options::overwrite_existing);
    GTEST_SKIP() << "golden file rewritten: " << kGolden;
  }
  ASSERT_TRUE(std::filesystem::exists(kGolden)) << "missing golden file " << kGolden;
  std::vector<std::string> args = {"compare", out, kGolden};
  for (const auto& [flag, value] : kTolerances) {
    args.push_back(flag);
    args.push_back(value);
  }
  const CliResult compared = RunCli(args, dir.path());
  EXPECT_EQ(compared.exit_code, 0) << compared.Describe();
  // Every channel of the file, so that a golden file cut short cannot pass.
  EXPECT_EQ(compared.out, "all 26 channels within tolerance\n");
}

}  // namespace
}  // namespace moorsim::testing
