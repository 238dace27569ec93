// The lumped-mass Galerkin FEM of all mooring lines (Aamo & Fossen 2001, as written in
// Ren & Skjetne 2016, eq. 7).
//
// Each line of unstretched length L is split into n equal segments, nodes 0..n from the
// anchor to the fairlead. A node carries half of each adjacent segment: its dry mass, its
// submerged weight, the normal added mass C1 |l_s| / 2 (I - t_s t_s^T) with
// C1 = C_MN rho_w pi d^2 / 4, and Morison drag on the velocity relative to the current at
// the node's depth (normal: 0.5 rho C_DN d, tangential: 0.5 rho C_DT d, on the stretched
// half-segment length). Segments carry tension only: T = EA e + c de/dt when the strain
// e = |l| / l0 - 1 is positive, else 0. Nodes touching the seabed get a smooth penalty
// contact and regularised Coulomb friction with separate axial and lateral coefficients.
//
// State: every node that is not held (anchor, fairlead) has [r (3), v (3)] in the Earth
// frame, stored contiguously per node and per chain. The node equation is
//   r' = v,   M_k(r) v' = F_k(r, v)
// solved for v' with the 3x3 node mass matrix. The Jacobian is analytic and includes the
// configuration dependence of the added mass (d(M a)/dr); its pattern is block
// tridiagonal per chain and fixed until the topology changes.
//
// Failure events split a line into chains with free ends: a chain is a run of nodes whose
// two ends are each anchored, attached to a fairlead, or free.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/coupled_system.h"
#include "core/ode_system.h"
#include "core/types.h"
#include "mooring_fem/composite_catenary.h"
#include "mooring_fem/environment.h"
#include "mooring_fem/parameters.h"
#include "mooring_fem/wave_kinematics.h"

namespace moorsim::mooring_fem {

/// Constants of one section of a line, derived from its type, the water and its segments.
struct SectionProperties {
  std::string type;
  int segments = 0;
  double length = 0.0;                      ///< unstretched [m]
  double segment_length = 0.0;              ///< l0 = length / segments [m]
  double diameter = 0.0;                    ///< [m]
  double mass_per_length = 0.0;             ///< dry [kg/m]
  double weight_per_length = 0.0;           ///< submerged [N/m]; negative for a buoyant section
  double axial_stiffness = 0.0;             ///< EA [N]; with a curve its largest slope
  std::shared_ptr<const AxialCurve> curve;  ///< the tension-strain law; null: T = EA e
  double axial_damping = 0.0;               ///< c [N s], internal force c de/dt
  double displaced_mass_per_length = 0.0;   ///< rho pi d^2/4 [kg/m]
  double added_mass_per_length = 0.0;       ///< C1 = C_MN rho pi d^2/4 [kg/m]
  double tangential_added_mass_per_length = 0.0;  ///< C_MT rho pi d^2/4 [kg/m]
  /// A visco-elastic rope (ViscoElastic): axial_stiffness is its quasi-static stiffness EA_s,
  /// and each segment a spring EA_d in series with a creep spring K and dashpot c in
  /// parallel (1 / EA_s = 1 / EA_d + 1 / K, c = K x the creep time).
  bool visco = false;
  double dynamic_stiffness = 0.0;  ///< EA_d [N] (at no mean load)
  double creep_stiffness = 0.0;    ///< K [N] (at no mean load)
  double creep_damping = 0.0;      ///< c [N s]
  /// EA_d's rise per newton of the creep spring's tension (ViscoElastic) [-]; 0: constant.
  double dynamic_stiffness_slope = 0.0;
  double drag_normal = 0.0;       ///< 0.5 rho C_DN d [kg/m^2]
  double drag_tangential = 0.0;   ///< 0.5 rho C_DT d [kg/m^2]
  double friction_axial = 0.0;    ///< [-]
  double friction_lateral = 0.0;  ///< [-]
};

/// Constants of a body at a joint (PointBody with the water).
struct PointBodyProperties {
  double mass = 0.0;            ///< [kg]
  double weight = 0.0;          ///< in water [N], negative for a buoy
  double added_mass = 0.0;      ///< C_A rho V [kg]
  double drag = 0.0;            ///< 0.5 rho C_D A [kg/m]
  double displaced_mass = 0.0;  ///< rho V [kg]
};

/// Constants of one line: its sections from the anchor up and the bodies at their joints.
/// Segments and nodes are numbered along the whole line from the anchor (node 0) to the
/// fairlead (node `segments`).
struct LineProperties {
  int id = 0;  ///< 1-based
  int segments = 0;
  double length = 0.0;  ///< unstretched [m]
  std::vector<SectionProperties> sections;
  Vec3 anchor = Vec3::Zero();         ///< Earth frame [m]
  Vec3 fairlead_body = Vec3::Zero();  ///< body frame [m]
  int lower_point = -1;               ///< the free point at the lower end, or -1: the anchor
  int upper_point = -1;               ///< the free point at the upper end, or -1: the fairlead
  /// Per segment: the index of its section.
  std::vector<int> section_of;
  /// The bodies on the line's joints, and per node the index of the one there (-1: none).
  std::vector<PointBodyProperties> bodies;
  std::vector<int> body_at;

  const SectionProperties& SectionOf(int segment) const { return sections[section_of[segment]]; }
  const PointBodyProperties* BodyAt(int node) const {
    return body_at[node] < 0 ? nullptr : &bodies[body_at[node]];
  }
};

/// What a node carries of its line: half of each adjacent segment (of the sections
/// `below` and `above`, -1 at a free end) and the body there (an index into the line's
/// bodies, -1 for none).
struct NodeShare {
  double length = 0.0;  ///< unstretched line length the node stands for [m]
  double mass = 0.0;    ///< line and body [kg] (with the body's isotropic added mass)
  double weight = 0.0;  ///< line and body, in water [N]
  double line_weight_per_length = 0.0;  ///< of the line alone [N/m]
  double contact = 0.0;  ///< seabed contact area of the line, diameter x length [m^2]
  double friction_axial = 0.0, friction_lateral = 0.0;  ///< contact-weighted [-]
  int below = -1, above = -1, body = -1;
};
/// The share of node `node` (0..segments) of `line`, with or without the segment below
/// and above it (a chain's free end has one).
NodeShare ShareOf(const LineProperties& line, int node, bool has_below, bool has_above);

/// Throws moorsim::InputError if a section's type is not one of spec.line_types, the line
/// has no section or a section no segment, or the joints do not match the sections.
LineProperties MakeLineProperties(const MooringParameters& spec, const LineParameters& line);
/// A body's constants in the water.
PointBodyProperties BodyProperties(const PointBody& body, const Water& water);

/// The line as the composite catenary sees it (composite_catenary.h): its sections'
/// lengths, weights and stiffnesses, the bodies' weights at the joints, and the seabed's
/// angle of rise toward the fairlead [rad] (SeabedSurface::RiseAlong).
CompositeLine CatenaryLineOf(const LineProperties& line, double seabed_rise = 0.0);
/// CatenaryLineOf for the line at rest from `lower` to `upper`: one from a free point
/// (`lower_is_point`), or from an anchor held more than 1 m above the seabed, hangs free of
/// it (!lower_on_seabed); one from an anchor on the seabed lies on it, rising along it.
CompositeLine RestingLineOf(const LineProperties& line, const Vec3& lower, const Vec3& upper,
                            bool lower_is_point, const SeabedSurface& seabed);
/// Unstretched arc length of every node from the anchor [m] (nodes 0..segments).
std::vector<double> NodeArcLengths(const LineProperties& line);
/// The fairlead tension [N] of the line's elastic catenary (SolveLineCatenary for a
/// homogeneous line, SolveCompositeCatenary otherwise) with its fairlead at `fairlead`
/// (Earth frame) on `seabed`. Throws moorsim::Error if there is none.
double CatenaryFairleadTension(const LineProperties& line, const Vec3& fairlead,
                               const SeabedSurface& seabed);

/// A chain's end: held at its anchor or at the vessel's fairlead, hanging from a free point
/// (whose states the mooring integrates), or free.
enum class EndCondition { kAnchored, kFairlead, kPoint, kFree };

/// A connected run of a line's nodes first_node..first_node+segments.
struct Chain {
  int line = 0;  ///< 0-based index into the lines
  int first_node = 0;
  int segments = 0;
  EndCondition lower = EndCondition::kAnchored;
  EndCondition upper = EndCondition::kFairlead;
  Vec3 anchor = Vec3::Zero();  ///< held position of the lower end when kAnchored
  int lower_point = -1;        ///< the free point (0-based) of a kPoint lower end
  int upper_point = -1;        ///< and of a kPoint upper end
  int state_offset = 0;        ///< index of the first state component of the chain

  int first_state_node() const { return lower == EndCondition::kFree ? 0 : 1; }
  int last_state_node() const { return upper == EndCondition::kFree ? segments : segments - 1; }
  int num_state_nodes() const { return last_state_node() - first_state_node() + 1; }
};

/// A node's mass matrix M = m I + sum_i [a_i (I - t_i t_i^T) + b_i t_i t_i^T]: its share of
/// the line's mass and, for each of its (at most two) half segments of direction t_i, the
/// normal and tangential added mass a_i and b_i.
struct NodeMass {
  double m = 0.0;
  int segments = 0;
  double a[2] = {0.0, 0.0};
  double b[2] = {0.0, 0.0};
  Vec3 t[2] = {Vec3::Zero(), Vec3::Zero()};

  void Add(double added, const Vec3& direction, double tangential = 0.0);
  Mat3 Matrix() const;
  /// M^{-1} F without forming or inverting M (Sherman-Morrison-Woodbury: M is m' I minus a
  /// rank-2 term), the right-hand side's acceleration.
  Vec3 Solve(const Vec3& F) const;
};

/// A line parts at its fairlead, at an internal node (1..n-1, counted from the anchor), or
/// its anchor lets go.
struct LineFailure {
  int line = 0;  ///< 0-based line index
  FailureMode mode = FailureMode::kFairlead;
  int node = 0;  ///< for kNode
};

// FairleadCoupling (core/coupled_system.h): the blocks that couple a line's last free node
// and its fairlead force to the body moving the fairlead.

/// Per-line static/quasi-static summary.
struct LineLoad {
  Vec3 fairlead_force = Vec3::Zero();  ///< force of the line on the body, Earth frame [N]
  /// Force of the line on what holds its upper end: the vessel (fairlead_force) or a free
  /// point, Earth frame [N].
  Vec3 upper_end_force = Vec3::Zero();
  double grounded_length = 0.0;  ///< unstretched length carried by the seabed [m]
  bool attached = true;
};

class MooringSystem {
 public:
  explicit MooringSystem(const MooringParameters& spec);

  int num_lines() const { return static_cast<int>(lines_.size()); }
  /// The free points: states 6 p .. 6 p + 5 are point p's [r (3), v (3)] (the points come
  /// first in the state, then the chains).
  int num_points() const { return static_cast<int>(point_bodies_.size()); }
  Vec3 PointPosition(const double* x, int point) const { return Vec3(x + 6 * point); }
  const LineProperties& line(int index) const { return lines_[index]; }
  const std::vector<Chain>& chains() const { return chains_; }
  const SeabedContact& seabed() const { return seabed_; }
  const CurrentField& current() const { return current_; }
  /// The waves' water motion the lines see in drag and inertia (wave_kinematics.h), or
  /// none (null: still water but for the current).
  void SetWaves(std::shared_ptr<const WaveKinematics> waves) { waves_ = std::move(waves); }
  const WaveKinematics* waves() const { return waves_.get(); }
  /// The time [s] the waves are taken at by the next evaluations (the right-hand side and
  /// its Jacobian depend on time only through them).
  void SetTime(double t) { time_ = t; }
  int StateSize() const { return state_size_; }
  /// Whether line `index` is still attached at its upper end (the vessel's fairlead or a
  /// free point).
  bool attached(int index) const;
  /// Whether line `index` ends at the vessel and is still attached there (the lines whose
  /// force the vessel feels).
  bool at_vessel(int index) const;

  /// Per state component: position components 'p', velocity components 'v', and the
  /// visco-elastic segments' creep stretches 's' [m].
  std::vector<char> StateKinds() const;
  /// Whether Blocks() covers the whole state: not with visco-elastic segments, whose creep
  /// states a general sparse LU then solves with the rest.
  bool has_blocks() const { return creep_.empty(); }

  /// Places every node on the analytic elastic catenary between its anchor and the given
  /// fairlead position (Earth frame), at rest; the free points at their given positions and
  /// the lines between them on a sag of their length. Intact topology only.
  void CatenaryState(std::span<const Vec3> fairleads, double* x) const;

  /// Moves the positions in x to the FEM's own static equilibrium (v = 0) for the given
  /// fairlead positions by Newton's method on the sparse stiffness, starting from x; slack
  /// stretches (a singular stiffness) get a Levenberg-Marquardt shift and a line search on
  /// the potential energy. Returns the largest residual node force [N], below 1e-11 EA.
  /// Throws moorsim::Error naming the line and the residual if it does not converge (500
  /// iterations, or no step makes progress) or the start state is degenerate.
  ///
  /// With free points, the lines are settled with the points held, and the points moved by
  /// Newton's method on their force balance (a finite-difference Jacobian over the settled
  /// lines) until the largest residual point force is below 1e-9 EA. Throws moorsim::Error
  /// naming the point if it does not converge or a point rises above the water.
  double SettleStatic(std::span<const Vec3> fairleads, double* x);

  /// x' = f(x) for the given fairlead kinematics (one per line, Earth frame). If `forces`
  /// is not empty (one per line), it receives what FairleadForces() would, at little cost.
  void Derivatives(const double* x, std::span<const PointKinematics> fairleads, double* xdot,
                   std::span<Vec3> forces = {});

  /// CSR pattern of df/dx for the current topology.
  const SparsityPattern& JacobianPattern() const { return pattern_; }
  /// The pattern's block structure: one node chain per piece of line, no border.
  const BlockStructure& Blocks() const { return blocks_; }
  /// df/dx values in pattern order.
  void Jacobian(const double* x, std::span<const PointKinematics> fairleads, double* values);

  /// Force each line exerts on the body at its fairlead (what a load cell reads), Earth
  /// frame: the top segment's tension plus the fairlead node's share of weight, drag,
  /// seabed contact and inertia. Zero for detached lines.
  void FairleadForces(const double* x, std::span<const PointKinematics> fairleads,
                      std::span<Vec3> forces);

  /// For each line whose upper end is at a free point (and only those), the force it
  /// exerts on the point, Earth frame (what a load cell there reads).
  void PointEndForces(const double* x, std::span<const PointKinematics> fairleads,
                      std::span<Vec3> forces);

  /// State index of node n-1 of line `index` if it is attached to its fairlead and has a
  /// free node below it, else -1.
  int CouplingNode(int index) const;
  /// The creep state of line `index`'s top segment if it is visco-elastic and attached to
  /// its fairlead, else -1.
  int CouplingCreep(int index) const;
  /// Coupling blocks of line `index` (0-based), which must be attached to its fairlead.
  FairleadCoupling FairleadJacobian(const double* x, std::span<const PointKinematics> fairleads,
                                    int index);

  /// Fairlead forces plus the grounded length of each line.
  std::vector<LineLoad> LineLoads(const double* x, std::span<const PointKinematics> fairleads);

  /// Mechanical energy of the lines [J]: kinetic (with added mass), gravitational
  /// (submerged weight), elastic and seabed-spring energy.
  double MechanicalEnergy(const double* x, std::span<const PointKinematics> fairleads);

  /// Position of node `node` (0..n) of line `line` (0-based); for a node split by a
  /// failure, the copy in the chain nearer the anchor.
  Vec3 NodePosition(const double* x, int line, int node,
                    std::span<const PointKinematics> fairleads) const;

  /// The tension [N] of each of line `line`'s (0-based) segments, from the anchor up (a
  /// parted line's pieces included): what a load cell in line there would read, without
  /// the node's weight and inertia that a fairlead or anchor force adds.
  std::vector<double> SegmentTensions(const double* x, int line,
                                      std::span<const PointKinematics> fairleads);

  /// Changes the topology and returns the new state, carrying every node's position and
  /// velocity over (nodes that were held take the holder's position and velocity).
  std::vector<double> ApplyFailure(const LineFailure& failure, const double* x,
                                   std::span<const PointKinematics> fairleads);

 private:
  struct SegmentState {
    Vec3 t;       // unit tangent toward the upper node
    double L;     // stretched length
    double T;     // tension
    double rate;  // strain rate
    // A visco-elastic segment's creep stretch state (-1: none) and creep strain.
    int creep = -1;
    double creep_strain = 0.0;
  };
  struct NodeJacobian {
    Mat3 dF_dr[3], dF_dv[3], dMa_dr[3];  // w.r.t. node k-1, k, k+1
  };

  void Layout();
  void BuildPattern();
  /// SettleStatic's work: the chains, then the points over them.
  double SettleLinesAndPoints(std::span<const PointKinematics> fairleads, double* x);
  /// Moves the free points in x to where their lines' catenaries balance them
  /// (point_network.h) and lays those lines along their catenaries: the start of the
  /// points' Newton solve. Leaves x as it is where the catenaries find no balance in the
  /// water.
  void CatenaryPointStart(std::span<const PointKinematics> fairleads, double* x) const;
  /// Nodes 0..segments of chain `c` from `lower` to `upper` at rest: its catenary, or a sag
  /// between the ends where it has none.
  Eigen::Matrix3Xd StartNodes(const Chain& c, const Vec3& lower, const Vec3& upper) const;
  /// SettleStatic for the chains with the points held.
  double SettleChains(std::span<const PointKinematics> fairleads, double* x);
  /// The free points' net force with their bodies and the lines' end shares, and their mass
  /// matrices, into point_force_ and point_mass_ (chains with a point end are gathered).
  void PointLoads(const double* x, std::span<const PointKinematics> fairleads);
  /// Sets point q's force and mass to its own body's (weight, drag, fluid inertia).
  void PointBodyLoad(int q, const double* x);
  /// Adds a chain end node k's force and mass to its point's (pos_, seg_ gathered).
  void AddEndToPoint(const Chain& chain, int k, int point);
  Vec3 PointAcceleration(int point) const;
  /// The force of chain c's top node on what holds it, moving with `acceleration`.
  Vec3 UpperEndForce(const Chain& c, const double* x, std::span<const PointKinematics> fairleads,
                     const Vec3& acceleration);
  /// The first state of the 6-block a chain end's neighbour node is (the next node along
  /// the chain, or the point at its other end), or -1 when that is held (an anchor).
  int EndNeighbourState(const Chain& chain, bool lower) const;
  /// pos_, vel_ and the segments' creep of a chain from the state x.
  void GatherChain(const Chain& chain, const double* x, std::span<const PointKinematics> fairleads);
  /// pos_ and vel_ alone (x may be of another layout's creep).
  void GatherNodes(const Chain& chain, const double* x, std::span<const PointKinematics> fairleads);
  void ComputeSegments(const Chain& chain);
  /// Net force F and mass M of chain node k from the gathered state.
  void NodeForce(const Chain& chain, int k, Vec3* F, NodeMass* M) const;
  /// NodeForce with or without the waves (two instantiations, so still water costs nothing
  /// extra).
  template <bool kWaves>
  void NodeForceIn(const Chain& chain, int k, Vec3* F, NodeMass* M) const;
  /// Node k's share of its line: kept for an inner node, computed into *end for a chain's
  /// end node (it lacks the segment beyond it).
  const NodeShare& ShareAt(const Chain& chain, int k, NodeShare* end) const;
  /// Adds the node's force derivatives; needs the node's acceleration for d(M a)/dr.
  void NodeForceJacobian(const Chain& chain, int k, const Vec3& accel, NodeJacobian* J) const;

  std::vector<LineProperties> lines_;
  /// The visco-elastic segments: state creep_offset_ + i is segment creep_[i]'s creep
  /// stretch [m]; creep_index_[line][segment] is i, or -1.
  struct CreepSegment {
    int line, segment;
  };
  std::vector<CreepSegment> creep_;
  std::vector<std::vector<int>> creep_index_;
  int creep_offset_ = 0;
  /// Set while SettleStatic runs: the visco-elastic segments at their quasi-static stiffness
  /// (their creep at rest, slaved to the tension).
  bool settling_ = false;
  /// The state of segment `segment` of line `line`'s creep stretch, or -1.
  int CreepState(int line, int segment) const;
  /// Chain node k's segments' creep states, below and above (-1: none).
  std::array<int, 2> NodeCreepStates(const Chain& c, int k) const;
  /// The first state of chain node k's 6-block (a node or a point), or -1 where it is held.
  int NodeStateOf(const Chain& c, int k) const;
  /// dT / d(creep stretch) of a gathered segment: (EA_d'(e) (strain - e) - EA_d) / l0
  /// while its dynamic spring is stretched, else (and while settling) 0.
  double CreepSlope(const SegmentState& g, const SectionProperties& sp) const;
  /// Per creep state, its segment's lower and upper node's 6-blocks (NodeStateOf).
  struct CreepRow {
    int lower = -1, upper = -1;
  };
  std::vector<CreepRow> creep_rows_;
  /// Per point, the creep states (ascending) of its lines' end segments.
  std::vector<std::vector<int>> point_creep_;
  /// Each creep stretch at rest for the segment's stretch in x (T = EA_s e through both).
  void CreepAtRest(double* x, std::span<const PointKinematics> fairleads) const;
  /// The elastic tension a visco-elastic segment carries through its creep element.
  double CreepTension(const SectionProperties& sp, double strain, double creep_strain) const;
  std::vector<PointBodyProperties> point_bodies_;
  std::vector<Vec3> point_start_;
  // Per point, the 6-blocks (first states, ascending) its velocity rows have columns in.
  std::vector<std::vector<int>> point_blocks_;
  std::vector<Vec3> point_force_;  // scratch: PointLoads()
  // Scratch of Jacobian(): the points' accelerations and their rows' blocks per column.
  std::vector<Vec3> point_accel_;
  std::vector<std::vector<Mat3>> point_dr_, point_dv_;
  std::vector<std::vector<Vec3>> point_dq_;
  std::vector<Mat3> point_mass_;
  /// Per line, the share of every interior node (with both its half segments).
  std::vector<std::vector<NodeShare>> shares_;
  std::vector<Chain> chains_;
  SeabedContact seabed_;
  CurrentField current_;
  std::shared_ptr<const WaveKinematics> waves_;
  double time_ = 0.0;
  int state_size_ = 0;
  SparsityPattern pattern_;
  BlockStructure blocks_;

  // Scratch for one chain (sized for the longest), reused by every call.
  std::vector<Vec3> pos_, vel_;
  std::vector<SegmentState> seg_;
};

}  // namespace moorsim::mooring_fem
