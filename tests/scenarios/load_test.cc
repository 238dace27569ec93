// Scenario loading: the seed file's numbers, defaults, unit conversion, and one test per
// input error, each asserting the whole one-line message. Expected positions are found
// by searching the test's own YAML text, not taken from yaml-cpp, so a wrong mark fails.
#include "scenarios/load.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "bad_input_cases.h"
#include "core/error.h"

namespace moorsim::scenarios {
namespace {

using test_cases::BadInput;
using test_cases::Edit;
using test_cases::kBase;
using test_cases::kParseErrors;
using test_cases::kValidationErrors;
using test_cases::PositionOf;

std::string ErrorOf(const std::string& text) {
  try {
    ParseScenario(text, "test.yaml");
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return std::string("not an InputError: ") + error.what();
  }
  return "(no error)";
}

std::string ValidateError(const Scenario& scenario) {
  try {
    Validate(scenario);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

std::string ReadFile(const std::string& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// ---------------------------------------------------------------------------------------
// The seed case.

const std::string kSeedPath = std::string(MOORSIM_SOURCE_DIR) + "/scenarios/library/seed_tapm.yaml";

TEST(SeedScenario, HasTheReferenceNumbers) {
  const Scenario seed = LoadScenario(kSeedPath);
  EXPECT_EQ(seed.name, "seed_tapm");
  EXPECT_EQ(seed.source_path, kSeedPath);
  EXPECT_EQ(seed.text, ReadFile(kSeedPath));

  const MooringSpec& mooring = seed.mooring;
  EXPECT_EQ(mooring.water.density, 1025.0);
  EXPECT_EQ(mooring.water.gravity, 9.81);
  EXPECT_EQ(mooring.water.depth, 1000.0);
  EXPECT_TRUE(mooring.current.depth.empty());  // no current in the seed case

  ASSERT_EQ(mooring.line_types.size(), 1u);
  const LineType& chain = mooring.line_types[0];
  EXPECT_EQ(chain.name, "chain_seed");
  EXPECT_EQ(chain.diameter, 0.08);
  EXPECT_EQ(chain.mass_per_length, 275.0);
  EXPECT_DOUBLE_EQ(chain.axial_stiffness, 4.5757e10 * 0.005);
  EXPECT_EQ(chain.drag_normal, 0.3);
  EXPECT_EQ(chain.drag_tangential, 1.0);
  EXPECT_EQ(chain.added_mass_normal, 1.5);
  EXPECT_EQ(chain.axial_damping_ratio, 0.5);
  EXPECT_FALSE(chain.axial_damping.has_value());
  EXPECT_EQ(chain.friction_axial, 0.5);
  EXPECT_EQ(chain.friction_lateral, 1.0);

  // TAPM thesis table 4.2, z = +1000 in NED (the thesis prints -1000, z up).
  const double anchors[8][2] = {{1950, 0},          {0, 1950},        {-1950, 0},
                                {0, -1950},         {1378.9, 1378.9}, {-1378.9, 1378.9},
                                {-1378.9, -1378.9}, {1378.9, -1378.9}};
  ASSERT_EQ(mooring.lines.size(), 8u);
  for (int k = 0; k < 8; ++k) {
    SCOPED_TRACE("line " + std::to_string(k + 1));
    const LineSpec& line = mooring.lines[k];
    EXPECT_EQ(line.id, k + 1);
    EXPECT_EQ(line.type, "chain_seed");
    EXPECT_EQ(line.length, 2250.0);
    EXPECT_EQ(line.segments, 50);
    EXPECT_EQ(line.anchor, Vec3(anchors[k][0], anchors[k][1], 1000.0));
    // On the 20 m turret at 12 m draught, on the horizontal ray toward the anchor. The
    // file gives 20/sqrt(2) to 17 digits, so radius and direction hold to rounding.
    const Vec3& fairlead = line.fairlead_body;
    EXPECT_EQ(fairlead.z(), 12.0);
    EXPECT_NEAR(fairlead.head<2>().norm(), 20.0, 1e-12);
    const Eigen::Vector2d toward_anchor = line.anchor.head<2>().normalized();
    EXPECT_NEAR(fairlead.head<2>().dot(toward_anchor), 20.0, 1e-12);
  }

  // Seabed and solver blocks are written out with the defaults.
  const Seabed default_seabed;
  EXPECT_EQ(mooring.seabed.stiffness, default_seabed.stiffness);
  EXPECT_EQ(mooring.seabed.damping, default_seabed.damping);
  EXPECT_EQ(mooring.seabed.friction_velocity, default_seabed.friction_velocity);
  const SolverSpec default_solver;
  EXPECT_EQ(seed.solver.rtol, default_solver.rtol);
  EXPECT_EQ(seed.solver.atol_position, default_solver.atol_position);
  EXPECT_EQ(seed.solver.atol_velocity, default_solver.atol_velocity);
  EXPECT_EQ(seed.solver.max_order, default_solver.max_order);
  EXPECT_EQ(seed.solver.stability_limit_detection, default_solver.stability_limit_detection);
  EXPECT_EQ(seed.solver.max_step, default_solver.max_step);
}

// ---------------------------------------------------------------------------------------
// Reading valid text.

TEST(ParseScenario, ReadsEveryKeyOfTheBaseText) {
  const Scenario s = ParseScenario(kBase, "dir/test.yaml");
  EXPECT_EQ(s.name, "base");
  EXPECT_EQ(s.source_path, "dir/test.yaml");
  EXPECT_EQ(s.text, kBase);
  EXPECT_EQ(s.mooring.seabed.stiffness, 3.0e6);
  EXPECT_EQ(s.mooring.current.depth, (std::vector<double>{0, 500}));
  EXPECT_EQ(s.mooring.current.speed, (std::vector<double>{0.2, 0.1}));
  ASSERT_EQ(s.mooring.line_types.size(), 2u);
  const LineType& wire = s.mooring.line_types[1];
  EXPECT_EQ(wire.axial_damping, 1.0e5);
  EXPECT_FALSE(wire.axial_damping_ratio.has_value());  // no default ratio beside a given c
  EXPECT_EQ(wire.friction_axial, 0.0);
  EXPECT_EQ(wire.friction_lateral, 0.0);
  ASSERT_EQ(s.mooring.lines.size(), 3u);
  EXPECT_EQ(s.mooring.lines[0].segments, 30);  // its own
  EXPECT_EQ(s.mooring.lines[1].segments, 40);  // mooring.defaults.segments
  EXPECT_EQ(s.solver.atol_velocity, 2.0e-3);
  EXPECT_EQ(s.solver.max_order, 4);
  EXPECT_FALSE(s.solver.stability_limit_detection);
  EXPECT_EQ(s.solver.max_step, 0.5);
}

TEST(ParseScenario, DefaultsApplyToEverythingOptional) {
  const std::string minimal = R"(mooring:
  water: {depth: 300}
  line_types:
    - {name: c, diameter: 0.1, mass_per_length: 200, axial_stiffness: 1e9, drag_normal: 1,
       drag_tangential: 0.5, added_mass_normal: 1}
  lines:
    - {type: c, anchor: [800, 0, 300], fairlead: [10, 0, 10], length: 1000}
    - {type: c, anchor: [-800, 0, 300], fairlead: [-10, 0, 10], length: 1000}
)";
  const Scenario s = ParseScenario(minimal, "cases/minimal.yaml");
  EXPECT_EQ(s.name, "minimal");  // the file stem
  EXPECT_EQ(s.mooring.water.density, 1025.0);
  EXPECT_EQ(s.mooring.water.gravity, 9.81);
  EXPECT_EQ(s.mooring.seabed.stiffness, 3.0e6);
  EXPECT_EQ(s.mooring.seabed.damping, 3.0e5);
  EXPECT_EQ(s.mooring.seabed.contact_smoothing, 0.5);
  EXPECT_EQ(s.mooring.seabed.friction_velocity, 0.1);
  EXPECT_TRUE(s.mooring.current.depth.empty());
  EXPECT_TRUE(s.mooring.current.speed.empty());
  const LineType& type = s.mooring.line_types[0];
  EXPECT_EQ(type.axial_damping_ratio, 0.5);
  EXPECT_FALSE(type.axial_damping.has_value());
  EXPECT_EQ(type.friction_axial, 0.0);
  EXPECT_EQ(type.friction_lateral, 0.0);
  ASSERT_EQ(s.mooring.lines.size(), 2u);
  EXPECT_EQ(s.mooring.lines[0].id, 1);  // position in the list, from 1
  EXPECT_EQ(s.mooring.lines[1].id, 2);
  EXPECT_EQ(s.mooring.lines[0].segments, 50);
  EXPECT_EQ(s.solver.rtol, 1e-4);
  EXPECT_EQ(s.solver.atol_position, 1e-3);
  EXPECT_EQ(s.solver.atol_velocity, 1e-3);
  EXPECT_EQ(s.solver.max_order, 2);
  EXPECT_FALSE(s.solver.stability_limit_detection);
  EXPECT_EQ(s.solver.max_step, 0.0);
}

TEST(ParseScenario, ConvertsDegreesToRadians) {
  EXPECT_DOUBLE_EQ(ParseScenario(kBase, "test.yaml").mooring.current.direction,
                   std::numbers::pi / 2);
  const std::string toward_north_west = Edit(kBase, "", "direction_deg: 90", "direction_deg: 315");
  EXPECT_DOUBLE_EQ(ParseScenario(toward_north_west, "test.yaml").mooring.current.direction,
                   7 * std::numbers::pi / 4);
}

TEST(ParseScenario, RecordsWhereValuesWereWritten) {
  const Scenario s = ParseScenario(kBase, "test.yaml");
  const LineSpec& line2 = s.mooring.lines[1];
  EXPECT_EQ(std::to_string(line2.length_mark.line) + ":" + std::to_string(line2.length_mark.column),
            PositionOf(kBase, "- id: 2", "length: ^2250"));
  EXPECT_EQ(std::to_string(line2.mark.line) + ":" + std::to_string(line2.mark.column),
            PositionOf(kBase, "", "id: 2"));
  const SourceMark diameter = s.marks.at("mooring.line_types[2].diameter");
  EXPECT_EQ(std::to_string(diameter.line) + ":" + std::to_string(diameter.column),
            PositionOf(kBase, "- name: wire", "diameter: ^0.1"));
}

TEST(ParseScenario, OrdersLinesByIdAndNamesEntriesAsWritten) {
  std::string swapped = Edit(kBase, "", "- id: 1", "- id: 3");
  swapped = Edit(swapped, "type: wire", "- id: 3", "- id: 1");
  const Scenario s = ParseScenario(swapped, "test.yaml");
  ASSERT_EQ(s.mooring.lines.size(), 3u);
  EXPECT_EQ(s.mooring.lines[0].id, 1);
  EXPECT_EQ(s.mooring.lines[0].anchor.x(), -1950.0);  // written third
  EXPECT_EQ(s.mooring.lines[0].entry, 3);
  EXPECT_EQ(s.mooring.lines[2].anchor.x(), 1950.0);  // written first

  // Checks after sorting still name the entry the user wrote, at its position.
  Scenario changed = s;
  changed.mooring.lines[0].length = 100;
  EXPECT_EQ(ValidateError(changed),
            "test.yaml:" + PositionOf(swapped, "- id: 1", "length: ^2250") +
                ": mooring.lines[3].length: 100 m is shorter than the anchor-fairlead distance "
                "2168.2 m");
}

// ---------------------------------------------------------------------------------------
class BadScenario : public testing::TestWithParam<BadInput> {};

TEST_P(BadScenario, GivesOneLineWithPlaceKeyValueAndRule) {
  const BadInput& input = GetParam();
  const std::string text = Edit(kBase, input.after, input.old_text, input.new_text);
  EXPECT_EQ(ErrorOf(text),
            "test.yaml:" + PositionOf(text, input.after, input.at) + ": " + input.message);
}

std::string CaseName(const testing::TestParamInfo<BadInput>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Parse, BadScenario, ::testing::ValuesIn(kParseErrors), CaseName);

INSTANTIATE_TEST_SUITE_P(Validate, BadScenario, ::testing::ValuesIn(kValidationErrors), CaseName);

// Errors that need more than one edit of the base text.

TEST(BadScenarioText, MissingKeyIsReportedAtItsParent) {
  const std::size_t lines = kBase.find("  lines:");
  const std::size_t solver = kBase.find("solver:");
  const std::string text = kBase.substr(0, lines) + kBase.substr(solver);
  // A block map's position is its first key.
  EXPECT_EQ(ErrorOf(text), "test.yaml:" + PositionOf(text, "mooring:", "water:") +
                               ": mooring: required key 'lines' is missing");
}

TEST(BadScenarioText, MissingTopLevelSection) {
  EXPECT_EQ(ErrorOf("name: nothing\n"), "test.yaml:1:1: required key 'mooring' is missing");
}

TEST(BadScenarioText, NoLines) {
  const std::size_t lines = kBase.find("  lines:");
  const std::size_t solver = kBase.find("solver:");
  const std::string text = kBase.substr(0, lines) + "  lines: []\n" + kBase.substr(solver);
  EXPECT_EQ(ErrorOf(text), "test.yaml:" + PositionOf(text, "", "lines: ^[]") +
                               ": mooring.lines: [] must list at least one line");
}

TEST(BadScenarioText, EmptyFile) {
  EXPECT_EQ(ErrorOf(""), "test.yaml: the scenario is empty (expected a map with 'mooring')");
  EXPECT_EQ(ErrorOf("# only a comment\n"),
            "test.yaml: the scenario is empty (expected a map with 'mooring')");
}

TEST(BadScenarioText, TopLevelIsNotAMap) {
  EXPECT_EQ(ErrorOf("- 1\n- 2\n"), "test.yaml:1:1: [1, 2] must be a map");
}

TEST(BadScenarioText, YamlSyntaxError) {
  const std::string text = Edit(kBase, "- id: 1", "[20, 0, 12]", "[20, 0, 12]]");
  EXPECT_EQ(ErrorOf(text), "test.yaml:" + PositionOf(text, "- id: 1", "12]^]") +
                               ": YAML syntax error: illegal flow end");
}

TEST(BadScenarioText, CurrentDepthsAndSpeedsDifferInNumber) {
  // Only a scenario built or changed in code can get here: YAML gives them in pairs.
  Scenario s = ParseScenario(kBase, "test.yaml");
  s.mooring.current.speed.pop_back();
  EXPECT_EQ(ValidateError(s), "test.yaml:" + PositionOf(kBase, "profile:", "- {depth: 0") +
                                  ": mooring.current.profile: 2 depths and 1 speeds differ in "
                                  "number; every point needs both");
}

TEST(BadScenarioText, ValuesWithoutPositionAreNamedByPathOnly) {
  Scenario s = ParseScenario(kBase, "test.yaml");
  s.marks.clear();
  s.mooring.lines[2].segments = 1;
  EXPECT_EQ(ValidateError(s), "test.yaml: mooring.lines[3].segments: 1 must be in 2..10000");
}

std::string LoadError(const std::string& path) {
  try {
    LoadScenario(path);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(LoadScenario, MissingFile) {
  EXPECT_EQ(LoadError("/nonexistent/dir/case.yaml"),
            "/nonexistent/dir/case.yaml: cannot open the scenario file: No such file or directory");
}

TEST(LoadScenario, Directory) {
  const std::string library = std::string(MOORSIM_SOURCE_DIR) + "/scenarios/library";
  EXPECT_EQ(LoadError(library), library + ": is a directory, not a scenario file");
}

}  // namespace
}  // namespace moorsim::scenarios
