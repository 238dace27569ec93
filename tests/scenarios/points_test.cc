// The points-and-lines form of a mooring: free points named under mooring.points, lines
// running from and to them. What loads, what it becomes for the FEM, and one test per
// input error, each asserting the whole one-line message at its place in the text.
#include <gtest/gtest.h>

#include <string>

#include "bad_input_cases.h"
#include "core/error.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace moorsim::scenarios {
namespace {

using test_cases::BadInput;
using test_cases::Edit;
using test_cases::ErrorOf;
using test_cases::PositionOf;

// A bridle (an apex with a clump weight, a ground chain, two legs to the vessel), a buoy on
// a pendant above the apex, and a plain line to the west.
const std::string kBridle = R"(name: bridle
mooring:
  water: {density: 1025, gravity: 9.81, depth: 1000}
  line_types:
    - {name: chain, diameter: 0.08, mass_per_length: 275, axial_stiffness: 2.28785e8, drag_normal: 0.3, drag_tangential: 1.0, added_mass_normal: 1.5}
  points:
    - {name: apex, position: [120, 0, 120], mass: 20000, volume: 2.55, added_mass: 1, drag_area: 2}
    - {name: buoy, position: [120, 0, 90], mass: 500, volume: 3}
  lines:
    - {id: 1, type: chain, anchor: [1950, 0, 1000], to: apex, length: 2096, segments: 40}
    - {id: 2, type: chain, from: apex, fairlead: [19.08, 6, 12], length: 160, segments: 8}
    - {id: 3, type: chain, from: apex, fairlead: [19.08, -6, 12], length: 160, segments: 8}
    - {id: 4, type: chain, from: apex, to: buoy, length: 40, segments: 4}
    - {id: 5, type: chain, anchor: [-1950, 0, 1000], fairlead: [-20, 0, 12], length: 2250, segments: 40}
)";

TEST(PointsAndLines, LoadIntoTheFemsPointsAndLineEnds) {
  const Scenario s = ParseScenario(kBridle, "test.yaml");
  const mooring_fem::MooringParameters p = ToMooringParameters(s.mooring);
  ASSERT_EQ(p.points.size(), 2u);
  EXPECT_EQ(p.points[0].position, Vec3(120.0, 0.0, 120.0));
  EXPECT_EQ(p.points[0].body.mass, 20000.0);
  EXPECT_EQ(p.points[0].body.volume, 2.55);
  EXPECT_EQ(p.points[0].body.added_mass, 1.0);
  EXPECT_EQ(p.points[0].body.drag_area, 2.0);
  EXPECT_EQ(p.points[1].body.drag_area, 0.0);
  ASSERT_EQ(p.lines.size(), 5u);
  EXPECT_EQ(p.lines[0].lower_point, -1);
  EXPECT_EQ(p.lines[0].upper_point, 0);
  EXPECT_EQ(p.lines[1].lower_point, 0);
  EXPECT_EQ(p.lines[1].upper_point, -1);
  EXPECT_EQ(p.lines[3].lower_point, 0);
  EXPECT_EQ(p.lines[3].upper_point, 1);
  EXPECT_EQ(p.lines[4].lower_point, -1);
  EXPECT_EQ(p.lines[4].upper_point, -1);
}

const BadInput kPointErrors[] = {
    {"UnknownPoint", "- {id: 1", "to: apex", "to: apx", "apx",
     "mooring.lines[1].to: unknown point 'apx' (known: apex, buoy)"},
    {"AnchorAndFrom", "- {id: 2", "from: apex", "anchor: [0, 0, 1000], from: apex",
     "anchor: ^[0, 0, 1000]",
     "mooring.lines[2].anchor: give a line's end either anchor or from, not both"},
    {"NeitherFairleadNorTo", "- {id: 5", "fairlead: [-20, 0, 12], ", "", "{id: 5",
     "mooring.lines[5]: needs fairlead or to (a free point's name)"},
    {"DuplicatePointName", "", "  lines:", "    - {name: apex, position: [0, 0, 50]}\n  lines:",
     "name: ^apex, position: [0, 0, 50]",
     "mooring.points[3].name: 'apex' is already the name of mooring.points[1]"},
    {"PointAboveTheWater", "", "[120, 0, 120]", "[120, 0, -5]", "[120, 0, -5]",
     "mooring.points[1].position: z = -5 m is not below the water surface (z points down, 0 at "
     "the surface)"},
    {"PointBelowTheSeabed", "", "[120, 0, 120]", "[120, 0, 1200]", "[120, 0, 1200]",
     "mooring.points[1].position: z = 1200 m is below the seabed there, at depth 1000 m"},
    {"PointsThatCoincide", "", "[120, 0, 90]", "[120, 0, 120.005]", "[120, 0, 120.005]",
     "mooring.points[2].position: coincides with mooring.points[1] (points must be at least "
     "0.01 m apart)"},
    {"ALineFromAPointToItself", "- {id: 4", "to: buoy", "to: apex", "to: ^apex",
     "mooring.lines[4].to: 'apex' is the point the line starts from too"},
    {"APointNoLineReaches", "", "  lines:", "    - {name: spare, position: [0, 0, 50]}\n  lines:",
     "{name: spare", "mooring.points[3]: no line starts or ends at 'spare' (from, to)"},
    {"ALegOfOneSegmentToTheVessel", "- {id: 2", "type: chain, from: apex",
     "sections: [{type: chain, length: 160, segments: 1}], from: apex", "[{type",
     "mooring.lines[2].sections: a line from a free point to the vessel needs 2 segments or "
     "more"},
};

class BadPointsAndLines : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadPointsAndLines, GiveOneLineWithPlaceKeyValueAndRule) {
  const BadInput& input = GetParam();
  std::string text = Edit(kBridle, input.after, input.old_text, input.new_text);
  // The leg given in sections has no length of its own.
  if (input.name == "ALegOfOneSegmentToTheVessel") {
    text = Edit(text, "- {id: 2", ", length: 160, segments: 8", "");
  }
  EXPECT_EQ(ErrorOf(text),
            "test.yaml:" + PositionOf(text, input.after, input.at) + ": " + input.message);
}

INSTANTIATE_TEST_SUITE_P(Points, BadPointsAndLines, ::testing::ValuesIn(kPointErrors),
                         [](const auto& info) { return info.param.name; });

TEST(PointsAndLines, PointsJoinedToNoAnchorOrFairleadThatFloatAreRefused) {
  // The buoy on a pendant from a second buoy, neither held by anything: 30 m^3 of lift.
  std::string text =
      Edit(kBridle, "",
           "  lines:", "    - {name: float, position: [300, 0, 200], volume: 30}\n  lines:");
  text = Edit(text, "- {id: 4", "from: apex", "from: float");
  EXPECT_EQ(ErrorOf(text), "test.yaml:" + PositionOf(text, "", "{name: buoy") +
                               ": mooring.points[2]: 'buoy' and the points and lines "
                               "joined to it reach no anchor or fairlead and weigh -221 kN "
                               "in water: they would float away");
}

// The detectors take free points (their quasi-static model solves the points' balance),
// load cells too: one at each line's upper end.
TEST(PointsAndLines, LoadCellsAreOffered) {
  const std::string base = "base: " MOORSIM_SOURCE_DIR "/scenarios/library/seed_bridled.yaml\n";
  EXPECT_EQ(ErrorOf(base + "detectors: [{type: dht}]\n"), "(no error)");
  EXPECT_EQ(ErrorOf(base + "sensors:\n  tension_cells: {rate_hz: 1}\n"), "(no error)");
}

}  // namespace
}  // namespace moorsim::scenarios
