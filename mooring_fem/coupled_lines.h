// The mooring lines coupled to a body that someone else integrates: a vessel model, a
// wave-energy converter, a CFD solver. The caller owns the body's motion and hands its
// pose and velocity at each coupling instant; the lines integrate from the previous instant
// along a cubic Hermite path through both (position and velocity continuous, so the lines'
// right-hand side is too) and return their load on the body. This is MoorDyn's coupling
// lifecycle (create, init, step, read, close) with the state saved and restored whole, so
// that an estimator can branch a mooring (a particle filter, a hypothesis bank).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/integrator.h"
#include "core/types.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"

namespace moorsim::mooring_fem {

/// The body's six coupled degrees of freedom: its reference point's position north, east,
/// down [m] and its roll, pitch, yaw [rad] (the fairleads carried by Rz(yaw) Ry(pitch)
/// Rx(roll)); or their time derivatives [m/s, rad/s].
using BodyDofs = std::array<double, 6>;

class CoupledLines {
 public:
  /// The lines of `mooring`, integrated with `solver`'s settings. `waves` (null: none) are
  /// the water motion the lines see. Nothing is placed until Init().
  CoupledLines(const MooringParameters& mooring, const SolverSettings& solver,
               std::shared_ptr<const WaveKinematics> waves = nullptr);
  // The integrated system refers to the mooring it holds: not copied or moved.
  CoupledLines(const CoupledLines&) = delete;
  CoupledLines& operator=(const CoupledLines&) = delete;

  int num_lines() const { return mooring_.num_lines(); }
  /// Nodes of line `line` (0-based): its segments + 1, anchor first.
  int num_nodes(int line) const { return mooring_.line(line).segments + 1; }
  bool initialized() const { return initialized_; }
  double time() const { return t_; }

  /// Puts the body at `pose` moving with `velocity` at time `t0` and the lines at their
  /// static equilibrium for that pose; returns the lines' load on the body (LoadOnBody).
  /// May be called again to start over (intact lines). Throws moorsim::Error if the static
  /// solve fails, moorsim::InputError for values that are not finite or a pose that puts a
  /// fairlead where its line cannot hang (beyond its reach, below its anchor).
  Vec6 Init(const BodyDofs& pose, const BodyDofs& velocity, double t0 = 0.0);

  /// The shortest and the longest step [s]: shorter ones are lost in the integrator's
  /// arithmetic (so is one shorter than kMinStepShare of the time), longer ones are no
  /// coupling step (and would run for minutes unasked).
  static constexpr double kMinStep = 1e-9;
  static constexpr double kMinStepShare = 1e-12;
  static constexpr double kMaxStep = 86400.0;

  /// Integrates the lines over [time(), time() + dt] with the body's path ending at `pose`
  /// and `velocity`, and returns their load on the body there. Throws moorsim::SolverError
  /// (the time and the CVODE flag) if the integrator fails, and moorsim::Interrupted once
  /// `interrupt` (asked as the integrator evaluates the lines, empty: never) returns true;
  /// the state is then the one before the step. Throws moorsim::InputError for a dt outside
  /// [max(kMinStep, kMinStepShare x time()), kMaxStep] or values that are not finite,
  /// ContractError before Init().
  Vec6 Step(const BodyDofs& pose, const BodyDofs& velocity, double dt,
            const std::function<bool()>& interrupt = {});

  /// The lines' load on the body at the current state: force [N] and moment about the
  /// reference point [N m], both in Earth axes (north, east, down).
  Vec6 LoadOnBody();
  /// Each line's force on what holds its upper end (the body's fairlead or a free point),
  /// Earth frame [N]; zero for a line parted there.
  std::vector<Vec3> FairleadForces();
  /// Each line's tension at its anchor: its lowest segment's [N].
  std::vector<double> AnchorTensions();
  /// Line `line`'s segment tensions from the anchor up [N].
  std::vector<double> SegmentTensions(int line);
  /// Position of every node of line `line` (0-based), anchor first, Earth frame [m].
  std::vector<Vec3> NodePositions(int line);

  /// Parts line `failure.line` now (at its fairlead, an internal node, or its anchor) and
  /// restarts the integrator. Throws moorsim::InputError for a line or node that is not
  /// there or already detached.
  void Part(const LineFailure& failure);

  /// What the last Init() or Step() found doubtful but did anyway, one sentence each, taken
  /// (the list is empty after the call): a fairlead far above the water (the lines are
  /// modelled submerged all along), a body that moves faster than any moored body can
  /// (a pose in other units, a jump). Each kind is said once per instance.
  std::vector<std::string> TakeWarnings();
  /// Beyond these a step's motion is said to be doubtful: the reference point's mean speed
  /// over the step [m/s], and the mean rate of any angle [rad/s].
  static constexpr double kDoubtfulSpeed = 50.0;
  static constexpr double kDoubtfulTurnRate = 1.0;
  /// A fairlead this share of its line's length or more above the water is said to be.
  static constexpr double kDoubtfulHeightShare = 0.01;

  /// The whole state (time, the body's last pose and velocity, parted lines, every node and
  /// creep state) as bytes, tagged with the model's fingerprint and the program's version.
  /// Saving restarts the integrator from the saved state, as Restore() does, so that
  /// stepping on after a Save() and stepping after a Restore() of its bytes give the same
  /// trajectory bit for bit.
  std::vector<std::uint8_t> Save();
  /// The size Save() would return now [bytes].
  std::size_t SavedSize() const;
  /// Returns to a state from Save(). Throws moorsim::InputError naming what does not match
  /// for bytes that are not a moorsim lines state, are from another model or another
  /// version, or are cut short.
  void Restore(std::span<const std::uint8_t> bytes);

  /// A number that changes with anything in the model or the solver settings that the
  /// state depends on.
  std::uint64_t fingerprint() const { return fingerprint_; }
  const MooringSystem& mooring() const { return mooring_; }
  const std::vector<double>& state() const { return x_; }
  IntegratorStats stats() const;

 private:
  class HermitePath;
  void CheckInitialized(const char* call) const;
  void CheckLine(int line) const;  // InputError for a 0-based index that is not a line
  void StartIntegrator();
  std::span<const PointKinematics> FairleadsNow();

  MooringParameters spec_;
  SolverSettings solver_;
  std::shared_ptr<const WaveKinematics> waves_;
  MooringSystem mooring_;
  std::shared_ptr<HermitePath> path_;
  PrescribedMotionSystem system_;
  std::unique_ptr<Integrator> integrator_;
  IntegratorStats finished_;
  std::vector<double> x_;
  std::vector<LineFailure> failures_;  // applied, in order
  bool topology_changed_ = false;      // since the integrator was made: make a new one
  double t_ = 0.0;
  bool initialized_ = false;
  std::vector<std::string> warnings_;  // since the last TakeWarnings()
  bool warned_height_ = false, warned_motion_ = false;
  std::uint64_t fingerprint_ = 0;
};

}  // namespace moorsim::mooring_fem
