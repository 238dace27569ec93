// Lines that meet at free points (a bridle's apex, a buoy or clump weight shared by several
// lines) as elastic catenaries: the points rest where their weights and their lines' end
// tensions balance, each line a composite catenary between its two ends
// (composite_catenary.h), and the fairleads feel the tensions of the lines that end at
// them. The detectors' quasi-static mooring model (detectors/hypothesis_bank.h) and the
// static solve's start for free points (MooringSystem::SettleStatic) use it.
//
// A line's end tensions depend on where both its ends are: its horizontal tension H and the
// vertical tensions at its upper and lower ends are functions of its horizontal span s and
// of the height h of its upper end above its lower one. LineEndTable tabulates them on a
// grid over the chord between the ends (its length and angle) and interpolates bicubically
// (Hermite), so that the points' Newton
// solve and the Jacobians built on it see one smooth (C1) function; SolveLineEnds gives
// the same values straight from the catenary, where the grid's range is not known yet.
//
// PointNetwork is one connected set of free points and the lines between them, their
// anchors and the vessel's fairleads. Given the fairleads' positions it solves the points'
// force balance by Newton's method,
//   R(q) = W + sum over the lines at each point of their end forces = 0,
// with the analytic Jacobian dR/dq of the lines' end forces, and returns the forces on the
// fairleads with their total derivative with respect to the fairleads' horizontal
// positions: dF/dp = dF/dp|q - dF/dq (dR/dq)^-1 dR/dp (the points move with the vessel).
//
// Frames and units: SI; Earth NED (z down); a point's weight W is in water, positive down.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/types.h"
#include "mooring_fem/composite_catenary.h"

namespace moorsim::mooring_fem {

/// A line's end tensions and their derivatives with respect to (span, height) [N/m].
struct LineEnds {
  double horizontal = 0.0;      ///< H, along the line's vertical plane [N]
  double vertical = 0.0;        ///< V at the upper end, pulling it down [N]
  double lower_vertical = 0.0;  ///< V at the lower end, pulling it up [N] (free lower ends)
  Eigen::Vector2d d_horizontal = Eigen::Vector2d::Zero();
  Eigen::Vector2d d_vertical = Eigen::Vector2d::Zero();
  Eigen::Vector2d d_lower_vertical = Eigen::Vector2d::Zero();
};

/// The composite catenary's end tensions with the upper end `span` [m] away from and
/// `height` [m] above the lower end, with derivatives by central differences of 1 cm (closed
/// forms for a weightless line, which hangs straight). The
/// lower end's V is given for a line whose lower end hangs free (!line.lower_on_seabed):
/// an anchor holds whatever it is asked to. Throws moorsim::Error where the catenary has
/// no solution.
LineEnds SolveLineEnds(const CompositeLine& line, double span, double height);

/// SolveLineEnds tabulated over the chord between the line's ends: its length c and its
/// angle of rise a above the horizontal (span = c cos a, height = c sin a), on a uniform
/// grid, interpolated by bicubic Hermite polynomials from each node's values, first
/// derivatives (the central differences of SolveLineEnds) and cross derivative (central
/// differences of the chord derivatives between nodes). The chord is the natural axis: a
/// taut line's tensions turn from sag to stretch over a fraction of a metre of chord (its
/// sag's shortening, L (w L / T)^2 / 24), at any angle. The grid is refined, axis by axis,
/// until the interpolant at the edges' midpoints is within 1e-6 of the line's tension of
/// the catenary there (or the node cap is reached). Grid corners no state reaches, beyond
/// the catenary's strain limit, carry the same elastic model strained further (to 100 %),
/// so the function stays smooth across the grid. The interpolant is C1 and its
/// derivatives are returned exactly. Beyond the grid the values are extended linearly
/// from the nearest point on it (continuous, with the gradient there); Covers() tells
/// whether a point is inside.
class LineEndTable {
 public:
  struct Range {
    double chord_min = 0.0, chord_max = 0.0;  ///< [m]
    double angle_min = 0.0, angle_max = 0.0;  ///< [rad], in [-pi/2, pi/2]
  };
  /// `step`: the largest grid spacing [m] (along the chord; across it, c times the angle
  /// step); `max_nodes` caps the grid. Throws moorsim::Error where the catenary has no
  /// solution on the grid.
  LineEndTable(const CompositeLine& line, const Range& range, double step, int max_nodes = 40000);

  /// At a span `span` >= 0 and height `height` [m] (not both zero).
  LineEnds At(double span, double height) const;
  bool Covers(double span, double height) const;
  const Range& range() const { return range_; }
  int num_nodes() const { return chords_ * angles_; }
  /// The largest relative error measured at the edges' midpoints when the grid was built.
  double measured_error() const { return measured_error_; }

 private:
  void Build(const CompositeLine& line);
  // Bicubic Hermite interpolation of one quantity's grid (value, d/dc, d/da, d2/dcda per
  // node) at a point inside the grid: the value and its gradient in (c, a).
  double Interpolate(const std::vector<Eigen::Vector4d>& grid, double chord, double angle,
                     Eigen::Vector2d* gradient) const;

  Range range_;
  int chords_ = 0, angles_ = 0;  // nodes along each axis
  double chord_step_ = 0.0, angle_step_ = 0.0;
  bool free_lower_end_ = false;
  double weight_ = 0.0;  // the line's weight in water, joints included [N]
  double measured_error_ = 0.0;
  std::vector<Eigen::Vector4d> horizontal_, vertical_;  // node (i chord, j angle): i * angles_ + j
};

/// Where a line of a network ends.
struct NetworkEnd {
  enum class Kind { kPoint, kAnchor, kFairlead };
  Kind kind = Kind::kAnchor;
  int index = 0;  ///< into the network's points, anchors or fairleads
};

struct NetworkLine {
  int id = 0;  ///< 1-based, for messages
  NetworkEnd lower, upper;
  CompositeLine line;  ///< lower_on_seabed: its lower end is an anchor
  /// Its end tensions; null: SolveLineEnds, straight from the catenary.
  std::shared_ptr<const LineEndTable> table;
};

/// One connected set of free points and lines (file comment).
class PointNetwork {
 public:
  /// `weights`: each point's weight in water [N] (positive down); `anchors`: Earth frame
  /// [m]; `rest`: the points' positions (3 x points) the solves start from. Throws
  /// moorsim::Error on ends that name no point, anchor or fairlead.
  PointNetwork(std::vector<NetworkLine> lines, std::vector<double> weights,
               std::vector<Vec3> anchors, int num_fairleads, Eigen::Matrix3Xd rest);

  struct Equilibrium {
    Eigen::Matrix3Xd points;           ///< where the points rest (3 x points) [m]
    Eigen::Matrix3Xd fairlead_forces;  ///< the lines' force on each fairlead [N]
    /// d (horizontal force on fairlead f) / d (horizontal position of fairlead g): rows
    /// 2 f .. 2 f + 1, columns 2 g .. 2 g + 1 [N/m]; only if asked for.
    Eigen::MatrixXd d_horizontal;
    std::vector<double> upper_tension;  ///< each line's tension at its upper end [N]
    double residual = 0.0;              ///< the largest force left on a point [N]
    bool converged = false;
  };

  /// The points' rest with the fairleads at `fairleads` (3 x num_fairleads, Earth frame),
  /// from `start` (or the rest positions), to a residual of 1e-9 of the stiffest line's EA.
  /// Newton's method with a line search (the full step where the residual falls or the
  /// energy still falls at its end, else Newton corrections from its end where they bring
  /// the residual below the start's (a point swinging on a taut, stiff line), else a
  /// halving where the residual falls, else the energy's least along the step) and a
  /// Levenberg-Marquardt shift (dR/dq - mu s I) where no step descends, which moves a point on
  /// slack lines along its force. Does not throw for want of convergence: `converged` says, and the
  /// last iterate is returned; throws moorsim::Error only where a line's end tensions cannot be
  /// evaluated at the start.
  Equilibrium Solve(const Eigen::Matrix3Xd& fairleads, bool jacobian,
                    const Eigen::Matrix3Xd* start = nullptr) const;

  int num_points() const { return static_cast<int>(weights_.size()); }
  int num_fairleads() const { return num_fairleads_; }
  const std::vector<NetworkLine>& lines() const { return lines_; }
  const Eigen::Matrix3Xd& rest() const { return rest_; }
  /// A copy whose lines read `tables` (one per line, in order) and whose solves start
  /// from `rest`.
  PointNetwork WithTables(const std::vector<std::shared_ptr<const LineEndTable>>& tables,
                          const Eigen::Matrix3Xd& rest) const;

 private:
  struct Evaluation;
  // The residual (and, with `jacobian`, its derivatives) at points `q`; false where a
  // line's end tensions cannot be evaluated there.
  bool Evaluate(const Eigen::Matrix3Xd& fairleads, const Eigen::Matrix3Xd& q, bool jacobian,
                Evaluation* out) const;
  Vec3 EndPosition(const NetworkEnd& end, const Eigen::Matrix3Xd& q,
                   const Eigen::Matrix3Xd& fairleads) const;

  std::vector<NetworkLine> lines_;
  std::vector<double> weights_;
  std::vector<Vec3> anchors_;
  int num_fairleads_ = 0;
  Eigen::Matrix3Xd rest_;
  double tolerance_ = 0.0;  // [N]
};

}  // namespace moorsim::mooring_fem
