#include "mooring_fem/seabed.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "core/format.h"

namespace moorsim::mooring_fem {

namespace {

constexpr double kMaxSlope = 89.0 * std::numbers::pi / 180.0;

// Where v lies on the increasing axis a: the cell [a[i], a[i+1]] and the fraction across
// it; beyond the ends the end value holds (fraction 0 or 1, no gradient).
struct AxisCell {
  std::size_t i = 0;
  double fraction = 0.0;
  double width = 1.0;
  bool inside = true;
};

AxisCell Locate(const std::vector<double>& a, double v) {
  AxisCell c;
  if (!(v > a.front())) {
    c.inside = false;
  } else if (!(v < a.back())) {
    c.i = a.size() - 2;
    c.fraction = 1.0;
    c.inside = false;
  } else {
    c.i = static_cast<std::size_t>(std::upper_bound(a.begin(), a.end(), v) - a.begin()) - 1;
    c.fraction = (v - a[c.i]) / (a[c.i + 1] - a[c.i]);
  }
  c.width = a[c.i + 1] - a[c.i];
  return c;
}

// The first problem of the increasing axis a and its index (-1 for none or a size).
std::string AxisProblem(const std::vector<double>& a, const char* name, int* index) {
  *index = -1;
  if (a.size() < 2) {
    return std::string("the ") + name + " axis has " + std::to_string(a.size()) +
           " point(s); a grid needs at least 2";
  }
  for (std::size_t i = 0; i < a.size(); ++i) {
    *index = static_cast<int>(i);
    if (!std::isfinite(a[i])) {
      return std::string(name) + "[" + std::to_string(i + 1) + "] is not a number";
    }
    if (i > 0 && !(a[i] > a[i - 1])) {
      return std::string(name) + " = " + FormatNumber(a[i]) + " m does not follow " + name + " = " +
             FormatNumber(a[i - 1]) + " m (the axis must increase)";
    }
  }
  *index = -1;
  return "";
}

}  // namespace

std::string DepthGridProblem(const DepthGrid& grid, int* row) {
  int ignored = 0;
  int& at = row != nullptr ? *row : ignored;
  if (std::string problem = AxisProblem(grid.x, "x", &at); !problem.empty()) return problem;
  if (std::string problem = AxisProblem(grid.y, "y", &at); !problem.empty()) {
    at = -1;
    return problem;
  }
  at = -1;
  if (grid.depth.size() != grid.x.size() * grid.y.size()) {
    return std::to_string(grid.depth.size()) + " depths for " + std::to_string(grid.x.size()) +
           " x " + std::to_string(grid.y.size()) + " grid points";
  }
  for (std::size_t i = 0; i < grid.x.size(); ++i) {
    at = static_cast<int>(i);
    for (std::size_t j = 0; j < grid.y.size(); ++j) {
      const double d = grid.depth[i * grid.y.size() + j];
      const std::string where =
          " at x = " + FormatNumber(grid.x[i]) + " m, y = " + FormatNumber(grid.y[j]) + " m";
      if (!std::isfinite(d)) return "no depth" + where + " (a hole in the grid)";
      if (!(d > 0.0)) {
        return "depth " + FormatNumber(d) + " m" + where +
               " is not below the water surface (z points down)";
      }
    }
  }
  at = -1;
  return "";
}

SeabedSurface::SeabedSurface(const Seabed& seabed, double depth) : depth_(depth) {
  if (!seabed.grid.empty()) {
    if (seabed.slope != 0.0) throw InputError("seabed: a depth grid and a slope are exclusive");
    if (const std::string problem = DepthGridProblem(seabed.grid); !problem.empty()) {
      throw InputError("seabed grid" +
                       (seabed.grid.source.empty() ? "" : " " + seabed.grid.source) + ": " +
                       problem);
    }
    kind_ = Kind::kGrid;
    grid_ = seabed.grid;
    return;
  }
  if (!(seabed.slope >= 0.0 && seabed.slope <= kMaxSlope) ||
      !std::isfinite(seabed.slope_direction)) {
    throw InputError("seabed: slope " + FormatNumber(seabed.slope * 180.0 / std::numbers::pi) +
                     " deg must be in [0, 89] with a finite direction");
  }
  if (seabed.slope == 0.0) return;
  kind_ = Kind::kPlane;
  const double rate = std::tan(seabed.slope);
  gradient_x_ = rate * std::cos(seabed.slope_direction);
  gradient_y_ = rate * std::sin(seabed.slope_direction);
}

SeabedPoint SeabedSurface::At(double x, double y) const {
  SeabedPoint p;
  switch (kind_) {
    case Kind::kFlat:
      p.depth = depth_;
      break;
    case Kind::kPlane:
      p.depth = depth_ + gradient_x_ * x + gradient_y_ * y;
      p.dx = gradient_x_;
      p.dy = gradient_y_;
      break;
    case Kind::kGrid: {
      const AxisCell cx = Locate(grid_.x, x);
      const AxisCell cy = Locate(grid_.y, y);
      const std::size_t n = grid_.y.size();
      const double h00 = grid_.depth[cx.i * n + cy.i];
      const double h01 = grid_.depth[cx.i * n + cy.i + 1];
      const double h10 = grid_.depth[(cx.i + 1) * n + cy.i];
      const double h11 = grid_.depth[(cx.i + 1) * n + cy.i + 1];
      const double fx = cx.fraction;
      const double fy = cy.fraction;
      p.depth = (1.0 - fx) * ((1.0 - fy) * h00 + fy * h01) + fx * ((1.0 - fy) * h10 + fy * h11);
      if (cx.inside) p.dx = ((1.0 - fy) * (h10 - h00) + fy * (h11 - h01)) / cx.width;
      if (cy.inside) p.dy = ((1.0 - fx) * (h01 - h00) + fx * (h11 - h10)) / cy.width;
      if (cx.inside && cy.inside) p.dxy = (h11 - h10 - h01 + h00) / (cx.width * cy.width);
      break;
    }
  }
  return p;
}

double SeabedSurface::RiseAlong(const Vec3& from, const Vec3& to) const {
  const double dx = to.x() - from.x();
  const double dy = to.y() - from.y();
  const double distance = std::hypot(dx, dy);
  if (kind_ == Kind::kFlat || !(distance > 0.0)) return 0.0;
  if (kind_ == Kind::kPlane) return std::atan(-(gradient_x_ * dx + gradient_y_ * dy) / distance);
  return std::atan((DepthAt(from.x(), from.y()) - DepthAt(to.x(), to.y())) / distance);
}

}  // namespace moorsim::mooring_fem
