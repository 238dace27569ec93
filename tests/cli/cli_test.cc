// End-to-end tests of the `moorsim` command line: the built binary (MOORSIM_CLI) runs as a
// child process, and the tests check its exit code, stdout and stderr the way a user or a
// script sees them (docs/design.md sections 2 and 7):
//
// - bad input (a scenario the loader rejects, a bad flag) is exit code 2 and exactly one
//   line on stderr naming the file/field or flag and the value;
// - `static --json` prints one JSON object whose numbers agree with the analytic catenary
//   and with the symmetry of the seed case's spread;
// - `simulate-lines` writes the documented CSV;
// - the help texts exist and say how `static` computes its numbers.
//
// Bad scenarios are the seed file with one textual edit; the expected line:col is found by
// searching the edited text, never hard-coded, so a wrong mark fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/run_cli.h"
#include "tests/scenarios/bad_input_cases.h"

namespace moorsim::testing {
namespace {

using nlohmann::json;

// ---------------------------------------------------------------------------------------
// Helpers.

class CliTest : public ::testing::Test {
 protected:
  CliResult Run(const std::vector<std::string>& args) { return RunCli(args, dir_.path()); }
  std::filesystem::path Scratch(const std::string& name) const { return dir_.path() / name; }

  TempDirectory dir_{::testing::TempDir()};
};

std::size_t Count(const std::string& text, char c) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), c));
}

// Exit code 2 (bad input), nothing on stdout, and exactly one non-empty line on stderr that
// contains `flag` and at least one of `values` (the value as the user wrote it, or as the
// message spells it).
::testing::AssertionResult IsOneLineInputError(const CliResult& r, const std::string& flag,
                                               const std::vector<std::string>& values) {
  auto fail = [&](const std::string& why) {
    return ::testing::AssertionFailure() << why << "\n" << r.Describe();
  };
  if (r.signal != 0 || r.timed_out) return fail("moorsim crashed or hung");
  if (r.exit_code != 2) return fail("expected exit code 2 (bad input)");
  if (!r.out.empty()) return fail("expected nothing on stdout");
  if (r.err.empty() || r.err == "\n") return fail("expected a message on stderr");
  if (r.err.back() != '\n' || Count(r.err, '\n') != 1) {
    return fail("expected exactly one line on stderr");
  }
  if (r.err.find(flag) == std::string::npos)
    return fail("the message does not name '" + flag + "'");
  const bool names_value = std::any_of(values.begin(), values.end(), [&](const std::string& v) {
    return r.err.find(v) != std::string::npos;
  });
  if (!names_value) return fail("the message does not name the value '" + values.front() + "'");
  return ::testing::AssertionSuccess();
}

// "line:col" (both 1-based) of byte `offset` of `text`.
std::string LineCol(const std::string& text, std::size_t offset) {
  const std::size_t line = 1 + Count(text.substr(0, offset), '\n');
  const std::size_t line_start = text.rfind('\n', offset == 0 ? 0 : offset - 1);
  const std::size_t column =
      line_start == std::string::npos || offset == 0 ? offset + 1 : offset - line_start;
  return std::to_string(line) + ":" + std::to_string(column);
}

// ---------------------------------------------------------------------------------------
// 1. Scenarios the loader rejects: exit 2 and the loader's one-line message, via
//    `validate` and via `static`.

struct BadScenario {
  std::string name;
  std::string after;  // the edit is the first `old_text` at or after the first `after`
  std::string old_text;
  std::string new_text;
  std::string mark;         // the error's position is the first `mark` at or after `after`...
  std::size_t mark_offset;  // ...plus this many characters
  std::string message;      // what follows "<file>:<line>:<col>: "
  bool exact = true;        // false: `message` is only the start (yaml-cpp's own text follows)
};

// gtest prints parameters in test names and failures; the case name is enough.
void PrintTo(const BadScenario& c, std::ostream* os) { *os << c.name; }

std::string Distance(double dx, double dz) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", std::hypot(dx, dz));
  return buffer;
}

std::string Significant4(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

// Line 3 of the seed: anchor (-1950, 0, 1000), fairlead (-20, 0, 12) with the vessel at the
// origin; the straight distance is sqrt(1930^2 + 988^2) = 2168.2 m.
const std::string kLine3Distance = Distance(-1950.0 - -20.0, 1000.0 - 12.0);
// Chain of 0.08 m in water of 1025 kg/m^3 displaces 1025 pi 0.08^2 / 4 = 5.152 kg/m.
const std::string kDisplaced = Significant4(1025.0 * std::numbers::pi * 0.08 * 0.08 / 4.0);

std::vector<BadScenario> BadScenarios() {
  return {
      {"LengthShorterThanAnchorFairleadDistance", "- id: 3", "length: 2250", "length: 1800",
       "length: 1800", 8,
       "mooring.lines[3].length: 1800 m is shorter than the anchor-fairlead distance " +
           kLine3Distance + " m"},
      {"NegativeDiameter", "line_types:", "diameter: 0.08", "diameter: -0.08", "diameter: -0.08",
       10, "mooring.line_types[1].diameter: -0.08 m must be > 0"},
      {"ZeroSegments", "- id: 2", "segments: 50", "segments: 0", "segments: 0", 10,
       "mooring.lines[2].segments: 0 must be in 2..10000"},
      {"UnknownKey", "- id: 1", "length: 2250", "lenght: 2250", "lenght", 0,
       "mooring.lines[1]: unknown key 'lenght' (did you mean 'length'?)"},
      {"UnknownLineType", "- id: 4", "type: chain_seed", "type: chian_seed", "chian_seed", 0,
       "mooring.lines[4].type: unknown line type 'chian_seed' (known: chain_seed)"},
      // A stray ']' after line 1's fairlead list: yaml-cpp stops right on it.
      {"YamlSyntaxError", "- id: 1", "fairlead: [20, 0, 12]", "fairlead: [20, 0, 12]]", "12]]", 3,
       "YAML syntax error: ", false},
      // A missing key is reported at its parent: the entry's first key.
      {"MissingRequiredKey", "- id: 5", "      type: chain_seed\n", "", "id: 5", 0,
       "mooring.lines[5]: required key 'type' is missing"},
      {"AnchorBelowSeabed", "- id: 7", "anchor: [-1378.9, -1378.9, 1000]",
       "anchor: [-1378.9, -1378.9, 1000.5]", "[-1378.9, -1378.9, 1000.5]", 0,
       "mooring.lines[7].anchor: z = 1000.5 m is below the seabed at depth 1000 m"},
      {"LineWouldFloat", "line_types:", "mass_per_length: 275", "mass_per_length: 5",
       "mass_per_length: 5", 17,
       "mooring.line_types[1].mass_per_length: 5 kg/m must exceed the displaced water mass " +
           kDisplaced + " kg/m (the line would float)"},
      {"NegativeDragCoefficient", "line_types:", "drag_normal: 0.3", "drag_normal: -0.3",
       "drag_normal: -0.3", 13, "mooring.line_types[1].drag_normal: -0.3 must be >= 0"},
      {"SolverRtolOutOfRange", "solver:", "rtol: 1.0e-4", "rtol: 1.5", "rtol: 1.5", 6,
       "solver.rtol: 1.5 must be in (0, 1)"},
      {"QuotedNumber", "line_types:", "diameter: 0.08", "diameter: \"0.08\"", "\"0.08\"", 0,
       "mooring.line_types[1].diameter: \"0.08\" must be a number"},
  };
}

class CliBadScenario
    : public ::testing::TestWithParam<std::tuple<BadScenario, std::string /*command*/>> {
 protected:
  TempDirectory dir_{::testing::TempDir()};
};

TEST_P(CliBadScenario, ExitsWithCode2AndTheLoadersOneLineMessage) {
  const auto& [c, command] = GetParam();
  const std::string seed = ReadWholeFile(kSeed);
  ASSERT_FALSE(seed.empty()) << kSeed;

  const std::size_t from = seed.find(c.after);
  ASSERT_NE(from, std::string::npos) << "'" << c.after << "' is not in the seed";
  const std::size_t at = seed.find(c.old_text, from);
  ASSERT_NE(at, std::string::npos) << "'" << c.old_text << "' is not in the seed";
  std::string text = seed;
  text.replace(at, c.old_text.size(), c.new_text);
  // Written elsewhere, the scenario needs the hull's data where it is (the loader reports
  // every problem of a file, a missing WAMIT file among them).
  const std::string stem = "../../data/fpso_wamit/fpso";
  const std::size_t hydrodynamics = text.find(stem);
  ASSERT_NE(hydrodynamics, std::string::npos);
  text.replace(hydrodynamics, stem.size(), MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso");
  const std::size_t mark = text.find(c.mark, text.find(c.after));
  ASSERT_NE(mark, std::string::npos) << "'" << c.mark << "' is not in the edited text";

  const std::string path = (dir_.path() / "bad.yaml").string();
  WriteWholeFile(path, text);
  const CliResult r = RunCli({command, path}, dir_.path());

  const std::string expected =
      "moorsim: " + path + ":" + LineCol(text, mark + c.mark_offset) + ": " + c.message;
  ASSERT_TRUE(IsOneLineInputError(r, path, {c.message})) << "scenario edit: " << c.new_text;
  if (c.exact) {
    EXPECT_EQ(r.err, expected + "\n");
  } else {
    EXPECT_EQ(r.err.substr(0, expected.size()), expected) << r.err;
    EXPECT_GT(r.err.size(), expected.size() + 1) << "yaml-cpp's text is missing: " << r.err;
  }
}

INSTANTIATE_TEST_SUITE_P(Loader, CliBadScenario,
                         ::testing::Combine(::testing::ValuesIn(BadScenarios()),
                                            ::testing::Values(std::string("validate"),
                                                              std::string("static"))),
                         [](const ::testing::TestParamInfo<CliBadScenario::ParamType>& info) {
                           return std::get<0>(info.param).name + "_" + std::get<1>(info.param);
                         });

// Every input rule of the loader (the cases of tests/scenarios/bad_input_cases.h, each a
// one-spot edit of a valid scenario) through the real binary: exit code 2 and exactly the
// loader's one line, prefixed by the program name. Slow: 230 runs of the program, two
// minutes of CPU under the sanitizers, where the loader's rules run in process
// (BadScenario) and the program's path from loader to message in CliBadScenario.
class CliEveryLoaderRuleSlow
    : public ::testing::TestWithParam<::moorsim::scenarios::test_cases::BadInput> {
 protected:
  TempDirectory dir_{::testing::TempDir()};
};

TEST_P(CliEveryLoaderRuleSlow, ValidateExitsWithCode2AndTheLoadersMessage) {
  using namespace scenarios::test_cases;
  const BadInput& c = GetParam();
  const std::string text = Edit(kBase, c.after, c.old_text, c.new_text);
  const std::string path = (dir_.path() / "test.yaml").string();
  WriteWholeFile(path, text);
  const CliResult r = RunCli({"validate", path}, dir_.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err,
            "moorsim: " + path + ":" + PositionOf(text, c.after, c.at) + ": " + c.message + "\n");
  EXPECT_TRUE(r.out.empty()) << r.Describe();
}

std::string RuleName(
    const ::testing::TestParamInfo<::moorsim::scenarios::test_cases::BadInput>& info) {
  return info.param.name;
}

INSTANTIATE_TEST_SUITE_P(Parse, CliEveryLoaderRuleSlow,
                         ::testing::ValuesIn(::moorsim::scenarios::test_cases::kParseErrors),
                         RuleName);
INSTANTIATE_TEST_SUITE_P(Validate, CliEveryLoaderRuleSlow,
                         ::testing::ValuesIn(::moorsim::scenarios::test_cases::kValidationErrors),
                         RuleName);

TEST_F(CliTest, MissingScenarioFileIsExit2WithOneLine) {
  const std::string path = Scratch("no_such_scenario.yaml").string();
  for (const std::string command : {"validate", "static"}) {
    SCOPED_TRACE(command);
    const CliResult r = Run({command, path});
    ASSERT_TRUE(IsOneLineInputError(r, path, {"cannot open"}));
    EXPECT_EQ(r.err,
              "moorsim: " + path + ": cannot open the scenario file: No such file or directory\n");
  }
}

// A buoy on a tether longer than the water is deep: the static solve cannot leave it under
// water. static, simulate-lines and run each say so in one line at the point's entry.
TEST_F(CliTest, ABuoyThatWouldSurfaceIsOneLineAtThePoint) {
  const std::string path = Scratch("surfacing.yaml").string();
  std::ofstream(path) << R"(name: surfacing
mooring:
  water: {density: 1025, gravity: 9.81, depth: 100}
  line_types:
    - {name: chain, diameter: 0.08, mass_per_length: 275, axial_stiffness: 2.28785e8, drag_normal: 0.3, drag_tangential: 1.0, added_mass_normal: 1.5}
  points:
    - {name: buoy, position: [0, 0, 40], mass: 20000, volume: 120}
  lines:
    - {id: 1, type: chain, anchor: [5, 0, 100], to: buoy, length: 150, segments: 30}
)";
  const std::string expected = "moorsim: " + path +
                               ":7:7: mooring.points[1]: rises above the water at rest: its "
                               "buoyancy is more than its lines hold down below the surface\n";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"static", path},
        std::vector<std::string>{"simulate-lines", path, "--duration", "10", "--motion",
                                 "surge:1,20"}}) {
    const CliResult r = Run(args);
    EXPECT_TRUE(IsOneLineInputError(r, "mooring.points[1]", {"rises above the water"}));
    EXPECT_EQ(r.err, expected);
  }
}

TEST_F(CliTest, TopLevelHelpListsEachCommandOnOneLine) {
  const CliResult r = Run({"--help"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const std::string listing = r.out.substr(r.out.find("Subcommands:\n") + 13);
  std::istringstream lines(listing);
  std::vector<std::string> commands;
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    ASSERT_EQ(line.rfind("  ", 0), 0u) << line;
    ASSERT_NE(line[2], ' ') << "a continuation line: " << line;
    commands.push_back(line.substr(2, line.find(' ', 2) - 2));
  }
  EXPECT_EQ(commands, (std::vector<std::string>{"static", "run", "simulate-lines", "validate",
                                                "schema", "analyze", "detect", "monitor", "stream",
                                                "template", "import", "batch", "compare"}));
}

TEST_F(CliTest, AnEndlessInputIsRejectedNotReadForever) {
  const CliResult r = Run({"validate", "/dev/zero"});
  ASSERT_TRUE(IsOneLineInputError(r, "/dev/zero", {"larger than 4 MiB"}));
}

TEST_F(CliTest, ValidateAcceptsTheSeed) {
  const CliResult r = Run({"validate", kSeed});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(r.out, kSeed + ": ok (seed_tapm, 8 lines)\n");
}

TEST_F(CliTest, ValidateReportsEveryErrorOfTheFileEachOnItsOwnLine) {
  std::string text = ReadWholeFile(kSeed);
  for (const auto& [old_text, new_text] :
       {std::pair<std::string, std::string>{"depth: 1000}", "dept: 1000}"},
        {"diameter: 0.08", "diameter: -0.08"},
        {"max_order: 2", "max_order: 9"}}) {
    const std::size_t at = text.find(old_text);
    ASSERT_NE(at, std::string::npos) << old_text;
    text.replace(at, old_text.size(), new_text);
  }
  const std::string stem = "../../data/fpso_wamit/fpso";
  text.replace(text.find(stem), stem.size(), MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso");
  const std::string path = (dir_.path() / "three.yaml").string();
  WriteWholeFile(path, text);
  const CliResult r = Run({"validate", path});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.out, "");
  const auto at = [&](const std::string& what) {
    return "moorsim: " + path + ":" + LineCol(text, text.find(what)) + ": ";
  };
  EXPECT_EQ(r.err, at("dept: 1000}") +
                       "mooring.water: unknown key 'dept' (did you mean 'depth'?)\n" + at("-0.08") +
                       "mooring.line_types[1].diameter: -0.08 m must be > 0\n" + at("9\n") +
                       "solver.max_order: 9 must be in 1..5\n");
}

TEST_F(CliTest, ValidateRejectsACircularOrMissingBaseWithOneLocatedLine) {
  const std::string a = (dir_.path() / "a.yaml").string(), b = (dir_.path() / "b.yaml").string();
  WriteWholeFile(a, "base: b.yaml\n");
  WriteWholeFile(b, "# the other half\nbase: a.yaml\n");
  CliResult r = Run({"validate", a});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err,
            "moorsim: " + b + ":2:7: base: 'a.yaml' includes itself: a.yaml -> b.yaml -> a.yaml\n");
  WriteWholeFile(a, "base: gone.yaml\n");
  r = Run({"validate", a});
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: " + a + ":1:7: base: 'gone.yaml': no such file (" +
                       (dir_.path() / "gone.yaml").string() + ")\n");
}

TEST_F(CliTest, ValidateResolvedPrintsTheMergedScenario) {
  const CliResult r = Run(
      {"validate", "--resolved", kSeed.substr(0, kSeed.rfind('/')) + "/thesis_line6_current.yaml"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.out.find("base:"), std::string::npos);
  EXPECT_NE(r.out.find("failure: {line: 6, time: 400, mode: fairlead}"), std::string::npos);
  EXPECT_NE(r.out.find("direction_deg: 315"), std::string::npos);
  EXPECT_NE(r.out.find("line_types:"), std::string::npos);
}

// ---------------------------------------------------------------------------------------
// 2. Flag errors: exit 2 and one line that names the flag and the value.

struct FlagCase {
  std::string name;
  std::vector<std::string> args;    // "SEED" is replaced by seed_tapm.yaml's path
  std::string flag;                 // what the message must name
  std::vector<std::string> values;  // ...and at least one of these
};

void PrintTo(const FlagCase& c, std::ostream* os) { *os << c.name; }

// A short dynamic run for the simulate-lines cases that get past flag parsing.
std::vector<std::string> SimulateLines(std::vector<std::string> extra) {
  std::vector<std::string> args = {"simulate-lines", "SEED", "--segments", "10", "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

std::vector<FlagCase> FlagCases() {
  return {
      {"StaticOffsetTwoNumbers", {"static", "SEED", "--offset", "1,2"}, "--offset", {"1,2"}},
      {"StaticOffsetNotNumbers", {"static", "SEED", "--offset", "a,b,c"}, "--offset", {"a"}},
      {"StaticBrokenLine9", {"static", "SEED", "--broken", "9"}, "--broken", {"9"}},
      {"StaticBrokenLine0", {"static", "SEED", "--broken", "0"}, "--broken", {"0"}},
      {"StaticBrokenFraction", {"static", "SEED", "--broken", "1.5"}, "--broken", {"1.5"}},
      {"StaticBrokenEmpty", {"static", "SEED", "--broken", ""}, "--broken", {"''"}},
      // 400 m north: line 3 would have to stretch 12 % to reach its fairlead.
      {"StaticOffsetUnreachable",
       {"static", "SEED", "--offset", "400,0,0"},
       "--offset",
       {"400,0,0", "line 3", "cannot reach"}},
      {"StaticUnknownFlag", {"static", "SEED", "--bogus"}, "--bogus", {"--bogus"}},
      {"StaticMissingScenario", {"static"}, "scenario", {"required"}},
      {"UnknownSubcommand", {"bogus", "SEED"}, "bogus", {"bogus"}},
      {"SimulateLinesMotionUnknownDof",
       SimulateLines({"--motion", "bob:1,2", "--duration", "1"}),
       "--motion",
       {"bob"}},
      {"SimulateLinesRollBeyondNinetyDegrees",
       SimulateLines({"--motion", "roll:120,10", "--duration", "1"}),
       "--motion",
       {"120 deg"}},
      {"SimulateLinesMotionAndMotionFile",
       SimulateLines({"--motion", "surge:2,20", "--motion-file", "m.csv", "--duration", "1"}),
       "--motion-file",
       {"give one or more"}},
      {"SimulateLinesMotionFileMissing",
       SimulateLines({"--motion-file", "nowhere.csv", "--duration", "1"}),
       "--motion-file",
       {"nowhere.csv"}},
      {"SimulateLinesMotionOddNumbers",
       SimulateLines({"--motion", "surge:1", "--duration", "1"}),
       "--motion",
       {"surge:1"}},
      {"SimulateLinesMotionNegativePeriod",
       SimulateLines({"--motion", "surge:1,-5", "--duration", "1"}),
       "--motion",
       {"-5"}},
      {"SimulateLinesNegativeDuration",
       SimulateLines({"--motion", "surge:2,20", "--duration", "-1"}),
       "--duration",
       {"-1"}},
      {"SimulateLinesDurationNotANumber",
       SimulateLines({"--motion", "surge:2,20", "--duration", "abc"}),
       "--duration",
       {"abc"}},
      {"SimulateLinesPartLine9",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--part", "9:10"}),
       "--part",
       {"9"}},
      {"SimulateLinesPartNegativeTime",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--part", "1:-1"}),
       "--part",
       {"-1"}},
      {"SimulateLinesPartUnknownMode",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--part", "1:0.5:middle"}),
       "--part",
       {"middle"}},
      // Node 0 is the anchor, not an internal node: bad input whether or not the part time
      // falls inside the run. (Here it falls after the end of the run.)
      {"SimulateLinesPartNode0AfterTheRun",
       SimulateLines({"--motion", "surge:2,20", "--duration", "4", "--part", "1:10:node=0"}),
       "--part",
       {"node=0", "node 0"}},
      // ...and here inside it.
      {"SimulateLinesPartNode0DuringTheRun",
       SimulateLines({"--motion", "surge:2,20", "--duration", "2", "--part", "1:1:node=0"}),
       "--part",
       {"node=0", "node 0"}},
      // A node number must be an integer, not silently truncated.
      {"SimulateLinesPartNodeFraction",
       SimulateLines({"--motion", "surge:2,20", "--duration", "2", "--part", "1:1:node=1.5"}),
       "--part",
       {"1.5"}},
      // LINE is one number, not a list of which only the first is used.
      {"SimulateLinesPartLineList",
       SimulateLines({"--motion", "surge:2,20", "--duration", "2", "--part", "1,2:1"}),
       "--part",
       {"1,2"}},
      {"SimulateLinesSegments1",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--segments", "1"}),
       "--segments",
       {"1"}},
      {"SimulateLinesNegativeOutputInterval",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--output-interval", "-1"}),
       "--output-interval",
       {"-1"}},
      {"SimulateLinesNegativeToleranceScale",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--tolerance-scale", "-1"}),
       "--tolerance-scale",
       {"-1"}},
      {"SimulateLinesMissingMotion",
       SimulateLines({"--duration", "1"}),
       "--motion",
       {"give one or more"}},
      // An empty value, a trailing comma or a repeated line is an error, never "not given".
      {"RunEmptyDuration", {"run", "SEED", "--duration", ""}, "--duration", {"empty"}},
      {"RunEmptySeed", {"run", "SEED", "--seed", ""}, "--seed", {"empty"}},
      {"RunEmptyOut", {"run", "SEED", "--out", ""}, "--out", {"empty"}},
      {"StaticOffsetTrailingComma",
       {"static", "SEED", "--offset", "1,2,3,"},
       "--offset",
       {"empty item", "1,2,3,"}},
      {"StaticBrokenTrailingComma", {"static", "SEED", "--broken", "1,"}, "--broken", {"1,"}},
      {"StaticBrokenTwice", {"static", "SEED", "--broken", "1,1"}, "--broken", {"given twice"}},
      {"StaticSetUnknownKey",
       {"static", "SEED", "--set", "mooring.water.dept=1000"},
       "unknown key 'dept'",
       {"depth"}},
      {"SimulateLinesMotionTrailingComma",
       SimulateLines({"--motion", "surge:2,20,", "--duration", "1"}),
       "--motion",
       {"empty item"}},
      {"SimulateLinesSegments0",
       {"simulate-lines", "SEED", "--motion", "surge:2,20", "--duration", "1", "--segments", "0"},
       "--segments",
       {"0"}},
      {"SimulateLinesTinyOutputInterval",
       SimulateLines({"--motion", "surge:2,20", "--duration", "5", "--output-interval", "1e-9"}),
       "--output-interval",
       {"1e-09", "at most 1e7"}},
      {"SimulateLinesSetUnknownKey",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--set", "solver.rtl=1e-4"}),
       "unknown key 'rtl'",
       {"rtol"}},
      {"SimulateLinesMissingDuration",
       SimulateLines({"--motion", "surge:2,20"}),
       "--duration",
       {"required"}},
      // Nonsense that would otherwise reach the integrator and come back as its failure.
      {"SimulateLinesMotionVanishingPeriod",
       SimulateLines({"--motion", "surge:5,1e-300", "--duration", "1"}),
       "--motion",
       {"period 1e-300 s must be in 0.1..1e+06 s"}},
      {"SimulateLinesMotionHugeAmplitude",
       SimulateLines({"--motion", "surge:1e9,20", "--duration", "1"}),
       "--motion",
       {"amplitude 1e+09 m"}},
      {"SimulateLinesToleranceScaleInfinite",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--tolerance-scale", "inf"}),
       "--tolerance-scale",
       {"'inf'"}},
      {"SimulateLinesToleranceScaleHuge",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--tolerance-scale", "1e300"}),
       "--tolerance-scale",
       {"1e300 makes solver.rtol"}},
      {"SimulateLinesToleranceScaleTiny",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--tolerance-scale", "1e-20"}),
       "--tolerance-scale",
       {"1e-20 makes solver.rtol"}},
      // Empty values are errors, not zeros.
      {"SimulateLinesEmptyDuration",
       SimulateLines({"--motion", "surge:2,20", "--duration", ""}),
       "--duration",
       {"''"}},
      {"SimulateLinesEmptyToleranceScale",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--tolerance-scale", ""}),
       "--tolerance-scale",
       {"''"}},
      {"SimulateLinesEmptySegments",
       {"simulate-lines", "SEED", "--motion", "surge:2,20", "--duration", "1", "--segments", ""},
       "--segments",
       {"''"}},
      {"SimulateLinesEmptyOut",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--out", ""}),
       "--out",
       {"empty"}},
      {"SimulateLinesOutIsAFolder",
       SimulateLines({"--motion", "surge:2,20", "--duration", "1", "--out", "/tmp"}),
       "--out",
       {"'/tmp' is a folder"}},
  };
}

class CliFlagError : public ::testing::TestWithParam<FlagCase> {
 protected:
  TempDirectory dir_{::testing::TempDir()};
};

TEST_P(CliFlagError, ExitsWithCode2AndOneLineNamingFlagAndValue) {
  std::vector<std::string> args = GetParam().args;
  for (std::string& a : args) {
    if (a == "SEED") a = kSeed;
  }
  const CliResult r = RunCli(args, dir_.path());
  EXPECT_TRUE(IsOneLineInputError(r, GetParam().flag, GetParam().values));
}

INSTANTIATE_TEST_SUITE_P(Flags, CliFlagError, ::testing::ValuesIn(FlagCases()),
                         [](const ::testing::TestParamInfo<FlagCase>& info) {
                           return info.param.name;
                         });

// ---------------------------------------------------------------------------------------
// 3. `static --json`.

// The seed case's geometry (scenarios/library/seed_tapm.yaml), horizontal only [m]: anchors in
// the Earth frame, fairleads in the body frame.
constexpr double kDiag = 14.142135623730951;
constexpr std::array<std::array<double, 2>, 8> kAnchors = {{{1950, 0},
                                                            {0, 1950},
                                                            {-1950, 0},
                                                            {0, -1950},
                                                            {1378.9, 1378.9},
                                                            {-1378.9, 1378.9},
                                                            {-1378.9, -1378.9},
                                                            {1378.9, -1378.9}}};
constexpr std::array<std::array<double, 2>, 8> kFairleads = {{{20, 0},
                                                              {0, 20},
                                                              {-20, 0},
                                                              {0, -20},
                                                              {kDiag, kDiag},
                                                              {-kDiag, kDiag},
                                                              {-kDiag, -kDiag},
                                                              {kDiag, -kDiag}}};

// The analytic elastic catenary for lines 1-4 (anchor 1930 m out and 988 m down from the
// fairlead, 2250 m of 2647.2 N/m chain, EA 2.28785e8 N): 6.059 MN at the fairlead.
constexpr double kCatenaryFairleadTension = 6.059e6;

class CliStatic : public CliTest {
 protected:
  // Runs `static SEED --json extra...`, expects success and one JSON object on stdout.
  json RunJson(std::vector<std::string> extra) {
    std::vector<std::string> args = {"static", kSeed, "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliResult r = Run(args);
    EXPECT_EQ(r.exit_code, 0) << r.Describe();
    EXPECT_EQ(r.err, "") << r.Describe();
    json j = json::parse(r.out, nullptr, /*allow_exceptions=*/false);
    EXPECT_FALSE(j.is_discarded()) << "stdout is not one JSON document:\n" << r.out;
    EXPECT_TRUE(j.is_object()) << r.out;
    return j;
  }

  // Shape common to every --json answer: 8 lines with ids 1..8 and the documented keys,
  // and a 3-number net_force.
  void ExpectShape(const json& j) {
    ASSERT_TRUE(j.contains("lines") && j["lines"].is_array()) << j.dump(2);
    ASSERT_EQ(j["lines"].size(), 8u) << j.dump(2);
    for (std::size_t i = 0; i < 8; ++i) {
      const json& line = j["lines"][i];
      EXPECT_EQ(line.value("id", -1), static_cast<int>(i) + 1) << line.dump();
      for (const char* key :
           {"fairlead_tension", "horizontal_tension", "vertical_tension", "grounded_length"}) {
        ASSERT_TRUE(line.contains(key) && line[key].is_number()) << key << " in " << line.dump();
        EXPECT_TRUE(std::isfinite(line[key].get<double>())) << key << " in " << line.dump();
      }
    }
    ASSERT_TRUE(j.contains("net_force") && j["net_force"].is_array()) << j.dump(2);
    ASSERT_EQ(j["net_force"].size(), 3u) << j.dump(2);
    for (const json& v : j["net_force"]) ASSERT_TRUE(v.is_number()) << j["net_force"].dump();
  }
};

TEST_F(CliStatic, SeedJsonMatchesCatenaryAndSymmetry) {
  const json j = RunJson({});
  ASSERT_NO_FATAL_FAILURE(ExpectShape(j));
  for (const json& line : j["lines"]) {
    for (const char* key :
         {"fairlead_tension", "horizontal_tension", "vertical_tension", "grounded_length"}) {
      EXPECT_GT(line[key].get<double>(), 0.0) << key << " in " << line.dump();
    }
  }
  // Lines 1-4 against the analytic catenary (6.059 MN to the 4 figures docs/design.md
  // section 9 gives, 0.01 %): 0.1 % leaves room for the FEM's 50-segment discretisation and the
  // seabed penalty's sink, and still catches the wrong end of the line (the top segment's
  // midpoint tension is 0.8 % lower, docs/design.md section 8.4).
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(j["lines"][i]["fairlead_tension"].get<double>(), kCatenaryFairleadTension,
                1e-3 * kCatenaryFairleadTension)
        << "line " << i + 1;
  }
  // The spread is point-symmetric: line k and line k+2 (1-3, 2-4, 5-7, 6-8) are the same
  // line turned by 180 degrees, so their forces cancel exactly up to round-off, and every
  // line pulls along its own fairlead's radius (no moment). The diagonal lines (anchor
  // radius 1950.05 m) differ from the axis lines (1950 m) by ~1 kN, so a mistake that
  // mixes the groups would show as ~1 kN; round-off on 3.5 MN terms is ~1e-9 N. 1 N
  // (and 1 N m) separates the two by orders of magnitude.
  const json& f = j["net_force"];
  EXPECT_NEAR(f[0].get<double>(), 0.0, 1.0) << f.dump();
  EXPECT_NEAR(f[1].get<double>(), 0.0, 1.0) << f.dump();
  EXPECT_NEAR(f[2].get<double>(), 0.0, 1.0) << f.dump();
}

TEST_F(CliStatic, BrokenLine6PullsAwayFromItsAnchor) {
  const json intact = RunJson({});
  const json j = RunJson({"--broken", "6"});
  ASSERT_NO_FATAL_FAILURE(ExpectShape(intact));
  ASSERT_NO_FATAL_FAILURE(ExpectShape(j));
  EXPECT_EQ(j["lines"][5]["fairlead_tension"].get<double>(), 0.0) << j["lines"][5].dump();
  const double fx = j["net_force"][0].get<double>();
  const double fy = j["net_force"][1].get<double>();
  // Line 6's anchor is at (-1378.9, 1378.9): without it, its opposite line 8 is unbalanced
  // and the net force points along (+1, -1), away from line 6's anchor.
  EXPECT_GT(fx, 0.0);
  EXPECT_LT(fy, 0.0);
  EXPECT_LT(fx * kAnchors[5][0] + fy * kAnchors[5][1], 0.0);
  const double magnitude = std::hypot(fx, fy);
  EXPECT_NEAR(magnitude, 3.5e6, 0.01 * 3.5e6);
  // Exactly: the other lines sit where they did, so the net force is line 8's horizontal
  // pull, i.e. minus line 6's intact one. The settle stops at residual node forces of
  // ~1e-6 N; 10 N is 3e-6 of it.
  EXPECT_NEAR(magnitude, intact["lines"][5]["horizontal_tension"].get<double>(), 10.0);
  EXPECT_NEAR(fx, -fy, 10.0);
  EXPECT_NEAR(j["net_force"][2].get<double>(), 0.0, 1.0);
}

TEST_F(CliStatic, OffsetNorthIsRestoredAndNetForceIsTheSumOfTheLines) {
  const json j = RunJson({"--offset", "10,0,0"});
  ASSERT_NO_FATAL_FAILURE(ExpectShape(j));
  const double fx = j["net_force"][0].get<double>();
  const double fy = j["net_force"][1].get<double>();
  const double mz = j["net_force"][2].get<double>();
  EXPECT_LT(fx, 0.0) << "10 m north of the origin, the mooring must pull back south";
  // Mirror symmetry about the x axis (2-4, 5-8, 6-7): no sideways force, no yaw moment.
  EXPECT_NEAR(fy, 0.0, 1.0);
  EXPECT_NEAR(mz, 0.0, 1.0);

  // Sum of the lines: with no current every line hangs in the vertical plane through its
  // anchor and fairlead, so its horizontal pull on the vessel points from the fairlead to
  // the anchor.
  double sum_x = 0.0, sum_y = 0.0, sum_mz = 0.0;
  for (std::size_t i = 0; i < 8; ++i) {
    const double h = j["lines"][i]["horizontal_tension"].get<double>();
    const double px = kFairleads[i][0] + 10.0, py = kFairleads[i][1];  // heading 0
    const double dx = kAnchors[i][0] - px, dy = kAnchors[i][1] - py;
    const double n = std::hypot(dx, dy);
    const double lx = h * dx / n, ly = h * dy / n;
    sum_x += lx;
    sum_y += ly;
    sum_mz += kFairleads[i][0] * ly - kFairleads[i][1] * lx;  // arm from the reference point
  }
  // The net force is a difference of ~3.5 MN pulls, ~0.8 MN here; the per-line numbers
  // carry full double precision, so agreement to 1 N (1e-6 of the net force) is round-off
  // plus the static settle's residual.
  EXPECT_NEAR(fx, sum_x, 1.0);
  EXPECT_NEAR(fy, sum_y, 1.0);
  EXPECT_NEAR(mz, sum_mz, 1.0);
}

// ---------------------------------------------------------------------------------------
// 4. `simulate-lines` CSV.

std::vector<std::string> SplitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::vector<std::string> SplitCommas(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

TEST_F(CliTest, SimulateLinesWritesTensionCsv) {
  const std::string csv = Scratch("tensions.csv").string();
  const CliResult r = Run({"simulate-lines", kSeed, "--motion", "surge:2,20", "--duration", "4",
                           "--out", csv, "--segments", "10", "--quiet"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_EQ(r.err, "") << "--quiet run wrote to stderr";
  EXPECT_NE(r.out.find("real time"), std::string::npos) << r.out;

  const std::vector<std::string> lines = SplitLines(ReadWholeFile(csv));
  std::size_t i = 0;
  while (i < lines.size() && !lines[i].empty() && lines[i][0] == '#') ++i;
  EXPECT_GE(i, 1u) << "no '#' comment header";
  ASSERT_LT(i, lines.size()) << "no column header";
  EXPECT_EQ(lines[i], "time,line1,line2,line3,line4,line5,line6,line7,line8");
  ++i;

  // Rows every 0.5 s from 0 through 4 s. The seed case's static tension is 6.06 MN; 2 m of
  // surge moves it by ~2 % (10 m of offset moves line 1 by 3 %), so every value within
  // 10 % of it is physical and a unit or sign slip is not.
  ASSERT_EQ(lines.size() - i, 9u) << "expected rows at t = 0, 0.5, ..., 4";
  for (int k = 0; k <= 8; ++k, ++i) {
    SCOPED_TRACE("row " + lines[i]);
    const std::vector<std::string> fields = SplitCommas(lines[i]);
    ASSERT_EQ(fields.size(), 9u);
    EXPECT_NEAR(std::stod(fields[0]), 0.5 * k, 1e-9);
    for (std::size_t c = 1; c < fields.size(); ++c) {
      const double tension = std::stod(fields[c]);
      EXPECT_TRUE(std::isfinite(tension));
      EXPECT_GT(tension, 0.0);
      EXPECT_NEAR(tension, 6.06e6, 0.1 * 6.06e6) << "line " << c;
    }
  }
}

// A full disk (here /dev/full) is a failure naming the file, never exit 0 with a cut table.
TEST_F(CliTest, SimulateLinesOnAFullDiskFailsNamingTheFile) {
  const CliResult r = Run({"simulate-lines", kSeed, "--motion", "surge:2,20", "--duration", "20",
                           "--out", "/dev/full", "--segments", "10", "--quiet"});
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_NE(r.err.find("--out '/dev/full': write failed: No space left on device"),
            std::string::npos)
      << r.Describe();
}

// A run that fails leaves no table under the name asked for (it is written aside and named
// once complete).
TEST_F(CliTest, SimulateLinesThatFailsLeavesNoCsv) {
  const std::filesystem::path csv = Scratch("failed.csv");
  // One solver step allowed between two rows: the solver gives up once the CSV is open.
  const CliResult r =
      Run({"simulate-lines", kSeed, "--motion", "surge:2,20", "--duration", "2", "--out",
           csv.string(), "--segments", "10", "--quiet", "--set", "solver.max_steps=1"});
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_FALSE(std::filesystem::exists(csv));
  EXPECT_FALSE(std::filesystem::exists(csv.string() + ".partial"));
}

// A number too small for a normal double is read as the nearest double, not refused as
// "not a finite number".
TEST_F(CliTest, ANumberBelowTheNormalRangeReadsAsTheNearestDouble) {
  const CliResult r = Run({"static", kSeed, "--offset", "1e-320,0,0"});
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
}

// ---------------------------------------------------------------------------------------
// 5. Help.

TEST_F(CliTest, HelpListsTheSubcommands) {
  const CliResult r = Run({"--help"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  for (const char* word : {"static", "simulate-lines", "validate"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word << " missing from\n" << r.out;
  }
}

TEST_F(CliTest, StaticHelpSaysHowItIsComputed) {
  const CliResult r = Run({"static", "--help"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  for (const char* word : {"Newton", "catenary", "--offset", "--broken", "--json"}) {
    EXPECT_NE(r.out.find(word), std::string::npos) << word << " missing from\n" << r.out;
  }
}

TEST_F(CliTest, VersionExitsZero) {
  const CliResult r = Run({"--version"});
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_FALSE(r.out.empty());
}

}  // namespace
}  // namespace moorsim::testing
