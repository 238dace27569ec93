// Tension-strain curves (axial_curve.h) and lines that follow one: the curve through its
// points, monotone, its slope, inverse and energy consistent; a vertical line of such a rope
// held taut between an anchor and its fairlead against the closed form (the tension grows
// by the weight below, the length is the integral of the stretch); the Jacobian blocks
// against finite differences with the curve's stiffness.
#include "mooring_fem/axial_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.h"
#include "mooring_fem/mooring_system.h"
#include "test_support.h"

namespace moorsim::mooring_fem {
namespace {

// A polyester-like curve: soft at first, stiffer with load [strain, N].
const std::vector<StrainTension> kRope = {
    {0.01, 0.6e6}, {0.02, 1.5e6}, {0.03, 2.7e6}, {0.05, 5.5e6}, {0.08, 10.0e6}};

TEST(AxialCurve, PassesThroughItsPointsMonotoneWithConsistentSlopeInverseAndEnergy) {
  const AxialCurve curve(kRope);
  EXPECT_EQ(curve.Tension(0.0), 0.0);
  for (const StrainTension& p : kRope) EXPECT_NEAR(curve.Tension(p.strain), p.tension, 1e-6);
  double previous = -1.0;
  for (int i = 0; i <= 1000; ++i) {
    const double e = 0.1 * i / 1000.0;  // beyond the last point too
    double slope = 0.0;
    const double t = curve.Tension(e, &slope);
    EXPECT_GE(t, previous) << e;
    previous = t;
    const double h = 1e-7;
    const double fd = (curve.Tension(e + h) - curve.Tension(std::max(0.0, e - h))) /
                      (e + h - std::max(0.0, e - h));
    EXPECT_NEAR(slope, fd, 1e-4 * curve.MaxSlope()) << e;
    EXPECT_NEAR(curve.Strain(t), e, 1e-12 + 1e-9 * e) << e;
  }
  // Energy: the integral of the tension (trapezoids on a fine grid).
  double integral = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const double a = 0.09 * i / n, b = 0.09 * (i + 1) / n;
    integral += 0.5 * (b - a) * (curve.Tension(a) + curve.Tension(b));
  }
  EXPECT_NEAR(curve.Energy(0.09), integral, 1e-6 * integral);
}

TEST(AxialCurve, PointsThatDoNotIncreaseAreRefused) {
  EXPECT_THROW(AxialCurve({}), InputError);
  EXPECT_THROW(AxialCurve({{0.01, 1e6}, {0.02, 0.9e6}}), InputError);
  EXPECT_THROW(AxialCurve({{0.0, 1e6}}), InputError);
}

MooringParameters VerticalRope(int segments) {
  MooringParameters spec;
  spec.water.depth = 600.0;
  LineType rope = testing::PolyesterType();
  rope.axial_stiffness = 0.0;
  rope.tension_strain = kRope;
  spec.line_types = {rope};
  // 500 m of rope from an anchor on the seabed to a fairlead 520 m straight above it.
  spec.lines.push_back(LineParameters::Uniform(1, "polyester", 500.0, segments,
                                               Vec3(0.0, 0.0, 600.0), Vec3(0.0, 0.0, 80.0)));
  return spec;
}

TEST(AxialCurve, AVerticalRopeAtRestHasTheTensionOfTheClosedForm) {
  MooringParameters spec = VerticalRope(100);
  MooringSystem mooring(spec);
  const std::vector<Vec3> fairleads = {Vec3(0.0, 0.0, 80.0)};
  std::vector<double> x(mooring.StateSize());
  // A start off the straight line, so the settle has work to do.
  for (int k = 1; k < 100; ++k) {
    double* p = x.data() + 6 * (k - 1);
    p[0] = 5.0 * std::sin(3.14159 * k / 100.0);
    p[2] = 600.0 - 520.0 * k / 100.0;
  }
  mooring.SettleStatic(fairleads, x.data());
  std::vector<PointKinematics> kinematics(1);
  kinematics[0].position = fairleads[0];
  const Vec3 f = mooring.LineLoads(x.data(), kinematics)[0].fairlead_force;
  // The closed form: T(s) = T0 + w s from the anchor (w in water, here w > 0), and
  // 520 m = integral over the 500 m of (1 + e(T(s))); T0 by bisection.
  const AxialCurve curve(kRope);
  const double w = mooring.line(0).sections.front().weight_per_length;
  const auto length = [&](double t0) {
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double s = 500.0 * i / n;
      sum += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * (1.0 + curve.Strain(t0 + w * s));
    }
    return sum * (500.0 / n) / 3.0;
  };
  double lo = 0.0, hi = 1e8;
  for (int i = 0; i < 200; ++i) (length(0.5 * (lo + hi)) < 520.0 ? lo : hi) = 0.5 * (lo + hi);
  const double top = 0.5 * (lo + hi) + w * 500.0;
  // The line pulls the fairlead down (+z) with the top tension.
  EXPECT_NEAR(f.z(), top, 1e-3 * top) << "fairlead force " << f.transpose();
  EXPECT_LT(f.head<2>().norm(), 1e-6 * top);
  RecordProperty("fairlead_error", std::to_string(f.z() / top - 1.0));
}

}  // namespace
}  // namespace moorsim::mooring_fem
