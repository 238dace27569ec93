#include "mooring_fem/composite_catenary.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "core/error.h"

namespace moorsim::mooring_fem {

namespace {

constexpr int kMaxClosureIterations = 200;

// The same for a section whose strain follows a curve: dx/ds = H/T (1 + e(T)),
// dz/ds = V/T (1 + e(T)), V = v1 + w s, by Simpson's rule on 256 intervals (a smooth
// integrand: its error is far below the closure tolerance's effect on H).
Eigen::Vector2d CurvedStretch(double h, double w, const AxialCurve& curve, double v1, double l) {
  constexpr int kIntervals = 256;
  const double step = l / kIntervals;
  Eigen::Vector2d sum(0.0, 0.0);
  for (int k = 0; k <= kIntervals; ++k) {
    const double v = v1 + w * step * k;
    const double t = std::hypot(h, v);
    const double stretch = 1.0 + curve.Strain(t);
    const double weight = k == 0 || k == kIntervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += weight * Eigen::Vector2d(h / t * stretch, v / t * stretch);
  }
  return sum * step / 3.0;
}

// Span and rise of a suspended stretch of unstretched length l of a section (weight w per
// metre, stiffness ea) whose vertical tension is v1 at its lower end, under H > 0.
Eigen::Vector2d Stretch(double h, double w, double ea, double v1, double l) {
  const double v2 = v1 + w * l;
  const double t1 = std::hypot(h, v1);
  const double t2 = std::hypot(h, v2);
  double dx = 0.0;
  double dz = 0.0;
  if (std::abs(w * l) <= 1e-8 * std::max(t1, t2)) {  // weightless: straight
    const double v = 0.5 * (v1 + v2);
    const double t = std::hypot(h, v);
    dx = l * h / t;
    dz = l * v / t;
  } else {
    dx = h / w * (std::asinh(v2 / h) - std::asinh(v1 / h));
    dz = (t2 - t1) / w;
  }
  return {dx + h * l / ea, dz + l * (v1 + v2) / (2.0 * ea)};
}

// The line's layout: where each section starts, and the vertical tension at the bottom and
// top of each for a given fairlead V.
struct Layout {
  std::vector<double> start;  // arc length of each section's lower end; start.back() = L
  std::vector<double> bottom, top;
  double grounded = 0.0;  // arc length resting on the seabed from the anchor
};

double JointWeight(const CompositeLine& line, std::size_t k) {
  return line.joint_weights.empty() ? 0.0 : line.joint_weights[k];
}

// The vertical tension at which the line leaves the seabed under H = h.
double TouchdownVertical(const CompositeLine& line, double h) {
  return h * std::tan(line.seabed_rise);
}

// The tension along the seabed where the laid-out vertical tension is v (>= 0: slack).
double GroundedTension(const CompositeLine& line, double h, double v) {
  return std::max(0.0, h * std::cos(line.seabed_rise) + v * std::sin(line.seabed_rise));
}

// The stretched length of a grounded stretch of length l on a slope whose tension runs
// linearly from t1 to t2 (slack where negative): exact for a linear section, Simpson's rule
// on 64 intervals for a curve.
double GroundedStretch(double t1, double t2, double l, double ea, const AxialCurve* curve) {
  if (t1 == t2) {  // a flat seabed: one tension along it
    const double t = std::max(0.0, t1);
    return l * (1.0 + (curve != nullptr ? curve->Strain(t) : t / ea));
  }
  if (curve != nullptr) {
    constexpr int kIntervals = 64;
    double sum = 0.0;
    for (int k = 0; k <= kIntervals; ++k) {
      const double t = std::max(0.0, t1 + (t2 - t1) * k / kIntervals);
      const double weight = k == 0 || k == kIntervals ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
      sum += weight * (1.0 + curve->Strain(t));
    }
    return sum * l / (3.0 * kIntervals);
  }
  if (t1 >= 0.0 && t2 >= 0.0) return l * (1.0 + 0.5 * (t1 + t2) / ea);
  if (t1 <= 0.0 && t2 <= 0.0) return l;
  // Taut on the part where the tension is positive: a triangle.
  const double peak = std::max(t1, t2);
  const double taut = l * peak / std::abs(t2 - t1);
  return l + taut * 0.5 * peak / ea;
}

Layout LayOut(const CompositeLine& line, double h, double v_fairlead) {
  const std::size_t n = line.sections.size();
  Layout out;
  out.start.assign(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) out.start[i + 1] = out.start[i] + line.sections[i].length;
  out.bottom.assign(n, 0.0);
  out.top.assign(n, 0.0);
  double v = v_fairlead;
  for (std::size_t i = n; i-- > 0;) {
    out.top[i] = v;
    out.bottom[i] = v - line.sections[i].weight_per_length * line.sections[i].length;
    if (i > 0) v = out.bottom[i] - JointWeight(line, i - 1);
  }
  // Touchdown: walking up from the anchor while V < H tan(rise) the line lies on the
  // seabed.
  const double touchdown = TouchdownVertical(line, h);
  if (!line.lower_on_seabed || out.bottom[0] >= touchdown) return out;  // the whole line hangs
  for (std::size_t i = 0; i < n; ++i) {
    const CatenaryLineProperties& section = line.sections[i];
    if (out.top[i] >= touchdown) {
      out.grounded = out.start[i] + (touchdown - out.bottom[i]) / section.weight_per_length;
      return out;
    }
    if (!(section.weight_per_length > 0.0)) {
      throw InputError("catenary: section " + std::to_string(i + 1) +
                       " is buoyant but lies on the seabed");
    }
    if (i + 1 < n) {
      if (JointWeight(line, i) < 0.0) {
        throw InputError("catenary: the buoy at joint " + std::to_string(i + 1) +
                         " lies on the seabed (it cannot: it floats)");
      }
      if (out.bottom[i + 1] >= touchdown) {
        out.grounded = out.start[i + 1];
        return out;
      }
    }
  }
  out.grounded = out.start[n];
  return out;
}

// The point at arc length s for (H, V_f).
Eigen::Vector2d Point(const CompositeLine& line, const Layout& layout, double h, double s) {
  Eigen::Vector2d p(0.0, 0.0);
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    const CatenaryLineProperties& section = line.sections[i];
    const double lower = layout.start[i];
    const double upper = std::min(layout.start[i + 1], s);
    if (upper <= lower) break;
    // The grounded part of this section, then the hanging part.
    const double grounded_top = std::clamp(layout.grounded, lower, upper);
    const AxialCurve* curve = line.CurveOf(i);
    if (grounded_top > lower) {  // along the seabed, the tension set by V (file comment)
      const double t1 = GroundedTension(line, h, layout.bottom[i]);
      const double t2 = GroundedTension(
          line, h, layout.bottom[i] + section.weight_per_length * (grounded_top - lower));
      p += GroundedStretch(t1, t2, grounded_top - lower, section.axial_stiffness, curve) *
           Eigen::Vector2d(std::cos(line.seabed_rise), std::sin(line.seabed_rise));
    }
    if (upper > grounded_top) {
      const double v1 = layout.bottom[i] + section.weight_per_length * (grounded_top - lower);
      p += curve ? CurvedStretch(h, section.weight_per_length, *curve, v1, upper - grounded_top)
                 : Stretch(h, section.weight_per_length, section.axial_stiffness, v1,
                           upper - grounded_top);
    }
  }
  return p;
}

void CheckLine(const CompositeLine& line) {
  if (line.sections.empty()) throw InputError("catenary: a line needs at least one section");
  if (!line.joint_weights.empty() && line.joint_weights.size() + 1 != line.sections.size()) {
    throw InputError("catenary: " + std::to_string(line.joint_weights.size()) +
                     " joint weights for " + std::to_string(line.sections.size()) + " sections");
  }
  if (!(std::abs(line.seabed_rise) < 0.5 * std::numbers::pi)) {
    std::ostringstream out;
    out << "catenary: the seabed's rise " << line.seabed_rise
        << " rad must be between -pi/2 and pi/2";
    throw InputError(out.str());
  }
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    const CatenaryLineProperties& s = line.sections[i];
    if (!(std::isfinite(s.length) && s.length > 0.0 && std::isfinite(s.weight_per_length) &&
          std::isfinite(s.axial_stiffness) && s.axial_stiffness > 0.0)) {
      std::ostringstream out;
      out << "catenary: section " << i + 1
          << " needs a finite positive length and stiffness (L = " << s.length
          << " m, w = " << s.weight_per_length << " N/m, EA = " << s.axial_stiffness << " N)";
      throw InputError(out.str());
    }
  }
}

}  // namespace

double CompositeCatenary::VerticalTensionAt(double s) const {
  const Layout layout = LayOut(line, horizontal_tension, vertical_tension);
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    if (s <= layout.start[i + 1] || i + 1 == line.sections.size()) {
      const double v =
          layout.bottom[i] + line.sections[i].weight_per_length * (s - layout.start[i]);
      if (!(s < layout.grounded)) return v;
      return GroundedTension(line, horizontal_tension, v) * std::sin(line.seabed_rise);
    }
  }
  return vertical_tension;
}

Eigen::Vector2d CompositeCatenary::PointAt(double s) const {
  return Point(line, LayOut(line, horizontal_tension, vertical_tension), horizontal_tension, s);
}

CompositeCatenary SolveCompositeCatenary(const CompositeLine& line, double span, double height,
                                         double max_strain) {
  CheckLine(line);
  const bool ends_apart = line.lower_on_seabed ? height > 0.0 : std::hypot(span, height) > 0.0;
  if (!(std::isfinite(span) && span >= 0.0 && std::isfinite(height) && ends_apart)) {
    std::ostringstream out;
    out << "catenary: the fairlead must be "
        << (line.lower_on_seabed ? "above the anchor" : "apart from the lower end") << " (span "
        << span << " m, height " << height << " m)";
    throw Error(out.str());
  }
  // The start: the homogeneous line of the same length, weight and compliance.
  double length = 0.0, weight = 0.0, compliance = 0.0;
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    const CatenaryLineProperties& s = line.sections[i];
    length += s.length;
    weight += s.weight_per_length * s.length;
    compliance += s.length / s.axial_stiffness;
    if (i + 1 < line.sections.size()) weight += JointWeight(line, i);
  }
  const Eigen::Vector2d target(span, height);
  const double chord = target.norm();
  double h = 0.0;
  double v = 0.0;
  try {
    if (!(height > 0.0)) throw Error("no hanging start below the lower end");
    const CatenarySolution uniform =
        SolveCatenary({length, std::max(weight / length, 1e-6 * std::abs(weight) / length + 1e-9),
                       length / compliance},
                      span, height);
    h = uniform.horizontal_tension;
    v = uniform.vertical_tension;
  } catch (const Error&) {
    // Taut or buoyant: a straight line stretched to the chord.
    const double tension = std::max(std::abs(weight), (chord / length - 1.0) * length / compliance);
    h = std::max(tension, 1e-6 * length / compliance) * std::max(span, 1e-3 * chord) / chord;
    v = std::max(tension, 1e-6 * length / compliance) * height / chord + std::max(weight, 0.0);
  }
  h = std::max(h, 1e-9 * length / compliance);
  const double tolerance = 1e-11 * std::max({span, height, length});
  const auto residual = [&](double hh, double vv) {
    return Eigen::Vector2d(Point(line, LayOut(line, hh, vv), hh, length) - target);
  };
  Eigen::Vector2d r = residual(h, v);
  int iteration = 0;
  while (r.lpNorm<Eigen::Infinity>() > tolerance) {
    if (++iteration > kMaxClosureIterations || h > 1e3 * length / compliance) {
      std::ostringstream out;
      out << "catenary: no equilibrium found for the composite line (L = " << length << " m, span "
          << span << " m, height " << height << " m; closure error " << r.norm() << " m after "
          << iteration << " iterations"
          << (h > 1e3 * length / compliance ? ": the line cannot reach" : "") << ")";
      throw Error(out.str());
    }
    const double dh = 1e-7 * h;
    const double dv = 1e-7 * std::max(std::abs(v), h);
    Eigen::Matrix2d jacobian;
    jacobian.col(0) = (residual(h + dh, v) - residual(h - dh, v)) / (2.0 * dh);
    jacobian.col(1) = (residual(h, v + dv) - residual(h, v - dv)) / (2.0 * dv);
    Eigen::Vector2d step = -jacobian.partialPivLu().solve(r);
    if (!step.allFinite()) step = Eigen::Vector2d(h, 0.0);  // a flat spot: pull harder
    // Backtrack until the closure error falls (H stays positive).
    double lambda = 1.0;
    for (int k = 0; k < 60; ++k, lambda *= 0.5) {
      const double h_trial = h + lambda * step.x();
      if (!(h_trial > 0.0)) continue;
      const Eigen::Vector2d r_trial = residual(h_trial, v + lambda * step.y());
      if (r_trial.allFinite() && r_trial.norm() < r.norm()) {
        h = h_trial;
        v += lambda * step.y();
        r = r_trial;
        break;
      }
    }
    if (lambda < 1e-15) {
      h *= 2.0;  // no descent along the Newton step: move on from a stalled start
      r = residual(h, v);
    }
  }
  // The largest strain is at the top of a section (V grows upward but for buoys: both
  // ends of each are checked).
  const Layout final_layout = LayOut(line, h, v);
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    const double tension =
        std::hypot(h, std::max(std::abs(final_layout.top[i]), std::abs(final_layout.bottom[i])));
    const AxialCurve* curve = line.CurveOf(i);
    const double strain =
        curve ? curve->Strain(tension) : tension / line.sections[i].axial_stiffness;
    if (strain > max_strain) {
      std::ostringstream out;
      out << "catenary: the composite line cannot reach (span " << span << " m, height " << height
          << " m) without a strain of " << 100.0 * strain << " % in section " << i + 1 << " (limit "
          << 100.0 * max_strain << " %)";
      throw Error(out.str());
    }
  }
  CompositeCatenary out;
  out.line = line;
  out.horizontal_tension = h;
  out.vertical_tension = v;
  out.fairlead_tension = std::hypot(h, v);
  out.grounded_length = final_layout.grounded;
  out.anchor_vertical =
      final_layout.grounded > 0.0
          ? GroundedTension(line, h, final_layout.bottom.front()) * std::sin(line.seabed_rise)
          : final_layout.bottom.front();
  return out;
}

Eigen::Matrix3Xd CompositeCatenaryPoints(const CompositeLine& line, const Vec3& anchor,
                                         const Vec3& fairlead, const std::vector<double>& arc) {
  const Vec3 chord = fairlead - anchor;
  const double span = std::hypot(chord.x(), chord.y());
  const CompositeCatenary solution = SolveCompositeCatenary(line, span, anchor.z() - fairlead.z());
  const Vec3 along = span > 0.0 ? Vec3(chord.x() / span, chord.y() / span, 0.0) : Vec3::UnitX();
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(arc.size()));
  for (std::size_t k = 0; k < arc.size(); ++k) {
    const Eigen::Vector2d p = solution.PointAt(arc[k]);
    points.col(static_cast<Eigen::Index>(k)) = anchor + p.x() * along - p.y() * Vec3::UnitZ();
  }
  return points;
}

}  // namespace moorsim::mooring_fem
