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

}  // namespace
}  // namespace moorsim::scenarios
