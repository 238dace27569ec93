// Analytic elastic catenary of a composite line: sections of different weight and axial
// stiffness in series, from the anchor up, with point weights (clump weights, or buoys as
// negative weights) at the joints between them, on a frictionless flat seabed through the
// anchor.
//
// The horizontal tension H is the same everywhere (no horizontal load acts on the line in
// still water). The vertical tension V(s) at unstretched arc length s from the anchor is
// the fairlead's V_f less the weight in water of everything between s and the fairlead.
// Where V stays >= 0 down to the anchor the whole line hangs (the anchor then carries V(0)
// upward); otherwise the line rests on the seabed from the anchor to the point where V
// reaches zero, under the tension H. Each suspended stretch of a section of weight w and
// axial stiffness EA between vertical tensions V1 < V2 (w > 0) spans
//   dx = H/w [asinh(V2/H) - asinh(V1/H)] + H l/EA,
//   dz = H/w [sqrt(1 + (V2/H)^2) - sqrt(1 + (V1/H)^2)] + l (V1 + V2) / (2 EA),
// with l = (V2 - V1)/w its unstretched length (a weightless stretch is straight). H and V_f
// are found by Newton's method on the two closure conditions (the span and the height).
//
// On a seabed that rises at the angle a toward the fairlead (a plane, in the vertical plane
// of the line) the line leaves the seabed tangentially, where V = H tan(a). Below that it
// lies on the slope, frictionless, carrying the tension T(s) = H cos(a) + V(s) sin(a)
// along it (the weight's component along the slope changes the tension; where T would
// fall below zero the line lies slack). a = 0 is the flat case above.
//
// Used to place the FEM's nodes at the start of a run on a composite line, whose static
// equilibrium SettleStatic then finds exactly.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <memory>
#include <vector>

#include "core/types.h"
#include "mooring_fem/axial_curve.h"
#include "mooring_fem/catenary.h"

namespace moorsim::mooring_fem {

struct CompositeLine {
  /// From the anchor up. A section's weight may be zero or negative (a buoyant section).
  std::vector<CatenaryLineProperties> sections;
  /// Weight in water at each joint [N] (sections.size() - 1 of them, or empty: none);
  /// negative for a buoy.
  std::vector<double> joint_weights;
  /// Each section's tension-strain law in place of its EA (one per section, a null one for
  /// a linear section; or empty: all linear).
  std::vector<std::shared_ptr<const AxialCurve>> curves;
  /// The seabed's angle of rise from the anchor toward the fairlead [rad], in (-pi/2,
  /// pi/2): 0 for a flat seabed, positive where it gets shallower toward the fairlead.
  double seabed_rise = 0.0;
  /// Whether the lower end is on the seabed (an anchor). False for a line whose lower end
  /// hangs in the water (from a free point): it never touches the seabed, its vertical
  /// tension may change sign along it (a sag below both ends), and its "anchor" may even
  /// lie above its "fairlead".
  bool lower_on_seabed = true;
  /// One linear section, no joint weight and a flat seabed: the homogeneous catenary
  /// (catenary.h) is it.
  bool Uniform() const {
    return lower_on_seabed && sections.size() == 1 && CurveOf(0) == nullptr &&
           (joint_weights.empty() || joint_weights.front() == 0.0) && seabed_rise == 0.0;
  }
  /// No weight in water worth a force (every section's |w| l below 1e-9 of its EA, no
  /// joint weight): a neutral rope, which hangs straight.
  bool Weightless() const {
    for (const CatenaryLineProperties& s : sections) {
      if (!(std::abs(s.weight_per_length) * s.length < 1e-9 * s.axial_stiffness)) return false;
    }
    for (double joint : joint_weights) {
      if (joint != 0.0) return false;
    }
    return true;
  }
  /// The curve of section `i`, or null.
  const AxialCurve* CurveOf(std::size_t i) const {
    return i < curves.size() ? curves[i].get() : nullptr;
  }
};

struct CompositeCatenary {
  CompositeLine line;
  double horizontal_tension = 0.0;  ///< H [N]
  double vertical_tension = 0.0;    ///< V at the fairlead [N]
  double fairlead_tension = 0.0;    ///< sqrt(H^2 + V^2) [N]
  double anchor_vertical = 0.0;     ///< upward pull on the anchor [N] (0 with touchdown
                                    ///< on a flat seabed; < 0 pulls a free lower end down)
  double grounded_length = 0.0;     ///< unstretched length on the seabed [m]
  /// The point at unstretched arc length s from the anchor, in the vertical plane through
  /// anchor and fairlead: x horizontal toward the fairlead, z up, from the anchor [m].
  Eigen::Vector2d PointAt(double s) const;
  /// V(s) [N] just above arc length s (a joint's weight counts below it); on the seabed,
  /// the vertical component of the tension along it.
  double VerticalTensionAt(double s) const;
};

/// Solves the composite catenary for a fairlead `span` >= 0 away from and `height` > 0
/// above the anchor (any height but a coincident pair of ends for a line whose lower end
/// hangs free, !lower_on_seabed). Throws moorsim::InputError for a line it cannot represent (no
/// section, a non-positive length or stiffness, joints that do not match the sections, a buoyant
/// section or a buoy on the part resting on the seabed) and moorsim::Error if no solution
/// is found (e.g. the line cannot reach).
/// `max_strain`: the largest strain accepted (a tabulation that must extend a taut line's
/// values smoothly past the elastic model's meaningful range may raise it).
CompositeCatenary SolveCompositeCatenary(const CompositeLine& line, double span, double height,
                                         double max_strain = kMaxCatenaryStrain);

/// The composite catenary between an anchor and a fairlead in the Earth frame (NED), and
/// the positions of the points at unstretched arc lengths `arc` (from the anchor).
Eigen::Matrix3Xd CompositeCatenaryPoints(const CompositeLine& line, const Vec3& anchor,
                                         const Vec3& fairlead, const std::vector<double>& arc);

}  // namespace moorsim::mooring_fem
