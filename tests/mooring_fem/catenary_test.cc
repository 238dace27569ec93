// Tests of the analytic elastic catenary (mooring_fem/catenary.h).
//
// The references here are independent of the implementation: the textbook equations as
// printed in Irvine, "Cable Structures" (1981) (direct asinh / sqrt form, not the
// cancellation-free form the solver uses), numerical integration of the line's tangent
// direction over arc length, the classic inextensible catenary, and a hand check of the
// seed case.
#include "mooring_fem/catenary.h"
#include "core/angles.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/types.h"

namespace moorsim::mooring_fem {
namespace {

// Seed case: 80 mm chain-like line, 275 kg/m dry, steel E = 4.5757e10 Pa on 0.005 m^2.
CatenaryLineProperties SeedLine() {
  CatenaryLineProperties line;
  line.length = 2250.0;
  line.weight_per_length = (275.0 - 1025.0 * kPi * 0.08 * 0.08 / 4.0) * 9.81;
  line.axial_stiffness = 4.5757e10 * 0.005;
  return line;
}

constexpr double kSeedSpan = 1930.0;   // anchor radius 1950 m - fairlead radius 20 m
constexpr double kSeedHeight = 988.0;  // anchor depth 1000 m - fairlead depth 12 m

/// The textbook equations (Irvine 1981 eqs. 2.21-2.22 and the touchdown variant) in their
/// printed form: fairlead position (span, height) produced by tensions (H, V).
Eigen::Vector2d TextbookEndpoint(const CatenaryLineProperties& line, double h, double v) {
  const double len = line.length;
  const double w = line.weight_per_length;
  const double ea = line.axial_stiffness;
  if (v < w * len) {
    const double grounded = len - v / w;
    return {grounded + (h / w) * std::asinh(v / h) + h * len / ea,
            (h / w) * (std::sqrt(1.0 + (v / h) * (v / h)) - 1.0) + v * v / (2.0 * ea * w)};
  }
  const double va = v - w * len;
  return {(h / w) * (std::asinh(v / h) - std::asinh(va / h)) + h * len / ea,
          (h / w) * (std::sqrt(1.0 + (v / h) * (v / h)) - std::sqrt(1.0 + (va / h) * (va / h))) +
              (v * len - 0.5 * w * len * len) / ea};
}

/// Tangent of the stretched line at unstretched arc length s, from the tensions alone:
/// d(x, z)/ds = (H, V(s)) / T(s) * (1 + T(s)/EA), with V(s) the vertical force there.
Eigen::Vector2d StretchedTangent(const CatenaryLineProperties& line, const CatenarySolution& sol,
                                 double s) {
  const double ea = line.axial_stiffness;
  const double h = sol.horizontal_tension;
  if (!sol.anchor_lifted && s <= sol.grounded_length) return {1.0 + h / ea, 0.0};
  const double vertical = sol.anchor_lifted ? sol.anchor_vertical + line.weight_per_length * s
                                            : line.weight_per_length * (s - sol.grounded_length);
  const double tension = std::hypot(h, vertical);
  return Eigen::Vector2d(h, vertical) / tension * (1.0 + tension / ea);
}

/// Composite Simpson integral of f over [a, b] with `panels` (even) intervals.
template <typename F>
auto Simpson(F f, double a, double b, int panels) {
  using Value = decltype(f(a));  // a plain value (double or Eigen::Vector2d), not an expression
  const double step = (b - a) / panels;
  Value sum = f(a);
  sum += f(b);
  for (int i = 1; i < panels; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * f(a + i * step);
  return Value(sum * (step / 3.0));
}

/// Position at arc length s by integrating the tangent (grounded and suspended pieces are
/// integrated separately: the integrand has a kink at touchdown).
Eigen::Vector2d IntegratedPoint(const CatenaryLineProperties& line, const CatenarySolution& sol,
                                double s) {
  const auto tangent = [&](double t) { return StretchedTangent(line, sol, t); };
  const double grounded = sol.anchor_lifted ? 0.0 : std::min(s, sol.grounded_length);
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  if (grounded > 0.0) p += Simpson(tangent, 0.0, grounded, 2);
  if (s > grounded) p += Simpson(tangent, grounded, s, 40000);
  return p;
}

/// Stretched length of the whole line: integral of (1 + T/EA) over unstretched length.
double StretchedLength(const CatenaryLineProperties& line, const CatenarySolution& sol) {
  const auto stretch = [&](double s) { return StretchedTangent(line, sol, s).norm(); };
  const double grounded = sol.anchor_lifted ? 0.0 : sol.grounded_length;
  double total = 0.0;
  if (grounded > 0.0) total += Simpson(stretch, 0.0, grounded, 2);
  total += Simpson(stretch, grounded, line.length, 40000);
  return total;
}

struct Geometry {
  std::string name;
  CatenaryLineProperties line;
  double span;
  double height;
};

/// A spread of regimes for the self-consistency tests.
std::vector<Geometry> Geometries() {
  const CatenaryLineProperties seed = SeedLine();
  CatenaryLineProperties light = seed;  // lighter, stiffer line in shallower water
  light.length = 400.0;
  light.weight_per_length = 700.0;
  light.axial_stiffness = 5e8;
  return {
      {"seed", seed, kSeedSpan, kSeedHeight},
      {"seed_offset_toward_anchor", seed, kSeedSpan - 80.0, kSeedHeight},
      {"seed_offset_away_from_anchor", seed, kSeedSpan + 80.0, kSeedHeight},
      {"seed_fully_suspended", seed, 2100.0, kSeedHeight},
      {"seed_slack_small_tension", seed, 1300.0, kSeedHeight},
      {"deep_anchor_suspended", seed, 1500.0, 1600.0},
      {"light_touchdown", light, 330.0, 90.0},
      {"light_suspended", light, 380.0, 90.0},
  };
}

// --- Seed case --------------------------------------------------------------------------

TEST(SolveCatenaryTest, SeedCaseMatchesIndependentCheck) {
  const CatenarySolution sol = SolveCatenary(SeedLine(), kSeedSpan, kSeedHeight);
  // The check printed 4 significant figures; 0.05 % is a few units in the last digit.
  constexpr double kRelative = 5e-4;
  EXPECT_NEAR(sol.horizontal_tension, 3.497e6, kRelative * 3.497e6);
  EXPECT_NEAR(sol.vertical_tension, 4.948e6, kRelative * 4.948e6);
  EXPECT_NEAR(sol.fairlead_tension, 6.059e6, kRelative * 6.059e6);
  // Printed to 0.1 m; Lb = L - V/w is sensitive, so allow the full last digit.
  EXPECT_NEAR(sol.grounded_length, 380.8, 0.1);
  EXPECT_FALSE(sol.anchor_lifted);
  EXPECT_EQ(sol.anchor_vertical, 0.0);
  EXPECT_EQ(sol.anchor_horizontal, sol.horizontal_tension);
}

TEST(SolveCatenaryTest, SeedWeightPerLengthIsAsQuoted) {
  // Quoted as 2647.2 N/m (rounded to 0.1 N/m).
  EXPECT_NEAR(SeedLine().weight_per_length, 2647.2, 0.05);
}

// --- Self-consistency ----------------------------------------------------------------------

TEST(SolveCatenaryTest, TextbookEquationResidualsVanish) {
  for (const Geometry& g : Geometries()) {
    SCOPED_TRACE(g.name);
    const CatenarySolution sol = SolveCatenary(g.line, g.span, g.height);
    const Eigen::Vector2d end =
        TextbookEndpoint(g.line, sol.horizontal_tension, sol.vertical_tension);
    // Solver converges to 1e-12 of the problem size; the printed formulas add rounding of a
    // few ulps of terms up to H/w * asinh(V/H) (< 1e4 m here), i.e. < 1e-11 m.
    const double tolerance = 2e-12 * std::max({g.span, g.height, g.line.length});
    EXPECT_NEAR(end.x(), g.span, tolerance);
    EXPECT_NEAR(end.y(), g.height, tolerance);
  }
}

TEST(CatenaryPointAtTest, EndpointsAreAnchorAndFairlead) {
  for (const Geometry& g : Geometries()) {
    SCOPED_TRACE(g.name);
    const CatenarySolution sol = SolveCatenary(g.line, g.span, g.height);
    const Eigen::Vector2d anchor = CatenaryPointAt(g.line, sol, 0.0);
    EXPECT_EQ(anchor.x(), 0.0);
    EXPECT_EQ(anchor.y(), 0.0);
    const Eigen::Vector2d fairlead = CatenaryPointAt(g.line, sol, g.line.length);
    // Required accuracy of the profile end (solver residual is ~1e-9 m at most).
    EXPECT_NEAR(fairlead.x(), g.span, 1e-8);
    EXPECT_NEAR(fairlead.y(), g.height, 1e-8);
  }
}

TEST(CatenaryPointAtTest, ProfileMatchesIntegratedTangent) {
  for (const Geometry& g : Geometries()) {
    SCOPED_TRACE(g.name);
    const CatenarySolution sol = SolveCatenary(g.line, g.span, g.height);
    for (int k = 0; k <= 16; ++k) {
      const double s = g.line.length * k / 16.0;
      SCOPED_TRACE("s = " + std::to_string(s));
      const Eigen::Vector2d expected = IntegratedPoint(g.line, sol, s);
      const Eigen::Vector2d actual = CatenaryPointAt(g.line, sol, s);
      // Simpson error ~ L d^4 k^4 / 180 with panel d <= 0.06 m and curvature k <= w/H
      // (0.15 /m in the slack case): < 1e-10 m; summation rounding of 4e4 terms: < 1e-10 m.
      EXPECT_NEAR(actual.x(), expected.x(), 1e-8);
      EXPECT_NEAR(actual.y(), expected.y(), 1e-8);
    }
    // The integrated profile ends at the fairlead: the same 1e-8 m as above.
    const Eigen::Vector2d end = IntegratedPoint(g.line, sol, g.line.length);
    EXPECT_NEAR(end.x(), g.span, 1e-8);
    EXPECT_NEAR(end.y(), g.height, 1e-8);
  }
}

/// Length of the polyline through `points` + 1 equally spaced material points.
double PolylineLength(const CatenaryLineProperties& line, const CatenarySolution& sol, int points) {
  double length = 0.0;
  Eigen::Vector2d previous = CatenaryPointAt(line, sol, 0.0);
  for (int k = 1; k <= points; ++k) {
    const Eigen::Vector2d p = CatenaryPointAt(line, sol, line.length * k / points);
    length += (p - previous).norm();
    previous = p;
  }
  return length;
}

TEST(CatenaryPointAtTest, StretchedLengthMatchesPolylineLength) {
  for (const Geometry& g : Geometries()) {
    SCOPED_TRACE(g.name);
    const CatenarySolution sol = SolveCatenary(g.line, g.span, g.height);
    const double stretched = StretchedLength(g.line, sol);
    EXPECT_GT(stretched, g.line.length);
    const double coarse = PolylineLength(g.line, sol, 10000);
    const double fine = PolylineLength(g.line, sol, 20000);
    EXPECT_LE(fine, stretched + 1e-9);  // a chord never exceeds its arc (1e-9: rounding)
    EXPECT_LE(coarse, fine + 1e-9);     // refining only adds length
    // A chord of arc d and curvature k is shorter by d^3 k^2 / 24, so the polyline error is
    // O(d^2); Richardson extrapolation removes that term, leaving O(d^4) (~1e-9 m), the
    // rounding of summing 2e4 lengths (~1e-10 m), and the chords straddling touchdown,
    // where k jumps from 0 to w/H: up to (w/H)^2 d^3 / 24 with d = L/1e4.
    const double extrapolated = (4.0 * fine - coarse) / 3.0;
    const double d = g.line.length / 10000.0;
    const double k = g.line.weight_per_length / sol.horizontal_tension;
    EXPECT_NEAR(extrapolated, stretched, 1e-7 + k * k * d * d * d / 24.0);
  }
}

TEST(CatenaryPointAtTest, GroundedPartIsStretchedByHorizontalTension) {
  const CatenaryLineProperties line = SeedLine();
  const CatenarySolution sol = SolveCatenary(line, kSeedSpan, kSeedHeight);
  for (double s : {1.0, 100.0, 0.5 * sol.grounded_length, sol.grounded_length}) {
    const Eigen::Vector2d p = CatenaryPointAt(line, sol, s);
    // Closed form x = s (1 + H/EA); only rounding differs.
    EXPECT_NEAR(p.x(), s * (1.0 + sol.horizontal_tension / line.axial_stiffness), 1e-12 * s);
    EXPECT_EQ(p.y(), 0.0);
  }
}

TEST(CatenaryPointAtTest, TangentAtEndsMatchesForces) {
  for (const Geometry& g : Geometries()) {
    if (g.name == "seed_slack_small_tension") continue;  // H tiny: slope ill-conditioned
    SCOPED_TRACE(g.name);
    const CatenarySolution sol = SolveCatenary(g.line, g.span, g.height);
    const double ds = 1e-3;
    // One-sided differences of step ds: slope error ~ ds * curvature < 1e-6, plus
    // rounding ~1e-13 m / 1e-3 m = 1e-10.
    const Eigen::Vector2d top = CatenaryPointAt(g.line, sol, g.line.length) -
                                CatenaryPointAt(g.line, sol, g.line.length - ds);
    EXPECT_NEAR(top.y() / top.x(), sol.vertical_tension / sol.horizontal_tension,
                1e-5 * sol.vertical_tension / sol.horizontal_tension);
    const Eigen::Vector2d bottom =
        CatenaryPointAt(g.line, sol, ds) - CatenaryPointAt(g.line, sol, 0.0);
    EXPECT_NEAR(bottom.y() / bottom.x(), sol.anchor_vertical / sol.anchor_horizontal, 1e-5);
  }
}

TEST(CatenaryPointAtTest, RejectsArcLengthOutsideLine) {
  const CatenaryLineProperties line = SeedLine();
  const CatenarySolution sol = SolveCatenary(line, kSeedSpan, kSeedHeight);
  EXPECT_THROW(CatenaryPointAt(line, sol, -1.0), Error);
  EXPECT_THROW(CatenaryPointAt(line, sol, line.length + 1.0), Error);
  EXPECT_THROW(CatenaryPointAt(line, sol, std::nan("")), Error);
}

// --- Force balance -------------------------------------------------------------------------

TEST(SolveCatenaryTest, VerticalForceEqualsSuspendedWeight) {
  for (const Geometry& g : Geometries()) {
    SCOPED_TRACE(g.name);
    const CatenarySolution sol = SolveCatenary(g.line, g.span, g.height);
    const double w = g.line.weight_per_length;
    const double suspended = g.line.length - sol.grounded_length;
    // Vertical equilibrium of the free body "suspended part": exact up to rounding.
    EXPECT_NEAR(sol.vertical_tension, w * suspended + sol.anchor_vertical,
                1e-12 * sol.vertical_tension);
    // Horizontal equilibrium: no horizontal load along the line.
    EXPECT_EQ(sol.anchor_horizontal, sol.horizontal_tension);
    EXPECT_NEAR(sol.fairlead_tension, std::hypot(sol.horizontal_tension, sol.vertical_tension),
                1e-12 * sol.fairlead_tension);
    if (sol.anchor_lifted) {
      EXPECT_GT(sol.anchor_vertical, 0.0);
      EXPECT_EQ(sol.grounded_length, 0.0);
    } else {
      EXPECT_EQ(sol.anchor_vertical, 0.0);
      EXPECT_GE(sol.grounded_length, 0.0);
    }
  }
}

// --- Fully suspended and the transition ----------------------------------------------------

TEST(SolveCatenaryTest, FullySuspendedLineLiftsAnchor) {
  const CatenaryLineProperties line = SeedLine();
  const CatenarySolution sol = SolveCatenary(line, 2100.0, kSeedHeight);
  EXPECT_TRUE(sol.anchor_lifted);
  EXPECT_EQ(sol.grounded_length, 0.0);
  EXPECT_GT(sol.anchor_vertical, 0.0);
  // Whole weight carried by the two ends (rounding only).
  EXPECT_NEAR(sol.vertical_tension - sol.anchor_vertical, line.weight_per_length * line.length,
              1e-12 * sol.vertical_tension);

  const CatenarySolution deep = SolveCatenary(line, 1500.0, 1600.0);
  EXPECT_TRUE(deep.anchor_lifted);
  EXPECT_GT(deep.anchor_vertical, 0.0);
}

/// Span at which the seed line just lifts off (Lb = 0, V = w L): with V = w L the touchdown
/// height equation gives a = H/w from sqrt(a^2 + L^2) - a = height - w L^2/(2 EA).
double LiftoffSpan(const CatenaryLineProperties& line, double height) {
  const double len = line.length;
  const double w = line.weight_per_length;
  const double ea = line.axial_stiffness;
  const double reduced = height - w * len * len / (2.0 * ea);
  const double a = (len * len - reduced * reduced) / (2.0 * reduced);
  return a * std::asinh(len / a) + w * a * len / ea;
}

TEST(SolveCatenaryTest, TouchdownAndSuspendedSolutionsJoinContinuously) {
  const CatenaryLineProperties line = SeedLine();
  const double liftoff = LiftoffSpan(line, kSeedHeight);
  ASSERT_GT(liftoff, 2010.0);  // sanity: seed offsets stay in touchdown
  ASSERT_LT(liftoff, 2100.0);

  const double delta = 1e-6 * liftoff;
  const CatenarySolution below = SolveCatenary(line, liftoff - delta, kSeedHeight);
  const CatenarySolution above = SolveCatenary(line, liftoff + delta, kSeedHeight);
  EXPECT_FALSE(below.anchor_lifted);
  EXPECT_TRUE(above.anchor_lifted);
  // dH/dspan and dV/dspan are ~3e4 N/m here, so over 2 delta ~ 4e-3 m the tensions move
  // by ~1e2 N, i.e. ~2e-5 relative; a jump between regimes would be far larger.
  EXPECT_NEAR(below.horizontal_tension, above.horizontal_tension, 1e-4 * above.horizontal_tension);
  EXPECT_NEAR(below.vertical_tension, above.vertical_tension, 1e-4 * above.vertical_tension);
  // At lift-off Lb -> 0 and Va -> 0: dLb/dspan ~ 5 m/m, dVa/dspan ~ 9e3 N/m.
  EXPECT_LT(below.grounded_length, 0.05);
  EXPECT_LT(above.anchor_vertical, 100.0);
  // The exact lift-off tensions: V = w L, H = w a.
  EXPECT_NEAR(above.vertical_tension, line.weight_per_length * line.length,
              1e-4 * above.vertical_tension);

  // Slopes match too (the map (H, V) -> (span, height) is C1 across lift-off): one-sided
  // differences over 1 m differ from the derivative by ~(1 m) * d2H/dspan2 / (dH/dspan),
  // about 1 % here.
  const auto h_at = [&](double span) {
    return SolveCatenary(line, span, kSeedHeight).horizontal_tension;
  };
  const double slope_below = (h_at(liftoff - delta) - h_at(liftoff - 1.0)) / (1.0 - delta);
  const double slope_above = (h_at(liftoff + 1.0) - h_at(liftoff + delta)) / (1.0 - delta);
  EXPECT_NEAR(slope_below, slope_above, 0.03 * slope_above);
}

// --- Inextensible limit --------------------------------------------------------------------

TEST(SolveCatenaryTest, RigidLineTouchdownMatchesClassicCatenary) {
  CatenaryLineProperties line = SeedLine();
  line.axial_stiffness = 1e20;  // strain ~1e-14: below double resolution of the geometry
  const CatenarySolution sol = SolveCatenary(line, kSeedSpan, kSeedHeight);
  ASSERT_FALSE(sol.anchor_lifted);
  const double a = sol.horizontal_tension / line.weight_per_length;  // catenary parameter
  const double suspended = line.length - sol.grounded_length;
  // Classic touchdown catenary: Ls^2 = h^2 + 2 a h, span = Lb + a acosh(1 + h/a).
  // Solver accuracy 1e-12 relative, amplified by cancellation in L - Lb: 1e-10 relative.
  EXPECT_NEAR(suspended * suspended, kSeedHeight * kSeedHeight + 2.0 * a * kSeedHeight,
              1e-10 * suspended * suspended);
  EXPECT_NEAR(sol.grounded_length + a * std::acosh(1.0 + kSeedHeight / a), kSeedSpan, 1e-8);
  // Fairlead tension of a touchdown catenary: T = H + w h.
  EXPECT_NEAR(sol.fairlead_tension, sol.horizontal_tension + line.weight_per_length * kSeedHeight,
              1e-10 * sol.fairlead_tension);
}

TEST(SolveCatenaryTest, RigidLineSuspendedMatchesClassicCatenary) {
  CatenaryLineProperties line = SeedLine();
  line.axial_stiffness = 1e20;  // see above
  const double span = 2000.0;
  const double height = 1000.0;
  const CatenarySolution sol = SolveCatenary(line, span, height);
  ASSERT_TRUE(sol.anchor_lifted);
  const double w = line.weight_per_length;
  const double a = sol.horizontal_tension / w;
  const double lambda = span / (2.0 * a);
  // Irvine (1981) sec. 1.3: L^2 - h^2 = (2 a sinh(span / 2a))^2 and
  // V + Va = w h coth(span / 2a). Rounding in sinh of lambda ~ 0.5: 1e-10 relative.
  EXPECT_NEAR(line.length * line.length - height * height, std::pow(2.0 * a * std::sinh(lambda), 2),
              1e-10 * line.length * line.length);
  EXPECT_NEAR(sol.vertical_tension + sol.anchor_vertical, w * height / std::tanh(lambda),
              1e-10 * sol.vertical_tension);
}

// --- Degenerate geometries -----------------------------------------------------------------

TEST(SolveCatenaryTest, VerticalLineWithGroundedPart) {
  const CatenaryLineProperties line = SeedLine();
  const CatenarySolution sol = SolveCatenary(line, 0.0, kSeedHeight);
  EXPECT_EQ(sol.horizontal_tension, 0.0);
  EXPECT_FALSE(sol.anchor_lifted);
  const double w = line.weight_per_length;
  const double suspended = sol.vertical_tension / w;
  // A hanging vertical line: height = Ls + w Ls^2 / (2 EA) (its own stretch); rounding only.
  EXPECT_NEAR(suspended + w * suspended * suspended / (2.0 * line.axial_stiffness), kSeedHeight,
              1e-10);
  EXPECT_NEAR(sol.grounded_length, line.length - suspended, 1e-10);
  EXPECT_EQ(sol.fairlead_tension, sol.vertical_tension);
  for (double s : {0.0, 100.0, sol.grounded_length, 2000.0, line.length}) {
    const Eigen::Vector2d p = CatenaryPointAt(line, sol, s);
    EXPECT_EQ(p.x(), 0.0);  // straight above the anchor, nothing off the vertical
  }
  const Eigen::Vector2d top = CatenaryPointAt(line, sol, line.length);
  EXPECT_NEAR(top.y(), kSeedHeight, 1e-8);  // endpoint requirement
}

TEST(SolveCatenaryTest, VerticalLineLiftedOff) {
  const CatenaryLineProperties line = SeedLine();
  const double height = 2300.0;  // 50 m more than L: the line is stretched off the seabed
  const CatenarySolution sol = SolveCatenary(line, 0.0, height);
  EXPECT_EQ(sol.horizontal_tension, 0.0);
  EXPECT_TRUE(sol.anchor_lifted);
  const double w = line.weight_per_length;
  // Mean tension (V + Va)/2 stretches L by 50 m: EA * 50 / L; rounding only.
  EXPECT_NEAR(0.5 * (sol.vertical_tension + sol.anchor_vertical),
              line.axial_stiffness * (height - line.length) / line.length,
              1e-10 * sol.vertical_tension);
  EXPECT_NEAR(sol.vertical_tension - sol.anchor_vertical, w * line.length,
              1e-12 * sol.vertical_tension);
  const Eigen::Vector2d top = CatenaryPointAt(line, sol, line.length);
  EXPECT_EQ(top.x(), 0.0);
  EXPECT_NEAR(top.y(), height, 1e-8);  // endpoint requirement
}

TEST(SolveCatenaryTest, SlackLineCarriesNoHorizontalTension) {
  const CatenaryLineProperties line = SeedLine();
  // The vertical hanging part is ~982.4 m, so any span below L - 982.4 m = 1267.6 m would
  // need the grounded part to double back: frictionless contact holds no H.
  const CatenarySolution vertical = SolveCatenary(line, 0.0, kSeedHeight);
  const double threshold = line.length - vertical.vertical_tension / line.weight_per_length;
  const CatenarySolution slack = SolveCatenary(line, 0.5 * threshold, kSeedHeight);
  EXPECT_EQ(slack.horizontal_tension, 0.0);
  EXPECT_EQ(slack.vertical_tension, vertical.vertical_tension);
  EXPECT_EQ(slack.grounded_length, vertical.grounded_length);

  // Just past the threshold H is tiny but positive and V continuous: the span gained by a
  // tension H is (H/w) (ln(2V/H) - 1), so 1 mm needs only H ~ 0.16 N.
  const CatenarySolution taut = SolveCatenary(line, threshold + 1e-3, kSeedHeight);
  EXPECT_GT(taut.horizontal_tension, 0.0);
  EXPECT_LT(taut.horizontal_tension, 1.0);
  // The height equation fixes T - H (up to stretch), and T ~ V here, so V moves by ~H.
  EXPECT_NEAR(taut.vertical_tension, vertical.vertical_tension, 2.0 * taut.horizontal_tension);
  const Eigen::Vector2d end = CatenaryPointAt(line, taut, line.length);
  EXPECT_NEAR(end.x(), threshold + 1e-3, 1e-8);  // endpoint requirement
  EXPECT_NEAR(end.y(), kSeedHeight, 1e-8);
}

TEST(SolveCatenaryTest, TautNearlyStraightLine) {
  CatenaryLineProperties line = SeedLine();
  line.axial_stiffness = 1e15;  // stretch ~1e-7: the slack below comes from L - chord
  // Chord 0.9999 L: 0.225 m of slack over 2250 m, tension ~20 times the line's weight.
  const double chord = 0.9999 * line.length;
  const double angle = 0.4;
  const double span = chord * std::cos(angle);
  const double height = chord * std::sin(angle);
  const CatenarySolution sol = SolveCatenary(line, span, height);
  EXPECT_TRUE(sol.anchor_lifted);
  EXPECT_GT(sol.fairlead_tension, 10.0 * line.weight_per_length * line.length);
  const Eigen::Vector2d end = CatenaryPointAt(line, sol, line.length);
  EXPECT_NEAR(end.x(), span, 1e-8);  // endpoint requirement
  EXPECT_NEAR(end.y(), height, 1e-8);
  // Shallow-sag parabola (Irvine 1981 sec. 3.2): arc - chord = 8 d^2 / (3 chord) for the
  // midspan sag d perpendicular to the chord. The neglected terms are O((d/chord)^2) and the
  // along-chord weight makes the profile slightly asymmetric (tension varies by
  // w L sin(angle) / T ~ 2 %), so allow 3 %.
  const double arc = StretchedLength(line, sol);
  const double expected_sag = std::sqrt(3.0 * chord * (arc - chord) / 8.0);
  const Eigen::Vector2d mid = CatenaryPointAt(line, sol, 0.5 * line.length);
  const double sag = (mid.x() * height - mid.y() * span) / chord;  // below the chord
  EXPECT_NEAR(sag, expected_sag, 0.03 * expected_sag);
}

TEST(SolveCatenaryTest, StretchedLineLongerThanUnstretchedLength) {
  const CatenaryLineProperties line = SeedLine();
  // Chord 5 % longer than L: only the elastic stretch lets the line reach.
  const double chord = 1.05 * line.length;
  const double span = chord * std::cos(0.5);
  const double height = chord * std::sin(0.5);
  const CatenarySolution sol = SolveCatenary(line, span, height);
  EXPECT_TRUE(sol.anchor_lifted);
  const Eigen::Vector2d end = CatenaryPointAt(line, sol, line.length);
  EXPECT_NEAR(end.x(), span, 1e-8);  // endpoint requirement
  EXPECT_NEAR(end.y(), height, 1e-8);
  // The stretched arc is at least the chord; the line still sags (~120 m at midspan:
  // w cos(angle) chord^2 / (8 T)), so the shallow-sag parabola adds 8 d^2 / (3 chord)
  // ~ 15 m; allow up to twice that.
  const double arc = StretchedLength(line, sol);
  EXPECT_GE(arc, chord);
  EXPECT_LE(arc, chord + 30.0);
  // Tension grows monotonically from anchor to fairlead by at most the weight w L, so the
  // fairlead strain lies between the mean strain (arc - L)/L and that plus w L / EA.
  const double fairlead_strain = sol.fairlead_tension / line.axial_stiffness;
  const double mean_strain = arc / line.length - 1.0;
  EXPECT_GE(fairlead_strain, mean_strain);
  EXPECT_LE(fairlead_strain,
            mean_strain + line.weight_per_length * line.length / line.axial_stiffness);
}

TEST(SolveCatenaryTest, ConvergesOverWideRangeOfGeometries) {
  // Spans from vertical to beyond taut, heights from 0.1 % to 100 % of L, stiffness from
  // rope-soft to rigid: every case either solves with the end reproduced or throws Error
  // because it would need more than 10 % strain.
  const CatenaryLineProperties seed = SeedLine();
  int solved = 0;
  for (double ea : {1e6, 1e8, 2.3e8, 1e10, 1e13}) {
    for (double height_fraction : {0.001, 0.05, 0.3, 0.44, 0.7, 0.95, 1.0}) {
      for (double chord_fraction :
           {0.0, 0.3, 0.56, 0.57, 0.6, 0.9, 0.99, 0.9999, 1.0, 1.001, 1.05, 1.09}) {
        CatenaryLineProperties line = seed;
        line.axial_stiffness = ea;
        const double height = height_fraction * line.length;
        const double chord = std::max(chord_fraction * line.length, height);
        const double span = std::sqrt(chord * chord - height * height);
        SCOPED_TRACE("EA " + std::to_string(ea) + " span " + std::to_string(span) + " height " +
                     std::to_string(height));
        CatenarySolution sol;
        try {
          sol = SolveCatenary(line, span, height);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("cannot reach"), std::string::npos) << e.what();
          continue;
        }
        ++solved;
        EXPECT_LE(sol.fairlead_tension / ea, 0.1);
        const Eigen::Vector2d end = CatenaryPointAt(line, sol, line.length);
        // Required endpoint accuracy; slack cases with H = 0 place the hanging part over
        // the anchor (documented), so compare the height only there.
        if (sol.horizontal_tension > 0.0 || span == 0.0) {
          EXPECT_NEAR(end.x(), span, 1e-8);
        }
        EXPECT_NEAR(end.y(), height, 1e-8);
      }
    }
  }
  EXPECT_GT(solved, 300);  // most of the 420 cases are reachable
}

TEST(SolveCatenaryTest, NearlyVerticalAndTwentyKilometreLinesSolveOrSayTheyCannotReach) {
  // An anchor (almost) straight under its fairlead, and lines of up to
  // 20 km, at every regime (slack, touchdown, lifted, taut). No iteration may end
  // unconverged: either the end is reproduced or Error says the line cannot reach.
  int solved = 0;
  for (double length : {1.0, 2250.0, 20000.0}) {
    for (double height_fraction : {1e-6, 0.3, 0.999, 1.0005}) {
      for (double span_fraction : {0.0, 1e-15, 1e-9, 1e-6, 1e-3, 0.05, 1.0}) {
        CatenaryLineProperties line = SeedLine();
        line.length = length;
        const double height = height_fraction * length;
        const double span = span_fraction * length;
        SCOPED_TRACE("L " + std::to_string(length) + " span " + std::to_string(span) + " height " +
                     std::to_string(height));
        CatenarySolution sol;
        try {
          sol = SolveCatenary(line, span, height);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("cannot reach"), std::string::npos) << e.what();
          continue;
        }
        ++solved;
        const Eigen::Vector2d end = CatenaryPointAt(line, sol, line.length);
        const double tolerance = 1e-9 * length;
        // Slack (H = 0) solutions place the hanging part over the anchor (documented).
        if (sol.horizontal_tension > 0.0 || span == 0.0) {
          EXPECT_NEAR(end.x(), span, tolerance);
        }
        EXPECT_NEAR(end.y(), height, tolerance);
        EXPECT_TRUE(std::isfinite(sol.fairlead_tension));
      }
    }
  }
  EXPECT_GT(solved, 60);  // of 84
}

// --- Errors ----------------------------------------------------------------------------------

TEST(SolveCatenaryTest, RejectsFairleadNotAboveAnchor) {
  const CatenaryLineProperties line = SeedLine();
  EXPECT_THROW(SolveCatenary(line, kSeedSpan, 0.0), Error);
  EXPECT_THROW(SolveCatenary(line, kSeedSpan, -10.0), Error);
  EXPECT_THROW(SolveCatenary(line, -1.0, kSeedHeight), Error);
  EXPECT_THROW(SolveCatenary(line, std::nan(""), kSeedHeight), Error);
  EXPECT_THROW(SolveCatenary(line, kSeedSpan, std::numeric_limits<double>::infinity()), Error);
}

TEST(SolveCatenaryTest, RejectsUnreachableFairlead) {
  const CatenaryLineProperties line = SeedLine();
  // Chord 2500 m vs L = 2250 m: 11 % strain just to reach.
  try {
    SolveCatenary(line, 2300.0, kSeedHeight);
    FAIL() << "expected moorsim::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot reach"), std::string::npos) << e.what();
  }
  // Chord 8 % longer, but the soft line would need > 10 % at the fairlead.
  CatenaryLineProperties soft = line;
  soft.axial_stiffness = 5e7;
  EXPECT_THROW(
      SolveCatenary(soft, 1.08 * line.length * std::cos(0.4), 1.08 * line.length * std::sin(0.4)),
      Error);
}

TEST(SolveCatenaryTest, RejectsInvalidLineProperties) {
  CatenaryLineProperties line = SeedLine();
  line.length = 0.0;
  EXPECT_THROW(SolveCatenary(line, kSeedSpan, kSeedHeight), Error);
  line = SeedLine();
  line.weight_per_length = -1.0;
  EXPECT_THROW(SolveCatenary(line, kSeedSpan, kSeedHeight), Error);
  line = SeedLine();
  line.axial_stiffness = 0.0;
  EXPECT_THROW(SolveCatenary(line, kSeedSpan, kSeedHeight), Error);
}

// --- 3D: SolveLineCatenary ---------------------------------------------------------------------

/// Seed geometry on a ray at `azimuth` from a vessel centre away from the origin.
struct SeedLayout {
  Vec3 anchor;
  Vec3 fairlead;
};

SeedLayout SeedGeometry(double azimuth, double offset_toward_anchor) {
  const Vec3 centre(120.0, -45.0, 0.0);
  const Vec3 ray(std::cos(azimuth), std::sin(azimuth), 0.0);
  return {centre + 1950.0 * ray + Vec3(0.0, 0.0, 1000.0),
          centre + (20.0 + offset_toward_anchor) * ray + Vec3(0.0, 0.0, 12.0)};
}

TEST(SolveLineCatenaryTest, MatchesPlanarSolution) {
  const CatenaryLineProperties line = SeedLine();
  const SeedLayout g = SeedGeometry(2.2, 0.0);
  const LineCatenary lc = SolveLineCatenary(line, g.anchor, g.fairlead);
  const CatenarySolution planar = SolveCatenary(line, kSeedSpan, kSeedHeight);
  // Span from the 3D coordinates differs from 1930 m by rounding (~1e-13 m), the tensions
  // by that times dH/dspan (~4e4 N/m): far below 1e-9 relative.
  EXPECT_NEAR(lc.solution.horizontal_tension, planar.horizontal_tension,
              1e-9 * planar.horizontal_tension);
  EXPECT_NEAR(lc.solution.vertical_tension, planar.vertical_tension,
              1e-9 * planar.vertical_tension);
  EXPECT_EQ(lc.anchor, g.anchor);
  EXPECT_EQ(lc.fairlead, g.fairlead);
  EXPECT_EQ(lc.line.length, line.length);
}

TEST(SolveLineCatenaryTest, FairleadForcePointsTowardAnchorAndDown) {
  const CatenaryLineProperties line = SeedLine();
  for (double azimuth : {0.0, 0.7, 2.2, -2.9}) {
    SCOPED_TRACE("azimuth " + std::to_string(azimuth));
    const SeedLayout g = SeedGeometry(azimuth, 0.0);
    const LineCatenary lc = SolveLineCatenary(line, g.anchor, g.fairlead);
    const Vec3 force = lc.fairlead_force;
    Vec3 toward_anchor = g.anchor - g.fairlead;
    toward_anchor.z() = 0.0;
    toward_anchor.normalize();
    const Vec3 horizontal(force.x(), force.y(), 0.0);
    // Directions and magnitudes are exact up to rounding of unit vectors (1e-15 relative).
    EXPECT_NEAR(horizontal.dot(toward_anchor), lc.solution.horizontal_tension,
                1e-12 * lc.solution.horizontal_tension);
    EXPECT_NEAR(horizontal.cross(toward_anchor).norm(), 0.0,
                1e-12 * lc.solution.horizontal_tension);
    EXPECT_GT(force.z(), 0.0);  // down in NED
    EXPECT_EQ(force.z(), lc.solution.vertical_tension);
    EXPECT_NEAR(force.norm(), lc.solution.fairlead_tension, 1e-12 * force.norm());
  }
}

TEST(SolveLineCatenaryTest, VerticalLineForceIsVertical) {
  const CatenaryLineProperties line = SeedLine();
  const Vec3 anchor(10.0, 20.0, 1000.0);
  const Vec3 fairlead(10.0, 20.0, 12.0);
  const LineCatenary lc = SolveLineCatenary(line, anchor, fairlead);
  EXPECT_EQ(lc.fairlead_force.x(), 0.0);
  EXPECT_EQ(lc.fairlead_force.y(), 0.0);
  EXPECT_GT(lc.fairlead_force.z(), 0.0);
  const Eigen::Matrix3Xd nodes = lc.NodePositions(10);
  EXPECT_NEAR((nodes.col(10) - fairlead).norm(), 0.0, 1e-8);  // endpoint requirement
}

TEST(SolveLineCatenaryTest, RejectsFairleadBelowAnchor) {
  const CatenaryLineProperties line = SeedLine();
  EXPECT_THROW(SolveLineCatenary(line, Vec3(0, 0, 100), Vec3(50, 0, 100)), Error);
  EXPECT_THROW(SolveLineCatenary(line, Vec3(0, 0, 100), Vec3(50, 0, 150)), Error);
  EXPECT_THROW(SolveLineCatenary(line, Vec3(0, 0, 1000), Vec3(3000, 0, 12)), Error);
}

TEST(NodePositionsTest, EndpointsAndMonotoneProgress) {
  const CatenaryLineProperties line = SeedLine();
  for (double offset : {-80.0, 0.0, 80.0, 180.0}) {  // 180 m: fully suspended
    SCOPED_TRACE("offset " + std::to_string(offset));
    const SeedLayout g = SeedGeometry(0.9, -offset);
    const LineCatenary lc = SolveLineCatenary(line, g.anchor, g.fairlead);
    constexpr int kSegments = 50;
    const Eigen::Matrix3Xd nodes = lc.NodePositions(kSegments);
    ASSERT_EQ(nodes.rows(), 3);
    ASSERT_EQ(nodes.cols(), kSegments + 1);
    EXPECT_EQ(Vec3(nodes.col(0)), g.anchor);                             // exactly
    EXPECT_NEAR((nodes.col(kSegments) - g.fairlead).norm(), 0.0, 1e-8);  // requirement

    Vec3 along = g.fairlead - g.anchor;
    along.z() = 0.0;
    along.normalize();
    const Vec3 across = along.cross(Vec3::UnitZ());
    const double w = line.weight_per_length;
    const double h = lc.solution.horizontal_tension;
    const double unstretched = line.length / kSegments;
    double previous_chord = 0.0;
    for (int k = 0; k < kSegments; ++k) {
      const Vec3 d = nodes.col(k + 1) - nodes.col(k);
      EXPECT_GT(d.dot(along), 0.0) << "k = " << k;  // progresses toward the fairlead
      EXPECT_LE(d.z(), 1e-12) << "k = " << k;       // never descends (NED z up is -z)
      // In the vertical plane through anchor and fairlead, up to rounding.
      EXPECT_NEAR((nodes.col(k) - g.anchor).dot(across), 0.0, 1e-9);
      // Each chord is at least the unstretched segment and at most the most stretched one.
      const double chord = d.norm();
      EXPECT_GE(chord, unstretched * (1.0 - 1e-3)) << "k = " << k;
      EXPECT_LE(chord, unstretched * (1.0 + lc.solution.fairlead_tension / line.axial_stiffness));
      // Spacing grows toward the fairlead (tension, hence stretch, grows); a chord can be
      // shorter than its arc by (k d)^2 / 24 with curvature k <= w/H, which is the only
      // allowed decrease (it shows at touchdown, where the line starts to curve).
      const double curvature_allowance = std::pow(w / h * chord, 2) / 24.0;
      EXPECT_GE(chord, previous_chord * (1.0 - curvature_allowance)) << "k = " << k;
      previous_chord = chord;
    }
  }
}

TEST(NodePositionsTest, NodesLieOnPlanarProfile) {
  const CatenaryLineProperties line = SeedLine();
  const SeedLayout g = SeedGeometry(-1.3, 0.0);
  const LineCatenary lc = SolveLineCatenary(line, g.anchor, g.fairlead);
  Vec3 along = g.fairlead - g.anchor;
  along.z() = 0.0;
  along.normalize();
  const Eigen::Matrix3Xd nodes = lc.NodePositions(20);
  for (int k = 0; k <= 20; ++k) {
    const Eigen::Vector2d p = CatenaryPointAt(line, lc.solution, line.length * k / 20.0);
    const Vec3 expected = g.anchor + p.x() * along - p.y() * Vec3::UnitZ();
    EXPECT_NEAR((nodes.col(k) - expected).norm(), 0.0, 1e-9);  // rounding of the mapping
  }
}

TEST(NodePositionsTest, SlackLineReachesFairlead) {
  // Fairlead 1000 m from the anchor horizontally: below the slack threshold (~1268 m), so
  // H = 0 and the grounded part is heaped between the anchor and the foot of the vertical.
  const CatenaryLineProperties line = SeedLine();
  const Vec3 anchor(0.0, 0.0, 1000.0);
  const Vec3 fairlead(600.0, 800.0, 12.0);
  const LineCatenary lc = SolveLineCatenary(line, anchor, fairlead);
  EXPECT_EQ(lc.solution.horizontal_tension, 0.0);
  const Eigen::Matrix3Xd nodes = lc.NodePositions(40);
  EXPECT_EQ(Vec3(nodes.col(0)), anchor);
  EXPECT_NEAR((nodes.col(40) - fairlead).norm(), 0.0, 1e-8);  // endpoint requirement
  for (int k = 0; k < 40; ++k) {
    EXPECT_LE(nodes(2, k + 1), nodes(2, k) + 1e-12);  // never descends
  }
}

TEST(NodePositionsTest, RejectsZeroSegments) {
  const SeedLayout g = SeedGeometry(0.0, 0.0);
  const LineCatenary lc = SolveLineCatenary(SeedLine(), g.anchor, g.fairlead);
  EXPECT_THROW(lc.NodePositions(0), Error);
}

// --- Touchdown range and the span for a pretension ---------------------------------------

TEST(TouchdownRangeTest, EndsAreTheSlackLineAndLiftOff) {
  const CatenaryLineProperties line = SeedLine();
  const double w = line.weight_per_length;
  const TouchdownRange range = SolveTouchdownRange(line, kSeedHeight);
  // Slack end: a vertical hanging length Ls with Ls + w Ls^2 / (2 EA) = height, the rest on
  // the seabed.
  const double hanging = range.min_tension / w;
  EXPECT_NEAR(hanging + w * hanging * hanging / (2.0 * line.axial_stiffness), kSeedHeight, 1e-9);
  EXPECT_NEAR(range.min_span, line.length - hanging, 1e-9);
  // Lift-off end, checked on the printed textbook equations: V = w L, and (H, V) put the
  // fairlead at (max_span, height).
  const double v = w * line.length;
  const double h = std::sqrt(range.max_tension * range.max_tension - v * v);
  const Eigen::Vector2d end = TextbookEndpoint(line, h, v * (1.0 - 1e-15));
  EXPECT_NEAR(end.x(), range.max_span, 1e-6);
  EXPECT_NEAR(end.y(), kSeedHeight, 1e-6);
  // The seed line's anchors (1930 m from their fairleads) lie inside.
  EXPECT_LT(range.min_span, kSeedSpan);
  EXPECT_GT(range.max_span, kSeedSpan);
  const CatenarySolution at_lift_off = SolveCatenary(line, range.max_span, kSeedHeight);
  EXPECT_NEAR(at_lift_off.fairlead_tension, range.max_tension, 1e-9 * range.max_tension);
  EXPECT_NEAR(at_lift_off.grounded_length, 0.0, 1e-6);
}

TEST(TouchdownRangeTest, SpanForTensionGivesThatTension) {
  const CatenaryLineProperties line = SeedLine();
  const TouchdownRange range = SolveTouchdownRange(line, kSeedHeight);
  for (double fraction : {1e-6, 0.01, 0.3, 0.7, 0.999, 1.0}) {
    const double tension = range.min_tension + fraction * (range.max_tension - range.min_tension);
    const double span = SpanForFairleadTension(line, kSeedHeight, tension);
    EXPECT_GE(span, range.min_span);
    EXPECT_LE(span, range.max_span);
    EXPECT_NEAR(SolveCatenary(line, span, kSeedHeight).fairlead_tension, tension, 1e-6 * tension)
        << "fraction " << fraction;
  }
  // The seed span gives back its own tension.
  const double seed_tension = SolveCatenary(line, kSeedSpan, kSeedHeight).fairlead_tension;
  EXPECT_NEAR(SpanForFairleadTension(line, kSeedHeight, seed_tension), kSeedSpan, 1e-6);
}

TEST(TouchdownRangeTest, RejectsTensionsOutsideAndLinesThatCannotTouchDown) {
  const CatenaryLineProperties line = SeedLine();
  const TouchdownRange range = SolveTouchdownRange(line, kSeedHeight);
  EXPECT_THROW(SpanForFairleadTension(line, kSeedHeight, range.min_tension), Error);
  EXPECT_THROW(SpanForFairleadTension(line, kSeedHeight, range.max_tension * 1.001), Error);
  EXPECT_THROW(SpanForFairleadTension(line, kSeedHeight, std::nan("")), Error);
  CatenaryLineProperties short_line = line;
  // Hanging straight down it needs 982.4 m to reach 988 m below (stretched by its weight).
  short_line.length = 980.0;
  EXPECT_THROW(SolveTouchdownRange(short_line, kSeedHeight), Error);
  EXPECT_THROW(SolveTouchdownRange(line, 0.0), Error);
  // 20 km in 1000 m of water: lift-off only beyond 10 % strain.
  CatenaryLineProperties long_line = line;
  long_line.length = 20000.0;
  EXPECT_THROW(SolveTouchdownRange(long_line, kSeedHeight), Error);
}

}  // namespace
}  // namespace moorsim::mooring_fem
