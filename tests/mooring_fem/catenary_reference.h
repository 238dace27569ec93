// An independent reference for lines at rest, for the tests: the elastic catenary's
// differential equations integrated by Simpson's rule (not the closed forms the code uses),
// a line of sections with point weights at their joints, from its lower end to its upper
// end. With `seabed`, the seabed (a plane rising at `rise` toward the upper end) carries the
// line from the lower end to where its vertical tension reaches H tan(rise); without, the
// whole line hangs in the water (a line between two points).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "mooring_fem/axial_curve.h"

namespace moorsim::mooring_fem::reference {

// On a seabed that rises at the angle a from the anchor toward the fairlead, the reference
// lays the line on the slope up to where V reaches H tan(a), with the tension along it
// H cos(a) + V sin(a) (frictionless: the weight's component along the slope changes it),
// integrated by Simpson's rule too.

// --- The reference: a line of sections (w, EA, L) with point weights at the joints.

struct RefSection {
  double length, weight, stiffness;   // [m], in water [N/m], EA [N]
  const AxialCurve* curve = nullptr;  // in place of EA
  double Strain(double tension) const {
    return curve != nullptr ? curve->Strain(tension) : tension / stiffness;
  }
};

struct Reference {
  double h = 0.0, v_fairlead = 0.0, v_anchor = 0.0, grounded = 0.0, anchor_tension = 0.0;
  double FairleadTension() const { return std::hypot(h, v_fairlead); }
  double AnchorTension() const { return anchor_tension; }
};

// x and z of the fairlead relative to the anchor for (H, V_f), by quadrature of
// dx/ds = H/T + H/EA, dz/ds = V/T + V/EA on each suspended stretch.
inline Eigen::Vector2d Closure(const std::vector<RefSection>& sections,
                               const std::vector<double>& joints, double rise, double h, double v_f,
                               Reference* out = nullptr, bool seabed = true) {
  const std::size_t n = sections.size();
  // V just above the lower end of each section, walking down from the fairlead.
  std::vector<double> v_low(n);
  double v = v_f;
  for (std::size_t i = n; i-- > 0;) {
    v -= sections[i].weight * sections[i].length;
    v_low[i] = v;
    if (i > 0) v -= joints[i - 1];
  }
  // The grounded stretch from the anchor: while V < H tan(rise) (weights below are all >= 0
  // here).
  const double lift_off = h * std::tan(rise);
  double grounded = 0.0;
  if (seabed && v_low[0] < lift_off) {
    double start = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double top = v_low[i] + sections[i].weight * sections[i].length;
      if (top >= lift_off) {
        grounded = start + (lift_off - v_low[i]) / sections[i].weight;
        break;
      }
      start += sections[i].length;
      if (i + 1 < n && v_low[i + 1] >= lift_off) {
        grounded = start;
        break;
      }
    }
  }
  Eigen::Vector2d p(0.0, 0.0);
  double start = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const RefSection& s = sections[i];
    const double g = std::clamp(grounded - start, 0.0, s.length);  // grounded part here
    if (g > 0.0) {  // along the slope, its tension varying with V (slack where it is <= 0)
      constexpr int kIntervals = 2000;
      const double step = g / kIntervals;
      double sum = 0.0;
      for (int k = 0; k <= kIntervals; ++k) {
        const double vs = v_low[i] + s.weight * k * step;
        const double t = std::max(0.0, h * std::cos(rise) + vs * std::sin(rise));
        sum += (k == 0 || k == kIntervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0)) * (1.0 + s.Strain(t));
      }
      p += sum * step / 3.0 * Eigen::Vector2d(std::cos(rise), std::sin(rise));
    }
    const double a = g, b = s.length;
    if (b > a) {
      constexpr int kIntervals = 4000;  // even: Simpson
      const double step = (b - a) / kIntervals;
      Eigen::Vector2d sum(0.0, 0.0);
      for (int k = 0; k <= kIntervals; ++k) {
        const double vs = v_low[i] + s.weight * (a + k * step);
        const double t = std::hypot(h, vs);
        const double stretch = 1.0 + s.Strain(t);
        const Eigen::Vector2d f(h / t * stretch, vs / t * stretch);
        sum += (k == 0 || k == kIntervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0)) * f;
      }
      p += sum * step / 3.0;
    }
    start += s.length;
  }
  if (out != nullptr) {
    out->h = h;
    out->v_fairlead = v_f;
    out->v_anchor = grounded > 0.0 ? 0.0 : v_low[0];
    out->anchor_tension = grounded > 0.0
                              ? std::max(0.0, h * std::cos(rise) + v_low[0] * std::sin(rise))
                              : std::hypot(h, v_low[0]);
    out->grounded = grounded;
  }
  return p;
}

inline Reference SolveReference(const std::vector<RefSection>& sections,
                                const std::vector<double>& joints, double rise, double span,
                                double height, double h, double v, bool seabed = true) {
  const Eigen::Vector2d target(span, height);
  const auto closure = [&](double hh, double vv) {
    return Closure(sections, joints, rise, hh, vv, nullptr, seabed);
  };
  for (int iteration = 0; iteration < 100; ++iteration) {
    const Eigen::Vector2d r = closure(h, v) - target;
    if (r.norm() < 1e-9) break;
    Eigen::Matrix2d j;
    const double dh = 1e-4 * h, dv = 1e-4 * h;
    j.col(0) = (closure(h + dh, v) - closure(h - dh, v)) / (2.0 * dh);
    j.col(1) = (closure(h, v + dv) - closure(h, v - dv)) / (2.0 * dv);
    const Eigen::Vector2d step = j.partialPivLu().solve(-r);
    double lambda = 1.0;
    while (h + lambda * step.x() <= 0.0) lambda *= 0.5;
    h += lambda * step.x();
    v += lambda * step.y();
  }
  Reference out;
  const Eigen::Vector2d r = Closure(sections, joints, rise, h, v, &out, seabed) - target;
  EXPECT_LT(r.norm(), 1e-8) << "the reference did not close";
  return out;
}

}  // namespace moorsim::mooring_fem::reference
