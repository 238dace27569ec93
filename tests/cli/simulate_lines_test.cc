// `moorsim simulate-lines` with a prescribed motion in all six degrees of freedom: several
// harmonics at once, and a motion read from a CSV of samples, which gives the tensions of
// the harmonic motion it samples.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kSeed = MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml";

// Line 1's tension column of a simulate-lines CSV.
std::vector<double> LineOneTension(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::vector<double> tension;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::istringstream row(line);
    std::string time, first;
    std::getline(row, time, ',');
    std::getline(row, first, ',');
    tension.push_back(std::stod(first));
  }
  return tension;
}

TEST(SimulateLines, SixDegreesOfFreedomFromHarmonicsOrFromASampledFile) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path harmonic = dir.path() / "harmonic.csv";
  const std::vector<std::string> common = {"simulate-lines", kSeed, "--segments",        "10",
                                           "--duration",     "40",  "--output-interval", "1",
                                           "--quiet"};
  std::vector<std::string> args = common;
  for (const char* m : {"--motion", "heave:1.5,11", "--motion", "roll:3,13", "--motion",
                        "pitch:2,10", "--motion", "yaw:4,60", "--out"}) {
    args.push_back(m);
  }
  args.push_back(harmonic.string());
  const CliResult a = RunCli(args, dir.path());
  ASSERT_EQ(a.exit_code, 0) << a.Describe();

  // The same motion sampled every 0.1 s (angles in degrees).
  const std::filesystem::path samples = dir.path() / "motion.csv";
  {
    std::ofstream out(samples);
    out << "# the harmonic motion above, sampled\ntime,x,y,z,roll_deg,pitch_deg,yaw_deg\n";
    out.precision(17);
    const double w = 2.0 * std::numbers::pi;
    for (int k = 0; k <= 450; ++k) {
      const double t = 0.1 * k;
      out << t << ",0,0," << 1.5 * std::sin(w * t / 11.0) << "," << 3.0 * std::sin(w * t / 13.0)
          << "," << 2.0 * std::sin(w * t / 10.0) << "," << 4.0 * std::sin(w * t / 60.0) << "\n";
    }
  }
  const std::filesystem::path sampled = dir.path() / "sampled.csv";
  args = common;
  for (const std::string& m :
       {std::string("--motion-file"), samples.string(), std::string("--out"), sampled.string()}) {
    args.push_back(m);
  }
  const CliResult b = RunCli(args, dir.path());
  ASSERT_EQ(b.exit_code, 0) << b.Describe();

  const std::vector<double> ta = LineOneTension(harmonic);
  const std::vector<double> tb = LineOneTension(sampled);
  ASSERT_EQ(ta.size(), 41u);
  ASSERT_EQ(tb.size(), ta.size());
  double low = ta[0], high = ta[0], worst = 0.0;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    low = std::min(low, ta[i]);
    high = std::max(high, ta[i]);
    worst = std::max(worst, std::abs(ta[i] - tb[i]));
  }
  EXPECT_GT(high - low, 1e4);  // the motion moves the tension
  EXPECT_LT(worst, 0.01 * (high - low)) << "worst " << worst << " N of a range " << high - low;
}

// The scenario's waves reach the lines only where it asks (environment.waves.on_lines): off,
// the lines move in still water whatever the sea (the same tensions as with calm waves);
// on, the water's motion changes them, near the fairlead, by a small part of the swing the
// vessel's motion makes.
TEST(SimulateLines, TheScenariosWavesReachTheLinesOnlyWhereItAsks) {
  TempDirectory dir(::testing::TempDir());
  const auto run = [&](const std::string& name, std::vector<std::string> set) {
    std::vector<std::string> args = {"simulate-lines",
                                     kSeed,
                                     "--segments",
                                     "20",
                                     "--duration",
                                     "60",
                                     "--output-interval",
                                     "1",
                                     "--quiet",
                                     "--motion",
                                     "surge:1,20",
                                     "--set",
                                     "environment.waves.hs=6",
                                     "--set",
                                     "environment.waves.tp=11",
                                     "--out",
                                     (dir.path() / name).string()};
    for (const std::string& s : set) {
      args.push_back("--set");
      args.push_back(s);
    }
    const CliResult r = RunCli(args, dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.Describe();
    return LineOneTension(dir.path() / name);
  };
  const std::vector<double> off = run("off.csv", {"environment.waves.on_lines=false"});
  const std::vector<double> calm = run("calm.csv", {"environment.waves.hs=0.01"});
  const std::vector<double> on = run("on.csv", {"environment.waves.on_lines=true"});
  ASSERT_EQ(off.size(), 61u);
  ASSERT_EQ(calm.size(), off.size());
  ASSERT_EQ(on.size(), off.size());
  double low = off[0], high = off[0], changed = 0.0;
  for (std::size_t i = 0; i < off.size(); ++i) {
    EXPECT_EQ(off[i], calm[i]) << "t = " << i << " s";
    low = std::min(low, off[i]);
    high = std::max(high, off[i]);
    changed = std::max(changed, std::abs(on[i] - off[i]));
  }
  EXPECT_GT(changed, 100.0);  // [N]
  EXPECT_LT(changed, 0.5 * (high - low)) << changed << " N against a swing of " << high - low;
}

TEST(SimulateLines, AMotionFileIsCheckedRowByRow) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path file = dir.path() / "m.csv";
  const auto run = [&](const std::string& text) {
    std::ofstream(file) << text;
    return RunCli(
        {"simulate-lines", kSeed, "--motion-file", file.string(), "--duration", "1", "--quiet"},
        dir.path());
  };
  const CliResult header = run("t,x,y,z,roll,pitch,yaw\n0,0,0,0,0,0,0\n");
  EXPECT_EQ(header.exit_code, 2);
  EXPECT_EQ(header.err, "moorsim: " + file.string() +
                            ":1: the header must be 'time,x,y,z,roll_deg,pitch_deg,yaw_deg' "
                            "(angles in degrees)\n");
  const CliResult order =
      run("time,x,y,z,roll_deg,pitch_deg,yaw_deg\n0,0,0,0,0,0,0\n1,0,0,0,0,0,0\n1,1,0,0,0,0,0\n");
  EXPECT_EQ(order.exit_code, 2);
  EXPECT_EQ(order.err, "moorsim: " + file.string() + ":4: time 1 s does not follow 1 s\n");
  const CliResult width = run("time,x,y,z,roll_deg,pitch_deg,yaw_deg\n0,0,0\n");
  EXPECT_EQ(width.exit_code, 2);
  EXPECT_EQ(width.err, "moorsim: " + file.string() + ":2: '0,0,0' is not 7 numbers\n");
}

}  // namespace
}  // namespace moorsim::testing
