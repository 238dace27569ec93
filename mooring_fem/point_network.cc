#include "mooring_fem/point_network.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.h"
#include "mooring_fem/catenary.h"

namespace moorsim::mooring_fem {

namespace {

/// Step of the central differences of the end tensions [m] (as the span tables').
constexpr double kDifferenceStep = 1e-2;

struct EndTensions {
  double horizontal = 0.0, vertical = 0.0, lower_vertical = 0.0;
};

/// The strain a table's nodes may reach: a taut line's tensions extended smoothly past the
/// elastic model's meaningful range, so that a grid corner no state reaches still has a
/// value.
constexpr double kTableStrain = 1.0;

// A weightless line (CompositeLine::Weightless, linear sections) hangs straight: slack,
// with no tension, while its ends are closer than its length, and stretched elastically
// beyond, T = k (c - L) with k = 1 / sum(l / EA). Its end forces and their derivatives
// are closed forms: H = T s / c, V = T h / c, and with dT/ds = k s / c, dT/dh = k h / c,
//   dH/ds = k s^2 / c^2 + T h^2 / c^3,   dH/dh = dV/ds = (k - T / c) s h / c^2,
//   dV/dh = k h^2 / c^2 + T s^2 / c^3
// (finite differences across the kink where the line draws taut would be wrong by the
// axial stiffness times the step, and a taut stiff line's swing, T / c, is far smaller).
std::optional<LineEnds> Weightless(const CompositeLine& line, double span, double height) {
  if (!line.Weightless()) return std::nullopt;
  double length = 0.0, compliance = 0.0;
  for (std::size_t i = 0; i < line.sections.size(); ++i) {
    if (line.CurveOf(i) != nullptr) return std::nullopt;
    length += line.sections[i].length;
    compliance += line.sections[i].length / line.sections[i].axial_stiffness;
  }
  LineEnds out;
  const double chord = std::hypot(span, height);
  if (!(chord > length)) return out;
  const double k = 1.0 / compliance, tension = k * (chord - length);
  const double c2 = chord * chord, c3 = c2 * chord;
  out.horizontal = tension * span / chord;
  out.vertical = out.lower_vertical = tension * height / chord;
  const double mixed = (k - tension / chord) * span * height / c2;
  out.d_horizontal = {k * span * span / c2 + tension * height * height / c3, mixed};
  out.d_vertical = {mixed, k * height * height / c2 + tension * span * span / c3};
  out.d_lower_vertical = out.d_vertical;
  return out;
}

EndTensions Tensions(const CompositeLine& line, double span, double height, double max_strain) {
  if (const std::optional<LineEnds> straight = Weightless(line, span, height)) {
    return {straight->horizontal, straight->vertical, straight->lower_vertical};
  }
  if (line.Uniform() && max_strain == kMaxCatenaryStrain) {
    const auto s = SolveCatenary(line.sections.front(), span, height);
    return {s.horizontal_tension, s.vertical_tension, s.anchor_vertical};
  }
  const auto s = SolveCompositeCatenary(line, span, height, max_strain);
  return {s.horizontal_tension, s.vertical_tension, s.anchor_vertical};
}

// The values alone, or with their central differences.
LineEnds Ends(const CompositeLine& line, double span, double height, bool derivatives,
              double max_strain = kMaxCatenaryStrain) {
  if (const std::optional<LineEnds> straight = Weightless(line, span, height)) {
    if (line.lower_on_seabed) {
      LineEnds out = *straight;
      out.lower_vertical = 0.0;
      out.d_lower_vertical = Eigen::Vector2d::Zero();
      return out;
    }
    return *straight;
  }
  const EndTensions c = Tensions(line, span, height, max_strain);
  LineEnds out;
  out.horizontal = c.horizontal;
  out.vertical = c.vertical;
  out.lower_vertical = line.lower_on_seabed ? 0.0 : c.lower_vertical;
  if (!derivatives) return out;
  // One-sided where the lower bound of span (0) or of height (an anchor's seabed) is near.
  const double s_low = span >= kDifferenceStep ? span - kDifferenceStep : span;
  const double h_low =
      !line.lower_on_seabed || height - kDifferenceStep > 0.0 ? height - kDifferenceStep : height;
  const EndTensions s1 = Tensions(line, s_low, height, max_strain);
  const EndTensions s2 = Tensions(line, span + kDifferenceStep, height, max_strain);
  const EndTensions h1 = Tensions(line, span, h_low, max_strain);
  const EndTensions h2 = Tensions(line, span, height + kDifferenceStep, max_strain);
  const double ds = span + kDifferenceStep - s_low, dh = height + kDifferenceStep - h_low;
  out.d_horizontal = {(s2.horizontal - s1.horizontal) / ds, (h2.horizontal - h1.horizontal) / dh};
  out.d_vertical = {(s2.vertical - s1.vertical) / ds, (h2.vertical - h1.vertical) / dh};
  if (!line.lower_on_seabed) out.d_lower_vertical = out.d_vertical;  // V_l = V - weight
  return out;
}

double WeightInWater(const CompositeLine& line) {
  double weight = 0.0;
  for (const auto& section : line.sections) weight += section.weight_per_length * section.length;
  for (double joint : line.joint_weights) weight += joint;
  return weight;
}

// Cubic Hermite basis on [0, 1]: the value basis (at 0, at 1), the slope basis (at 0, at
// 1), and their derivatives.
struct Hermite {
  double value[2], slope[2], d_value[2], d_slope[2];
  explicit Hermite(double t) {
    const double t2 = t * t, t3 = t2 * t;
    value[0] = 2.0 * t3 - 3.0 * t2 + 1.0;
    value[1] = -2.0 * t3 + 3.0 * t2;
    slope[0] = t3 - 2.0 * t2 + t;
    slope[1] = t3 - t2;
    d_value[0] = 6.0 * t2 - 6.0 * t;
    d_value[1] = -6.0 * t2 + 6.0 * t;
    d_slope[0] = 3.0 * t2 - 4.0 * t + 1.0;
    d_slope[1] = 3.0 * t2 - 2.0 * t;
  }
};

std::string Describe(double span, double height) {
  std::ostringstream out;
  out << "span " << span << " m, height " << height << " m";
  return out.str();
}

}  // namespace

LineEnds SolveLineEnds(const CompositeLine& line, double span, double height) {
  return Ends(line, span, height, true);
}

// ---------------------------------------------------------------------------------------
// LineEndTable

namespace {

/// The interpolant's error target at the edges' midpoints, relative to the line's tension.
constexpr double kTableTolerance = 1e-6;

}  // namespace

LineEndTable::LineEndTable(const CompositeLine& line, const Range& range, double step,
                           int max_nodes)
    : range_(range), free_lower_end_(!line.lower_on_seabed), weight_(WeightInWater(line)) {
  const double chord_length = range.chord_max - range.chord_min;
  const double angle_length = range.angle_max - range.angle_min;
  constexpr double kRight = 0.5 * std::numbers::pi;
  if (!(std::isfinite(chord_length) && chord_length > 0.0 && range.chord_min > 0.0 &&
        std::isfinite(angle_length) && angle_length > 0.0 && range.angle_min >= -kRight &&
        range.angle_max <= kRight && std::isfinite(step) && step > 0.0 && max_nodes >= 4)) {
    std::ostringstream out;
    out << "line end table: an empty or invalid grid (chord " << range.chord_min << " to "
        << range.chord_max << " m, angle " << range.angle_min << " to " << range.angle_max
        << " rad)";
    throw Error(out.str());
  }
  const double middle = 0.5 * (range.chord_min + range.chord_max);
  int chords = std::max(1, static_cast<int>(std::ceil(chord_length / step)));
  int angles = std::max(1, static_cast<int>(std::ceil(angle_length * middle / step)));
  while ((chords + 1) * (angles + 1) > max_nodes && (chords > 1 || angles > 1)) {
    chords = std::max(1, chords / 2);
    angles = std::max(1, angles / 2);
  }
  // Refine each axis while the interpolant misses the catenary at its edges' midpoints.
  const auto error_at = [&](double chord, double angle) {
    const double span = std::max(0.0, chord * std::cos(angle)), height = chord * std::sin(angle);
    LineEnds exact;
    try {
      exact = Ends(line, span, height, false, kTableStrain);
    } catch (const Error&) {
      return 0.0;  // no catenary to compare with
    }
    const LineEnds t = At(span, height);
    return std::max(std::abs(t.horizontal - exact.horizontal),
                    std::abs(t.vertical - exact.vertical)) /
           std::max(std::hypot(exact.horizontal, exact.vertical), 1e-300);
  };
  for (int round = 0;; ++round) {
    chords_ = chords + 1;
    angles_ = angles + 1;
    chord_step_ = chord_length / chords;
    angle_step_ = angle_length / angles;
    Build(line);
    double chord_error = 0.0, angle_error = 0.0;
    for (int q = 0; q <= 4; ++q) {
      const int j = q * angles / 4, i = q * chords / 4;
      for (int k = 0; k < chords; ++k) {
        chord_error = std::max(chord_error, error_at(range.chord_min + (k + 0.5) * chord_step_,
                                                     range.angle_min + j * angle_step_));
      }
      for (int k = 0; k < angles; ++k) {
        angle_error = std::max(angle_error, error_at(range.chord_min + i * chord_step_,
                                                     range.angle_min + (k + 0.5) * angle_step_));
      }
    }
    measured_error_ = std::max(chord_error, angle_error);
    const int next_chords = chord_error > kTableTolerance ? 2 * chords : chords;
    const int next_angles = angle_error > kTableTolerance ? 2 * angles : angles;
    if ((next_chords == chords && next_angles == angles) ||
        (next_chords + 1) * (next_angles + 1) > max_nodes || round >= 10) {
      break;
    }
    chords = next_chords;
    angles = next_angles;
  }
}

void LineEndTable::Build(const CompositeLine& line) {
  horizontal_.assign(static_cast<std::size_t>(chords_ * angles_), Eigen::Vector4d::Zero());
  vertical_.assign(horizontal_.size(), Eigen::Vector4d::Zero());
  for (int i = 0; i < chords_; ++i) {
    for (int j = 0; j < angles_; ++j) {
      const double chord = range_.chord_min + i * chord_step_;
      const double angle = range_.angle_min + j * angle_step_;
      const double span = std::max(0.0, chord * std::cos(angle)), height = chord * std::sin(angle);
      LineEnds e;
      try {
        e = Ends(line, span, height, true, kTableStrain);
      } catch (const Error& error) {
        throw Error("line end table: no catenary at " + Describe(span, height) + ": " +
                    error.what());
      }
      // d/dc = cos a d/ds + sin a d/dh; d/da = -h d/ds + s d/dh.
      const Eigen::Vector2d along(std::cos(angle), std::sin(angle)), across(-height, span);
      const std::size_t k = static_cast<std::size_t>(i * angles_ + j);
      horizontal_[k] = {e.horizontal, along.dot(e.d_horizontal), across.dot(e.d_horizontal), 0.0};
      vertical_[k] = {e.vertical, along.dot(e.d_vertical), across.dot(e.d_vertical), 0.0};
    }
  }
  // The cross derivatives: the chord derivatives differenced along the angle.
  for (std::vector<Eigen::Vector4d>* grid : {&horizontal_, &vertical_}) {
    for (int i = 0; i < chords_; ++i) {
      for (int j = 0; j < angles_; ++j) {
        const int below = std::max(j - 1, 0), above = std::min(j + 1, angles_ - 1);
        const Eigen::Vector4d& a = (*grid)[static_cast<std::size_t>(i * angles_ + below)];
        const Eigen::Vector4d& b = (*grid)[static_cast<std::size_t>(i * angles_ + above)];
        (*grid)[static_cast<std::size_t>(i * angles_ + j)](3) =
            (b(1) - a(1)) / ((above - below) * angle_step_);
      }
    }
  }
}

bool LineEndTable::Covers(double span, double height) const {
  const double chord = std::hypot(span, height), angle = std::atan2(height, span);
  return chord >= range_.chord_min && chord <= range_.chord_max && angle >= range_.angle_min &&
         angle <= range_.angle_max;
}

double LineEndTable::Interpolate(const std::vector<Eigen::Vector4d>& grid, double chord,
                                 double angle, Eigen::Vector2d* gradient) const {
  const double x = (chord - range_.chord_min) / chord_step_;
  const double y = (angle - range_.angle_min) / angle_step_;
  const int i = std::clamp(static_cast<int>(std::floor(x)), 0, chords_ - 2);
  const int j = std::clamp(static_cast<int>(std::floor(y)), 0, angles_ - 2);
  const Hermite a(x - i), b(y - j);
  double value = 0.0, d_chord = 0.0, d_angle = 0.0;
  for (int p = 0; p < 2; ++p) {
    for (int q = 0; q < 2; ++q) {
      const Eigen::Vector4d& f = grid[static_cast<std::size_t>((i + p) * angles_ + j + q)];
      const double fc = chord_step_ * f(1), fa = angle_step_ * f(2);
      const double fca = chord_step_ * angle_step_ * f(3);
      value += a.value[p] * b.value[q] * f(0) + a.slope[p] * b.value[q] * fc +
               a.value[p] * b.slope[q] * fa + a.slope[p] * b.slope[q] * fca;
      d_chord += a.d_value[p] * b.value[q] * f(0) + a.d_slope[p] * b.value[q] * fc +
                 a.d_value[p] * b.slope[q] * fa + a.d_slope[p] * b.slope[q] * fca;
      d_angle += a.value[p] * b.d_value[q] * f(0) + a.slope[p] * b.d_value[q] * fc +
                 a.value[p] * b.d_slope[q] * fa + a.slope[p] * b.d_slope[q] * fca;
    }
  }
  *gradient = {d_chord / chord_step_, d_angle / angle_step_};
  return value;
}

LineEnds LineEndTable::At(double span, double height) const {
  const double chord = std::max(std::hypot(span, height), 1e-9);
  const double angle = std::atan2(height, span);
  const double c = std::clamp(chord, range_.chord_min, range_.chord_max);
  const double a = std::clamp(angle, range_.angle_min, range_.angle_max);
  const Eigen::Vector2d outside(chord - c, angle - a);
  Eigen::Vector2d dh, dv;
  double h = Interpolate(horizontal_, c, a, &dh);
  double v = Interpolate(vertical_, c, a, &dv);
  h += dh.dot(outside);
  v += dv.dot(outside);
  // (c, a) -> (span, height): dc/ds = s/c, dc/dh = h/c, da/ds = -h/c^2, da/dh = s/c^2.
  Eigen::Matrix2d to_span_height;
  to_span_height << span / chord, height / chord, -height / (chord * chord), span / (chord * chord);
  LineEnds out;
  out.horizontal = h;
  out.vertical = v;
  out.d_horizontal = to_span_height.transpose() * dh;
  out.d_vertical = to_span_height.transpose() * dv;
  if (out.horizontal < 0.0) {  // beyond the grid only: a line pushes nothing
    out.horizontal = 0.0;
    out.d_horizontal.setZero();
  }
  if (free_lower_end_) {
    out.lower_vertical = out.vertical - weight_;
    out.d_lower_vertical = out.d_vertical;
  }
  return out;
}

// ---------------------------------------------------------------------------------------
// PointNetwork

struct PointNetwork::Evaluation {
  Eigen::VectorXd residual;           // 3 per point [N]
  Eigen::MatrixXd d_points;           // dR/dq
  Eigen::MatrixXd d_fairleads;        // dR/d(fairleads' x, y): 3 np x 2 nf
  Eigen::Matrix3Xd fairlead_forces;   // 3 x nf
  Eigen::MatrixXd force_d_points;     // d(fairlead forces' x, y)/dq: 2 nf x 3 np
  Eigen::MatrixXd force_d_fairleads;  // 2 nf x 2 nf
  std::vector<double> upper_tension;
};

PointNetwork::PointNetwork(std::vector<NetworkLine> lines, std::vector<double> weights,
                           std::vector<Vec3> anchors, int num_fairleads, Eigen::Matrix3Xd rest)
    : lines_(std::move(lines)),
      weights_(std::move(weights)),
      anchors_(std::move(anchors)),
      num_fairleads_(num_fairleads),
      rest_(std::move(rest)) {
  if (rest_.cols() != num_points()) throw Error("point network: one rest position per point");
  double stiffest = 0.0;
  for (const NetworkLine& line : lines_) {
    for (const NetworkEnd& end : {line.lower, line.upper}) {
      const int size = end.kind == NetworkEnd::Kind::kPoint    ? num_points()
                       : end.kind == NetworkEnd::Kind::kAnchor ? static_cast<int>(anchors_.size())
                                                               : num_fairleads_;
      if (end.index < 0 || end.index >= size) {
        throw Error("point network: line " + std::to_string(line.id) + " ends nowhere");
      }
    }
    for (const auto& section : line.line.sections) {
      stiffest = std::max(stiffest, section.axial_stiffness);
    }
  }
  tolerance_ = 1e-9 * stiffest;
}

PointNetwork PointNetwork::WithTables(
    const std::vector<std::shared_ptr<const LineEndTable>>& tables,
    const Eigen::Matrix3Xd& rest) const {
  if (tables.size() != lines_.size() || rest.cols() != num_points()) {
    throw Error("point network: one table per line and one rest position per point");
  }
  PointNetwork copy = *this;
  for (std::size_t l = 0; l < lines_.size(); ++l) copy.lines_[l].table = tables[l];
  copy.rest_ = rest;
  return copy;
}

Vec3 PointNetwork::EndPosition(const NetworkEnd& end, const Eigen::Matrix3Xd& q,
                               const Eigen::Matrix3Xd& fairleads) const {
  switch (end.kind) {
    case NetworkEnd::Kind::kPoint:
      return q.col(end.index);
    case NetworkEnd::Kind::kAnchor:
      return anchors_[static_cast<std::size_t>(end.index)];
    case NetworkEnd::Kind::kFairlead:
      break;
  }
  return fairleads.col(end.index);
}

bool PointNetwork::Evaluate(const Eigen::Matrix3Xd& fairleads, const Eigen::Matrix3Xd& q,
                            bool jacobian, Evaluation* out) const {
  const int np = num_points(), nf = num_fairleads_;
  out->residual.setZero(3 * np);
  for (int p = 0; p < np; ++p) out->residual(3 * p + 2) = weights_[static_cast<std::size_t>(p)];
  out->fairlead_forces.setZero(3, nf);
  out->upper_tension.assign(lines_.size(), 0.0);
  if (jacobian) {
    out->d_points.setZero(3 * np, 3 * np);
    out->d_fairleads.setZero(3 * np, 2 * nf);
    out->force_d_points.setZero(2 * nf, 3 * np);
    out->force_d_fairleads.setZero(2 * nf, 2 * nf);
  }
  for (std::size_t l = 0; l < lines_.size(); ++l) {
    const NetworkLine& line = lines_[l];
    const Vec3 a = EndPosition(line.lower, q, fairleads);
    const Vec3 b = EndPosition(line.upper, q, fairleads);
    const Eigen::Vector2d d = (b - a).head<2>();
    const double span = d.norm(), height = a.z() - b.z();
    LineEnds e;
    if (line.table) {
      e = line.table->At(span, height);
    } else {
      try {
        e = Ends(line.line, span, height, jacobian, kTableStrain);
      } catch (const Error&) {
        return false;
      }
    }
    const Eigen::Vector2d u = span > 1e-12 ? Eigen::Vector2d(d / span) : Eigen::Vector2d::UnitX();
    out->upper_tension[l] = std::hypot(e.horizontal, e.vertical);
    // The forces on the upper end (toward the lower end, and down) and on the lower end.
    const Vec3 f_upper(-e.horizontal * u.x(), -e.horizontal * u.y(), e.vertical);
    const Vec3 f_lower(e.horizontal * u.x(), e.horizontal * u.y(), -e.lower_vertical);
    Mat3 upper_d_upper = Mat3::Zero(), lower_d_upper = Mat3::Zero();
    if (jacobian) {
      // d f / d (upper end), with d span / d b = u, d height / d b_z = -1; the derivatives
      // with respect to the lower end are their negatives.
      const Eigen::Matrix2d uu = u * u.transpose();
      const Eigen::Matrix2d across =
          span > 1e-12 ? Eigen::Matrix2d(e.horizontal / span * (Eigen::Matrix2d::Identity() - uu))
                       : Eigen::Matrix2d::Zero();
      const Eigen::Matrix2d planar = e.d_horizontal.x() * uu + across;
      upper_d_upper.topLeftCorner<2, 2>() = -planar;
      upper_d_upper.block<2, 1>(0, 2) = e.d_horizontal.y() * u;
      upper_d_upper.block<1, 2>(2, 0) = e.d_vertical.x() * u.transpose();
      upper_d_upper(2, 2) = -e.d_vertical.y();
      lower_d_upper.topLeftCorner<2, 2>() = planar;
      lower_d_upper.block<2, 1>(0, 2) = -e.d_horizontal.y() * u;
      lower_d_upper.block<1, 2>(2, 0) = -e.d_lower_vertical.x() * u.transpose();
      lower_d_upper(2, 2) = e.d_lower_vertical.y();
    }
    // Each end's force, and its derivatives with respect to both ends.
    struct Share {
      const NetworkEnd& at;
      const Vec3& force;
      Mat3 d_upper;
    };
    for (const Share& share :
         {Share{line.upper, f_upper, upper_d_upper}, Share{line.lower, f_lower, lower_d_upper}}) {
      if (share.at.kind == NetworkEnd::Kind::kAnchor) continue;
      const bool on_point = share.at.kind == NetworkEnd::Kind::kPoint;
      const int row = share.at.index;
      if (on_point) {
        out->residual.segment<3>(3 * row) += share.force;
      } else {
        out->fairlead_forces.col(row) += share.force;
      }
      if (!jacobian) continue;
      for (const auto& [end, sign] : {std::pair<const NetworkEnd&, double>{line.upper, 1.0},
                                      std::pair<const NetworkEnd&, double>{line.lower, -1.0}}) {
        const Mat3 block = sign * share.d_upper;
        if (end.kind == NetworkEnd::Kind::kAnchor) continue;
        const int col = end.index;
        if (end.kind == NetworkEnd::Kind::kPoint) {
          if (on_point) {
            out->d_points.block<3, 3>(3 * row, 3 * col) += block;
          } else {
            out->force_d_points.block<2, 3>(2 * row, 3 * col) += block.topRows<2>();
          }
        } else if (on_point) {
          out->d_fairleads.block<3, 2>(3 * row, 2 * col) += block.leftCols<2>();
        } else {
          out->force_d_fairleads.block<2, 2>(2 * row, 2 * col) += block.topLeftCorner<2, 2>();
        }
      }
    }
  }
  return true;
}

PointNetwork::Equilibrium PointNetwork::Solve(const Eigen::Matrix3Xd& fairleads, bool jacobian,
                                              const Eigen::Matrix3Xd* start) const {
  if (fairleads.cols() != num_fairleads_) throw Error("point network: one position per fairlead");
  Eigen::Matrix3Xd q = start != nullptr ? *start : rest_;
  const int n = 3 * num_points();
  Evaluation e, trial;
  if (!Evaluate(fairleads, q, true, &e)) {
    throw Error("point network: a line's catenary has no solution at the start");
  }
  // Newton's method on R(q) = 0, with the Levenberg-Marquardt shift of the FEM's own
  // static solve where a step does not descend: (dR/dq - mu s I) step = -R, which for a
  // point on slack lines (dR/dq = 0) steps along its force. A step is taken where the
  // residual falls or, as in a line search on the potential energy, where the force still
  // points along it at its end (the energy still falling: a point sinking on slack lines).
  double mu = 0.0;
  bool converged = e.residual.lpNorm<Eigen::Infinity>() <= tolerance_;
  for (int iteration = 0; iteration < 200 && !converged; ++iteration) {
    const double scale =
        std::max({e.d_points.diagonal().cwiseAbs().maxCoeff(), e.residual.norm() / 1.0, 1e-300});
    const Eigen::Matrix3Xd q_before = q;
    bool accepted = false;
    for (int attempt = 0; attempt < 30 && !accepted; ++attempt) {
      Eigen::MatrixXd shifted = e.d_points;
      shifted.diagonal().array() -= mu * scale;
      const Eigen::VectorXd step = shifted.fullPivLu().solve(-e.residual);
      const double slope = e.residual.dot(step);  // minus the energy's slope along the step
      if (step.allFinite() && slope > 0.0 && step.lpNorm<Eigen::Infinity>() > 1e-12) {
        // phi(lambda) = R(q + lambda step) . step is minus the energy's slope along the
        // step: the full step is taken where the residual falls or phi is still > 0 at its
        // end; otherwise the first of its halvings where the residual falls; otherwise the
        // step stops where phi changes sign (bisection), at the energy's least along it (a
        // slack line drawing taut).
        const auto phi = [&](double lambda) {
          Eigen::Matrix3Xd q_trial = q;
          q_trial.reshaped() += lambda * step;
          if (!Evaluate(fairleads, q_trial, false, &trial)) return -1.0;  // beyond: back off
          return trial.residual.dot(step);
        };
        const double full = phi(1.0);
        double lambda = 1.0;
        const auto falls = [&](double value) {
          return value != -1.0 && trial.residual.norm() < e.residual.norm();
        };
        bool found = full > 0.0 || falls(full);
        if (!found) {
          // A step across a taut, stiff line (a pendulum swinging) leaves the circle its
          // length allows and meets the line's axial stiffness. Newton steps from the step's
          // end, each with the Jacobian where it starts, pull it back onto the circle.
          // (The step's end may lie beyond the strain a line can take; then from the first
          // of its halvings that a line can reach.)
          double reach = 1.0;
          for (double value = full; value == -1.0 && reach > 1e-2;) {
            reach *= 0.5;
            value = phi(reach);
          }
          Eigen::Matrix3Xd corrected = q;
          corrected.reshaped() += reach * step;
          for (int k = 0; k < 4 && !found; ++k) {
            if (!Evaluate(fairleads, corrected, true, &trial)) break;
            corrected.reshaped() += trial.d_points.fullPivLu().solve(-trial.residual);
            if (!Evaluate(fairleads, corrected, false, &trial)) break;
            found = trial.residual.norm() < e.residual.norm();
          }
          if (found) {
            q = corrected;
            accepted = true;
          }
        }
        // Backtracking first, as far as the residual falls; then the sign change of phi.
        for (int k = 0; k < 8 && !found; ++k) {
          lambda *= 0.5;
          found = falls(phi(lambda));
        }
        if (!found) {
          // Just past the sign change: on the far side of a kink (a line drawn just taut)
          // the next Newton step sees the line's stiffness.
          double low = 0.0, high = 1.0;
          bool high_evaluates = full != -1.0;
          const double length = step.lpNorm<Eigen::Infinity>();
          for (int k = 0; k < 60 && (high - low) * length > 1e-9; ++k) {
            const double middle = 0.5 * (low + high);
            const double value = phi(middle);
            if (value > 0.0) {
              low = middle;
            } else {
              high = middle;
              high_evaluates = value != -1.0;
            }
          }
          lambda = high_evaluates ? high : low;
        }
        if (!accepted && lambda > 0.0) {
          q.reshaped() += lambda * step;
          accepted = true;
        }
      }
      if (accepted) {
        mu = mu > 1e-10 ? 0.1 * mu : 0.0;
      } else {
        mu = mu > 0.0 ? 10.0 * mu : 1e-6;
      }
    }
    if (!accepted || !Evaluate(fairleads, q, true, &trial)) {
      q = q_before;  // the forces in `e` are this iterate's
      break;
    }
    std::swap(e, trial);
    converged = e.residual.lpNorm<Eigen::Infinity>() <= tolerance_;
  }
  Equilibrium out;
  out.points = q;
  out.fairlead_forces = e.fairlead_forces;
  out.upper_tension = e.upper_tension;
  out.residual = e.residual.lpNorm<Eigen::Infinity>();
  out.converged = converged;
  if (jacobian) {
    // The points follow the fairleads: dq/dp = -(dR/dq)^-1 dR/dp.
    out.d_horizontal = e.force_d_fairleads;
    if (n > 0) {
      const Eigen::MatrixXd dq_dp =
          -e.d_points.completeOrthogonalDecomposition().solve(e.d_fairleads);
      out.d_horizontal += e.force_d_points * dq_dp;
    }
  }
  return out;
}

}  // namespace moorsim::mooring_fem
