// The hypothesis-model bank (docs/design.md section 6): one quasi-static mooring model per
// hypothesis about which lines are intact, built from the scenario's mooring by the
// project's own catenary solver, never from hand-typed stiffness.
//
// Hypothesis 0 is "all lines intact", hypothesis k (1..N) is "line k failed", and, when
// pairs are asked for, hypotheses N+1.. are every pair (i, j), i < j, in lexicographic
// order. TAPM thesis eq. 3.15-3.17 writes the restoring load as g_mo(eta) = T(beta) L_p tau_H
// with the breakage matrix L_p zeroing the failed lines and tau_H the lines' horizontal
// tensions from a look-up table over the anchor-fairlead span; this file is that model:
// LineForceTable is the look-up table (one per line, shared by every hypothesis), and
// QuasiStaticMooring sums the intact lines with the exact geometry of body-fixed fairleads
// on a turret (the configuration matrix T(beta) evaluated at the current pose, not frozen).
//
// Frames and units: SI; Earth NED (x north, y east, z down); eta = (x, y, psi) is the
// position of the vessel's reference point and its heading; loads are [Fx, Fy, Mz] with Mz
// about the vertical axis through the reference point (positive turning north to east).
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/types.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/composite_catenary.h"
#include "mooring_fem/parameters.h"
#include "mooring_fem/point_network.h"

namespace moorsim::detectors {

struct LineForceTableOptions {
  /// Horizontal offsets of the vessel [m] the table must cover: the grid spans the nominal
  /// span +- (span_margin + turret radius), so any heading and any offset up to
  /// span_margin is inside it. Default 150 m, about 8 % of the seed case's 1930 m span.
  double span_margin = 150.0;
  /// Largest grid spacing [m]. With 1 m the interpolation error on the seed lines is
  /// ~3e-11 of H where H is smooth and 3.1e-7 in the interval that holds the lift-off of
  /// the anchor end; the bound tested is 1e-6 (tests/detectors/hypothesis_bank_test.cc).
  double span_step = 1.0;
  /// Largest grid spacing [m] of the two-dimensional end-tension tables of the lines that
  /// end at free points (mooring_fem/point_network.h: LineEndTable). With 2 m the interpolated
  /// tensions of the library's bridle lie within 1e-5 of the catenary's
  /// (tests/detectors/point_network_test.cc).
  double network_step = 2.0;
};

/// Horizontal (and vertical) fairlead tension of one line as a function of the horizontal
/// anchor-fairlead span, at a fixed fairlead depth: the elastic catenary of
/// mooring_fem/catenary.h or, for a composite line, mooring_fem/composite_catenary.h
/// (frictionless seabed) tabulated once on a uniform span grid and
/// interpolated by cubic Hermite polynomials. Node values come from SolveCatenary; node
/// slopes dH/dspan from a central difference of SolveCatenary with a 1 cm step (relative
/// error ~1e-7: the solver converges to ~1e-12 of the line length). The interpolant is
/// C1, so the Jacobians built on it are continuous; its derivative is returned exactly
/// (the derivative of the interpolant, consistent with the values to rounding).
///
/// Error: O(step^4) where H is smooth; in the one interval that holds the touchdown /
/// lift-off transition (where H is C1 but H'' is not smooth) it is larger: on the seed
/// lines 3e-7 of H and 1.4e-4 of dH/dspan at a 1 m step.
///
/// Outside [span_min, span_max] (documented rule): linear extrapolation from the end value
/// with the end slope, so the force and its Jacobian stay continuous; H and V are then
/// clamped at >= 0 (slope 0 where clamped). This is outside the model's validity and the
/// caller can test Covers(span). The upper end is the nominal span + span_margin + turret
/// radius, or, if the line cannot reach that far (SolveCatenary's strain limit), 1 m
/// short of the largest span it can reach.
class LineForceTable {
 public:
  /// `line`: its sections' unstretched lengths, submerged weights and EA, and the weights
  /// at their joints (mooring_fem::CatenaryLineOf); a line of one section and no joint
  /// weight is solved by SolveCatenary, any other by SolveCompositeCatenary;
  /// `anchor`: Earth frame [m]; `fairlead_body`: body frame [m] (its z is not used);
  /// `fairlead_depth`: Earth z of the fairlead [m] (NED, body z plus the moored heave).
  /// `line_id` (1-based) names the line in messages. Throws moorsim::InputError on bad
  /// properties or options, or when the catenary has no solution at the neutral pose.
  LineForceTable(int line_id, const mooring_fem::CompositeLine& line, const Vec3& anchor,
                 const Vec3& fairlead_body, double fairlead_depth,
                 const LineForceTableOptions& options = {});

  /// H [N] at horizontal span `span` [m]; if `d_dspan` is given, dH/dspan [N/m] there.
  double HorizontalTension(double span, double* d_dspan = nullptr) const;
  /// V [N] at the fairlead; if `d_dspan` is given, dV/dspan [N/m].
  double VerticalTension(double span, double* d_dspan = nullptr) const;
  /// Whether `span` lies on the tabulated range (no extrapolation).
  bool Covers(double span) const { return span >= span_min_ && span <= span_max_; }

  int line_id() const { return line_id_; }
  const mooring_fem::CompositeLine& line() const { return line_; }
  const Vec3& anchor() const { return anchor_; }
  const Vec3& fairlead_body() const { return fairlead_body_; }
  double fairlead_depth() const { return fairlead_depth_; }
  /// Height of the fairlead above the anchor [m].
  double height() const { return anchor_.z() - fairlead_depth_; }
  /// Span with the vessel at eta = 0 [m].
  double nominal_span() const { return nominal_span_; }
  double span_min() const { return span_min_; }
  double span_max() const { return span_max_; }
  double span_step() const { return step_; }
  int num_nodes() const { return static_cast<int>(h_.size()); }

 private:
  // Hermite interpolation of (values, slopes) at `span`, linear beyond the ends.
  double Interpolate(const std::vector<double>& values, const std::vector<double>& slopes,
                     double span, double* d_dspan) const;

  int line_id_ = 0;
  mooring_fem::CompositeLine line_;
  Vec3 anchor_ = Vec3::Zero();
  Vec3 fairlead_body_ = Vec3::Zero();
  double fairlead_depth_ = 0.0;
  double nominal_span_ = 0.0;
  double span_min_ = 0.0;
  double span_max_ = 0.0;
  double step_ = 0.0;
  std::vector<double> h_, dh_, v_, dv_;  // per node: H, dH/dspan, V, dV/dspan
};

/// A turret that turns on its bearing (vessel/turret.h: free or friction), as the
/// quasi-static mooring sees it: the lines hold the turret at a fixed absolute heading
/// `heading` (its heading at the start) while the hull turns about the turret centre
/// `centre` (body x, y) [m]. Friction is left out: the observers cannot know whether the
/// bearing slips.
struct TurretModel {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double heading = 0.0;  ///< [rad]
};

/// Lines that meet at free points and reach the vessel (mooring_fem/point_network.h), with where
/// their fairleads are on it.
struct AttachedNetwork {
  std::shared_ptr<const mooring_fem::PointNetwork> network;
  std::vector<Vec3> fairlead_body;     ///< per network fairlead, body frame [m] (z unused)
  std::vector<double> fairlead_depth;  ///< per network fairlead, Earth z [m] (NED)
};

/// Net horizontal load of a set of intact lines on the vessel (TAPM thesis eq. 3.15-3.16 with
/// the fairleads' true positions): line i's fairlead is at
///   p_i = (x, y) + Rz(psi) fairlead_body_i.xy,
/// it is pulled horizontally toward its anchor a_i with H_i(|a_i - p_i|), and
///   F = sum_i H_i u_i,   Mz = sum_i (R fairlead_body_i.xy) x (H_i u_i),
/// u_i = (a_i - p_i) / |a_i - p_i|. The Jacobian is analytic:
///   dF_i/dp = -H' u u^T - (H/s) (I - u u^T),   dp/dpsi = S r_i,  r_i = R fairlead_body.xy.
/// A span of exactly 0 (fairlead over the anchor) contributes no force and no Jacobian.
/// With a turning turret (TurretModel: centre c, heading psi_t) the fairleads sit at
///   p_i = (x, y) + Rz(psi) c + Rz(psi_t) (fairlead_body_i.xy - c)
/// and the hull feels the lines' net force at the turret centre: Mz = sum_i (R c) x F_i
/// (dp/dpsi = S R c). Lines that meet at free points are networks (AttachedNetwork): their
/// points are solved into balance at each call and their load joins the sum, with the
/// Jacobian of the points following the vessel. Allocates nothing per call without
/// networks.
class QuasiStaticMooring {
 public:
  /// No lines: zero load.
  QuasiStaticMooring() = default;
  /// `lines`: the lines from an anchor straight to the vessel; `turret`: unset = the
  /// fairleads fixed to the hull (a locked turret); `networks`: lines meeting at points.
  explicit QuasiStaticMooring(std::vector<std::shared_ptr<const LineForceTable>> lines,
                              std::optional<TurretModel> turret = std::nullopt,
                              std::vector<AttachedNetwork> networks = {});

  /// The lines straight from an anchor to the vessel (the networks' lines not counted).
  int num_lines() const { return static_cast<int>(lines_.size()); }
  const LineForceTable& line(int index) const { return *lines_[index]; }
  /// The list index of line `line_id` (1-based) among num_lines(), or -1 (a network's
  /// line, or a line this mooring does not hold).
  int IndexOf(int line_id) const;
  bool has_networks() const { return !networks_.empty(); }
  const std::vector<AttachedNetwork>& networks() const { return networks_; }
  /// The networks' share of Load (zero without networks), with its Jacobian.
  Vec3 NetworkLoad(const Vec3& eta, Mat3* J_load_eta = nullptr) const;

  /// [Fx, Fy, Mz] in the Earth frame [N, N, N m] at eta = (x, y, psi); if J_load_eta is
  /// given, d load / d eta [N/m, N/rad ...].
  Vec3 Load(const Vec3& eta, Mat3* J_load_eta = nullptr) const;
  /// The same load in body axes, [X, Y, N] = [R(psi)^T F; Mz], with its Jacobian w.r.t. eta.
  Vec3 LoadBody(const Vec3& eta, Mat3* J_load_eta = nullptr) const;
  /// Load of the line with list index `index` alone (Earth frame), with its Jacobian.
  Vec3 LineLoad(int index, const Vec3& eta, Mat3* J_load_eta = nullptr) const;
  /// The quasi-static fairlead tension sqrt(H^2 + V^2) [N] of the line with list index
  /// `index` at eta: what a load cell on it would read with the vessel held there.
  double LineTension(int index, const Vec3& eta) const;
  /// Each line's quasi-static tension at its upper end [N] at eta, in `by_line` at its
  /// 1-based id less one: what a load cell there would read (at the fairlead, or in line
  /// just below the free point it ends at). Lines this mooring does not hold are left as
  /// they are.
  void UpperTensions(const Vec3& eta, Eigen::Ref<VecX> by_line) const;

  const std::optional<TurretModel>& turret() const { return turret_; }

 private:
  /// The fairlead's offset r from (x, y) and the lever of its force about (x, y): the
  /// fairlead itself on a locked turret; on a turning one, the turret centre (R c), about
  /// which the fairlead holds its absolute direction.
  void FairleadOffset(const Eigen::Vector2d& fairlead_body, const Vec3& eta, Eigen::Vector2d* r,
                      Eigen::Vector2d* lever) const;

  std::vector<std::shared_ptr<const LineForceTable>> lines_;
  std::optional<TurretModel> turret_;
  std::vector<AttachedNetwork> networks_;
};

/// The low-frequency manoeuvring model of the vessel in surge, sway and yaw (TAPM thesis eq.
/// 3.6d; Fossen 2011 section 7.1): M nu' = -D nu + tau. Body axes; rows surge, sway, yaw.
struct LowFrequencyModel {
  Mat3 mass = Mat3::Zero();     ///< M = M_RB + A(0) [kg, kg, kg m^2]
  Mat3 damping = Mat3::Zero();  ///< D [N s/m, N s/m, N m s/rad]
};

/// The seed FPSO (docs/design.md section 9): M = diag(m + A11, m + A22, m 54^2 + A66) with
/// m = 1.0041e8 kg, A11 = 7.9427e6 kg, A22 = 6.4432e7 kg, A66 = 1.4513e11 kg m^2, and
/// D_ii = M_ii / T_i with T = 50, 100, 20 s (MSS rule).
LowFrequencyModel SeedLowFrequencyModel();

/// Linear mooring damping as a fraction of critical per DOF (TAPM thesis section 3.3.1: 10-20
/// % of critical, after DNV): D_mo = diag(2 ratio_i sqrt(max(G_ii, 0) M_ii)). It uses only
/// the diagonals of the stiffness G (Earth frame, about the neutral pose) and of the mass
/// M (body frame); the two frames agree at heading 0. Throws moorsim::InputError on a
/// negative or non-finite ratio.
Mat3 MooringDampingMatrix(const Mat3& stiffness, const Mat3& mass, const Vec3& ratio);

struct HypothesisBankOptions {
  /// Also every pair of failed lines (i, j), i < j (docs/design.md section 6).
  bool include_pairs = false;
  /// The vessel's moored heave [m] (NED, + down), added to every fairlead's body z.
  double moored_heave = 0.0;
  /// Pose about which the stiffness G_mo is linearised [m, m, rad]: the origin by default;
  /// the station-keeping setpoint where that differs (the thesis cases hold heading
  /// -135 deg, with the turret's fairleads turned to match).
  Vec3 reference_pose = Vec3::Zero();
  /// The turret on its bearing; unset = locked to the hull.
  std::optional<TurretModel> turret;
  LineForceTableOptions table;
};

/// One quasi-static mooring model per hypothesis; see the file comment for the numbering.
class HypothesisBank {
 public:
  /// Lines come from spec.lines (ordered by id, lines[k-1] is line k) through
  /// mooring_fem::MakeLineProperties. Throws moorsim::InputError on a spec without lines,
  /// bad options, or a line without a catenary solution at the neutral pose.
  explicit HypothesisBank(const mooring_fem::MooringParameters& spec,
                          const HypothesisBankOptions& options = {});

  int size() const { return static_cast<int>(hypotheses_.size()); }
  int num_lines() const { return static_cast<int>(tables_.size()); }
  /// Whether some lines meet at free points (their hypotheses' moorings hold networks).
  bool has_networks() const { return !network_lines_.empty(); }
  bool has_pairs() const { return size() > num_lines() + 1; }

  /// 1-based ids of the lines failed under hypothesis h (empty for h = 0).
  std::span<const int> failed_lines(int h) const { return hypotheses_.at(h).failed; }
  /// The quasi-static mooring of the lines intact under hypothesis h.
  const QuasiStaticMooring& mooring(int h) const { return hypotheses_.at(h).mooring; }
  /// "intact", "line 6", "lines 2+5".
  std::string Label(int h) const;
  /// The hypothesis whose failed lines are exactly `lines` (1-based ids, any order);
  /// -1 if the bank has none.
  int Find(std::span<const int> lines) const;

  /// Linearised stiffness G_mo(h) = -d load / d eta at options.reference_pose (default
  /// eta = 0), Earth frame [N/m, N/rad; N m/m, N m/rad] (docs/design.md section 6: for the
  /// observers that want a linear model). Analytic, from the tables; symmetric, since the
  /// lines' load is the gradient of their potential energy in (x, y, psi).
  const Mat3& stiffness(int h) const { return hypotheses_.at(h).stiffness; }
  /// MooringDampingMatrix(stiffness(h), mass, ratio).
  Mat3 MooringDamping(int h, const Mat3& mass, const Vec3& ratio) const;

  /// The table of line `index` (0-based; line id index + 1). Throws moorsim::Error for a
  /// line that ends at a free point (it has none: it is in a network).
  const LineForceTable& table(int index) const;

 private:
  struct Hypothesis {
    std::vector<int> failed;
    QuasiStaticMooring mooring;
    Mat3 stiffness = Mat3::Zero();
  };
  void Add(std::vector<int> failed);
  // The networks of the lines meeting at free points, for each failed set (networks_, in
  // the order Add will be called).
  void BuildNetworks(const mooring_fem::MooringParameters& spec,
                     const HypothesisBankOptions& options,
                     const std::vector<std::vector<int>>& failed_sets);

  Vec3 reference_pose_ = Vec3::Zero();
  std::optional<TurretModel> turret_;
  /// Per line (index id - 1); null for a line that ends at a free point.
  std::vector<std::shared_ptr<const LineForceTable>> tables_;
  std::vector<int> network_lines_;  // ids of the lines that end at free points
  /// Per failed set (in the order of the hypotheses), its networks.
  std::vector<std::vector<AttachedNetwork>> networks_;
  std::vector<Hypothesis> hypotheses_;
};

}  // namespace moorsim::detectors
