// scenarios/template.h: every kind's file loads at the very ends of the pretension range
// (which the command line cannot name exactly), and the layout is what the header promises.
#include "scenarios/template.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "core/error.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/mooring_system.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace moorsim::scenarios {
namespace {

const std::string kSeedHydrodynamics = "\"" MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso\"";

TemplateRequest Request(const std::string& kind, int lines, double depth, double length) {
  TemplateRequest request;
  request.kind = kind;
  request.lines = lines;
  request.depth = depth;
  request.length = length;
  request.hydrodynamics = kSeedHydrodynamics;
  return request;
}

/// Plans, writes and loads; returns the loaded scenario.
Scenario PlanWriteLoad(const TemplateRequest& request, TemplateLayout* layout_out = nullptr) {
  const TemplateLayout layout = PlanTemplate(request);
  if (layout_out != nullptr) *layout_out = layout;
  return ParseScenario(WriteTemplate(request, layout, "moorsim template (test)"), "t.yaml");
}

TEST(TemplateKinds, TheTableIsSortedAndUnknownKindsAreNamed) {
  EXPECT_TRUE(
      std::is_sorted(kTemplateKinds.begin(), kTemplateKinds.end(),
                     [](const TemplateKind& a, const TemplateKind& b) { return a.name < b.name; }));
  try {
    FindTemplateKind("catenary");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "kind: unknown mooring kind 'catenary' (known: spread, turret)");
  }
}

// Both ends of the range: 2250 m in 1000 m of water is pulled straight before it lifts off,
// 600 m in 200 m lifts off first.
TEST(PlanTemplate, EveryKindLoadsAtBothEndsOfThePretensionRange) {
  for (const TemplateKind& kind : kTemplateKinds) {
    for (const auto& [depth, length, radius, limit] :
         {std::tuple{1000.0, 2250.0, 1900.0, "the line pulled straight"},
          std::tuple{200.0, 600.0, 500.0, "the whole line lifted off the seabed"}}) {
      SCOPED_TRACE(std::string(kind.name) + " " + std::to_string(length));
      TemplateRequest request = Request(std::string(kind.name), 5, depth, length);
      request.radius = radius;  // inside the range, to read it
      TemplateLayout probe;
      ASSERT_NO_THROW(PlanWriteLoad(request, &probe));
      EXPECT_EQ(probe.max_pretension_limit, limit);
      request.radius.reset();
      for (double tension : {probe.max_pretension, probe.min_pretension * (1.0 + 1e-9)}) {
        request.pretension = tension;
        TemplateLayout layout;
        Scenario s;
        ASSERT_NO_THROW(s = PlanWriteLoad(request, &layout)) << tension;
        EXPECT_NEAR(layout.pretension, tension, 1e-9 * tension);
        ASSERT_EQ(s.mooring.lines.size(), 5u);
        for (const LineSpec& line : s.mooring.lines) {
          // Radial: the fairlead on the kind's circle, the anchor on the same ray.
          const double r_fairlead = std::hypot(line.fairlead_body.x(), line.fairlead_body.y());
          EXPECT_LE(r_fairlead, kind.fairlead_radius);
          EXPECT_NEAR(r_fairlead, kind.fairlead_radius, 1e-5);
          EXPECT_NEAR(std::hypot(line.anchor.x(), line.anchor.y()), layout.anchor_radius, 1e-9);
          EXPECT_NEAR(
              line.fairlead_body.x() * line.anchor.y() - line.fairlead_body.y() * line.anchor.x(),
              0.0, 1e-5 * layout.anchor_radius);
        }
      }
      request.pretension = probe.max_pretension * (1.0 + 1e-9);
      EXPECT_THROW(PlanTemplate(request), InputError);
      request.pretension = probe.min_pretension;
      EXPECT_THROW(PlanTemplate(request), InputError);
    }
  }
}

TEST(PlanTemplate, TurretLineOnePointsNorthAndSpreadLinesAvoidTheBow) {
  TemplateRequest request = Request("turret", 4, 1000.0, 2250.0);
  request.pretension = 3.5e6;
  const TemplateLayout turret = PlanTemplate(request);
  EXPECT_DOUBLE_EQ(turret.lines[0].bearing_deg, 0.0);
  EXPECT_DOUBLE_EQ(turret.lines[0].fairlead_body.x(), 20.0);
  EXPECT_DOUBLE_EQ(turret.lines[1].anchor.x(), 0.0);  // exactly east, no 1e-13 m residue
  request.kind = "spread";
  const TemplateLayout spread = PlanTemplate(request);
  EXPECT_DOUBLE_EQ(spread.lines[0].bearing_deg, 45.0);
  EXPECT_DOUBLE_EQ(spread.span, turret.span);  // same line, same pretension
  EXPECT_DOUBLE_EQ(spread.anchor_radius, spread.span + 22.0);
}

// Chain-polyester-chain lines in four groups of three: the file loads, the bearings are the
// groups', and the FEM settled at rest (an independent model: lumped masses, penalty seabed)
// gives every line the pretension the catenary placed its anchor for, within 0.2 %.
TEST(PlanTemplate, SectionedLinesInGroupsCarryTheirPretensionInTheFem) {
  TemplateRequest request = Request("turret", 12, 1500.0, 0.0);
  request.sections = ParseTemplateSections("chain:300,polyester:2200,chain:200");
  request.groups = 4;
  request.pretension = 1.5e6;
  TemplateLayout layout;
  Scenario s;
  ASSERT_NO_THROW(s = PlanWriteLoad(request, &layout));
  EXPECT_NEAR(layout.pretension, 1.5e6, 1e-6 * 1.5e6);
  ASSERT_EQ(s.mooring.lines.size(), 12u);
  for (int k = 0; k < 12; ++k) {
    const double expected = std::fmod(90.0 * (k / 3) + 5.0 * (k % 3 - 1) + 360.0, 360.0);
    EXPECT_NEAR(layout.lines[k].bearing_deg, expected, 1e-12) << "line " << k + 1;
    ASSERT_EQ(s.mooring.lines[k].sections.size(), 3u);
    EXPECT_EQ(s.mooring.lines[k].sections[1].type, "polyester");
    EXPECT_EQ(s.mooring.lines[k].sections[1].segments, 55);  // one per 40 m
  }
  // Both types carry what the design checks need: a breaking load and a T-N curve.
  ASSERT_EQ(s.mooring.line_types.size(), 2u);
  for (const LineType& type : s.mooring.line_types) {
    SCOPED_TRACE(type.name);
    EXPECT_GT(type.minimum_breaking_load, 0.0);
    ASSERT_TRUE(type.fatigue_curve.has_value());
  }
  EXPECT_EQ(s.mooring.line_types[0].fatigue_curve->a, 6.0e10);  // DNV's studless chain
  EXPECT_EQ(s.mooring.line_types[1].fatigue_curve->m, 5.2);     // API RP 2SM's polyester
  mooring_fem::MooringSystem mooring(ToMooringParameters(s.mooring));
  std::vector<Vec3> positions;
  std::vector<PointKinematics> fairleads(12);
  for (int i = 0; i < 12; ++i) {
    positions.push_back(mooring.line(i).fairlead_body);  // the vessel at the origin
    fairleads[i].position = positions.back();
  }
  std::vector<double> x(mooring.StateSize());
  mooring.CatenaryState(positions, x.data());
  mooring.SettleStatic(positions, x.data());
  for (const mooring_fem::LineLoad& load : mooring.LineLoads(x.data(), fairleads)) {
    EXPECT_NEAR(load.fairlead_force.norm(), 1.5e6, 2e-3 * 1.5e6);
  }
  // Both ends of the sectioned line's range load too.
  request.pretension.reset();
  for (double tension : {layout.max_pretension, layout.min_pretension * (1.0 + 1e-6)}) {
    request.pretension = tension;
    ASSERT_NO_THROW(PlanWriteLoad(request)) << tension;
  }
  request.pretension = layout.max_pretension * (1.0 + 1e-6);
  EXPECT_THROW(PlanTemplate(request), InputError);
}

TEST(PlanTemplate, BadSectionsAndGroupsAreOneMessageNamingTheFlag) {
  const auto error = [](auto&& body) {
    try {
      body();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(error([] { ParseTemplateSections("chain:400,wire:100"); }),
            "sections: 'wire:100' (section 2): unknown line type 'wire' (known: chain, "
            "polyester)");
  EXPECT_EQ(error([] { ParseTemplateSections("chain"); }),
            "sections: 'chain' (section 1) must be TYPE:LENGTH or TYPE:LENGTH:SEGMENTS");
  EXPECT_EQ(error([] { ParseTemplateSections("chain:-4"); }),
            "sections: 'chain:-4' (section 1): the length must be a number in (0, 20000] m");
  EXPECT_EQ(error([] { ParseTemplateSections("chain:400:2.5"); }),
            "sections: 'chain:400:2.5' (section 1): the segments must be a whole number in "
            "1..10000");
  TemplateRequest request = Request("turret", 12, 1500.0, 2000.0);
  request.pretension = 1.5e6;
  request.groups = 5;
  EXPECT_EQ(error([&] { PlanTemplate(request); }),
            "groups: 5 does not divide the 12 lines into equal groups");
  request.groups = 2;
  EXPECT_EQ(error([&] { PlanTemplate(request); }),
            "groups: 2 must be >= 3 (fewer groups cannot hold the vessel in every direction)");
  request.groups = 4;
  request.group_spread_deg = 50.0;
  EXPECT_EQ(error([&] { PlanTemplate(request); }),
            "group_spread: 50 deg must be > 0 and keep each group of 3 lines within its 90 deg "
            "(groups apart)");
  request.group_spread_deg = 5.0;
  request.sections = ParseTemplateSections("chain:2000");
  EXPECT_EQ(error([&] { PlanTemplate(request); }),
            "length, sections: give exactly one of them (both given)");
}

}  // namespace
}  // namespace moorsim::scenarios
