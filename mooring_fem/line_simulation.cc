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

namespace {

// The elementary rotation about axis `axis` (0 x, 1 y, 2 z) by `angle` and its first and
// second derivatives with respect to the angle.
std::array<Mat3, 3> Rotation(int axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  std::array<Mat3, 3> r;
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  r[0] = Mat3::Zero();
  r[0](axis, axis) = 1.0;
  r[0](i, i) = c;
  r[0](i, j) = -s;
  r[0](j, i) = s;
  r[0](j, j) = c;
  r[1] = Mat3::Zero();
  r[1](i, i) = -s;
  r[1](i, j) = -c;
  r[1](j, i) = c;
  r[1](j, j) = -s;
  r[2] = Mat3::Zero();
  r[2](i, i) = -c;
  r[2](i, j) = s;
  r[2](j, i) = -s;
  r[2](j, j) = -c;
  return r;
}

}  // namespace

MotionSpline::MotionSpline(MotionSeries series) : series_(std::move(series)) {
  const std::vector<double>& t = series_.time;
  const std::size_t n = t.size();
  if (n < 2) throw InputError("motion series: at least two samples are needed");
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(t[k]) || (k > 0 && !(t[k] > t[k - 1]))) {
      throw InputError("motion series: sample " + std::to_string(k + 1) +
                       ": times must be finite and increase");
    }
  }
  for (int d = 0; d < 6; ++d) {
    const std::vector<double>& y = series_.values[d];
    if (y.size() != n) throw InputError("motion series: a channel of another length");
    for (const double v : y) {
      if (!std::isfinite(v)) throw InputError("motion series: a value that is not finite");
    }
    // Natural spline: M_0 = M_{n-1} = 0, and for the interior the tridiagonal system
    // h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k + h_k M_{k+1} = 6 (slope_k - slope_{k-1}),
    // solved by the Thomas algorithm (diagonally dominant).
    std::vector<double>& m = second_[d];
    m.assign(n, 0.0);
    if (n < 3) continue;
    std::vector<double> diag(n, 0.0), rhs(n, 0.0);
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const double h0 = t[k] - t[k - 1], h1 = t[k + 1] - t[k];
      diag[k] = 2.0 * (h0 + h1);
      rhs[k] = 6.0 * ((y[k + 1] - y[k]) / h1 - (y[k] - y[k - 1]) / h0);
    }
    for (std::size_t k = 2; k + 1 < n; ++k) {
      const double h = t[k] - t[k - 1];
      const double w = h / diag[k - 1];
      diag[k] -= w * h;
      rhs[k] -= w * rhs[k - 1];
    }
    for (std::size_t k = n - 2; k >= 1; --k) {
      const double h1 = t[k + 1] - t[k];
      m[k] = (rhs[k] - h1 * m[k + 1]) / diag[k];
    }
  }
}

void MotionSpline::Evaluate(int dof, double t, double* value, double* rate,
                            double* acceleration) const {
  const std::vector<double>& ts = series_.time;
  const std::vector<double>& y = series_.values[dof];
  const std::vector<double>& m = second_[dof];
  if (t < ts.front() || t > ts.back()) {  // held at the end value
    *value = t < ts.front() ? y.front() : y.back();
    *rate = *acceleration = 0.0;
    return;
  }
  // The interval [t_k, t_k+1] that holds t (the last one for t at the last sample).
  const std::size_t k =
      std::min(static_cast<std::size_t>(std::upper_bound(ts.begin(), ts.end(), t) - ts.begin()) - 1,
               ts.size() - 2);
  const double h = ts[k + 1] - ts[k];
  const double a = (ts[k + 1] - t) / h, b = (t - ts[k]) / h;
  *value =
      a * y[k] + b * y[k + 1] + ((a * a * a - a) * m[k] + (b * b * b - b) * m[k + 1]) * h * h / 6.0;
  *rate = (y[k + 1] - y[k]) / h - (3.0 * a * a - 1.0) / 6.0 * h * m[k] +
          (3.0 * b * b - 1.0) / 6.0 * h * m[k + 1];
  *acceleration = a * m[k] + b * m[k + 1];
}

PrescribedMotion::State PrescribedMotion::At(double t) const {
  double q[6], dq[6], ddq[6];
  for (int d = 0; d < 6; ++d) {
    q[d] = dq[d] = ddq[d] = 0.0;
    if (path) {
      path->Evaluate(d, t, &q[d], &dq[d], &ddq[d]);
      continue;
    }
    for (const Component& c : components[d]) {
      const double w = 2.0 * std::numbers::pi / c.period;
      q[d] += c.amplitude * std::sin(w * t);
      dq[d] += c.amplitude * w * std::cos(w * t);
      ddq[d] -= c.amplitude * w * w * std::sin(w * t);
    }
  }
  State state;
  state.mean = mean;
  state.offset = {Vec3(q[kSurge], q[kSway], q[kHeave]), Vec3(dq[kSurge], dq[kSway], dq[kHeave]),
                  Vec3(ddq[kSurge], ddq[kSway], ddq[kHeave])};
  state.rotates = q[kRoll] != 0.0 || q[kPitch] != 0.0 || q[kYaw] != 0.0 || dq[kRoll] != 0.0 ||
                  dq[kPitch] != 0.0 || dq[kYaw] != 0.0 || ddq[kRoll] != 0.0 || ddq[kPitch] != 0.0 ||
                  ddq[kYaw] != 0.0;
  if (!state.rotates) return state;
  // R = Z Y X; its time derivatives through the angles' (chain rule on each factor).
  const std::array<Mat3, 3> X = Rotation(0, q[kRoll]);
  const std::array<Mat3, 3> Y = Rotation(1, q[kPitch]);
  const std::array<Mat3, 3> Z = Rotation(2, mean.psi + q[kYaw]);
  const double wx = dq[kRoll], wy = dq[kPitch], wz = dq[kYaw];
  state.R = Z[0] * Y[0] * X[0];
  state.dR = Z[1] * Y[0] * X[0] * wz + Z[0] * Y[1] * X[0] * wy + Z[0] * Y[0] * X[1] * wx;
  state.ddR = Z[2] * Y[0] * X[0] * (wz * wz) + Z[0] * Y[2] * X[0] * (wy * wy) +
              Z[0] * Y[0] * X[2] * (wx * wx) +
              2.0 * (Z[1] * Y[1] * X[0] * (wz * wy) + Z[1] * Y[0] * X[1] * (wz * wx) +
                     Z[0] * Y[1] * X[1] * (wy * wx)) +
              Z[1] * Y[0] * X[0] * ddq[kYaw] + Z[0] * Y[1] * X[0] * ddq[kPitch] +
              Z[0] * Y[0] * X[1] * ddq[kRoll];
  return state;
}

PointKinematics PrescribedMotion::State::Point(const Vec3& body) const {
  if (!rotates) {  // a translation: the fairleads move with the reference point
    return {FairleadPosition(mean, body) + offset.position, offset.velocity, offset.acceleration};
  }
  return {Vec3(mean.x, mean.y, 0.0) + offset.position + R * body, offset.velocity + dR * body,
          offset.acceleration + ddR * body};
}

PointKinematics PrescribedMotion::FairleadAt(double t, const Vec3& fairlead_body) const {
  return At(t).Point(fairlead_body);
}

PrescribedMotionSystem::PrescribedMotionSystem(MooringSystem& mooring, PrescribedMotion motion)
    : mooring_(mooring), motion_(std::move(motion)), fairleads_(mooring.num_lines()) {}

std::span<const PointKinematics> PrescribedMotionSystem::Fairleads(double t) {
  mooring_.SetTime(t);                                  // the waves, if the lines see any
  const PrescribedMotion::State state = motion_.At(t);  // once for every fairlead
  for (int i = 0; i < mooring_.num_lines(); ++i) {
    fairleads_[i] = state.Point(mooring_.line(i).fairlead_body);
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
  o.linear_solver = solver.linear_solver;
  for (char kind : mooring.StateKinds()) {
    // Positions and creep stretches [m] in metres, velocities in m/s.
    o.atol.push_back(kind == 'v' ? solver.atol_velocity : solver.atol_position);
  }
  return o;
}

LineSimulation::LineSimulation(const MooringParameters& mooring, const SolverSettings& solver,
                               PrescribedMotion motion)
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
  integrator_ = StartLineIntegrator(system_, solver_, mooring_, t_, x_);
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
  const auto fairleads = system_.Fairleads(t_);
  mooring_.FairleadForces(x_.data(), fairleads, forces);
  mooring_.PointEndForces(x_.data(), fairleads, forces);
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

std::unique_ptr<Integrator> StartLineIntegrator(OdeSystem& system, const SolverSettings& solver,
                                                const MooringSystem& mooring, double t,
                                                const std::vector<double>& x) {
  IntegratorOptions options = MakeIntegratorOptions(solver, mooring);
  options.reference = ToleranceReference(mooring, x);
  return std::make_unique<Integrator>(system, t, x.data(), options);
}

std::vector<double> ToleranceReference(const MooringSystem& mooring, const std::vector<double>& x) {
  // Tolerances relative to each node's displacement from where the integrator starts.
  const std::vector<char> kinds = mooring.StateKinds();
  std::vector<double> reference(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) reference[i] = kinds[i] == 'p' ? x[i] : 0.0;
  return reference;
}

}  // namespace moorsim::mooring_fem
