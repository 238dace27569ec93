// The mooring FEM's parameters: the water, the seabed, the current, the line types and the
// lines, and the integrator settings. Plain structs with the defaults the scenario schema
// documents (scenarios/README.md); the FEM takes these and nothing from the YAML layer, so
// it can be embedded without the scenario loader. scenarios/ fills them from YAML
// (scenarios::ToMooringParameters, scenarios/convert.h). All values SI, Earth-frame NED
// unless a name says otherwise; angles in radians. Line numbers are 1-based.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/integrator.h"
#include "core/types.h"
#include "mooring_fem/axial_curve.h"

namespace moorsim::mooring_fem {

/// A line parts at its fairlead, at an internal node, or its anchor lets go.
enum class FailureMode { kFairlead, kNode, kAnchor };

inline constexpr std::string_view kFailureModeNames[] = {"fairlead", "node", "anchor"};
constexpr ChoiceInfo ChoicesOf(FailureMode) { return {"failure mode", kFailureModeNames}; }

struct Water {
  double density = 1025.0;  ///< [kg/m^3]
  double gravity = 9.81;    ///< [m/s^2]
  double depth = 0.0;  ///< below the mean free surface [m], > 0: the waves' and a flat seabed's
};

/// The seabed's depth on a rectangular grid: depth[i * y.size() + j] below (x[i], y[j]),
/// bilinear inside each cell and held at the nearest edge's value beyond the grid.
struct DepthGrid {
  std::vector<double> x;      ///< north coordinates [m], strictly increasing, >= 2
  std::vector<double> y;      ///< east coordinates [m], strictly increasing, >= 2
  std::vector<double> depth;  ///< [m], > 0 (below the mean free surface), x.size() * y.size()
  std::string source;         ///< where it came from (a file name), for messages
  bool empty() const { return depth.empty(); }
};

/// The seabed: its shape, and penalty contact with it per unit of contact area
/// (diameter x length) with regularised Coulomb friction (coefficients per line type). The
/// shape is flat at z = water.depth (the default), a plane through depth water.depth below
/// the origin that deepens by `slope` toward `slope_direction`, or a depth grid; contact
/// acts along the local normal and friction in the local tangent plane.
struct Seabed {
  double stiffness = 3.0e6;  ///< [N/m^3] (pressure per metre of penetration)
  double damping = 3.0e5;    ///< [N s/m^3]
  /// Penetration [m] over which the contact stiffness ramps from zero to `stiffness`. A
  /// gradual ramp keeps touchdown smooth for the implicit integrator (benchmarks/README.md:
  /// with 2 mm, landing nodes caused most Newton failures and halved the step size).
  double contact_smoothing = 0.5;
  /// Speed [m/s] below which Coulomb friction is regularised (force ~ speed). Smaller is
  /// closer to true stick-slip and costs steps (0.05 m/s ran 20 % slower than 0.1).
  double friction_velocity = 0.1;
  double slope = 0.0;            ///< angle of a plane seabed to the horizontal [rad], < pi/2
  double slope_direction = 0.0;  ///< direction it deepens toward, from north to east [rad]
  DepthGrid grid;                ///< a depth grid in place of the plane (empty: none)
};

/// A current given as a table: the water's velocity (north, east, down) [m/s] at the nodes
/// of a grid over north x, east y, depth z and time t, interpolated linearly along each axis
/// (quadrilinear) and held constant beyond each axis's ends. An axis of one point makes the
/// current uniform along it: a steady profile has one x, one y and one t. With a `period`
/// the table repeats in time: at t the current of t0 + (t - t0) mod period (t0 the first
/// time), running from the last time's back to the first's over the gap to the period's
/// end; the period must exceed the last time minus the first.
struct CurrentTable {
  std::vector<double> x, y, z, t;  ///< strictly increasing, at least one point each
  /// The velocity at (x[i], y[j], z[k], t[l]): velocity[((i * ny + j) * nz + k) * nt + l].
  std::vector<Vec3> velocity;
  double period = 0.0;  ///< [s]; 0 = not repeating
  std::string source;   ///< where it came from (a file name), for messages
};

/// Current: a horizontal velocity whose speed varies piecewise linearly with depth and is
/// held constant beyond the first and last points. `direction` is the direction the water
/// flows TO, measured from north toward east [rad]. Or, with a table, the table's.
struct CurrentProfile {
  double direction = 0.0;
  std::vector<double> depth;  ///< strictly increasing depths [m], >= 0
  std::vector<double> speed;  ///< speeds at those depths [m/s], >= 0
  /// In place of the profile (then depth and speed are empty); shared, as it can be large.
  std::shared_ptr<const CurrentTable> table;
  /// Speed at the surface [m/s] (0 without a profile; a table's is not one number).
  double SurfaceSpeed() const { return speed.empty() ? 0.0 : speed.front(); }
};

/// A fibre rope's two stiffnesses (Hall, Duong & Lozon 2023): under slow loading (a mean
/// load that changes over minutes and hours: drift, current, the static offset) it is
/// softer than under the waves' cycles. Each segment is a spring of the dynamic stiffness in
/// series with a creep element, a spring and a dashpot in parallel, whose stretch (the
/// creep strain, a state of every segment) follows the tension with the creep time: slow
/// loading sees both springs in series, the quasi-static stiffness; fast loading finds the
/// dashpot rigid and sees the dynamic stiffness alone.
///
/// The dynamic stiffness may rise with the mean load, as fibre ropes' measured stiffness
/// does (Del Vecchio 1992): EA_d = dynamic_stiffness + dynamic_stiffness_slope x T_m, the
/// mean load T_m taken as the creep element's spring tension (it follows the tension with
/// the creep time), as MoorDyn v2's EA_s|EA_Dc|EA_D_Lm does. The creep spring then
/// follows from 1 / EA_s = 1 / EA_d + 1 / K, so that slow loading still sees EA_s; the
/// dashpot keeps the damping of the unloaded rope (K at T_m = 0 times the creep time).
struct ViscoElastic {
  double dynamic_stiffness = 0.0;  ///< EA_d [N] (at no mean load), > the quasi-static EA
  double creep_time = 0.0;  ///< [s]: under a constant tension, the creep strain's time constant
  double dynamic_stiffness_slope = 0.0;  ///< [-]: EA_d's rise per newton of mean load, >= 0
};

/// Material and hydrodynamic properties of one line type (Ren & Skjetne 2016, Table 2 style).
struct LineType {
  std::string name;
  double diameter = 0.0;         ///< nominal (hydrodynamic and displacement) diameter [m]
  double mass_per_length = 0.0;  ///< dry mass per unstretched length [kg/m]
  double axial_stiffness = 0.0;  ///< EA [N] (with a tension-strain table: left 0)
  /// A measured tension-strain table (AxialCurve) in place of a constant EA: empty = EA.
  std::vector<StrainTension> tension_strain;
  /// Axial structural damping: internal force = c * strain rate, c in [N s]. If
  /// axial_damping_ratio is set instead, c is chosen per line so that a single segment's
  /// axial mode has that fraction of critical damping (a numerical damping that vanishes
  /// as segments shrink). Neither set = no axial damping.
  std::optional<double> axial_damping;
  std::optional<double> axial_damping_ratio;
  /// A visco-elastic rope (a fibre rope: polyester): axial_stiffness is then its quasi-static
  /// stiffness, and this its dynamic stiffness and creep time (ViscoElastic). Not with a
  /// tension-strain table.
  std::optional<ViscoElastic> visco_elastic;
  double drag_normal = 0.0;            ///< C_DN [-]
  double drag_tangential = 0.0;        ///< C_DT [-]
  double added_mass_normal = 0.0;      ///< C_MN [-]
  double added_mass_tangential = 0.0;  ///< C_MT [-], along the line
  double friction_axial = 0.0;         ///< seabed Coulomb coefficient along the line [-]
  double friction_lateral = 0.0;       ///< seabed Coulomb coefficient across the line [-]
};

/// The seed chain of the library scenarios, "chain_seed" (Ren & Skjetne 2016), with the
/// seabed friction of chain on clay in the style of DNV-RP-E301 (the papers' seabed is
/// frictionless): 80 mm, 275 kg/m, EA 2.288e8 N.
inline LineType SeedChain() {
  LineType chain;
  chain.name = "chain_seed";
  chain.diameter = 0.08;
  chain.mass_per_length = 275.0;
  chain.axial_stiffness = 2.28785e8;
  chain.axial_damping_ratio = 0.5;
  chain.drag_normal = 0.3;
  chain.drag_tangential = 1.0;
  chain.added_mass_normal = 1.5;
  chain.friction_axial = 0.5;
  chain.friction_lateral = 1.0;
  return chain;
}

/// A generic polyester rope of 200 mm, "polyester" (the library's composite case): neutral
/// enough to hang between chains, linear-elastic at the slope of a rope in its working
/// range.
inline LineType PolyesterRope() {
  LineType rope;
  rope.name = "polyester";
  rope.diameter = 0.2;
  rope.mass_per_length = 40.0;
  rope.axial_stiffness = 2.0e8;
  rope.axial_damping_ratio = 0.5;
  rope.drag_normal = 1.2;
  rope.drag_tangential = 0.008;
  rope.added_mass_normal = 1.0;
  return rope;
}

/// A body on a line where two of its sections meet: a clump weight (heavier than the water
/// it displaces) or a buoy (lighter). It adds to the joint node its mass, its weight in
/// water, an isotropic added mass and an isotropic quadratic drag.
struct PointBody {
  double mass = 0.0;        ///< dry mass [kg]
  double volume = 0.0;      ///< displaced volume [m^3]
  double added_mass = 0.0;  ///< added-mass coefficient C_A on the displaced water [-]
  double drag_area = 0.0;   ///< C_D A [m^2]: drag 0.5 rho C_D A |u| u
};

/// A free point of the mooring: where lines meet (a bridle's apex, a buoy or clump weight
/// shared by lines) or a line's free end. Its position and velocity are states of the
/// mooring; it carries its body and the end nodes' shares of the lines it holds.
struct FreePoint {
  Vec3 position = Vec3::Zero();  ///< where it starts, Earth frame [m] (the static solve moves it)
  PointBody body;                ///< what sits there (a default PointBody: a plain connection)
};

/// A stretch of a line of one line type, split into equal segments.
struct LineSection {
  std::string type;     ///< name of a LineType
  double length = 0.0;  ///< unstretched length [m]
  int segments = 0;     ///< number of equal segments
};

/// One line as laid out (LineProperties, mooring_system.h, are the constants derived from
/// it, its types and the water): its sections from the anchor to the fairlead, and the
/// bodies at the joints between them. A homogeneous line has one section.
struct LineParameters {
  int id = 0;                         ///< 1-based line number
  Vec3 anchor = Vec3::Zero();         ///< anchor position, Earth frame [m] (z = +depth: seabed)
  Vec3 fairlead_body = Vec3::Zero();  ///< fairlead position in the body frame of the vessel [m]
  std::vector<LineSection> sections;  ///< from the anchor up, at least one
  /// joints[k] sits between sections k and k + 1 (sections.size() - 1 of them, or none: no
  /// bodies); a default PointBody is a plain joint.
  std::vector<PointBody> joints;
  /// The free points the line's ends hang from (0-based indices into MooringParameters::
  /// points), or -1: the lower end at `anchor`, the upper end at the vessel's `fairlead_body`.
  int lower_point = -1;
  int upper_point = -1;

  /// A homogeneous line: one section.
  static LineParameters Uniform(int id, const std::string& type, double length, int segments,
                                const Vec3& anchor, const Vec3& fairlead_body);
  double Length() const;  ///< unstretched, all sections [m]
  int Segments() const;   ///< all sections
  /// The node (0..Segments(), from the anchor) nearest the material point at unstretched
  /// arc length `arc_length` from the anchor.
  int NodeNearest(double arc_length) const;
};

struct MooringParameters {
  Water water;
  Seabed seabed;
  CurrentProfile current;  ///< empty profile = no current
  std::vector<LineType> line_types;
  std::vector<LineParameters> lines;  ///< ordered by id: lines[k - 1] is line k
  std::vector<FreePoint> points;      ///< the free points lines may end at
};

/// Integrator settings (CVODE BDF).
struct SolverSettings {
  double rtol = 1e-4;
  double atol_position = 1e-3;  ///< [m]
  double atol_velocity = 1e-3;  ///< [m/s]
  /// BDF order cap. 2 (A-stable) by default: orders 3-5 are not A-stable and the lines'
  /// lightly damped modes kept them at small steps (benchmarks/README.md).
  int max_order = 2;
  bool stability_limit_detection = false;
  double max_step = 0.0;  ///< [s]; 0 = no limit
  /// Steps CVODE may take between two stops (events, output instants) before it gives up
  /// with CV_TOO_MUCH_WORK: a run that crawls fails in seconds instead of hours.
  int max_steps = 200000;
  /// The Newton systems' linear solver: block (the lines' block-tridiagonal structure with
  /// the vessel as a dense border, core/block_solver.h) or klu (general sparse LU, the same
  /// solutions to rounding; kept for comparison).
  IntegratorOptions::LinearSolver linear_solver = IntegratorOptions::LinearSolver::kBlock;
};

}  // namespace moorsim::mooring_fem
