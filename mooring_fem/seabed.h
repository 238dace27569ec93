// The seabed's shape: flat, a sloping plane, or a bilinear depth grid (parameters.h,
// Seabed). The FEM's contact law (mooring_system.cc) needs, where a node is, the depth h
// and its first and second derivatives; the analytic catenary needs the slope along a line.
//
// Contact is along the local normal: with g(r) = z - h(x, y) and G = grad g = (-h_x, -h_y, 1)
// the unit normal into the seabed is n = G / |G| and the penetration is g / |G| (exact for a
// plane, first order for a curved surface). For a flat seabed n = (0, 0, 1) and every
// expression reduces, to the bit, to the vertical contact of a flat seabed.
#pragma once

#include <string>

#include "core/types.h"
#include "mooring_fem/parameters.h"

namespace moorsim::mooring_fem {

/// The depth below a point and its derivatives: h, (h_x, h_y), and h_xy (a plane and a
/// bilinear cell have h_xx = h_yy = 0; h_xy is a cell's twist).
struct SeabedPoint {
  double depth = 0.0;
  double dx = 0.0;
  double dy = 0.0;
  double dxy = 0.0;
};

class SeabedSurface {
 public:
  SeabedSurface() = default;
  /// Throws moorsim::InputError for a slope outside [0, 89 deg] or a grid that is not one
  /// (fewer than two points on an axis, an axis that does not increase, a depth count
  /// that is not x.size() * y.size(), a depth that is not finite or not below the surface).
  SeabedSurface(const Seabed& seabed, double depth);

  bool flat() const { return kind_ == Kind::kFlat; }
  /// The depth and its derivatives below the horizontal point (x, y).
  SeabedPoint At(double x, double y) const;
  double DepthAt(double x, double y) const {
    return kind_ == Kind::kFlat ? depth_ : At(x, y).depth;  // flat: inline, every node
  }
  /// The seabed's mean angle of rise [rad] along the straight horizontal path from `from`
  /// toward `to` (positive where it gets shallower): for a plane its slope in that
  /// direction, for a grid the depth difference over the horizontal distance.
  double RiseAlong(const Vec3& from, const Vec3& to) const;

 private:
  enum class Kind { kFlat, kPlane, kGrid };
  Kind kind_ = Kind::kFlat;
  double depth_ = 0.0;       // at the origin
  double gradient_x_ = 0.0;  // plane: dh/dx
  double gradient_y_ = 0.0;  // plane: dh/dy
  DepthGrid grid_;
};

/// The first thing wrong with `grid` ("" if nothing): a message naming the axis and the
/// value, or the point. `row`, if given, is set to the x index the problem is at (-1: the
/// y axis or the sizes), so a file reader can name the line.
std::string DepthGridProblem(const DepthGrid& grid, int* row = nullptr);

}  // namespace moorsim::mooring_fem
