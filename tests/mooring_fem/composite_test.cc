// Composite lines (sections of different types in series, clump weights and buoys at their
// joints) at rest, against an independent reference written here: the elastic catenary's
// differential equations integrated by Simpson's rule (not the closed forms the code uses)
// with the seabed carrying the line from the anchor to where its vertical tension reaches
// zero, and the fairlead's horizontal and vertical tension found by Newton's method on the
// two closure conditions; on a plane seabed rising or falling toward the fairlead, with the
// line resting on the slope. The FEM settled to rest must give every line's fairlead and
// anchor tension within 0.1 % of it; the composite catenary (which places the FEM's nodes
// at the start) within 1e-6.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <ostream>
#include <vector>

#include "catenary_reference.h"
#include "core/error.h"
#include "mooring_fem/composite_catenary.h"
#include "mooring_fem/mooring_system.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

constexpr double kSeaWater = 1025.0;
constexpr double kGravity = 9.81;

using reference::Reference;
using reference::RefSection;
using reference::SolveReference;

// --- The case: a deepwater chain-polyester-chain line in 1000 m.

double WeightInWater(const LineType& t) {
  return (t.mass_per_length - kSeaWater * std::numbers::pi / 4.0 * t.diameter * t.diameter) *
         kGravity;
}

struct Case {
  const char* name;
  std::vector<PointBody> joints;  // empty: none
  double anchor_x = 1750.0;       // [m]; the fairlead is at x = 20 m, 988 m above the anchor
  bool grounded = true;           // whether part of the line rests on the seabed
  double rope_mass = 26.0;        // [kg/m] dry; under 20.6 kg/m the rope floats
  bool rope_curve = false;        // the rope on kRopeCurve rather than a constant EA
  // A plane seabed through 1000 m below the origin, deepening toward north (slope > 0) or
  // toward south (< 0): it rises toward the fairlead by `slope_deg` [deg].
  double slope_deg = 0.0;
};

// A polyester-like tension-strain curve, soft at first [strain, N].
const std::vector<StrainTension> kRopeCurve = {
    {0.01, 0.6e6}, {0.02, 1.5e6}, {0.03, 2.7e6}, {0.05, 5.5e6}, {0.08, 10.0e6}};

LineType Rope(const Case& c) {
  LineType rope = testing::PolyesterType();
  rope.mass_per_length = c.rope_mass;
  if (c.rope_curve) {
    rope.axial_stiffness = 0.0;
    rope.tension_strain = kRopeCurve;
  }
  return rope;
}

MooringParameters CompositeSpec(const Case& c, int scale) {
  MooringParameters spec;
  spec.water.depth = 1000.0;
  // A hard seabed: the grounded chain sinks 0.3 cm into it, where the default seabed's
  // smoothed contact (0.5 m) lets it sink 7 cm, which moves H by about 0.1 % from the
  // rigid seabed of the reference.
  spec.seabed.stiffness = 3e7;
  spec.seabed.contact_smoothing = 0.02;
  spec.line_types = {testing::ChainType(), Rope(c)};
  spec.seabed.slope = std::abs(c.slope_deg) * std::numbers::pi / 180.0;
  spec.seabed.slope_direction = c.slope_deg < 0.0 ? std::numbers::pi : 0.0;
  LineParameters line;
  line.id = 1;
  const double anchor_depth =
      1000.0 + c.anchor_x * std::tan(c.slope_deg * std::numbers::pi / 180.0);
  line.anchor = Vec3(c.anchor_x, 0.0, anchor_depth);
  line.fairlead_body = Vec3(20.0, 0.0, 12.0);
  line.sections = {{"chain", 400.0, 20 * scale},
                   {"polyester", 1500.0, 60 * scale},
                   {"chain", 150.0, 10 * scale}};
  line.joints = c.joints;
  spec.lines.push_back(line);
  return spec;
}

std::vector<RefSection> ReferenceSections(const Case& c) {
  static const AxialCurve curve(kRopeCurve);
  return {
      {400.0, WeightInWater(testing::ChainType()), testing::ChainType().axial_stiffness},
      {1500.0, WeightInWater(Rope(c)), Rope(c).axial_stiffness, c.rope_curve ? &curve : nullptr},
      {150.0, WeightInWater(testing::ChainType()), testing::ChainType().axial_stiffness}};
}

std::vector<double> ReferenceJoints(const Case& c) {
  std::vector<double> w(2, 0.0);
  for (std::size_t k = 0; k < c.joints.size(); ++k) {
    w[k] = (c.joints[k].mass - kSeaWater * c.joints[k].volume) * kGravity;
  }
  return w;
}

const Case kCases[] = {
    {"plain", {}},
    // Pulled taut: the whole line hangs and the anchor carries an upward pull.
    {"taut", {}, 1850.0, false},
    // A 25 t clump weight where the bottom chain meets the polyester.
    {"clump", {{25000.0, 25000.0 / 7850.0, 1.0, 2.0}, {}}},
    // A buoy of 20 m^3 (5 t) where the polyester meets the top chain: 150 kN of lift.
    {"buoy", {{}, {5000.0, 20.0, 1.0, 6.0}}},
    // A buoyant rope (15 kg/m dry: 55 N/m of lift) hanging between the chains.
    {"buoyant_rope", {}, 1750.0, true, 15.0},
    // The rope on a measured tension-strain curve instead of a constant EA.
    {"rope_on_a_curve", {}, 1750.0, true, 26.0, true},
    // A seabed rising 2 deg toward the fairlead (the anchor 52 m deeper) and one falling
    // 4 deg (the anchor 122 m shallower); the chain lies on the slope.
    {"seabed_rising", {}, 1700.0, true, 26.0, false, 1.0},
    {"seabed_falling", {}, 1750.0, true, 26.0, false, -4.0},
    // A clump weight resting on the rising slope.
    {"clump_on_a_slope",
     {{25000.0, 25000.0 / 7850.0, 1.0, 2.0}, {}},
     1700.0,
     true,
     26.0,
     false,
     1.0},
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.name; }

class CompositeStatic : public ::testing::TestWithParam<Case> {};

TEST_P(CompositeStatic, FemTensionsMatchTheIndependentCatenary) {
  const Case& c = GetParam();
  const MooringParameters spec = CompositeSpec(c, 4);
  MooringSystem mooring(spec);
  const LineProperties& lp = mooring.line(0);
  PointKinematics fairlead;
  fairlead.position = lp.fairlead_body;  // the vessel at the origin
  const std::vector<Vec3> positions = {fairlead.position};
  std::vector<double> x(mooring.StateSize());
  mooring.CatenaryState(positions, x.data());
  mooring.SettleStatic(positions, x.data());

  const Vec3 chord = fairlead.position - lp.anchor;
  const double span = std::hypot(chord.x(), chord.y());
  const double height = lp.anchor.z() - fairlead.position.z();
  const double rise = c.slope_deg * std::numbers::pi / 180.0;
  const CompositeCatenary guess = SolveCompositeCatenary(CatenaryLineOf(lp, rise), span, height);
  const Reference ref = SolveReference(ReferenceSections(c), ReferenceJoints(c), rise, span, height,
                                       guess.horizontal_tension, guess.vertical_tension);

  // The closed forms against the quadrature.
  EXPECT_NEAR(guess.horizontal_tension, ref.h, 1e-6 * ref.h) << c.name;
  EXPECT_NEAR(guess.vertical_tension, ref.v_fairlead, 1e-6 * ref.FairleadTension()) << c.name;
  EXPECT_NEAR(guess.grounded_length, ref.grounded, 1e-6 * 2050.0) << c.name;
  EXPECT_EQ(ref.grounded > 1.0, c.grounded) << c.name << ": grounded " << ref.grounded << " m";

  // The FEM at rest: the fairlead force, and the anchor's from the first segment.
  const std::vector<PointKinematics> fairleads = {fairlead};
  const Vec3 f = mooring.LineLoads(x.data(), fairleads)[0].fairlead_force;
  EXPECT_NEAR(f.norm(), ref.FairleadTension(), 1e-3 * ref.FairleadTension()) << c.name;
  EXPECT_NEAR(f.head<2>().norm(), ref.h, 1e-3 * ref.h) << c.name;
  const double l0 = lp.sections.front().segment_length;
  const double stretched = (mooring.NodePosition(x.data(), 0, 1, fairleads) - lp.anchor).norm();
  const double anchor_tension = lp.sections.front().axial_stiffness * (stretched / l0 - 1.0);
  // That segment's tension is the tension half a segment up from the anchor: on a slope the
  // weight's component along it changes the tension by w sin(rise) per metre there.
  const double expected =
      ref.AnchorTension() +
      (ref.grounded > 0.0 ? WeightInWater(testing::ChainType()) * 0.5 * l0 * std::sin(rise) : 0.0);
  EXPECT_NEAR(anchor_tension, expected, 1e-3 * expected) << c.name;
  RecordProperty("fairlead_error", std::to_string(f.norm() / ref.FairleadTension() - 1.0));
  RecordProperty("anchor_error", std::to_string(anchor_tension / expected - 1.0));
}

INSTANTIATE_TEST_SUITE_P(Lines, CompositeStatic, ::testing::ValuesIn(kCases),
                         [](const auto& info) { return std::string(info.param.name); });

// The same model, written as one section per line type, is the homogeneous line exactly:
// a line cut into two sections of the same type at a node gives the same right-hand side
// to the last bit.
TEST(CompositeLine, TwoSectionsOfOneTypeAreTheHomogeneousLine) {
  MooringParameters one = CompositeSpec(kCases[0], 1);
  one.lines[0].sections = {{"chain", 2050.0, 41}};
  MooringParameters two = one;
  two.lines[0].sections = {{"chain", 1000.0, 20}, {"chain", 1050.0, 21}};
  MooringSystem a(one), b(two);
  const std::vector<Vec3> positions = {one.lines[0].fairlead_body};
  std::vector<double> x(a.StateSize());
  a.CatenaryState(positions, x.data());
  std::vector<PointKinematics> fairleads(1);
  fairleads[0].position = positions[0];
  std::vector<double> fa(x.size()), fb(x.size());
  a.Derivatives(x.data(), fairleads, fa.data());
  b.Derivatives(x.data(), fairleads, fb.data());
  for (std::size_t i = 0; i < x.size(); ++i) ASSERT_EQ(fa[i], fb[i]) << i;
}

// A line whose lower end hangs free (a line between two points in the water): no seabed
// under it, its vertical tension changing sign along a sag below both ends, and ends at
// any height (upper end below the lower one too): H and both ends' V within 1e-6 of the
// independent quadrature.
TEST(CompositeCatenary, AFreeLowerEndHangsAgainstTheReference) {
  CompositeLine line;
  line.sections = {{120.0, 900.0, 6e8}, {200.0, 40.0, 2e8}, {80.0, 900.0, 6e8}};
  line.joint_weights = {2e4, -3e4};
  line.lower_on_seabed = false;
  const std::vector<RefSection> sections = {
      {120.0, 900.0, 6e8}, {200.0, 40.0, 2e8}, {80.0, 900.0, 6e8}};
  const std::vector<double> joints = {2e4, -3e4};
  struct End {
    double span, height;
  };
  for (const End end : {End{300.0, 60.0}, End{340.0, 0.0}, End{250.0, -40.0}, End{380.0, 5.0}}) {
    const CompositeCatenary c = SolveCompositeCatenary(line, end.span, end.height);
    const Reference ref = SolveReference(sections, joints, 0.0, end.span, end.height,
                                         c.horizontal_tension * 1.01, c.vertical_tension, false);
    const double scale = c.fairlead_tension;
    EXPECT_NEAR(c.horizontal_tension, ref.h, 1e-6 * scale) << end.span << " " << end.height;
    EXPECT_NEAR(c.vertical_tension, ref.v_fairlead, 1e-6 * scale) << end.span << " " << end.height;
    EXPECT_NEAR(c.anchor_vertical, ref.v_anchor, 1e-6 * scale) << end.span << " " << end.height;
    EXPECT_DOUBLE_EQ(c.grounded_length, 0.0);
  }
  // A sag below both ends: the lower end is pulled down.
  EXPECT_LT(SolveCompositeCatenary(line, 300.0, 0.0).anchor_vertical, 0.0);
  // On the seabed the same ends give a grounded line, not a hanging one.
  line.lower_on_seabed = true;
  line.joint_weights = {2e4, 3e4};
  EXPECT_GT(SolveCompositeCatenary(line, 340.0, 80.0).grounded_length, 0.0);
  EXPECT_THROW(SolveCompositeCatenary(line, 300.0, -40.0), Error);
}

TEST(CompositeCatenary, LinesItCannotRepresentAreOneMessage) {
  CompositeLine line;
  EXPECT_THROW(SolveCompositeCatenary(line, 1000.0, 500.0), InputError);
  line.sections = {{500.0, 1000.0, 1e8}, {500.0, 1000.0, 1e8}};
  line.joint_weights = {1.0, 2.0};  // two joint weights for two sections
  EXPECT_THROW(SolveCompositeCatenary(line, 800.0, 300.0), InputError);
  // A buoy on the part that rests on the seabed.
  line.joint_weights = {-5e4};
  try {
    SolveCompositeCatenary(line, 400.0, 100.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("buoy at joint 1"), std::string::npos) << e.what();
  }
  // Too short to reach without straining beyond the elastic model's limit.
  line.joint_weights = {};
  EXPECT_THROW(SolveCompositeCatenary(line, 1150.0, 100.0), Error);
}

}  // namespace
}  // namespace moorsim::mooring_fem
