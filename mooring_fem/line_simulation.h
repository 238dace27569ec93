// Time-domain simulation of the mooring lines alone, with the turret (and so every
// fairlead) following a prescribed rigid-body motion. This is the verification and
// benchmark harness of the FEM; the coupled vessel simulation wires the same
// MooringSystem to the 6-DOF plant instead of to a prescribed motion.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "core/integrator.h"
#include "core/ode_system.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"

namespace moorsim::mooring_fem {

/// Horizontal pose of the vessel's reference point: x, y [m] (NED) and heading psi [rad].
struct PlanarPose {
  double x = 0.0;
  double y = 0.0;
  double psi = 0.0;
};

/// Earth-frame fairlead position for a body-frame fairlead at a planar pose.
Vec3 FairleadPosition(const PlanarPose& pose, const Vec3& fairlead_body);

/// Samples of a rigid-body motion (for a MotionSpline): times [s], strictly
/// increasing, at least two, and per degree of freedom one value per time (surge, sway,
/// heave [m], roll, pitch, yaw [rad]).
struct MotionSeries {
  std::vector<double> time;
  std::array<std::vector<double>, 6> values;
};

/// A rigid-body path given by its six degrees of freedom (PrescribedMotion::Dof) as functions
/// of time: a spline through samples (MotionSpline), or the piece between two coupling
/// instants of a body integrated by someone else (CoupledLines).
class MotionPath {
 public:
  virtual ~MotionPath() = default;
  /// Value, first and second time derivative of degree of freedom `dof` at time t.
  virtual void Evaluate(int dof, double t, double* value, double* rate,
                        double* acceleration) const = 0;
};

/// The vessel's prescribed rigid-body motion about a mean planar pose: its reference point
/// offset by (surge, sway, heave) in the Earth frame [m], and the hull turned by roll,
/// pitch and yaw [rad] (the body-frame fairleads carried by Rz(psi + yaw) Ry(pitch)
/// Rx(roll), Euler angles as the vessel's). Each degree of freedom is a sum of harmonics
/// A_i sin(2 pi t / T_i), or all six come from a path (a series of samples, interpolated
/// by a natural cubic spline with continuous velocity and acceleration and held at the end
/// values outside it; or a coupling's path).
struct PrescribedMotion {
  enum Dof { kSurge, kSway, kHeave, kRoll, kPitch, kYaw };
  struct Component {
    double amplitude = 0.0;  ///< [m] or [rad]
    double period = 0.0;     ///< [s]
  };
  PlanarPose mean;
  std::array<std::vector<Component>, 6> components;
  /// When set, replaces the components.
  std::shared_ptr<const MotionPath> path;

  /// The rigid-body motion at one time: the reference point's offset from the mean pose
  /// and, if the hull turns, its rotation and the rotation's first two time derivatives.
  struct State {
    PlanarPose mean;
    PointKinematics offset;
    bool rotates = false;
    Mat3 R = Mat3::Identity(), dR = Mat3::Zero(), ddR = Mat3::Zero();
    /// The point at `body` (body frame): its position, velocity and acceleration.
    PointKinematics Point(const Vec3& body) const;
  };
  State At(double t) const;
  /// At(t).Point(fairlead_body).
  PointKinematics FairleadAt(double t, const Vec3& fairlead_body) const;
};

/// The natural cubic spline of each degree of freedom of a MotionSeries. Throws
/// moorsim::InputError for fewer than two samples, times that do not increase, values
/// that are not finite or channels of another length.
class MotionSpline final : public MotionPath {
 public:
  explicit MotionSpline(MotionSeries series);
  void Evaluate(int dof, double t, double* value, double* rate,
                double* acceleration) const override;
  double start() const { return series_.time.front(); }
  double end() const { return series_.time.back(); }

 private:
  MotionSeries series_;
  std::array<std::vector<double>, 6> second_;  // second derivatives at the samples
};

/// The lines as an OdeSystem driven by a PrescribedMotion.
class PrescribedMotionSystem : public OdeSystem {
 public:
  PrescribedMotionSystem(MooringSystem& mooring, PrescribedMotion motion);

  int StateSize() const override { return mooring_.StateSize(); }
  void Derivatives(double t, const double* x, double* xdot) override;
  const SparsityPattern& JacobianPattern() const override { return mooring_.JacobianPattern(); }
  const BlockStructure* Blocks() const override {
    return mooring_.has_blocks() ? &mooring_.Blocks() : nullptr;
  }
  void Jacobian(double t, const double* x, const double* xdot, double* values) override;

  /// Fairlead kinematics of every line at time t.
  std::span<const PointKinematics> Fairleads(double t);

 private:
  MooringSystem& mooring_;
  PrescribedMotion motion_;
  std::vector<PointKinematics> fairleads_;
};

/// Multiplies rtol and every atol by `factor` (reference runs use 0.01).
void ScaleTolerances(SolverSettings& solver, double factor);

/// Builds the integrator options (per-component absolute tolerances) from the settings.
IntegratorOptions MakeIntegratorOptions(const SolverSettings& solver, const MooringSystem& mooring);

/// CVODE on `system` (the lines of `mooring`) from (t, x), with rtol relative to each node's
/// displacement from x.
std::unique_ptr<Integrator> StartLineIntegrator(OdeSystem& system, const SolverSettings& solver,
                                                const MooringSystem& mooring, double t,
                                                const std::vector<double>& x);

/// The tolerance reference of an integrator of the lines starting at x: the node
/// positions (rtol applies to their displacement from there), zero elsewhere.
std::vector<double> ToleranceReference(const MooringSystem& mooring, const std::vector<double>& x);

/// Drives a PrescribedMotionSystem with CVODE from the FEM's static equilibrium at the
/// motion's mean pose (analytic catenary, then Newton on the FEM), with scheduled failures.
class LineSimulation {
 public:
  LineSimulation(const MooringParameters& mooring, const SolverSettings& solver,
                 PrescribedMotion motion);

  /// A failure at time t [s]; the integrator stops exactly there, changes the topology and
  /// restarts with the state carried over.
  void ScheduleFailure(double t, const LineFailure& failure);
  void AdvanceTo(double t);

  double time() const { return t_; }
  const std::vector<double>& state() const { return x_; }
  MooringSystem& mooring() { return mooring_; }
  std::span<const PointKinematics> Fairleads() { return system_.Fairleads(t_); }
  /// Each line's force on what holds its upper end: the fairlead, or a free point.
  std::vector<Vec3> FairleadForces();
  double MechanicalEnergy();
  /// Largest residual node force of the static start [N].
  double static_residual() const { return static_residual_; }
  IntegratorStats stats() const;
  const Integrator& integrator() const { return *integrator_; }

 private:
  void StartIntegrator();

  SolverSettings solver_;
  MooringSystem mooring_;
  PrescribedMotionSystem system_;
  std::vector<double> x_;
  double t_ = 0.0;
  double static_residual_ = 0.0;
  std::unique_ptr<Integrator> integrator_;
  IntegratorStats finished_;  // counters of integrators replaced after a topology change
  struct Event {
    double time;
    LineFailure failure;
  };
  std::vector<Event> events_;  // sorted by time
};

}  // namespace moorsim::mooring_fem
