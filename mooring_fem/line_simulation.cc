#include "mooring_fem/line_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.h"
#include "core/sample_clock.h"

namespace moorsim::mooring_fem {

Vec3 FairleadPosition(const PlanarPose& pose, const Vec3& fairlead_body) {
  const double c = std::cos(pose.psi);
  const double s = std::sin(pose.psi);
  return Vec3(pose.x + c * fairlead_body.x() - s * fairlead_body.y(),
              pose.y + s * fairlead_body.x() + c * fairlead_body.y(), fairlead_body.z());
}

PointKinematics HarmonicMotion::At(double t) const {
  double p = 0.0, v = 0.0, a = 0.0;
  for (const Component& c : components) {
    const double w = 2.0 * std::numbers::pi / c.period;
    p += c.amplitude * std::sin(w * t);
    v += c.amplitude * w * std::cos(w * t);
    a -= c.amplitude * w * w * std::sin(w * t);
  }
  return {p * direction, v * direction, a * direction};
}

PrescribedMotionSystem::PrescribedMotionSystem(MooringSystem& mooring, HarmonicMotion motion)
    : mooring_(mooring), motion_(std::move(motion)), fairleads_(mooring.num_lines()) {}

std::span<const PointKinematics> PrescribedMotionSystem::Fairleads(double t) {
  const PointKinematics offset = motion_.At(t);
  for (int i = 0; i < mooring_.num_lines(); ++i) {
    fairleads_[i].position =
        FairleadPosition(motion_.mean, mooring_.line(i).fairlead_body) + offset.position;
    fairleads_[i].velocity = offset.velocity;
    fairleads_[i].acceleration = offset.acceleration;
  }
  return fairleads_;
}

void PrescribedMotionSystem::Derivatives(double t, const double* x, double* xdot) {
  mooring_.Derivatives(x, Fairleads(t), xdot);
}

void PrescribedMotionSystem::Jacobian(double t, const double* x, const double*, double* values) {
  mooring_.Jacobian(x, Fairleads(t), values);
}

void ScaleTolerances(SolverSettings& solver, double factor) {
  solver.rtol *= factor;
  solver.atol_position *= factor;
  solver.atol_velocity *= factor;
}

IntegratorOptions MakeIntegratorOptions(const SolverSettings& solver,
                                        const MooringSystem& mooring) {
  IntegratorOptions o;
  o.rtol = solver.rtol;
  o.max_order = solver.max_order;
  o.stability_limit_detection = solver.stability_limit_detection;
  o.max_step = solver.max_step;
  o.max_steps_per_call = solver.max_steps;
  o.linear_solver = solver.linear_solver == "klu" ? IntegratorOptions::LinearSolver::kKlu
                                                  : IntegratorOptions::LinearSolver::kBlock;
  for (char kind : mooring.StateKinds()) {
    o.atol.push_back(kind == 'p' ? solver.atol_position : solver.atol_velocity);
  }
  return o;
}

LineSimulation::LineSimulation(const MooringParameters& mooring, const SolverSettings& solver,
                               HarmonicMotion motion)
    : solver_(solver),
      mooring_(mooring),
      system_(mooring_, std::move(motion)),
      x_(mooring_.StateSize()) {
  std::vector<Vec3> fairleads;
  for (const PointKinematics& f : system_.Fairleads(0.0)) fairleads.push_back(f.position);
  mooring_.CatenaryState(fairleads, x_.data());
  static_residual_ = mooring_.SettleStatic(fairleads, x_.data());
  StartIntegrator();
}

void LineSimulation::StartIntegrator() {
  if (integrator_) finished_ += integrator_->stats();
  IntegratorOptions options = MakeIntegratorOptions(solver_, mooring_);
  // Tolerances relative to each node's displacement from where this integrator starts.
  const std::vector<char> kinds = mooring_.StateKinds();
  options.reference.resize(x_.size());
  for (std::size_t i = 0; i < x_.size(); ++i) options.reference[i] = kinds[i] == 'p' ? x_[i] : 0.0;
  integrator_ = std::make_unique<Integrator>(system_, t_, x_.data(), options);
  if (!events_.empty()) integrator_->SetStopTime(events_.front().time);
}

void LineSimulation::ScheduleFailure(double t, const LineFailure& failure) {
  if (t < t_) throw InputError("failure time " + std::to_string(t) + " s is in the past");
  events_.push_back({t, failure});
  std::stable_sort(events_.begin(), events_.end(),
                   [](const Event& a, const Event& b) { return a.time < b.time; });
  integrator_->SetStopTime(events_.front().time);
}

void LineSimulation::AdvanceTo(double t) {
  AdvanceThroughEvents(
      t, [this]() -> Integrator& { return *integrator_; },
      [this](double) {
        return events_.empty() ? std::numeric_limits<double>::infinity() : events_.front().time;
      },
      [this](double now) {
        if (now > t_) {
          t_ = now;
          std::copy(integrator_->state(), integrator_->state() + x_.size(), x_.begin());
        }
        while (!events_.empty() && events_.front().time <= t_) {
          const LineFailure failure = events_.front().failure;
          events_.erase(events_.begin());
          x_ = mooring_.ApplyFailure(failure, x_.data(), system_.Fairleads(t_));
          StartIntegrator();
        }
      });
}

std::vector<Vec3> LineSimulation::FairleadForces() {
  std::vector<Vec3> forces(mooring_.num_lines());
  mooring_.FairleadForces(x_.data(), system_.Fairleads(t_), forces);
  return forces;
}

double LineSimulation::MechanicalEnergy() {
  return mooring_.MechanicalEnergy(x_.data(), system_.Fairleads(t_));
}

IntegratorStats LineSimulation::stats() const {
  IntegratorStats s = finished_;
  if (integrator_) s += integrator_->stats();
  return s;
}

}  // namespace moorsim::mooring_fem
