#include "mooring_fem/coupled_lines.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/format.h"
#include "core/sha256.h"
#include "core/state_bytes.h"

namespace moorsim::mooring_fem {

/// The body between two coupling instants t0 < t1: per degree of freedom the cubic with the
/// given values and rates at both ends (held at the start before t0, for the static start).
class CoupledLines::HermitePath final : public MotionPath {
 public:
  void Hold(double t, const BodyDofs& q, const BodyDofs& dq) {
    t0_ = t1_ = t;
    q0_ = q1_ = q;
    dq0_ = dq1_ = dq;
  }
  void Extend(double t1, const BodyDofs& q1, const BodyDofs& dq1) {
    t0_ = t1_;
    q0_ = q1_;
    dq0_ = dq1_;
    t1_ = t1;
    q1_ = q1;
    dq1_ = dq1;
  }
  const BodyDofs& pose() const { return q1_; }
  const BodyDofs& velocity() const { return dq1_; }

  void Evaluate(int dof, double t, double* value, double* rate,
                double* acceleration) const override {
    const double h = t1_ - t0_;
    if (!(h > 0.0)) {  // one instant: the body there, moving at its rate
      *value = q1_[dof];
      *rate = dq1_[dof];
      *acceleration = 0.0;
      return;
    }
    // In s = (t - t0) / h: p(s) = q0 H00 + h dq0 H10 + q1 H01 + h dq1 H11.
    const double s = (t - t0_) / h;
    const double q0 = q0_[dof], q1 = q1_[dof], m0 = h * dq0_[dof], m1 = h * dq1_[dof];
    const double s2 = s * s, s3 = s2 * s;
    *value = (2 * s3 - 3 * s2 + 1) * q0 + (s3 - 2 * s2 + s) * m0 + (-2 * s3 + 3 * s2) * q1 +
             (s3 - s2) * m1;
    *rate = ((6 * s2 - 6 * s) * q0 + (3 * s2 - 4 * s + 1) * m0 + (-6 * s2 + 6 * s) * q1 +
             (3 * s2 - 2 * s) * m1) /
            h;
    *acceleration =
        ((12 * s - 6) * q0 + (6 * s - 4) * m0 + (-12 * s + 6) * q1 + (6 * s - 2) * m1) / (h * h);
  }

 private:
  double t0_ = 0.0, t1_ = 0.0;
  BodyDofs q0_{}, dq0_{}, q1_{}, dq1_{};
};

namespace {

// SHA-256 of the numbers that define a model's state and its meaning.
std::uint64_t ModelFingerprint(const MooringSystem& m, const SolverSettings& solver) {
  StateWriter f;
  f.Put(std::int64_t{m.num_lines()});
  f.Put(std::int64_t{m.num_points()});
  f.Put(std::int64_t{m.StateSize()});
  for (int i = 0; i < m.num_lines(); ++i) {
    const LineProperties& l = m.line(i);
    for (std::int64_t v : {l.segments, l.lower_point, l.upper_point}) f.Put(v);
    f.Put(l.length);
    for (const Vec3& v : {l.anchor, l.fairlead_body}) f.PutNumbers({v.data(), 3});
    for (const SectionProperties& s : l.sections) {
      for (double v : {s.segment_length, s.diameter, s.mass_per_length, s.weight_per_length,
                       s.axial_stiffness, s.axial_damping, s.added_mass_per_length,
                       s.dynamic_stiffness, s.creep_stiffness, s.creep_damping, s.drag_normal,
                       s.drag_tangential, s.friction_axial, s.friction_lateral}) {
        f.Put(v);
      }
    }
    for (const PointBodyProperties& b : l.bodies) {
      for (double v : {b.mass, b.weight, b.added_mass, b.drag}) f.Put(v);
    }
  }
  for (double v : {solver.rtol, solver.atol_position, solver.atol_velocity, solver.max_step}) {
    f.Put(v);
  }
  f.Put(std::int64_t{solver.max_order});
  const std::vector<std::uint8_t> bytes = f.Take();
  return Sha256Prefix64({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

void CheckFinite(const BodyDofs& values, const char* what) {
  static const char* const kNames[] = {"north", "east", "down", "roll", "pitch", "yaw"};
  for (int d = 0; d < 6; ++d) {
    if (!std::isfinite(values[d])) {
      throw InputError(std::string(what) + " " + kNames[d] + " is not a finite number");
    }
  }
}

// A saved state's tag and format (core/state_bytes.h): a state is for this program on
// this machine, as a MoorDyn state file is.
constexpr char kTag[9] = "moorsimL";
constexpr std::int64_t kFormat = 1;

}  // namespace

CoupledLines::CoupledLines(const MooringParameters& mooring, const SolverSettings& solver,
                           std::shared_ptr<const WaveKinematics> waves)
    : spec_(mooring),
      solver_(solver),
      waves_(std::move(waves)),
      mooring_(spec_),
      path_(std::make_shared<HermitePath>()),
      system_(mooring_, PrescribedMotion{.mean = {}, .components = {}, .path = path_}),
      x_(mooring_.StateSize(), 0.0),
      fingerprint_(ModelFingerprint(mooring_, solver_)) {
  mooring_.SetWaves(waves_);
}

void CoupledLines::CheckLine(int line) const {
  if (line < 0 || line >= num_lines()) {
    throw InputError("no line " + std::to_string(line + 1) + " (the mooring has " +
                     std::to_string(num_lines()) + ")");
  }
}

void CoupledLines::CheckInitialized(const char* call) const {
  if (!initialized_) throw ContractError(std::string(call) + " before the lines are initialised");
}

std::span<const PointKinematics> CoupledLines::FairleadsNow() { return system_.Fairleads(t_); }

Vec6 CoupledLines::Init(const BodyDofs& pose, const BodyDofs& velocity, double t0) {
  CheckFinite(pose, "pose");
  CheckFinite(velocity, "velocity");
  if (!std::isfinite(t0)) throw InputError("start time is not a finite number");
  if (!failures_.empty()) {  // start over intact
    mooring_ = MooringSystem(spec_);
    mooring_.SetWaves(waves_);
    failures_.clear();
    topology_changed_ = true;
  }
  initialized_ = false;
  path_->Hold(t0, pose, velocity);
  t_ = t0;
  x_.assign(mooring_.StateSize(), 0.0);
  std::vector<Vec3> fairleads;
  for (const PointKinematics& f : FairleadsNow()) fairleads.push_back(f.position);
  try {
    mooring_.CatenaryState(fairleads, x_.data());
  } catch (const InputError&) {
    throw;
  } catch (const Error& e) {  // a line that cannot hang between its anchor and the fairlead
    throw InputError("the body at x, y, z = " + FormatNumber(pose[0]) + ", " +
                     FormatNumber(pose[1]) + ", " + FormatNumber(pose[2]) +
                     " m puts a fairlead where its line cannot hang: " + e.what());
  }
  mooring_.SettleStatic(fairleads, x_.data());
  StartIntegrator();
  initialized_ = true;
  for (int i = 0; i < num_lines() && !warned_height_; ++i) {
    const double above = -fairleads[i].z(), length = spec_.lines[i].Length();
    if (mooring_.at_vessel(i) && above > kDoubtfulHeightShare * length) {
      warned_height_ = true;
      warnings_.push_back("line " + std::to_string(i + 1) + "'s fairlead is " +
                          FormatNumber(std::round(above * 10.0) / 10.0) +
                          " m above the water at this pose: the lines are modelled submerged "
                          "all along (their weight in water, drag and added mass), so the part "
                          "hanging in air is not what it would be");
    }
  }
  return LoadOnBody();
}

void CoupledLines::StartIntegrator() {
  if (integrator_) finished_ += integrator_->stats();
  if (integrator_ && !topology_changed_) {
    integrator_->Restart(t_, x_.data(), ToleranceReference(mooring_, x_));
    return;
  }
  integrator_ = StartLineIntegrator(system_, solver_, mooring_, t_, x_);
  topology_changed_ = false;
}

Vec6 CoupledLines::Step(const BodyDofs& pose, const BodyDofs& velocity, double dt,
                        const std::function<bool()>& interrupt) {
  CheckInitialized("a step");
  CheckFinite(pose, "pose");
  CheckFinite(velocity, "velocity");
  // Shorter than a millionth of a millionth of the time, a step is lost in its rounding.
  const double shortest = std::max(kMinStep, kMinStepShare * std::abs(t_));
  if (!(dt >= shortest && dt <= kMaxStep)) {
    throw InputError("time step " + FormatNumber(dt) + " s must be a number from " +
                     FormatNumber(shortest) + " to " + FormatNumber(kMaxStep) + " s" +
                     (shortest > kMinStep ? " at t = " + FormatNumber(t_) + " s" : "") +
                     " (step again to go further)");
  }
  const double t1 = t_ + dt;
  const BodyDofs q0 = path_->pose(), dq0 = path_->velocity();
  const double moved = std::hypot(pose[0] - q0[0], pose[1] - q0[1], pose[2] - q0[2]);
  double turned = 0.0;
  for (int d = 3; d < 6; ++d) turned = std::max(turned, std::abs(pose[d] - q0[d]));
  if (!warned_motion_ && (moved > kDoubtfulSpeed * dt || turned > kDoubtfulTurnRate * dt)) {
    warned_motion_ = true;
    warnings_.push_back("the body moves " + FormatNumber(moved) + " m and turns " +
                        FormatNumber(turned) + " rad in a step of " + FormatNumber(dt) +
                        " s at t = " + FormatNumber(t_) +
                        " s, faster than a moored body can (a pose in other units, or a jump?); "
                        "the lines follow it as given");
  }
  path_->Extend(t1, pose, velocity);
  try {
    integrator_->SetStopTime(t1);
    integrator_->SetInterruptCheck(interrupt);
    integrator_->AdvanceTo(t1);
    integrator_->SetInterruptCheck({});
  } catch (const Error&) {
    // Back to the state before the step, with an integrator that can go on from it.
    integrator_->SetInterruptCheck({});
    path_->Hold(t_, q0, dq0);
    StartIntegrator();
    throw;
  }
  t_ = t1;
  std::copy(integrator_->state(), integrator_->state() + x_.size(), x_.begin());
  return LoadOnBody();
}

std::vector<std::string> CoupledLines::TakeWarnings() { return std::exchange(warnings_, {}); }

Vec6 CoupledLines::LoadOnBody() {
  CheckInitialized("the load on the body");
  const auto fairleads = FairleadsNow();
  std::vector<Vec3> forces(mooring_.num_lines());
  mooring_.FairleadForces(x_.data(), fairleads, forces);
  const BodyDofs& q = path_->pose();
  const Vec3 reference(q[0], q[1], q[2]);
  Vec6 load = Vec6::Zero();
  for (int i = 0; i < mooring_.num_lines(); ++i) {
    if (!mooring_.at_vessel(i)) continue;
    load.head<3>() += forces[i];
    load.tail<3>() += (fairleads[i].position - reference).cross(forces[i]);
  }
  return load;
}

std::vector<Vec3> CoupledLines::FairleadForces() {
  CheckInitialized("the fairlead forces");
  std::vector<Vec3> forces(mooring_.num_lines());
  const auto fairleads = FairleadsNow();
  mooring_.FairleadForces(x_.data(), fairleads, forces);
  mooring_.PointEndForces(x_.data(), fairleads, forces);
  return forces;
}

std::vector<double> CoupledLines::SegmentTensions(int line) {
  CheckInitialized("the segment tensions");
  CheckLine(line);
  return mooring_.SegmentTensions(x_.data(), line, FairleadsNow());
}

std::vector<double> CoupledLines::AnchorTensions() {
  std::vector<double> tensions(num_lines());
  for (int i = 0; i < num_lines(); ++i) tensions[i] = SegmentTensions(i).front();
  return tensions;
}

std::vector<Vec3> CoupledLines::NodePositions(int line) {
  CheckInitialized("the node positions");
  CheckLine(line);
  const auto fairleads = FairleadsNow();
  std::vector<Vec3> nodes(num_nodes(line));
  for (int k = 0; k < num_nodes(line); ++k) {
    nodes[k] = mooring_.NodePosition(x_.data(), line, k, fairleads);
  }
  return nodes;
}

void CoupledLines::Part(const LineFailure& failure) {
  CheckInitialized("parting a line");
  x_ = mooring_.ApplyFailure(failure, x_.data(), FairleadsNow());
  failures_.push_back(failure);
  topology_changed_ = true;
  StartIntegrator();
}

std::vector<std::uint8_t> CoupledLines::Save() {
  CheckInitialized("saving the state");
  StateWriter w;
  w.PutHeader(kTag, kFormat, fingerprint_);
  w.Put(t_);
  for (double v : path_->pose()) w.Put(v);
  for (double v : path_->velocity()) w.Put(v);
  w.Put(static_cast<std::int64_t>(failures_.size()));
  for (const LineFailure& f : failures_) {
    w.Put(static_cast<std::int64_t>(f.line));
    w.Put(static_cast<std::int64_t>(f.mode));
    w.Put(static_cast<std::int64_t>(f.node));
  }
  w.PutNumbers(x_);
  // The continuation from here is the one a Restore() of these bytes starts.
  path_->Hold(t_, path_->pose(), path_->velocity());
  StartIntegrator();
  return w.Take();
}

std::size_t CoupledLines::SavedSize() const {
  const std::size_t numbers = 1 + 12 + 1 + 3 * failures_.size() + 1 + x_.size();
  return StateWriter::HeaderSize() + 8 * numbers;
}

void CoupledLines::Restore(std::span<const std::uint8_t> bytes) {
  StateReader r(bytes, "lines state");
  r.SetFingerprintMeaning("its lines or solver settings differ");
  r.CheckHeader(kTag, kFormat, fingerprint_);
  const double t = r.Get<double>("time");
  BodyDofs q{}, dq{};
  for (double& v : q) v = r.Get<double>("pose");
  for (double& v : dq) v = r.Get<double>("velocity");
  std::vector<LineFailure> failures(r.GetCount(24, "failures"));
  for (LineFailure& f : failures) {
    f.line = static_cast<int>(r.Get<std::int64_t>("failure"));
    const auto mode = r.Get<std::int64_t>("failure");
    f.node = static_cast<int>(r.Get<std::int64_t>("failure"));
    if (mode < 0 || mode > static_cast<std::int64_t>(FailureMode::kAnchor)) {
      r.Damaged("failure mode");
    }
    f.mode = static_cast<FailureMode>(mode);
  }
  std::vector<double> x(r.GetCount(8, "state size"));
  if (r.remaining() != 8 * x.size()) r.Damaged("state size");
  for (double& v : x) v = r.Get<double>("state");
  // Whole arrays at once (Eigen vectorises the test): the restore stays in microseconds.
  const auto finite = [](std::span<const double> values) {
    return Eigen::Map<const Eigen::ArrayXd>(values.data(), static_cast<Eigen::Index>(values.size()))
        .allFinite();
  };
  if (!std::isfinite(t) || !finite(q) || !finite(dq) || !finite(x)) r.Damaged("numbers");

  const auto same = [](const LineFailure& a, const LineFailure& b) {
    return a.line == b.line && a.mode == b.mode &&
           (a.mode != FailureMode::kNode || a.node == b.node);
  };
  if (!std::equal(failures.begin(), failures.end(), failures_.begin(), failures_.end(), same)) {
    // The topology of the saved failures, on a copy: a state that does not fit leaves this
    // instance as it was.
    MooringSystem mooring(spec_);
    mooring.SetWaves(waves_);
    for (const LineFailure& f : failures) {
      std::vector<double> zero(mooring.StateSize(), 0.0);
      std::vector<PointKinematics> fairleads(mooring.num_lines());
      mooring.ApplyFailure(f, zero.data(), fairleads);
    }
    if (mooring.StateSize() != static_cast<int>(x.size())) r.Damaged("state size");
    mooring_ = std::move(mooring);
    failures_ = std::move(failures);
    topology_changed_ = true;
  } else if (mooring_.StateSize() != static_cast<int>(x.size())) {
    r.Damaged("state size");
  }
  x_ = std::move(x);
  t_ = t;
  path_->Hold(t, q, dq);
  initialized_ = true;
  StartIntegrator();
}

IntegratorStats CoupledLines::stats() const {
  IntegratorStats s = finished_;
  if (integrator_) s += integrator_->stats();
  return s;
}

}  // namespace moorsim::mooring_fem
