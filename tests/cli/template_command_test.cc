// `moorsim template`: the written scenario loads wherever it is written, every line has the
// asked pretension in the FEM at rest, the anchors are evenly spread (at --radius when
// given), it runs, and every bad input is one line naming the flag, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "mooring_fem/catenary.h"
#include "scenarios/load.h"
#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

/// Horizontal bearing from fairlead to anchor [deg in [0, 360)], vessel at the origin,
/// heading 0 (as the template writes it).
double Bearing(const scenarios::LineSpec& line) {
  const double deg = std::atan2(line.anchor.y() - line.fairlead_body.y(),
                                line.anchor.x() - line.fairlead_body.x()) *
                     180.0 / std::numbers::pi;
  return deg < 0.0 ? deg + 360.0 : deg;
}

double HorizontalDistance(const Vec3& a, const Vec3& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

/// Runs `moorsim template ARGS --out DIR/NAME`, expects success, returns the file's path.
std::filesystem::path Write(const TempDirectory& dir, const std::string& name,
                            std::vector<std::string> args) {
  const std::filesystem::path path = dir.path() / name;
  args.insert(args.begin(), "template");
  args.insert(args.end(), {"--out", path.string()});
  const CliResult r = RunCli(args, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  return path;
}

/// The FEM at rest (`moorsim static --json`) on a scenario file.
nlohmann::json Static(const TempDirectory& dir, const std::filesystem::path& scenario) {
  const CliResult r = RunCli({"static", scenario.string(), "--json"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  return nlohmann::json::parse(r.out);
}

/// Every line: evenly spread bearings, 360/N apart; anchors on the seabed.
void ExpectEvenlySpread(const scenarios::Scenario& s, int lines, double depth) {
  ASSERT_EQ(static_cast<int>(s.mooring.lines.size()), lines);
  std::vector<double> bearings;
  for (const scenarios::LineSpec& line : s.mooring.lines) {
    bearings.push_back(Bearing(line));
    EXPECT_DOUBLE_EQ(line.anchor.z(), depth);
  }
  std::sort(bearings.begin(), bearings.end());
  bearings.push_back(bearings.front() + 360.0);
  // Fairleads are written to the micrometre: 1e-6 m over 1 km is 6e-8 deg.
  for (int k = 0; k < lines; ++k) {
    EXPECT_NEAR(bearings[k + 1] - bearings[k], 360.0 / lines, 1e-6) << "after line " << k + 1;
  }
}

constexpr double kDepth = 1000.0;
constexpr double kLength = 2250.0;
// Range of the seed chain, 2250 m long, fairlead 988 m above the seabed: 2600.7 kN (slack)
// to 8208.2 kN (pulled straight).
constexpr double kPretension = 3.5e6;

// The FEM at rest (50 segments, penalty seabed with friction, node-to-node touchdown) vs the
// analytic catenary the anchors are placed by: the project's bar for 50 segments is 0.5 %
// (tests/mooring_fem/static_test.cc). Measured: 0.04 % at 3500 kN, 0.01 % at the 1900 m
// radius, 0.1 % for 900 m of chain in 300 m of water; it grows to 1.5 % within 1 % of the
// slack end, where the 45 m segments resolve a nearly vertical hanging part coarsely.
constexpr double kFemTolerance = 0.005;

TEST(TemplateCommand, EveryKindAndLineCountLoadsEvenlySpreadWithThePretensionAtRest) {
  TempDirectory dir(::testing::TempDir());
  for (const std::string kind : {"turret", "spread"}) {
    for (int lines : {3, 4, 6, 8, 12}) {
      SCOPED_TRACE(kind + " " + std::to_string(lines));
      const std::filesystem::path path =
          Write(dir, kind + std::to_string(lines) + ".yaml",
                {kind, "--lines", std::to_string(lines), "--depth", "1000", "--length", "2250",
                 "--pretension", "3.5e6"});
      const scenarios::Scenario s = scenarios::LoadScenario(path.string());
      ExpectEvenlySpread(s, lines, kDepth);
      ASSERT_TRUE(s.vessel.has_value());
      EXPECT_EQ(s.failure.line, 0);  // no failure
      const nlohmann::json result = Static(dir, path);
      for (const nlohmann::json& line : result["lines"]) {
        EXPECT_NEAR(line["fairlead_tension"].get<double>(), kPretension,
                    kFemTolerance * kPretension)
            << "line " << line["id"];
      }
      // Equal pretension, evenly spread, and no yaw moment: the vessel is at rest.
      const nlohmann::json& net = result["net_force"];
      EXPECT_LT(std::hypot(net[0].get<double>(), net[1].get<double>()), 1e-3 * kPretension);
      EXPECT_LT(std::abs(net[2].get<double>()), 1e-3 * kPretension * 22.0);  // [N m]
    }
  }
}

TEST(TemplateCommand, StdoutHoldsTheSameScenarioAndStartsWithTheSchemaLine) {
  TempDirectory dir(::testing::TempDir());
  const std::vector<std::string> args = {"template", "spread",   "--lines", "8",        "--depth",
                                         "500",      "--length", "1200",    "--radius", "1000"};
  const CliResult r = RunCli(args, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.out.rfind("# yaml-language-server: $schema=moorsim.schema.json\n# (`moorsim schema "
                        "> moorsim.schema.json` writes",
                        0),
            0u)
      << r.out.substr(0, 200);
  const std::filesystem::path path = Write(dir, "spread.yaml", {args.begin() + 1, args.end()});
  EXPECT_EQ(ReadWholeFile(path), r.out);
}

TEST(TemplateCommand, RadiusPlacesTheAnchorsThereAndWritesTheirPretension) {
  TempDirectory dir(::testing::TempDir());
  for (const std::string kind : {"turret", "spread"}) {
    SCOPED_TRACE(kind);
    const double radius = 1900.0;
    const std::filesystem::path path =
        Write(dir, kind + ".yaml",
              {kind, "--lines", "6", "--depth", "1000", "--length", "2250", "--radius", "1900"});
    const scenarios::Scenario s = scenarios::LoadScenario(path.string());
    ExpectEvenlySpread(s, 6, kDepth);
    const nlohmann::json result = Static(dir, path);
    for (const scenarios::LineSpec& line : s.mooring.lines) {
      // From the reference point, written to the millimetre.
      EXPECT_NEAR(HorizontalDistance(line.anchor, Vec3::Zero()), radius, 1e-3)
          << "line " << line.id;
      // The pretension the comment states is the catenary's at that radius, and the FEM's.
      const double span = HorizontalDistance(line.anchor, line.fairlead_body);
      const mooring_fem::CatenaryLineProperties props{
          line.Length(), (275.0 - 1025.0 * std::numbers::pi / 4.0 * 0.08 * 0.08) * 9.81, 2.28785e8};
      const double tension = mooring_fem::SolveCatenary(props, span, 988.0).fairlead_tension;
      char stated[64];
      std::snprintf(stated, sizeof stated, "Pretension: %.1f kN", tension / 1e3);
      EXPECT_NE(ReadWholeFile(path).find(stated), std::string::npos) << stated;
      EXPECT_NEAR(result["lines"][line.id - 1]["fairlead_tension"].get<double>(), tension,
                  kFemTolerance * tension);
    }
  }
}

TEST(TemplateCommand, LoadsAndRunsFromAnotherFolder) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path written = Write(
      dir, "turret.yaml",
      {"turret", "--lines", "5", "--depth", "300", "--length", "900", "--pretension", "1.2e6"});
  // The WAMIT path is absolute: the file still loads and runs after it is moved.
  const std::filesystem::path moved = dir.path() / "elsewhere" / "deeper" / "case.yaml";
  std::filesystem::create_directories(moved.parent_path());
  std::filesystem::rename(written, moved);
  EXPECT_NO_THROW(scenarios::LoadScenario(moved.string()));
  const std::filesystem::path out = dir.path() / "run";
  const CliResult r = RunCli(
      {"run", moved.string(), "--duration", "5", "--out", out.string(), "--quiet"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out / "summary.json"));
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_DOUBLE_EQ(summary["simulated_time"].get<double>(), 5.0);
}

TEST(TemplateCommand, OutRefusesToReplaceAFileUnlessForced) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path path = dir.path() / "mine.yaml";
  WriteWholeFile(path, "precious\n");
  const std::vector<std::string> args = {"template", "turret",      "--lines",      "3",
                                         "--depth",  "1000",        "--length",     "2250",
                                         "--out",    path.string(), "--pretension", "3e6"};
  const CliResult refused = RunCli(args, dir.path());
  EXPECT_EQ(refused.exit_code, 2) << refused.Describe();
  EXPECT_EQ(refused.err,
            "moorsim: --out: '" + path.string() + "' exists (give --force to overwrite it)\n");
  EXPECT_EQ(ReadWholeFile(path), "precious\n");
  std::vector<std::string> forced = args;
  forced.push_back("--force");
  const CliResult r = RunCli(forced, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NO_THROW(scenarios::LoadScenario(path.string()));
}

// --force replaces a file only once the new one is whole: on a full disk (here a 1 kB file
// size limit) the old file stays as it was and nothing else is left beside it.
TEST(TemplateCommand, OnAFullDiskTheReplacedFileStaysWhole) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path path = dir.path() / "mine.yaml";
  WriteWholeFile(path, "precious\n");
  // The limit's signal is ignored here and so in the child: its write fails with EFBIG.
  const auto saved = std::signal(SIGXFSZ, SIG_IGN);
  const CliResult r = RunProgram(
      "/usr/bin/prlimit",
      {"--fsize=1000", MOORSIM_CLI, "template", "turret", "--lines", "3", "--depth", "1000",
       "--length", "2250", "--pretension", "3e6", "--out", path.string(), "--force"},
      dir.path());
  std::signal(SIGXFSZ, saved);
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_NE(r.err.find(path.string() + ": write failed"), std::string::npos) << r.Describe();
  EXPECT_EQ(ReadWholeFile(path), "precious\n");
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    files += entry.path().filename().string().rfind("cli_", 0) == 0 ? 0 : 1;
  }
  EXPECT_EQ(files, 1u);
}

// A WAMIT folder whose name holds a line break (or a quote, a colon) is written so that it
// reads back as that folder: the scenario loads and names the same files.
TEST(TemplateCommand, AHydrodynamicsFolderWithALineBreakInItsNameLoads) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path folder = dir.path() / "hydro\nfolder: \"x\"";
  std::filesystem::create_directories(folder);
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(MOORSIM_SOURCE_DIR) / "data" / "fpso_wamit")) {
    if (entry.path().stem() == "fpso") {
      std::filesystem::copy_file(entry.path(), folder / entry.path().filename());
    }
  }
  const std::filesystem::path path =
      Write(dir, "odd.yaml",
            {"turret", "--lines", "3", "--depth", "300", "--length", "900", "--pretension", "1e6",
             "--hydrodynamics", (folder / "fpso").string()});
  const scenarios::Scenario s = scenarios::LoadScenario(path.string());
  ASSERT_TRUE(s.vessel.has_value());
  EXPECT_EQ(s.vessel->hydrodynamics, (folder / "fpso").string());
}

TEST(TemplateCommand, OutMustBeARegularFile) {
  TempDirectory dir(::testing::TempDir());
  const std::vector<std::string> args = {"template",     "turret",   "--lines", "3",     "--depth",
                                         "1000",         "--length", "2250",    "--out", "",
                                         "--pretension", "3e6",      "--force"};
  std::vector<std::string> folder = args;
  folder[9] = dir.path().string();
  const CliResult r = RunCli(folder, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: --out: '" + dir.path().string() +
                       "' is a folder (give the scenario file's name)\n");
  std::vector<std::string> device = args;
  device[9] = "/dev/null";
  const CliResult d = RunCli(device, dir.path());
  EXPECT_EQ(d.exit_code, 2) << d.Describe();
  EXPECT_EQ(d.err,
            "moorsim: --out: '/dev/null' is not a regular file (without --out the scenario goes "
            "to stdout)\n");
}

struct BadInput {
  std::vector<std::string> args;  // after "template"
  std::string message;            // the whole line after "moorsim: "
};

TEST(TemplateCommand, BadInputIsOneLineNamingTheFlagAndExitTwo) {
  const std::vector<std::string> good = {"--lines", "8", "--depth", "1000", "--length", "2250"};
  const auto with = [&](std::vector<std::string> args) {
    std::vector<std::string> all = {"turret"};
    all.insert(all.end(), good.begin(), good.end());
    all.insert(all.end(), args.begin(), args.end());
    return all;
  };
  const auto replace = [&](const std::string& flag, const std::string& value,
                           std::vector<std::string> extra) {
    std::vector<std::string> all = with(extra);
    *(std::find(all.begin(), all.end(), flag) + 1) = value;
    return all;
  };
  const std::vector<BadInput> cases = {
      {{"catenary", "--lines", "8", "--depth", "1000", "--length", "2250", "--pretension", "3e6"},
       "kind: unknown mooring kind 'catenary' (known: spread, turret)"},
      {replace("--lines", "2", {"--pretension", "3e6"}),
       "--lines: 2 must be >= 3 (fewer lines cannot hold the vessel in every direction)"},
      {replace("--lines", "65", {"--pretension", "3e6"}),
       "--lines: 65 must be <= 64 (moorings in service have at most a few dozen lines)"},
      {replace("--lines", "7.5", {"--pretension", "3e6"}), "--lines: '7.5' must be a whole number"},
      {replace("--lines", "eight", {"--pretension", "3e6"}),
       "--lines: 'eight' in 'eight' is not a finite number"},
      {replace("--depth", "0", {"--pretension", "3e6"}), "--depth: 0 m must be > 0"},
      {replace("--depth", "-50", {"--pretension", "3e6"}), "--depth: -50 m must be > 0"},
      {replace("--depth", "10", {"--pretension", "3e6"}),
       "--depth: 10 m must be deeper than the fairleads, 12 m down at the FPSO's draught"},
      {replace("--depth", "13000", {"--pretension", "3e6"}),
       "--depth: 13000 m must be <= 12000 (the deepest ocean is 11 km)"},
      {replace("--depth", "nan", {"--pretension", "3e6"}),
       "--depth: 'nan' in 'nan' is not a finite number"},
      {replace("--length", "0", {"--pretension", "3e6"}), "--length: 0 m must be in (0, 20000] m"},
      {replace("--length", "900", {"--pretension", "3e6"}),
       "--length: 900 m in 1000 m of water: a line of 900 m hanging straight down from 988 m "
       "above the seabed does not reach it (it needs more than 982.416 m, stretched by its own "
       "weight)"},
      {replace("--length", "20000", {"--pretension", "3e6"}),
       "--length: 20000 m in 1000 m of water: a line of 20000 m with its fairlead 988 m above "
       "the seabed does not lift off below a fairlead strain of 10 %"},
      {with({}), "--pretension, --radius: give exactly one of them (neither given)"},
      {with({"--pretension", "3e6", "--radius", "1900"}),
       "--pretension, --radius: give exactly one of them (both given)"},
      {with({"--pretension", "2.5e6"}),
       "--pretension: 2.5e+06 N is not above 2600.7 kN, the weight in water of the line "
       "hanging straight down from the fairlead to the seabed (a line touching down pulls "
       "more)"},
      {with({"--pretension", "-1"}),
       "--pretension: -1 N is not above 2600.7 kN, the weight in water of the line hanging "
       "straight down from the fairlead to the seabed (a line touching down pulls more)"},
      {with({"--pretension", "9e6"}),
       "--pretension: 9e+06 N is above 8208.2 kN, where the line is pulled straight: its anchor "
       "as far from its fairlead as it is long (unstretched)"},
      // A short line in shallow water lifts off before it is pulled straight.
      {{"spread", "--lines", "4", "--depth", "200", "--length", "600", "--pretension", "3e6"},
       "--pretension: 3e+06 N is above 2809.0 kN, where the whole line is lifted off the seabed "
       "and pulls its anchor up (a drag anchor holds no uplift)"},
      {{"spread", "--lines", "4", "--depth", "200", "--length", "600", "--radius", "600"},
       "--radius: 600 m is too large: beyond 588.9 m from the reference point the whole line is "
       "lifted off the seabed and pulls its anchor up (a drag anchor holds no uplift)"},
      {with({"--pretension", "3MN"}), "--pretension: '3MN' in '3MN' is not a finite number"},
      {with({"--radius", "1200"}),
       "--radius: 1200 m is too small: the anchors must be more than 1287.6 m from the "
       "reference point, or the line lies slack on the seabed (no horizontal tension)"},
      {with({"--radius", "2500"}),
       "--radius: 2500 m is too large: beyond 2041.5 m from the reference point the line is "
       "pulled straight: its anchor as far from its fairlead as it is long (unstretched)"},
      {with({"--radius", "1.9e3,2e3"}), "--radius: '1.9e3,2e3' must be a single number"},
      {{"turret", "--lines", "8", "--depth", "1000", "--pretension", "3e6"},
       "--length, --sections: give exactly one of them (neither given)"},
      {{"turret", "--lines", "8", "--depth", "1000", "--sections", "chain:400,rope:1600",
        "--pretension", "2e6"},
       "--sections: 'rope:1600' (section 2): unknown line type 'rope' (known: chain, "
       "polyester)"},
      {with({"--pretension", "3e6", "--groups", "3"}),
       "--groups: 3 does not divide the 8 lines into equal groups"},
      {with({"--pretension", "3e6", "--group-spread", "3"}), "--group-spread: only with --groups"},
      {with({"--pretension", "3e6", "--out", "no/such/folder/x.yaml"}),
       "--out: folder 'no/such/folder' does not exist"},
      {with({"--pretension", "3e6", "--hydrodynamics", "no_such_stem"}),
       "--hydrodynamics: 'no_such_stem': no WAMIT file '"},
  };
  TempDirectory dir(::testing::TempDir());
  for (const BadInput& c : cases) {
    std::vector<std::string> args = {"template"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliResult r = RunCli(args, dir.path());
    std::string command;
    for (const std::string& a : args) command += " " + a;
    SCOPED_TRACE(command);
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("moorsim: " + c.message, 0), 0u) << r.err;
  }
  // Nothing was written into the scratch folder but the captured streams.
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(name == "cli_stdout.txt" || name == "cli_stderr.txt") << name;
  }
}

}  // namespace
}  // namespace moorsim::testing
