// `moorsim import moordyn`: a MoorDyn file in, a scenario out that the other commands run;
// warnings and refusals on stderr, one located line each.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

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
