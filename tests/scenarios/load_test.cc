// Scenario loading: the seed file's numbers, defaults, unit conversion, and one test per
// input error, each asserting the whole one-line message. Expected positions are found
// by searching the test's own YAML text, not taken from yaml-cpp, so a wrong mark fails.
#include "scenarios/load.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "bad_input_cases.h"
#include "core/error.h"
#include "core/format.h"
#include "scenarios/strict_yaml.h"

namespace moorsim::scenarios {
namespace {

using test_cases::BadInput;
using test_cases::Edit;
using test_cases::ErrorOf;
using test_cases::kBase;
using test_cases::kParseErrors;
using test_cases::kValidationErrors;
using test_cases::PositionOf;

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
// The library: every scenario loads as shipped, with the files it names (WAMIT data, a
// seabed grid) where it says.

TEST(Library, EveryScenarioLoadsWithTheFilesItNames) {
  const std::filesystem::path library = std::string(MOORSIM_SOURCE_DIR) + "/scenarios/library";
  int loaded = 0;
  for (const auto& entry : std::filesystem::directory_iterator(library)) {
    if (entry.path().extension() != ".yaml") continue;
    EXPECT_NO_THROW(LoadScenario(entry.path().string())) << entry.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 12);
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
    EXPECT_EQ(line.sections[0].type, "chain_seed");
    EXPECT_EQ(line.Length(), 2250.0);
    EXPECT_EQ(line.Segments(), 50);
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
  EXPECT_EQ(wire.minimum_breaking_load, 7.0e6);
  ASSERT_TRUE(wire.fatigue_curve.has_value());
  EXPECT_EQ(wire.fatigue_curve->range, analysis::TnRange::kNormalised);
  EXPECT_EQ(wire.fatigue_curve->a, 231.0);
  EXPECT_EQ(wire.fatigue_curve->m, 4.09);
  EXPECT_EQ(wire.fatigue_curve->mean_load_slope, 2.79);
  const LineType& chain = s.mooring.line_types[0];
  EXPECT_EQ(chain.minimum_breaking_load, 5.4e6);
  ASSERT_TRUE(chain.fatigue_curve.has_value());
  EXPECT_EQ(chain.fatigue_curve->a, 6.0e10);  // DNV-OS-E301's studless chain
  EXPECT_EQ(chain.fatigue_area, 0.0101);
  ASSERT_EQ(s.mooring.lines.size(), 3u);
  EXPECT_EQ(s.mooring.lines[0].Segments(), 30);  // its own
  EXPECT_EQ(s.mooring.lines[1].Segments(), 40);  // mooring.defaults.segments
  EXPECT_EQ(s.solver.atol_velocity, 2.0e-3);
  EXPECT_EQ(s.solver.max_order, 4);
  EXPECT_FALSE(s.solver.stability_limit_detection);
  EXPECT_EQ(s.solver.max_step, 0.5);
  EXPECT_EQ(s.solver.linear_solver, IntegratorOptions::LinearSolver::kKlu);
  EXPECT_EQ(s.detection.training_seed, 3u);
}

TEST(ParseScenario, ReadsTheHullAndWindage) {
  const Scenario s = ParseScenario(kBase, "test.yaml");
  ASSERT_TRUE(s.vessel.has_value());
  const HullSpec& hull = s.vessel->hull;
  EXPECT_EQ(hull.length, 200.0);
  EXPECT_EQ(hull.beam, 44.0);
  EXPECT_EQ(hull.draught, 12.0);
  EXPECT_EQ(hull.displaced_volume, 97961.0);
  EXPECT_EQ(hull.wetted_surface, 0.0);
  EXPECT_EQ(hull.cross_flow_drag_coefficient, 0.0);
  EXPECT_EQ(hull.form_factor, 0.505);
  EXPECT_EQ(hull.kinematic_viscosity, 1.19e-6);
  const WindageSpec& windage = s.vessel->windage;
  EXPECT_EQ(windage.frontal_area, 1200.0);
  EXPECT_EQ(windage.lateral_area, 4500.0);
  EXPECT_EQ(windage.length, 200.0);
  EXPECT_EQ(windage.lateral_centroid, 0.0);
  EXPECT_EQ(windage.air_density, 1.226);

  // A partial block keeps the other defaults; --set reaches the keys like any other.
  const std::string partial =
      Edit(kBase, "hull:", "length: 200, beam: 44, draught: 12, displaced_volume: 97961, ", "");
  const Scenario p = ParseScenario(partial, "test.yaml", {"vessel.windage.lateral_area=5000"});
  EXPECT_EQ(p.vessel->hull.length, HullSpec{}.length);
  EXPECT_EQ(p.vessel->hull.displaced_volume, HullSpec{}.displaced_volume);
  EXPECT_EQ(p.vessel->windage.lateral_area, 5000.0);
}

// The library's scenarios give the seed FPSO's hull and windage: the defaults' values.
TEST(ParseScenario, HullAndWindageDefaultToTheSeedFpso) {
  const Scenario s = LoadScenario(kSeedPath);
  ASSERT_TRUE(s.vessel.has_value());
  const HullSpec& hull = s.vessel->hull;
  EXPECT_EQ(hull.length, 200.0);
  EXPECT_EQ(hull.beam, 44.0);
  EXPECT_EQ(hull.draught, 12.0);
  EXPECT_EQ(hull.displaced_volume, 97961.0);
  EXPECT_EQ(hull.wetted_surface, 0.0);               // Denny-Mumford
  EXPECT_EQ(hull.cross_flow_drag_coefficient, 0.0);  // Hoerner
  EXPECT_FALSE(hull.form_factor.has_value());        // Watanabe
  EXPECT_EQ(hull.kinematic_viscosity, 1.19e-6);
  const WindageSpec& windage = s.vessel->windage;
  EXPECT_EQ(windage.frontal_area, 1200.0);
  EXPECT_EQ(windage.lateral_area, 4500.0);
  EXPECT_FALSE(windage.length.has_value());  // hull.length
  EXPECT_EQ(windage.lateral_centroid, 0.0);
  EXPECT_EQ(windage.air_density, 1.226);
}

// The windage length defaults to the hull's, and so does the centroid's range.
TEST(BadScenarioText, WindageCentroidBeyondHalfTheHullLength) {
  std::string text = Edit(kBase, "windage:", "length: 200, ", "");
  text = Edit(text, "hull:", "length: 200", "length: 300");
  text = Edit(text, "windage:", "lateral_centroid: 0", "lateral_centroid: -160");
  EXPECT_EQ(ErrorOf(text), "test.yaml:" + PositionOf(text, "windage:", "-160") +
                               ": vessel.windage.lateral_centroid: -160 m must be in [-150, 150] "
                               "(on the vessel: within half of hull.length from midship)");
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
  EXPECT_EQ(s.mooring.lines[0].Segments(), 50);
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

// A line a little shorter than its anchor-fairlead distance is a taut leg (stretched at
// rest, as a polyester taut mooring is); one that would stretch more than the catenary's
// 10 % cannot reach.
TEST(ParseScenario, ATautLegIsALineShorterThanItsDistance) {
  // |(-1950, 0, 1000) - (-20, 0, 12)| = 2168.2 m.
  Scenario s = ParseScenario(kBase, "test.yaml");
  const std::size_t line = 2;
  ASSERT_EQ(s.mooring.lines[line].anchor.x(), -1950.0);
  s.mooring.lines[line].sections[0].length = 2100.0;  // 3.2 % short
  EXPECT_EQ(ValidateError(s), "(no error)");
  s.mooring.lines[line].sections[0].length = 1960.0;  // 10.6 % short
  EXPECT_NE(ValidateError(s).find("1960 m is shorter than the anchor-fairlead distance 2168.2 m"),
            std::string::npos);
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
  changed.mooring.lines[0].sections[0].length = 100;
  EXPECT_EQ(ValidateError(changed),
            "test.yaml:" + PositionOf(swapped, "- id: 1", "length: ^2250") +
                ": mooring.lines[3].length: 100 m is shorter than the anchor-fairlead distance "
                "2168.2 m");
}

// ---------------------------------------------------------------------------------------
class BadScenario : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadScenario, GivesOneLineWithPlaceKeyValueAndRule) {
  const BadInput& input = GetParam();
  const std::string text = Edit(kBase, input.after, input.old_text, input.new_text);
  EXPECT_EQ(ErrorOf(text),
            "test.yaml:" + PositionOf(text, input.after, input.at) + ": " + input.message);
}

std::string CaseName(const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; }

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
  s.failure = {};
  s.mooring.lines[2].sections[0].length = 100.0;
  EXPECT_EQ(ValidateError(s),
            "test.yaml: mooring.lines[3].length: 100 m is shorter than the anchor-fairlead "
            "distance 2168.2 m");
}

// ---------------------------------------------------------------------------------------
// Tags, encodings and ranges: what must still be accepted, and the cases a
// one-spot edit of kBase cannot express.

std::string OverrideError(const std::vector<std::string>& overrides) {
  try {
    ParseScenario(kBase, "test.yaml", overrides);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(ScenarioText, QuotedBlockAndAnchoredValuesAreNotTags) {
  // yaml-cpp gives quoted and block scalars the tag "!", like an explicit `! x`.
  std::string text = Edit(kBase, "", "name: base", "name: \"base\"");
  text = Edit(text, "- id: 2", "type: wire", "type: >-\n        wire");
  text = Edit(text, "- id: 3", "type: chain", "type: 'chain'");
  text = Edit(text, "vessel:", "length_scale: 1", "length_scale: &one 1");
  text = Edit(text, "name: aft_port", "weight: 1", "weight: *one");
  Scenario s;
  ASSERT_NO_THROW(s = ParseScenario(text, "test.yaml")) << ErrorOf(text);
  EXPECT_EQ(s.name, "base");
  EXPECT_EQ(s.mooring.lines[1].sections[0].type, "wire");
  EXPECT_EQ(s.mooring.lines[2].sections[0].type, "chain");
  EXPECT_EQ(s.vessel->thrusters[0].weight, 1.0);
}

TEST(ScenarioText, ValidUtf8IsKept) {
  // Two-, three- and four-byte sequences, and a byte-order mark.
  const std::string name = "caf\xC3\xA9 \xE2\x9A\x93 \xF0\x9F\x8C\x8A";
  const std::string text = "\xEF\xBB\xBF" + Edit(kBase, "", "name: base", "name: " + name);
  EXPECT_EQ(ParseScenario(text, "test.yaml").name, name);
}

TEST(ScenarioText, BadByteAfterMultiByteCharactersIsPlacedByByteColumn) {
  // Columns count bytes, as yaml-cpp's own marks do: "name: é" is 8 bytes.
  const std::string text = Edit(kBase, "", "name: base", "name: \xC3\xA9\xFF");
  EXPECT_EQ(ErrorOf(text), "test.yaml:1:9: not valid UTF-8 (byte 0xFF); save the file as UTF-8");
}

TEST(ScenarioText, OverridesMustBeUtf8AndUntagged) {
  EXPECT_EQ(OverrideError({"name=caf\xE9"}),
            "set name=caf\\xE9: not valid UTF-8 (byte 0xE9 at character 9)");
  EXPECT_EQ(OverrideError({"vessel.mass=!!str 1.0041e8"}),
            "set vessel.mass=!!str 1.0041e8: tagged value '!!str' (tags are not accepted; "
            "write the plain value)");
  EXPECT_EQ(OverrideError({"vessel.mass=! 1.0041e8"}),
            "set vessel.mass=! 1.0041e8: tagged value '!' (tags are not accepted; write the "
            "plain value)");
  EXPECT_EQ(OverrideError({"environment.wind={speed: !!float 12, direction_from_deg: 0}"}),
            "set environment.wind={speed: !!float 12, direction_from_deg: 0}: tagged value "
            "'!!float' (tags are not accepted; write the plain value)");
  EXPECT_EQ(OverrideError({"name=\"caf\xC3\xA9\"", "vessel.mass=2.0e8"}), "(no error)");
  // Range checks see overridden values too, by key path only.
  EXPECT_EQ(OverrideError({"mooring.water.gravity=1e308"}),
            "test.yaml: mooring.water.gravity: 1e+308 m/s^2 must be in [9.7, 9.9] (Earth's "
            "gravity)");
}

// A key path has one spelling (a second would pass as another key), and `base` is read
// before --set applies.
TEST(ScenarioText, OverrideKeyPathsHaveOneSpellingAndBaseIsNotOne) {
  EXPECT_EQ(OverrideError({"simulation..duration=5"}),
            "set simulation..duration=5: empty key in 'simulation..duration' (one '.' between "
            "keys, none before '[')");
  EXPECT_EQ(OverrideError({"mooring.lines[01].length=2000"}),
            "set mooring.lines[01].length=2000: bad list index in 'mooring.lines[01].length' "
            "(write [1])");
  EXPECT_EQ(OverrideError({"mooring.lines.[1].length=2000"}),
            "set mooring.lines.[1].length=2000: empty key in 'mooring.lines.[1].length' (one "
            "'.' between keys, none before '[')");
  EXPECT_EQ(OverrideError({"mooring.lines[1]length=2000"}),
            "set mooring.lines[1]length=2000: 'mooring.lines[1]length': '.' or '[' must follow "
            "']'");
  EXPECT_EQ(OverrideError({"base=other.yaml"}),
            "set base=other.yaml: base is read before the overrides apply; write base: in the "
            "scenario file");
  EXPECT_EQ(OverrideError({"simulation.duration=5\n---\n6"}),
            "set simulation.duration=5\n---\n6: the value holds more than one YAML document");
  EXPECT_EQ(OverrideError({"simulation.duration=600", "mooring.lines[1].segments=20"}),
            "(no error)");
}

// yaml-cpp keeps both entries of a duplicate key and drops directives after `...`; aliases
// cost nothing to read but multiply every walk over the document.
TEST(BadScenarioText, DuplicateKeysTextAfterTheEndAndMultiplyingAliases) {
  EXPECT_EQ(ErrorOf(kBase + "...\n%YAML 1.2\n"),
            "test.yaml:" + std::to_string(std::count(kBase.begin(), kBase.end(), '\n') + 2) +
                ":1: text after the document-end marker '...' (a scenario file holds one YAML "
                "document)");
  const std::string twice = Edit(kBase, "", "name: base", "name: base\nname: other");
  EXPECT_EQ(ErrorOf(twice), "test.yaml:2:1: duplicate key 'name'");
  std::string lol = kBase + "lol:\n  - &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level < 9; ++level) {
    lol += "  - &a" + std::to_string(level) + " [";
    for (int k = 0; k < 10; ++k) lol += (k ? ", *a" : "*a") + std::to_string(level - 1);
    lol += "]\n";
  }
  const std::string error = ErrorOf(lol);
  EXPECT_EQ(error.rfind("test.yaml:", 0), 0u) << error;
  EXPECT_NE(error.find("aliases expand the document to more than 1048576 values"),
            std::string::npos)
      << error;
}

TEST(ScenarioText, BoundsThemselvesAreAccepted) {
  std::string text = Edit(kBase, "", "density: 1025", "density: 1100");
  text = Edit(text, "", "gravity: 9.81", "gravity: 9.7");
  text = Edit(text, "", "direction_deg: 90", "direction_deg: -360");
  text = Edit(text, "initial_pose:", "heading_deg: 10", "heading_deg: 360");
  text = Edit(text, "- id: 1", "segments: 30", "segments: 30\n      fairlead: [20, 0, 12]");
  text = Edit(text, "- name: chain", "drag_normal: 0.3", "drag_normal: 10");
  text = Edit(text, "controller:", "rate_hz: 1", "rate_hz: 1000");
  text = Edit(text, "simulation:", "duration: 1000", "duration: 1.0e7");
  // 1e7 s x 100 Hz = 1e9 rows, the most allowed.
  text = Edit(text, "simulation:", "output_rate_hz: 2", "output_rate_hz: 100");
  text = Edit(text, "environment:", "hs: 2.5", "hs: 10.7");  // g 9.7: steepness 0.1414 < 1/7
  const std::string error = ErrorOf(text);
  // The extra fairlead key is a duplicate: proves the edit landed, then drop it.
  EXPECT_NE(error.find("duplicate key 'fairlead'"), std::string::npos) << error;
  text = Edit(text, "- id: 1", "segments: 30\n      fairlead: [20, 0, 12]", "segments: 30");
  EXPECT_EQ(ErrorOf(text), "(no error)");
}

TEST(ScenarioText, LineRulesAtTheInitialPoseTurnTheFairleadsWithTheTurret) {
  // The vessel 1500 m south, heading 10 deg: line 1 cannot reach (bad_input_cases.h,
  // LineCannotReachAtTheInitialPose: 3569.8 m). A turret that starts at 190 deg holds its
  // fairleads half a turn from where the hull would put them: line 1's, 20 m from the turret
  // centre at 10 deg, is then at 190 deg, 3607.6 m from its anchor at (1950, 0, 1000) m
  // (by hand: the fairlead at (-1500 - 19.70, 2 - 3.47, 12) m). At 10 deg the turret
  // changes nothing.
  const std::string south = Edit(kBase, "initial_pose:", "x: 2,", "x: -1500,");
  const std::string turned =
      Edit(south, "turret:", "bearing: friction", "bearing: friction, initial_heading_deg: 190");
  const std::string error = ErrorOf(turned);
  const std::string head =
      "test.yaml:" + PositionOf(turned, "initial_pose:", "initial_pose: ^{") +
      ": vessel.initial_pose: at x -1500 m, y 2 m, heading 10 deg, turret heading 190 deg, "
      "mooring.lines[1].length 2250 m is shorter than the anchor-fairlead distance ";
  ASSERT_EQ(error.substr(0, head.size()), head) << error;
  const double distance = std::stod(error.substr(head.size()));
  EXPECT_NEAR(distance, 3607.6, 0.05);
  const std::string same =
      Edit(south, "turret:", "bearing: friction", "bearing: friction, initial_heading_deg: 10");
  EXPECT_NE(ErrorOf(same).find("heading 10 deg, turret heading 10 deg, mooring.lines[1].length "
                               "2250 m is shorter than the anchor-fairlead distance 3569.8 m"),
            std::string::npos)
      << ErrorOf(same);
}

TEST(ScenarioText, LineRulesWithoutAVesselUseTheOrigin) {
  // A lines-only scenario: the reach and slack rules at the origin, no initial pose.
  const std::string minimal = R"(mooring:
  water: {depth: 300}
  line_types:
    - {name: c, diameter: 0.1, mass_per_length: 200, axial_stiffness: 1e9, drag_normal: 1,
       drag_tangential: 0.5, added_mass_normal: 1}
  lines:
    - {type: c, anchor: [800, 0, 300], fairlead: [10, 0, 10], length: 1079.9}
)";
  EXPECT_EQ(ErrorOf(minimal), "(no error)");  // 790 m across + 290 m down = 1080 m
  const std::string slack = Edit(minimal, "", "length: 1079.9", "length: 1080");
  EXPECT_EQ(ErrorOf(slack),
            "test.yaml:" + PositionOf(slack, "", "length: ^1080") +
                ": mooring.lines[1].length: 1080 m must be shorter than the horizontal "
                "anchor-fairlead distance plus the fairlead's height above the anchor, 790.0 + "
                "290.0 = 1080.0 m (a longer line lies slack on the seabed, with no horizontal "
                "tension)");
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

// Without a turret that turns (bearing locked, no radius), the fairleads are hull points:
// a spread mooring has them at the bow and the stern, anywhere within the waterplane.
TEST(SpreadMooring, FairleadsAnywhereOnTheHullButNotOffIt) {
  const std::string turret = kBase.substr(kBase.find("  turret:"));
  std::string text = Edit(kBase, "", turret.substr(0, turret.find('\n') + 1), "");
  text = Edit(text, "- id: 1", "fairlead: [20, 0, 12]", "fairlead: [95, 15, 12]");
  text = Edit(text, "- id: 3", "fairlead: [-20, 0, 12]", "fairlead: [-95, -15, 12]");
  const Scenario s = ParseScenario(text, "test.yaml");
  EXPECT_EQ(s.vessel->turret.bearing, vessel::TurretBearing::kLocked);
  EXPECT_EQ(s.mooring.lines[0].fairlead_body.x(), 95.0);
  text = Edit(text, "- id: 1", "fairlead: [95, 15, 12]", "fairlead: [105, 15, 12]");
  EXPECT_EQ(ErrorOf(text), "test.yaml:" + PositionOf(text, "- id: 1", "[105") +
                               ": mooring.lines[1].fairlead: (105, 15) m is off the hull: |x| "
                               "must be <= hull.length / 2 = 100 m and |y| <= hull.beam / 2 = "
                               "22 m");
}

}  // namespace
}  // namespace moorsim::scenarios

namespace moorsim::scenarios {
namespace {

// A line type lighter than the water it displaces (a buoyant rope) may be a section of a
// composite line that weighs more than its water as a whole; alone it would float, and so
// would a composite line of too little chain.
TEST(ScenarioText, BuoyantSectionsHangBetweenHeavierOnes) {
  std::string text = test_cases::kBase;
  // The wire made buoyant: 5 kg/m dry in 8.05 kg/m of displaced water.
  text.replace(text.find("mass_per_length: 40"), 19, "mass_per_length: 5");
  const std::string alone =
      "      type: wire\n      anchor: [0, 1950, 1000]\n"
      "      fairlead: [0, 20, 12]\n      length: 2250\n";
  ASSERT_NE(text.find(alone), std::string::npos);
  const auto composite = [&](double chain_length, double wire_length) {
    std::string t = text;
    t.replace(t.find(alone), alone.size(),
              "      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n"
              "      sections:\n        - {type: chain, length: " +
                  FormatNumber(chain_length) + ", segments: 10}\n        - {type: wire, length: " +
                  FormatNumber(wire_length) + ", segments: 20}\n");
    return t;
  };
  const Scenario s = ParseScenario(composite(700.0, 1550.0), "test.yaml");
  EXPECT_EQ(s.mooring.lines[1].sections.size(), 2u);
  // The same type alone on a line: it floats.
  try {
    ParseScenario(text, "test.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mooring.line_types[2].mass_per_length: 5 kg/m must "
                                         "exceed the displaced water mass"),
              std::string::npos)
        << e.what();
  }
  // 10 m of chain (26 kN) cannot hold 2240 m of the rope (-67 kN) down.
  try {
    ParseScenario(composite(10.0, 2240.0), "test.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mooring.lines[2].sections: the line weighs -4"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace moorsim::scenarios
