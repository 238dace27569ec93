// Analytic elastic catenary of a single line with a frictionless flat seabed.
//
// Used for (a) the static initial state of the FEM lines (nodes placed along the
// catenary by unstretched arc length), (b) the independent reference the FEM is tested
// against, and (c) the quasi-static restoring force used by the detectors.
//
// Model: uniform line of unstretched length L, submerged weight w [N/m] per unstretched
// length, axial stiffness EA [N]; anchor at the lower end, fairlead at the upper end.
// Either part of the line rests on a frictionless horizontal seabed through the anchor
// (touchdown solution) or the whole line hangs free (fully suspended, the anchor then
// carries a vertical load too). Elastic stretch is included in both.
#pragma once

#include <Eigen/Core>

#include "core/types.h"

namespace moorsim::mooring_fem {

/// A line that would need more strain than this is treated as unable to reach: the
/// linear-elastic model (and any real rope or chain) is meaningless far beyond it.
inline constexpr double kMaxCatenaryStrain = 0.10;

struct CatenaryLineProperties {
  double length = 0.0;             ///< unstretched length L [m]
  double weight_per_length = 0.0;  ///< submerged weight w per unstretched length [N/m]
  double axial_stiffness = 0.0;    ///< EA [N]
};

/// Solution in the vertical plane through anchor and fairlead.
struct CatenarySolution {
  double horizontal_tension = 0.0;  ///< H, constant along the suspended part [N]
  double vertical_tension = 0.0;    ///< V at the fairlead [N]
  double fairlead_tension = 0.0;    ///< sqrt(H^2 + V^2) [N]
  double anchor_horizontal = 0.0;   ///< horizontal force at the anchor [N] (H when suspended)
  double anchor_vertical = 0.0;     ///< vertical force at the anchor [N] (0 with touchdown)
  double grounded_length = 0.0;     ///< unstretched length lying on the seabed [m]
  bool anchor_lifted = false;       ///< true for the fully suspended case
};

/// Solves the elastic catenary for a fairlead at horizontal distance `span` [m] (>= 0) and
/// height `height` [m] (> 0) above the anchor; the seabed is the horizontal plane through
/// the anchor. Throws moorsim::Error if no solution exists (e.g. the line cannot reach).
CatenarySolution SolveCatenary(const CatenaryLineProperties& line, double span, double height);

/// Where a line hangs with touchdown, for a fairlead at a given height above the seabed:
/// between a slack line (H = 0: hanging straight down onto its grounded part) and lift-off
/// (the whole line suspended, touching the seabed only at the anchor, which then carries
/// no vertical force). Within it the fairlead tension rises strictly with the span.
struct TouchdownRange {
  double min_span = 0.0;     ///< span of the slack line, L - (hanging length) [m]
  double max_span = 0.0;     ///< span at lift-off [m]
  double min_tension = 0.0;  ///< fairlead tension of the slack line: w x hanging length [N]
  double max_tension = 0.0;  ///< fairlead tension at lift-off, sqrt(H^2 + (w L)^2) [N]
};

/// The touchdown range of `line` with its fairlead `height` [m] (> 0) above the seabed.
/// Throws moorsim::Error if the line hanging straight down does not reach the seabed (no
/// touchdown at any span) or if lift-off needs more strain than SolveCatenary accepts.
TouchdownRange SolveTouchdownRange(const CatenaryLineProperties& line, double height);

/// The span [m] at which the fairlead tension is `tension` [N], for a line with touchdown
/// (bisection on SolveCatenary, to 1e-12 of the span). Throws moorsim::Error unless
/// min_tension < tension <= max_tension of SolveTouchdownRange(line, height).
double SpanForFairleadTension(const CatenaryLineProperties& line, double height, double tension);

/// Position of the material point at unstretched arc length s (0 = anchor, L = fairlead)
/// in the line's vertical plane: x horizontal from the anchor toward the fairlead, z up
/// from the anchor [m].
Eigen::Vector2d CatenaryPointAt(const CatenaryLineProperties& line,
                                const CatenarySolution& solution, double s);

/// The catenary in 3D Earth coordinates (NED, z down) between a given anchor and
/// fairlead; the seabed is the horizontal plane through the anchor.
struct LineCatenary {
  CatenarySolution solution;
  /// Force the line exerts on whatever holds the fairlead, Earth frame [N]: points toward
  /// the anchor horizontally and downward (+z).
  Vec3 fairlead_force = Vec3::Zero();
  /// Positions of nodes 0..n at unstretched arc lengths k L / n, Earth frame [m].
  Eigen::Matrix3Xd NodePositions(int segments) const;

  CatenaryLineProperties line;
  Vec3 anchor = Vec3::Zero();
  Vec3 fairlead = Vec3::Zero();
};

/// Throws moorsim::Error if the fairlead is not above the anchor (z_fairlead < z_anchor in
/// NED) or the line cannot reach.
LineCatenary SolveLineCatenary(const CatenaryLineProperties& line, const Vec3& anchor,
                               const Vec3& fairlead);

}  // namespace moorsim::mooring_fem
