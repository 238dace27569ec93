// The scenario's mooring converted to the FEM's parameter types (scenarios/convert.h):
// every field arrives, in order, and the shared types keep the schema's defaults.
#include "scenarios/convert.h"

#include <gtest/gtest.h>

#include <string>

#include "bad_input_cases.h"
#include "scenarios/load.h"

namespace moorsim::scenarios {
namespace {

TEST(ToMooringParameters, CarriesEveryField) {
  const Scenario s = ParseScenario(test_cases::kBase, "test.yaml");
  const mooring_fem::MooringParameters p = ToMooringParameters(s.mooring);
  EXPECT_EQ(p.water.density, s.mooring.water.density);
  EXPECT_EQ(p.water.gravity, s.mooring.water.gravity);
  EXPECT_EQ(p.water.depth, 1000.0);
  EXPECT_EQ(p.seabed.stiffness, s.mooring.seabed.stiffness);
  EXPECT_EQ(p.seabed.damping, s.mooring.seabed.damping);
  EXPECT_EQ(p.seabed.contact_smoothing, s.mooring.seabed.contact_smoothing);
  EXPECT_EQ(p.seabed.friction_velocity, 0.01);
  EXPECT_EQ(p.current.direction, s.mooring.current.direction);
  EXPECT_EQ(p.current.depth, (std::vector<double>{0, 500}));
  EXPECT_EQ(p.current.speed, (std::vector<double>{0.2, 0.1}));
  EXPECT_EQ(p.current.SurfaceSpeed(), 0.2);

  ASSERT_EQ(p.line_types.size(), 2u);
  for (std::size_t i = 0; i < p.line_types.size(); ++i) {
    const mooring_fem::LineType& t = p.line_types[i];
    const LineType& given = s.mooring.line_types[i];
    EXPECT_EQ(t.name, given.name);
    EXPECT_EQ(t.diameter, given.diameter);
    EXPECT_EQ(t.mass_per_length, given.mass_per_length);
    EXPECT_EQ(t.axial_stiffness, given.axial_stiffness);
    EXPECT_EQ(t.axial_damping, given.axial_damping);
    EXPECT_EQ(t.axial_damping_ratio, given.axial_damping_ratio);
    EXPECT_EQ(t.drag_normal, given.drag_normal);
    EXPECT_EQ(t.drag_tangential, given.drag_tangential);
    EXPECT_EQ(t.added_mass_normal, given.added_mass_normal);
    EXPECT_EQ(t.friction_axial, given.friction_axial);
    EXPECT_EQ(t.friction_lateral, given.friction_lateral);
  }
  EXPECT_EQ(p.line_types[1].name, "wire");
  EXPECT_EQ(p.line_types[1].axial_damping, 1.0e5);

  ASSERT_EQ(p.lines.size(), 3u);
  for (std::size_t i = 0; i < p.lines.size(); ++i) {
    const mooring_fem::LineParameters& l = p.lines[i];
    const LineSpec& given = s.mooring.lines[i];
    EXPECT_EQ(l.id, static_cast<int>(i) + 1);
    ASSERT_EQ(l.sections.size(), 1u);
    EXPECT_EQ(l.sections[0].type, given.sections[0].type);
    EXPECT_EQ(l.anchor, given.anchor);
    EXPECT_EQ(l.fairlead_body, given.fairlead_body);
    EXPECT_EQ(l.sections[0].length, given.sections[0].length);
    EXPECT_EQ(l.sections[0].segments, given.sections[0].segments);
  }
  EXPECT_EQ(p.lines[0].Segments(), 30);  // its own
  EXPECT_EQ(p.lines[1].Segments(), 40);  // mooring.defaults.segments
}

TEST(ToMooringParameters, EmptyCurrentStaysEmpty) {
  std::string text = test_cases::kBase;
  const std::size_t from = text.find("  current:");
  text.erase(from, text.find("  line_types:") - from);
  const mooring_fem::MooringParameters p =
      ToMooringParameters(ParseScenario(text, "test.yaml").mooring);
  EXPECT_TRUE(p.current.depth.empty());
  EXPECT_EQ(p.current.SurfaceSpeed(), 0.0);
}

}  // namespace
}  // namespace moorsim::scenarios
