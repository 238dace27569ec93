// `moorsim import moordyn`: a MoorDyn file in, a scenario out that the other commands run;
// warnings and refusals on stderr, one located line each.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

// One chain line in 100 m of water, its bending stiffness left out with a warning.
constexpr const char* kOneLine = R"(--------------------- MoorDyn Input File -----------------------
one line
----------------------- LINE TYPES ------------------------------------------
TypeName   Diam    Mass/m     EA         BA/-zeta    EI   Cd     Ca     CdAx    CaAx
(name)     (m)     (kg/m)     (N)        (N-s/-)     (N-m^2)  (-)  (-)    (-)     (-)
chain      0.09    120        6.0e8      -0.5        5    2.0    1.0    0.4     0.0
---------------------- POINTS --------------------------------
ID    Type      X       Y       Z       Mass   Volume  CdA    Ca
(#)   (-)       (m)     (m)     (m)     (kg)   (m^3)   (m^2)  (-)
1     Fixed     420     0       -100    0      0       0      0
2     Coupled   10      0       -10     0      0       0      0
---------------------- LINES ----------------------------------------
ID   LineType   AttachA  AttachB  UnstrLen  NumSegs  LineOutputs
(#)   (name)     (#)      (#)       (m)       (-)     (-)
1     chain      1        2         460       20      p
---------------------- OPTIONS -----------------------------------------
100           WtrDpth       water depth (m)
------------------------- need this line --------------------------------------
)";

TEST(ImportCommand, AMoorDynFileBecomesAScenarioThatStaticAndSimulateLinesRun) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path file = dir.path() / "one.txt";
  std::ofstream(file) << kOneLine;
  const std::string scenario = (dir.path() / "one.yaml").string();
  const CliResult r = RunCli({"import", "moordyn", file.string(), "--out", scenario}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.out, scenario + ": 1 line from " + file.string() + "\n");
  EXPECT_EQ(r.err, "moorsim: warning: " + file.string() +
                       ":6: line type chain: bending stiffness EI 5 left out (moorsim's lines "
                       "have none)\n");
  const CliResult s = RunCli({"static", scenario}, dir.path());
  EXPECT_EQ(s.exit_code, 0) << s.Describe();
  const CliResult m =
      RunCli({"simulate-lines", scenario, "--motion", "surge:2,15", "--duration", "30", "--quiet"},
             dir.path());
  EXPECT_EQ(m.exit_code, 0) << m.Describe();
  // The file is not replaced without --force.
  const CliResult again =
      RunCli({"import", "moordyn", file.string(), "--out", scenario}, dir.path());
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_EQ(again.err,
            "moorsim: --out: '" + scenario + "' exists (give --force to overwrite it)\n");
}

// The scenario and the depth grid it names are written together: when the scenario cannot
// be written (here a 1 kB file size limit, as on a full disk), the grid is not left beside
// it either, and the import can be run again once there is room.
TEST(ImportCommand, AFailedWriteLeavesNeitherFileBehind) {
  TempDirectory dir(::testing::TempDir());
  std::string text = kOneLine;
  text.replace(text.find("100           WtrDpth"), 0, "bottom.txt    SeafloorFile\n");
  const std::filesystem::path file = dir.path() / "one.txt";
  std::ofstream(file) << text;
  std::ofstream(dir.path() / "bottom.txt") << "2 2\n0 500\n-50 50\n0 -50 -100\n0 50 -100\n"
                                              "500 -50 -100\n500 50 -100\n";
  const std::filesystem::path scenario = dir.path() / "one.yaml";
  const auto saved = std::signal(SIGXFSZ, SIG_IGN);
  const CliResult full = RunProgram(
      "/usr/bin/prlimit",
      {"--fsize=1000", MOORSIM_CLI, "import", "moordyn", file.string(), "--out", scenario.string()},
      dir.path());
  std::signal(SIGXFSZ, saved);
  EXPECT_EQ(full.exit_code, 1) << full.Describe();
  EXPECT_NE(full.err.find(scenario.string() + ": write failed"), std::string::npos)
      << full.Describe();
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    if (name != "one.txt" && name != "bottom.txt" && name.rfind("cli_", 0) != 0) {
      left.push_back(name);
    }
  }
  EXPECT_TRUE(left.empty()) << left.front();
  const CliResult again =
      RunCli({"import", "moordyn", file.string(), "--out", scenario.string()}, dir.path());
  ASSERT_EQ(again.exit_code, 0) << again.Describe();
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "one_seabed.csv"));
  EXPECT_EQ(RunCli({"static", scenario.string()}, dir.path()).exit_code, 0);
}

// What moorsim refuses in the imported model is said of the MoorDyn file's line and field,
// never of the scenario that was not written.
TEST(ImportCommand, ARefusalNamesTheMoorDynLineAndField) {
  TempDirectory dir(::testing::TempDir());
  const auto refusal = [&](const std::string& from, const std::string& to) {
    std::string text = kOneLine;
    text.replace(text.find(from), from.size(), to);
    const std::filesystem::path file = dir.path() / "bad.txt";
    std::ofstream(file) << text;
    const CliResult r = RunCli({"import", "moordyn", file.string()}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.out, "");
    return r.err;
  };
  const std::string f = (dir.path() / "bad.txt").string();
  EXPECT_EQ(refusal("0.09    120", "-0.09   120"),
            "moorsim: " + f +
                ":6: line type chain, Diam: -0.09 m must be > 0 (the scenario's "
                "mooring.line_types[1].diameter)\n");
  EXPECT_EQ(refusal("460       20", "100       20"),
            "moorsim: " + f +
                ":15: line 1, UnstrLen: 100 m is shorter than the anchor-fairlead distance "
                "419.8 m (the scenario's mooring.lines[1].length)\n");
}

TEST(ImportCommand, AnUnknownFormatOrAMissingFileIsExitTwo) {
  TempDirectory dir(::testing::TempDir());
  const CliResult format = RunCli({"import", "orcaflex", "model.dat"}, dir.path());
  EXPECT_EQ(format.exit_code, 2);
  EXPECT_EQ(format.err, "moorsim: import: format 'orcaflex' is not known (known: moordyn)\n");
  const CliResult missing = RunCli({"import", "moordyn", "nowhere.txt"}, dir.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.err.rfind("moorsim: ", 0), 0u);
  EXPECT_NE(missing.err.find("nowhere.txt"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace moorsim::testing
