#include "mooring_fem/mooring_system.h"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "core/angles.h"
#include "core/error.h"
#include "mooring_fem/catenary.h"
#include "mooring_fem/composite_catenary.h"
#include "mooring_fem/point_network.h"

namespace moorsim::mooring_fem {

namespace {

const Vec3 kDown(0.0, 0.0, 1.0);  // NED: gravity along +z

// Index in NodeJacobian arrays: neighbour below, the node itself, neighbour above.
constexpr int kBelow = 0;
constexpr int kSelf = 1;
constexpr int kAbove = 2;

// Static equilibrium (SettleStatic): Newton's method on the node force balance F(x) = 0.
// Without current F is minus the gradient of a convex potential (tension-only springs,
// weight, seabed penalty), so K = dF/dx is negative semi-definite, but singular where a
// node has no taut segment and no seabed contact: nodes placed on the continuum catenary
// near touchdown, where a segment's chord is shorter than the arc it spans, hang slack. A
// shift (K - mu I) then makes the step solvable (Levenberg-Marquardt), and the line search
// follows the potential, not the residual norm, which a slack node falling does not change.
constexpr int kMaxStaticIterations = 500;
constexpr int kMaxLineSearchSteps = 60;
constexpr double kMaxLineSearchExtrapolation = 1e9;

// The static solves' line search for phi(lambda) = 0 (Crisfield), phi being the force
// along the step, minus the potential energy's slope there: a step is accepted once |phi|
// has fallen to half of phi0 (or the residual below the tolerance); it extrapolates while
// phi stays positive (a node or a buoy moving slack through the water feels the same force
// all the way) and bisects once phi turns negative. `move_to(lambda)` moves the state,
// leaves its force in `force` and returns its norm (infinite where the state is
// inadmissible). Returns the accepted lambda (0: no progress), and the last lambda moved to.
struct StepSearch {
  double accepted = 0.0;
  double evaluated_at = 0.0;
  double norm = 0.0;  // at evaluated_at
};
template <class MoveTo>
StepSearch SearchAlongStep(MoveTo&& move_to, const Eigen::VectorXd& force,
                           const Eigen::VectorXd& step, double tolerance, double norm) {
  const double phi0 = force.dot(step);
  StepSearch out;
  out.norm = norm;
  double below = 0.0;  // largest lambda known to have phi > 0
  double above = std::numeric_limits<double>::infinity();
  double lambda = 1.0;
  for (int k = 0; k < kMaxLineSearchSteps; ++k) {
    const double trial = move_to(lambda);
    out.norm = trial;
    out.evaluated_at = lambda;
    const double phi =
        std::isfinite(trial) ? force.dot(step) : -std::numeric_limits<double>::infinity();
    if (trial <= tolerance || std::abs(phi) <= 0.5 * phi0) {
      out.accepted = lambda;
      return out;
    }
    if (phi > 0.0) {
      below = lambda;
      lambda = std::isinf(above) ? 2.0 * lambda : 0.5 * (below + above);
      if (lambda > kMaxLineSearchExtrapolation) break;
    } else {
      above = lambda;
      lambda = 0.5 * (below + above);
    }
  }
  out.accepted = below;  // the energy fell all the way to `below`
  return out;
}

// Morison drag of half a segment (stretched length L) on relative velocity u, and its
// derivatives w.r.t. u and the segment vector l. Normal part -c_n (L/2)|u_n| u_n,
// tangential part -c_t (L/2) |s| s t with s = u . t (Ren & Skjetne 2016, eq. 7, drag on the
// stretched length).
struct HalfSegmentDrag {
  Vec3 force;
  Mat3 d_du;
  Mat3 d_dl;
};

// The force alone, for the right-hand side (inlined: it runs twice per node per evaluation).
inline Vec3 DragForce(const Vec3& u, const Vec3& t, double L, double c_n, double c_t) {
  const double s = u.dot(t);
  const Vec3 u_n = u - s * t;
  const double h = 0.5 * L;
  return -(c_n * h * u_n.norm()) * u_n - (c_t * h * std::abs(s) * s) * t;
}

// Froude-Krylov and added-mass force of the water's acceleration a on half a segment
// (stretched length L, tangent t): L/2 [(rho A + C_MN rho A) a_n + (rho A + C_MT rho A) a_t]
// with a_n and a_t the parts of a across and along the segment.
inline Vec3 FluidInertiaForce(const Vec3& a, const Vec3& t, double L, const SectionProperties& sp) {
  const double cn = sp.displaced_mass_per_length + sp.added_mass_per_length;
  const double dc = sp.tangential_added_mass_per_length - sp.added_mass_per_length;
  return 0.5 * L * (cn * a + dc * t.dot(a) * t);
}

HalfSegmentDrag Drag(const Vec3& u, const Vec3& t, double L, double c_n, double c_t,
                     bool with_jacobian) {
  HalfSegmentDrag d;
  const double s = u.dot(t);
  const Vec3 u_n = u - s * t;
  const double un = u_n.norm();
  const double h = 0.5 * L;
  d.force = DragForce(u, t, L, c_n, c_t);
  if (!with_jacobian) return d;
  const Mat3 I = Mat3::Identity();
  const Mat3 Pn = I - t * t.transpose();
  // d(|u_n| u_n)/du_n = |u_n| I + u_n u_n^T / |u_n| (-> 0 as u_n -> 0).
  Mat3 dn = un * I;
  if (un > 1e-300) dn += u_n * u_n.transpose() / un;
  d.d_du = -c_n * h * dn * Pn - c_t * h * 2.0 * std::abs(s) * (t * t.transpose());
  // du_n/dl = -(t u^T + s I) Pn / L ; ds/dl = u^T Pn / L ; dt/dl = Pn / L ; dL/dl = t^T.
  const Mat3 dun_dl = -(t * u.transpose() + s * I) * Pn / L;
  d.d_dl =
      -c_n * (0.5 * un * u_n * t.transpose() + h * dn * dun_dl) -
      c_t * (0.5 * std::abs(s) * s * t * t.transpose() +
             h * (2.0 * std::abs(s) * t * (u.transpose() * Pn) / L + std::abs(s) * s * Pn / L));
  return d;
}

// A body's drag -b |u| u on the water's velocity relative to it u and, in waves, its
// Froude-Krylov and added-mass force (rho V + C_A rho V) a_w.
Vec3 BodyFluidForce(const PointBodyProperties& body, const Vec3& u,
                    const Vec3* water_acceleration) {
  Vec3 F = -(body.drag * u.norm()) * u;
  if (water_acceleration != nullptr)
    F += (body.displaced_mass + body.added_mass) * *water_acceleration;
  return F;
}

// Its derivatives, with du/dr = du_dr and du/dv = I.
void AddBodyFluidJacobian(const PointBodyProperties& body, const Vec3& u, const Mat3& du_dr,
                          const WaterMotion* water, Mat3* dF_dr, Mat3* dF_dv) {
  // d(-b |u| u)/du = -b (|u| I + u u^T / |u|).
  const double speed = u.norm();
  Mat3 d_du = speed * Mat3::Identity();
  if (speed > 1e-300) d_du += u * u.transpose() / speed;
  d_du *= -body.drag;
  *dF_dv += d_du;
  *dF_dr += d_du * du_dr;
  if (water != nullptr) *dF_dr += (body.displaced_mass + body.added_mass) * water->d_acceleration;
}

// A visco-elastic segment's springs at creep strain e: the dynamic stiffness EA_d and the
// creep spring's tension T_m = K e (the mean load), with their slopes d/de.
struct CreepSprings {
  double dynamic = 0.0, d_dynamic = 0.0, tension = 0.0, d_tension = 0.0;
};

CreepSprings CreepSpringsAt(const SectionProperties& sp, double e) {
  if (sp.dynamic_stiffness_slope == 0.0 || !(e > 0.0)) {
    return {sp.dynamic_stiffness, 0.0, sp.creep_stiffness * e, sp.creep_stiffness};
  }
  // EA_d = a + b K e with K = S EA_d / (EA_d - S) is the quadratic
  //   EA_d^2 - B EA_d + a S = 0,  B = a + S + b S e,
  // whose larger root is the one above S (at e = 0 it is a). And K e = (EA_d - a) / b.
  const double S = sp.axial_stiffness, a = sp.dynamic_stiffness, b = sp.dynamic_stiffness_slope;
  const double B = a + S + b * S * e;
  const double root = std::sqrt(B * B - 4.0 * a * S);
  CreepSprings out;
  out.dynamic = 0.5 * (B + root);
  out.d_dynamic = 0.5 * b * S * (1.0 + B / root);
  out.tension = S * out.dynamic / (out.dynamic - S) * e;
  out.d_tension = 0.5 * S * (1.0 + B / root);
  return out;
}

// The creep spring's energy per unit length, the integral of T_m from 0 to e (5-point
// Gauss-Legendre where T_m is not linear: it is smooth on [0, e], and the rule's error is
// far below the tension's own tolerances).
double CreepSpringEnergy(const SectionProperties& sp, double e) {
  if (sp.dynamic_stiffness_slope == 0.0 || !(e > 0.0)) return 0.5 * sp.creep_stiffness * e * e;
  static constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                       0.5384693101056831, 0.9061798459386640};
  static constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                         0.4786286704993665, 0.2369268850561891};
  double sum = 0.0;
  for (int k = 0; k < 5; ++k) {
    sum += kWeights[k] * CreepSpringsAt(sp, 0.5 * e * (1.0 + kNodes[k])).tension;
  }
  return 0.5 * e * sum;
}

// A visco-elastic segment at strain `strain` and creep strain e: its springs, whether it
// pulls (its dynamic spring stretched) and then dT/de = EA_d'(e) (strain - e) - EA_d.
struct CreepPull {
  CreepSprings springs;
  bool taut = false;
  double d_tension_d_creep = 0.0;
};

CreepPull CreepPullAt(const SectionProperties& sp, double strain, double e) {
  CreepPull out;
  out.springs = CreepSpringsAt(sp, e);
  out.taut = strain > 0.0 && out.springs.dynamic * (strain - e) > 0.0;
  if (out.taut) out.d_tension_d_creep = out.springs.d_dynamic * (strain - e) - out.springs.dynamic;
  return out;
}

}  // namespace

LineParameters LineParameters::Uniform(int id, const std::string& type, double length, int segments,
                                       const Vec3& anchor, const Vec3& fairlead_body) {
  LineParameters line;
  line.id = id;
  line.anchor = anchor;
  line.fairlead_body = fairlead_body;
  line.sections = {{type, length, segments}};
  return line;
}

double LineParameters::Length() const {
  double total = 0.0;
  for (const LineSection& section : sections) total += section.length;
  return total;
}

int LineParameters::Segments() const {
  int total = 0;
  for (const LineSection& section : sections) total += section.segments;
  return total;
}

LineProperties MakeLineProperties(const MooringParameters& spec, const LineParameters& line) {
  const std::string where = "mooring.lines[" + std::to_string(line.id) + "]";
  if (line.sections.empty()) throw InputError(where + ": a line needs at least one section");
  if (!line.joints.empty() && line.joints.size() + 1 != line.sections.size()) {
    throw InputError(where + ": " + std::to_string(line.joints.size()) + " joints for " +
                     std::to_string(line.sections.size()) + " sections (one between each two)");
  }
  const double rho = spec.water.density;
  LineProperties p;
  p.id = line.id;
  p.anchor = line.anchor;
  p.fairlead_body = line.fairlead_body;
  p.lower_point = line.lower_point;
  p.upper_point = line.upper_point;
  for (std::size_t k = 0; k < line.sections.size(); ++k) {
    const LineSection& section = line.sections[k];
    const auto type = std::find_if(spec.line_types.begin(), spec.line_types.end(),
                                   [&](const LineType& t) { return t.name == section.type; });
    const std::string key =
        line.sections.size() == 1 ? where : where + ".sections[" + std::to_string(k) + "]";
    if (type == spec.line_types.end()) {
      throw InputError(key + ".type: unknown line type '" + section.type + "'");
    }
    if (section.segments < 1) throw InputError(key + ".segments: must be >= 1");
    const double area = kPi * type->diameter * type->diameter / 4.0;
    SectionProperties sp;
    sp.type = section.type;
    sp.segments = section.segments;
    sp.length = section.length;
    sp.segment_length = section.length / section.segments;
    sp.diameter = type->diameter;
    sp.mass_per_length = type->mass_per_length;
    sp.weight_per_length = (type->mass_per_length - rho * area) * spec.water.gravity;
    sp.axial_stiffness = type->axial_stiffness;
    if (!type->tension_strain.empty()) {
      try {
        sp.curve = std::make_shared<const AxialCurve>(type->tension_strain);
      } catch (const InputError& e) {
        throw InputError("mooring.line_types '" + type->name + "': " + e.what());
      }
      sp.axial_stiffness = sp.curve->MaxSlope();
    }
    if (type->visco_elastic) {
      const ViscoElastic& v = *type->visco_elastic;
      if (sp.curve || !(v.dynamic_stiffness > sp.axial_stiffness) || !(v.creep_time > 0.0)) {
        throw InputError("mooring.line_types '" + type->name +
                         "': a visco-elastic rope needs a dynamic stiffness above its "
                         "quasi-static one, a positive creep time and no tension-strain table");
      }
      if (!(v.dynamic_stiffness_slope >= 0.0)) {
        throw InputError("mooring.line_types '" + type->name +
                         "': a visco-elastic rope's dynamic stiffness slope must be >= 0");
      }
      sp.visco = true;
      sp.dynamic_stiffness = v.dynamic_stiffness;
      sp.dynamic_stiffness_slope = v.dynamic_stiffness_slope;
      sp.creep_stiffness =
          sp.axial_stiffness * v.dynamic_stiffness / (v.dynamic_stiffness - sp.axial_stiffness);
      sp.creep_damping = sp.creep_stiffness * v.creep_time;
    }
    if (type->axial_damping) {
      sp.axial_damping = *type->axial_damping;
    } else {
      // Damping ratio of the highest axial mode of the discretised line (neighbouring nodes
      // moving in opposition, w_max = 2 (n / L) sqrt(EA / m)): c = zeta l0 sqrt(EA m), with
      // a visco-elastic rope's dynamic EA (that mode is fast).
      const double zeta = type->axial_damping_ratio.value_or(0.0);
      const double fastest = sp.visco ? sp.dynamic_stiffness : sp.axial_stiffness;
      sp.axial_damping = zeta * sp.segment_length * std::sqrt(fastest * type->mass_per_length);
    }
    sp.displaced_mass_per_length = rho * area;
    sp.added_mass_per_length = type->added_mass_normal * rho * area;
    sp.tangential_added_mass_per_length = type->added_mass_tangential * rho * area;
    sp.drag_normal = 0.5 * rho * type->drag_normal * type->diameter;
    sp.drag_tangential = 0.5 * rho * type->drag_tangential * type->diameter;
    sp.friction_axial = type->friction_axial;
    sp.friction_lateral = type->friction_lateral;
    p.sections.push_back(sp);
    p.length += section.length;
    p.segments += section.segments;
    p.section_of.insert(p.section_of.end(), section.segments, static_cast<int>(k));
  }
  p.body_at.assign(p.segments + 1, -1);
  int node = 0;
  for (std::size_t k = 0; k < line.joints.size(); ++k) {
    node += line.sections[k].segments;
    const PointBody& body = line.joints[k];
    if (body.mass == 0.0 && body.volume == 0.0 && body.drag_area == 0.0) continue;
    p.body_at[node] = static_cast<int>(p.bodies.size());
    p.bodies.push_back(BodyProperties(body, spec.water));
  }
  return p;
}

PointBodyProperties BodyProperties(const PointBody& body, const Water& water) {
  PointBodyProperties b;
  b.mass = body.mass;
  b.weight = (body.mass - water.density * body.volume) * water.gravity;
  b.added_mass = body.added_mass * water.density * body.volume;
  b.drag = 0.5 * water.density * body.drag_area;
  b.displaced_mass = water.density * body.volume;
  return b;
}

CompositeLine RestingLineOf(const LineProperties& line, const Vec3& lower, const Vec3& upper,
                            bool lower_is_point, const SeabedSurface& seabed) {
  const bool on_seabed = !lower_is_point && lower.z() >= seabed.DepthAt(lower.x(), lower.y()) - 1.0;
  CompositeLine out = CatenaryLineOf(line, on_seabed ? seabed.RiseAlong(lower, upper) : 0.0);
  out.lower_on_seabed = on_seabed;
  return out;
}

CompositeLine CatenaryLineOf(const LineProperties& line, double seabed_rise) {
  CompositeLine out;
  out.seabed_rise = seabed_rise;
  for (const SectionProperties& sp : line.sections) {
    out.sections.push_back({sp.length, sp.weight_per_length, sp.axial_stiffness});
    out.curves.push_back(sp.curve);
  }
  int node = 0;
  for (std::size_t k = 0; k + 1 < line.sections.size(); ++k) {
    node += line.sections[k].segments;
    const PointBodyProperties* body = line.BodyAt(node);
    out.joint_weights.push_back(body != nullptr ? body->weight : 0.0);
  }
  return out;
}

std::vector<double> NodeArcLengths(const LineProperties& line) {
  std::vector<double> arc(1, 0.0);
  double start = 0.0;
  for (const SectionProperties& sp : line.sections) {
    for (int k = 1; k <= sp.segments; ++k) {
      arc.push_back(k == sp.segments ? start + sp.length : start + sp.length * k / sp.segments);
    }
    start += sp.length;
  }
  return arc;
}

double CatenaryFairleadTension(const LineProperties& line, const Vec3& fairlead,
                               const SeabedSurface& seabed) {
  const CompositeLine composite = CatenaryLineOf(line, seabed.RiseAlong(line.anchor, fairlead));
  if (composite.Uniform()) {
    return SolveLineCatenary(composite.sections.front(), line.anchor, fairlead)
        .solution.fairlead_tension;
  }
  const Vec3 chord = fairlead - line.anchor;
  return SolveCompositeCatenary(composite, std::hypot(chord.x(), chord.y()),
                                line.anchor.z() - fairlead.z())
      .fairlead_tension;
}

int LineParameters::NodeNearest(double arc_length) const {
  int first = 0;
  double start = 0.0;
  for (std::size_t k = 0; k < sections.size(); ++k) {
    const LineSection& section = sections[k];
    if (arc_length <= start + section.length || k + 1 == sections.size()) {
      return first + static_cast<int>(
                         std::lround((arc_length - start) / section.length * section.segments));
    }
    first += section.segments;
    start += section.length;
  }
  return first;
}

NodeShare ShareOf(const LineProperties& lp, int node, bool has_below, bool has_above) {
  const SectionProperties* below = has_below ? &lp.SectionOf(node - 1) : nullptr;
  const SectionProperties* above = has_above ? &lp.SectionOf(node) : nullptr;
  NodeShare n;
  n.below = has_below ? lp.section_of[node - 1] : -1;
  n.above = has_above ? lp.section_of[node] : -1;
  if (below == nullptr || above == nullptr || below == above) {
    const SectionProperties& sp = above != nullptr ? *above : *below;
    n.length = 0.5 * sp.segment_length * ((has_below ? 1 : 0) + (has_above ? 1 : 0));
    n.mass = sp.mass_per_length * n.length;
    n.weight = sp.weight_per_length * n.length;
    n.line_weight_per_length = sp.weight_per_length;
    n.contact = sp.diameter * n.length;
    n.friction_axial = sp.friction_axial;
    n.friction_lateral = sp.friction_lateral;
  } else {  // a joint: each section's half segment, friction weighted by contact area
    const double h_below = 0.5 * below->segment_length;
    const double h_above = 0.5 * above->segment_length;
    const double c_below = below->diameter * h_below;
    const double c_above = above->diameter * h_above;
    n.length = h_below + h_above;
    n.mass = below->mass_per_length * h_below + above->mass_per_length * h_above;
    n.weight = below->weight_per_length * h_below + above->weight_per_length * h_above;
    n.line_weight_per_length = n.weight / n.length;
    n.contact = c_below + c_above;
    n.friction_axial =
        (c_below * below->friction_axial + c_above * above->friction_axial) / n.contact;
    n.friction_lateral =
        (c_below * below->friction_lateral + c_above * above->friction_lateral) / n.contact;
  }
  n.body = lp.body_at[node];
  if (const PointBodyProperties* body = lp.BodyAt(node)) {
    n.mass += body->mass + body->added_mass;
    n.weight += body->weight;
  }
  return n;
}

MooringSystem::MooringSystem(const MooringParameters& spec) : current_(spec.current) {
  seabed_.surface = SeabedSurface(spec.seabed, spec.water.depth);
  seabed_.stiffness = spec.seabed.stiffness;
  seabed_.damping = spec.seabed.damping;
  seabed_.friction_velocity = spec.seabed.friction_velocity;
  seabed_.regularisation = spec.seabed.contact_smoothing;
  int max_segments = 0;
  for (const auto& line : spec.lines) {
    lines_.push_back(MakeLineProperties(spec, line));
    const LineProperties& lp = lines_.back();
    std::vector<NodeShare> shares(lp.segments + 1);
    for (int k = 1; k < lp.segments; ++k) shares[k] = ShareOf(lp, k, true, true);
    shares_.push_back(std::move(shares));
    Chain c;
    c.line = static_cast<int>(lines_.size()) - 1;
    c.segments = lines_.back().segments;
    c.anchor = line.anchor;
    c.lower_point = line.lower_point;
    c.upper_point = line.upper_point;
    if (line.lower_point >= 0) c.lower = EndCondition::kPoint;
    if (line.upper_point >= 0) c.upper = EndCondition::kPoint;
    chains_.push_back(c);
    max_segments = std::max(max_segments, c.segments);
  }
  // The free points, and the lines' ends at them.
  std::vector<int> lines_at(spec.points.size(), 0);
  for (const FreePoint& point : spec.points) {
    point_bodies_.push_back(BodyProperties(point.body, spec.water));
    point_start_.push_back(point.position);
  }
  for (const Chain& c : chains_) {
    const std::string where = "mooring.lines[" + std::to_string(lines_[c.line].id) + "]";
    for (const int point : {c.lower_point, c.upper_point}) {
      if (point < -1 || point >= num_points()) {
        throw InputError(where + ": no free point " + std::to_string(point + 1));
      }
      if (point >= 0) ++lines_at[point];
    }
    if (c.lower_point >= 0 && c.lower_point == c.upper_point) {
      throw InputError(where + ": both ends at free point " + std::to_string(c.lower_point + 1));
    }
    if (c.lower == EndCondition::kPoint && c.upper == EndCondition::kFairlead && c.segments < 2) {
      throw InputError(where + ": a line from a free point to the vessel needs 2 segments or more");
    }
  }
  for (int p = 0; p < num_points(); ++p) {
    if (lines_at[p] == 0) {
      throw InputError("free point " + std::to_string(p + 1) + ": no line ends at it");
    }
  }
  point_force_.resize(spec.points.size());
  point_mass_.resize(spec.points.size());
  for (std::size_t line = 0; line < lines_.size(); ++line) {
    creep_index_.emplace_back(lines_[line].segments, -1);
    for (int s = 0; s < lines_[line].segments; ++s) {
      if (!lines_[line].SectionOf(s).visco) continue;
      creep_index_[line][s] = static_cast<int>(creep_.size());
      creep_.push_back({static_cast<int>(line), s});
    }
  }
  pos_.resize(max_segments + 1);
  vel_.resize(max_segments + 1);
  seg_.resize(max_segments);
  Layout();
}

void MooringSystem::Layout() {
  int offset = 6 * num_points();
  for (auto& c : chains_) {
    c.state_offset = offset;
    offset += 6 * c.num_state_nodes();
  }
  creep_offset_ = offset;
  state_size_ = offset + static_cast<int>(creep_.size());
  BuildPattern();
}

bool MooringSystem::attached(int index) const {
  return std::any_of(chains_.begin(), chains_.end(), [&](const Chain& c) {
    return c.line == index &&
           (c.upper == EndCondition::kFairlead || c.upper == EndCondition::kPoint);
  });
}

bool MooringSystem::at_vessel(int index) const {
  return std::any_of(chains_.begin(), chains_.end(), [&](const Chain& c) {
    return c.line == index && c.upper == EndCondition::kFairlead;
  });
}

namespace {

// Nodes of a line between two points at rest, a start for the static solve: on the chord if
// the line is no longer than it, else on a parabola sagging across it, downward as far as
// the chord allows (sideways under a vertical chord rising from an anchor, folded along one
// hanging down), with about the line's length (sag h over chord D: length D + 8 h^2 /
// (3 D)), kept above the seabed. A neutral line stays on the chord.
Eigen::Matrix3Xd SagPoints(const LineProperties& lp, const Vec3& lower, const Vec3& upper,
                           const SeabedSurface& seabed) {
  const std::vector<double> arc = NodeArcLengths(lp);
  const Vec3 chord = upper - lower;
  const double D = chord.norm();
  // A neutral rope has no sag to take: it folds along its chord, slack.
  const bool neutral = CatenaryLineOf(lp).Weightless();
  const double sag = lp.length > D && !neutral ? std::sqrt(3.0 * D * (lp.length - D) / 8.0) : 0.0;
  Vec3 across = kDown - kDown.dot(chord) / (D * D) * chord;
  if (!(across.norm() > 0.1)) {
    // A vertical chord: a line hanging down from its lower end (a pendulum, a lifted mass)
    // folds along it, below; one rising from an anchor (a buoy's tether) sags sideways,
    // since below it is the seabed.
    across = chord.z() > 0.0 ? kDown : Vec3(1.0, 0.0, 0.0) - chord.x() / (D * D) * chord;
  }
  across.normalize();
  Eigen::Matrix3Xd nodes(3, arc.size());
  for (std::size_t k = 0; k < arc.size(); ++k) {
    const double xi = arc[k] / lp.length;
    Vec3 r = lower + xi * chord + 4.0 * sag * xi * (1.0 - xi) * across;
    r.z() = std::min(r.z(), seabed.DepthAt(r.x(), r.y()));
    nodes.col(static_cast<Eigen::Index>(k)) = r;
  }
  return nodes;
}

// Chain c's interior nodes 1..segments-1 in x at `nodes`, at rest.
void LayNodes(const Chain& c, const Eigen::Matrix3Xd& nodes, double* x) {
  for (int k = 1; k < c.segments; ++k) {
    double* p = x + c.state_offset + 6 * (k - 1);
    for (int m = 0; m < 3; ++m) {
      p[m] = nodes(m, k);
      p[m + 3] = 0.0;
    }
  }
}

// The free points chain state node i's rows have columns in (its held neighbours), in
// ascending order, with the NodeJacobian slot each is at; returns how many (0..2).
int HeldPoints(const Chain& c, int i, int points[2], int slots[2]) {
  int n = 0;
  if (i == 0 && c.lower == EndCondition::kPoint) {
    points[n] = c.lower_point;
    slots[n++] = kBelow;
  }
  if (i == c.num_state_nodes() - 1 && c.upper == EndCondition::kPoint) {
    points[n] = c.upper_point;
    slots[n++] = kAbove;
  }
  if (n == 2 && points[0] > points[1]) {
    std::swap(points[0], points[1]);
    std::swap(slots[0], slots[1]);
  }
  return n;
}

}  // namespace

int MooringSystem::EndNeighbourState(const Chain& c, bool lower) const {
  const int k = lower ? 1 : c.segments - 1;
  if (k >= c.first_state_node() && k <= c.last_state_node()) {
    return c.state_offset + 6 * (k - c.first_state_node());
  }
  // One segment: the neighbour is the other end.
  const EndCondition other = lower ? c.upper : c.lower;
  if (other != EndCondition::kPoint) return -1;
  return 6 * (lower ? c.upper_point : c.lower_point);
}

std::vector<char> MooringSystem::StateKinds() const {
  std::vector<char> kinds(state_size_);
  for (int i = 0; i < creep_offset_; ++i) kinds[i] = (i % 6) < 3 ? 'p' : 'v';
  for (int i = creep_offset_; i < state_size_; ++i) kinds[i] = 's';
  return kinds;
}

void MooringSystem::BuildPattern() {
  SparsityPattern& p = pattern_;
  p.size = state_size_;
  p.row_start.assign(1, 0);
  p.column.clear();
  blocks_.chains.clear();
  blocks_.border = 6 * num_points();
  auto kinematic_rows = [&](int base) {  // r' = v rows: the diagonal and v_comp
    for (int comp = 0; comp < 3; ++comp) {
      p.column.push_back(base + comp);
      p.column.push_back(base + 3 + comp);
      p.row_start.push_back(static_cast<int64_t>(p.column.size()));
    }
  };
  // The points' rows: their own states and each line end's neighbour node.
  point_blocks_.assign(num_points(), {});
  for (int q = 0; q < num_points(); ++q) point_blocks_[q].push_back(6 * q);
  for (const Chain& c : chains_) {
    if (c.lower == EndCondition::kPoint && EndNeighbourState(c, true) >= 0) {
      point_blocks_[c.lower_point].push_back(EndNeighbourState(c, true));
    }
    if (c.upper == EndCondition::kPoint && EndNeighbourState(c, false) >= 0) {
      point_blocks_[c.upper_point].push_back(EndNeighbourState(c, false));
    }
  }
  // And the creep stretches of the lines' end segments at them.
  point_creep_.assign(num_points(), {});
  // The Jacobian's scratch for the points' rows, sized once per topology.
  point_accel_.resize(num_points());
  point_dr_.resize(num_points());
  point_dv_.resize(num_points());
  point_dq_.resize(num_points());
  for (const Chain& c : chains_) {
    const int lower = CreepState(c.line, c.first_node);
    const int upper = CreepState(c.line, c.first_node + c.segments - 1);
    if (c.lower == EndCondition::kPoint && lower >= 0) point_creep_[c.lower_point].push_back(lower);
    if (c.upper == EndCondition::kPoint && upper >= 0) point_creep_[c.upper_point].push_back(upper);
  }
  for (int q = 0; q < num_points(); ++q) {
    std::vector<int>& blocks = point_blocks_[q];
    std::sort(blocks.begin(), blocks.end());
    blocks.erase(std::unique(blocks.begin(), blocks.end()), blocks.end());
    std::vector<int>& creep = point_creep_[q];
    std::sort(creep.begin(), creep.end());
    creep.erase(std::unique(creep.begin(), creep.end()), creep.end());
    point_dr_[q].resize(blocks.size());
    point_dv_[q].resize(blocks.size());
    point_dq_[q].resize(creep.size());
    kinematic_rows(6 * q);
    for (int comp = 0; comp < 3; ++comp) {
      for (const int block : blocks) {
        for (int col = 0; col < 6; ++col) p.column.push_back(block + col);
      }
      for (const int state : creep) p.column.push_back(state);
      p.row_start.push_back(static_cast<int64_t>(p.column.size()));
    }
  }
  for (const Chain& c : chains_) {
    const int S = c.num_state_nodes();
    if (S > 0) blocks_.chains.push_back({c.state_offset, S});
    for (int i = 0; i < S; ++i) {
      const int base = c.state_offset + 6 * i;
      kinematic_rows(base);
      for (int comp = 0; comp < 3; ++comp) {  // v' rows: the points held, nodes i-1, i, i+1
        int points[2], slots[2];
        const int held = HeldPoints(c, i, points, slots);
        for (int h = 0; h < held; ++h) {
          for (int col = 0; col < 6; ++col) p.column.push_back(6 * points[h] + col);
        }
        for (int j = std::max(0, i - 1); j <= std::min(S - 1, i + 1); ++j) {
          for (int col = 0; col < 6; ++col) p.column.push_back(c.state_offset + 6 * j + col);
        }
        for (const int state : NodeCreepStates(c, c.first_state_node() + i)) {
          if (state >= 0) p.column.push_back(state);
        }
        p.row_start.push_back(static_cast<int64_t>(p.column.size()));
      }
    }
  }
  // The creep rows: the segment's two nodes' positions (where they are states) and itself.
  creep_rows_.assign(creep_.size(), {});
  for (const Chain& c : chains_) {
    for (int k = 0; k < c.segments; ++k) {
      const int i = creep_index_.empty() ? -1 : creep_index_[c.line][c.first_node + k];
      if (i >= 0) creep_rows_[i] = {NodeStateOf(c, k), NodeStateOf(c, k + 1)};
    }
  }
  for (std::size_t i = 0; i < creep_.size(); ++i) {
    int a = creep_rows_[i].lower, b = creep_rows_[i].upper;
    if (a > b) std::swap(a, b);
    for (const int block : {a, b}) {
      if (block < 0) continue;
      for (int col = 0; col < 3; ++col) p.column.push_back(block + col);
    }
    p.column.push_back(creep_offset_ + static_cast<int>(i));
    p.row_start.push_back(static_cast<int64_t>(p.column.size()));
  }
}

int MooringSystem::CreepState(int line, int segment) const {
  const int i = creep_index_[line][segment];
  return i < 0 ? -1 : creep_offset_ + i;
}

std::array<int, 2> MooringSystem::NodeCreepStates(const Chain& c, int k) const {
  if (creep_.empty()) return {-1, -1};
  return {k > 0 ? CreepState(c.line, c.first_node + k - 1) : -1,
          k < c.segments ? CreepState(c.line, c.first_node + k) : -1};
}

int MooringSystem::NodeStateOf(const Chain& c, int k) const {
  if (k >= c.first_state_node() && k <= c.last_state_node()) {
    return c.state_offset + 6 * (k - c.first_state_node());
  }
  if (k == 0 && c.lower == EndCondition::kPoint) return 6 * c.lower_point;
  if (k == c.segments && c.upper == EndCondition::kPoint) return 6 * c.upper_point;
  return -1;
}

void MooringSystem::GatherChain(const Chain& c, const double* x,
                                std::span<const PointKinematics> fairleads) {
  GatherNodes(c, x, fairleads);
  if (!creep_.empty()) {
    const LineProperties& lp = lines_[c.line];
    for (int s = 0; s < c.segments; ++s) {
      const int i = creep_index_[c.line][c.first_node + s];
      seg_[s].creep = i < 0 ? -1 : creep_offset_ + i;
      seg_[s].creep_strain =
          i < 0 ? 0.0 : x[creep_offset_ + i] / lp.SectionOf(c.first_node + s).segment_length;
    }
  }
}

void MooringSystem::GatherNodes(const Chain& c, const double* x,
                                std::span<const PointKinematics> fairleads) {
  const int first = c.first_state_node();
  const int last = c.last_state_node();
  for (int k = first; k <= last; ++k) {
    const double* node = x + c.state_offset + 6 * (k - first);
    pos_[k] = Vec3(node[0], node[1], node[2]);
    vel_[k] = Vec3(node[3], node[4], node[5]);
  }
  if (c.lower == EndCondition::kAnchored) {
    pos_[0] = c.anchor;
    vel_[0].setZero();
  }
  if (c.upper == EndCondition::kFairlead) {
    pos_[c.segments] = fairleads[c.line].position;
    vel_[c.segments] = fairleads[c.line].velocity;
  }
  if (c.lower == EndCondition::kPoint) {
    pos_[0] = Vec3(x + 6 * c.lower_point);
    vel_[0] = Vec3(x + 6 * c.lower_point + 3);
  }
  if (c.upper == EndCondition::kPoint) {
    pos_[c.segments] = Vec3(x + 6 * c.upper_point);
    vel_[c.segments] = Vec3(x + 6 * c.upper_point + 3);
  }
}

void MooringSystem::ComputeSegments(const Chain& c) {
  const LineProperties& lp = lines_[c.line];
  const SectionProperties* sp_ptr = nullptr;
  double l0 = 0.0, inverse_l0 = 0.0;  // multiplications, not divisions, below
  for (int s = 0; s < c.segments; ++s) {
    const SectionProperties& sp = lp.SectionOf(c.first_node + s);
    if (&sp != sp_ptr) {  // a new section: its constants
      sp_ptr = &sp;
      l0 = sp.segment_length;
      inverse_l0 = 1.0 / l0;
    }
    const Vec3 l = pos_[s + 1] - pos_[s];
    const double L = l.norm();
    if (!(L > 1e-9 * l0)) {
      std::ostringstream msg;
      msg << "line " << lp.id << " segment " << c.first_node + s + 1 << " has length " << L << " m";
      throw RecoverableStateError(msg.str());
    }
    SegmentState& g = seg_[s];
    g.t = l * (1.0 / L);
    g.L = L;
    g.rate = g.t.dot(vel_[s + 1] - vel_[s]) * inverse_l0;
    const double strain = L * inverse_l0 - 1.0;
    if (!(strain > 0.0)) {
      g.T = 0.0;
    } else if (sp.visco) {
      const double elastic =
          settling_ ? sp.axial_stiffness * strain : CreepTension(sp, strain, g.creep_strain);
      g.T = elastic > 0.0 ? elastic + sp.axial_damping * g.rate : 0.0;
    } else if (sp.curve) {
      g.T = sp.curve->Tension(strain) + sp.axial_damping * g.rate;
    } else {
      g.T = sp.axial_stiffness * strain + sp.axial_damping * g.rate;
    }
  }
}

void NodeMass::Add(double added, const Vec3& direction, double tangential) {
  a[segments] = added;
  b[segments] = tangential;
  t[segments] = direction;
  ++segments;
}

Mat3 NodeMass::Matrix() const {
  Mat3 M = m * Mat3::Identity();
  for (int i = 0; i < segments; ++i) {
    M += a[i] * (Mat3::Identity() - t[i] * t[i].transpose());
    if (b[i] != 0.0) M += b[i] * (t[i] * t[i].transpose());
  }
  return M;
}

Vec3 NodeMass::Solve(const Vec3& F) const {
  // M = alpha I - U D U^T with alpha = m + a_0 + a_1, U = [t_0 t_1], D = diag(a_0, a_1) (an
  // absent half segment has a = 0), so by Woodbury M^{-1} F = (F + U z) / alpha with
  // z = (alpha I - D U^T U)^{-1} D U^T F. That 2x2 matrix N has det N = (alpha - a_0)
  // (alpha - a_1) - a_0 a_1 c^2 > 0 for m > 0 (c = t_0 . t_1, |c| <= 1). One division.
  // With tangential added mass b_i the rank-2 term's weights are a_i - b_i (zero b_i: the
  // same operations as without it).
  const double a0 = segments > 0 ? a[0] : 0.0;
  const double a1 = segments > 1 ? a[1] : 0.0;
  const double alpha = m + a0 + a1;
  const double d0 = segments > 0 && b[0] != 0.0 ? a0 - b[0] : a0;
  const double d1 = segments > 1 && b[1] != 0.0 ? a1 - b[1] : a1;
  const double c = segments > 1 ? t[0].dot(t[1]) : 0.0;
  const double y0 = segments > 0 ? d0 * t[0].dot(F) : 0.0;
  const double y1 = segments > 1 ? d1 * t[1].dot(F) : 0.0;
  const double det = (alpha - d0) * (alpha - d1) - d0 * d1 * c * c;
  const double inverse = 1.0 / (alpha * det);  // 1 / (alpha det N)
  const double z0 = ((alpha - d1) * y0 + d0 * c * y1) * alpha * inverse;
  const double z1 = (d1 * c * y0 + (alpha - d0) * y1) * alpha * inverse;
  Vec3 x = F;
  if (segments > 0) x += z0 * t[0];
  if (segments > 1) x += z1 * t[1];
  return x * (det * inverse);
}

void MooringSystem::NodeForce(const Chain& c, int k, Vec3* F_out, NodeMass* M_out) const {
  if (waves_ != nullptr) {
    NodeForceIn<true>(c, k, F_out, M_out);
  } else {
    NodeForceIn<false>(c, k, F_out, M_out);
  }
}

inline const NodeShare& MooringSystem::ShareAt(const Chain& c, int k, NodeShare* end) const {
  const bool has_below = k > 0;
  const bool has_above = k < c.segments;
  if (has_below && has_above) return shares_[c.line][c.first_node + k];
  *end = ShareOf(lines_[c.line], c.first_node + k, has_below, has_above);
  return *end;
}

template <bool kWaves>
void MooringSystem::NodeForceIn(const Chain& c, int k, Vec3* F_out, NodeMass* M_out) const {
  const LineProperties& lp = lines_[c.line];
  const bool has_below = k > 0;
  const bool has_above = k < c.segments;
  NodeShare end;
  const NodeShare& share = ShareAt(c, k, &end);
  const Vec3& r = pos_[k];
  const Vec3& v = vel_[k];
  Vec3 u = v - current_.VelocityAt(time_, r);
  Vec3 water_acceleration = Vec3::Zero();
  if constexpr (kWaves) {
    const WaterMotion water = waves_->At(time_, r, false);
    u -= water.velocity;
    water_acceleration = water.acceleration;
  }

  NodeMass M;
  M.m = share.mass;
  Vec3 F = share.weight * kDown;
  auto add_segment = [&](int s, const SectionProperties& sp, double sign) {
    const SegmentState& g = seg_[s];
    F += sign * g.T * g.t;
    M.Add(0.5 * sp.added_mass_per_length * g.L, g.t,
          0.5 * sp.tangential_added_mass_per_length * g.L);
    F += DragForce(u, g.t, g.L, sp.drag_normal, sp.drag_tangential);
  };
  if (has_above) add_segment(k, lp.sections[share.above], +1.0);
  if (has_below) add_segment(k - 1, lp.sections[share.below], -1.0);
  if constexpr (kWaves) {
    const Vec3& a = water_acceleration;
    if (has_above) F += FluidInertiaForce(a, seg_[k].t, seg_[k].L, lp.sections[share.above]);
    if (has_below)
      F += FluidInertiaForce(a, seg_[k - 1].t, seg_[k - 1].L, lp.sections[share.below]);
    if (share.body >= 0) F += BodyFluidForce(lp.bodies[share.body], u, &a);
  } else {
    if (share.body >= 0) F += BodyFluidForce(lp.bodies[share.body], u, nullptr);
  }

  if (seabed_.Below(r) > 0.0) {
    const SeabedFrame frame = seabed_.Frame(r);
    const Vec3& n = frame.normal;
    double q, dq, s, ds;
    seabed_.Penetration(frame.penetration, &q, &dq);
    seabed_.DamperWeight(frame.penetration, &s, &ds);
    const double contact = share.contact;
    const double normal = seabed_.stiffness * contact * q;
    F -= (normal + seabed_.damping * contact * n.dot(v) * s) * n;
    if (normal > 0.0 && (share.friction_axial > 0.0 || share.friction_lateral > 0.0)) {
      // Friction in the seabed's tangent plane: the sliding velocity and the line's
      // direction there.
      const Vec3 q_vec = pos_[has_above ? k + 1 : k] - pos_[has_below ? k - 1 : k];
      const Vec3 q_t = q_vec - n.dot(q_vec) * n;
      const double qn = q_t.norm();
      const Vec3 v_t = v - n.dot(v) * n;
      const double rho =
          std::sqrt(v_t.squaredNorm() + seabed_.friction_velocity * seabed_.friction_velocity);
      Vec3 resist = share.friction_lateral * v_t;
      if (qn > 1e-12) {
        const Vec3 th = q_t / qn;
        resist += (share.friction_axial - share.friction_lateral) * th.dot(v_t) * th;
      }
      F -= (normal / rho) * resist;
    }
  }
  *F_out = F;
  *M_out = M;
}

void MooringSystem::NodeForceJacobian(const Chain& c, int k, const Vec3& a, NodeJacobian* J) const {
  const LineProperties& lp = lines_[c.line];
  const Mat3 I = Mat3::Identity();
  for (int j = 0; j < 3; ++j) {
    J->dF_dr[j].setZero();
    J->dF_dv[j].setZero();
    J->dMa_dr[j].setZero();
  }
  const bool has_below = k > 0;
  const bool has_above = k < c.segments;
  NodeShare end;
  const NodeShare& share = ShareAt(c, k, &end);
  const Vec3& r = pos_[k];
  const Vec3& v = vel_[k];
  std::optional<WaterMotion> water;
  if (waves_ != nullptr) water = waves_->At(time_, r, true);
  Vec3 u = v - current_.VelocityAt(time_, r);
  if (water) u -= water->velocity;
  // du/dr = -d(current)/dr - d(wave velocity)/dr.
  Mat3 du_dr = -current_.GradientAt(time_, r);
  if (water) du_dr -= water->d_velocity;

  // sigma = dl/dr_k for the segment (l = r_upper - r_lower): -1 above, +1 below.
  auto add_segment = [&](int s, const SectionProperties& sp, int other, double sigma) {
    const SegmentState& g = seg_[s];
    const double l0 = sp.segment_length;
    const double EA = sp.axial_stiffness;
    const double cd = sp.axial_damping;
    const Vec3& t = g.t;
    const Mat3 Pn = I - t * t.transpose();
    // Elastic + structural damping: force on the lower node is T t, on the upper -T t.
    // d(T t)/dl = t (dT/dl)^T + T Pn / L, dT/dl = EA/l0 t + c/l0 Pn dv / L.
    // A visco-elastic segment pulls through its dynamic spring while that is stretched (at
    // its quasi-static stiffness while settling).
    bool taut = g.L / l0 - 1.0 > 0.0;
    double slope = EA;  // dT/de
    if (sp.visco && !settling_) {
      slope = CreepSpringsAt(sp, g.creep_strain).dynamic;
      taut = taut && CreepTension(sp, g.L / l0 - 1.0, g.creep_strain) > 0.0;
    }
    if (taut) {
      const Vec3 dv = vel_[s + 1] - vel_[s];
      if (sp.curve) sp.curve->Tension(g.L / l0 - 1.0, &slope);
      const Vec3 dT_dl = slope / l0 * t + cd / l0 * (Pn * dv) / g.L;
      const Mat3 K = t * dT_dl.transpose() + g.T * Pn / g.L;
      const Mat3 D = cd / l0 * t * t.transpose();
      J->dF_dr[kSelf] -= K;
      J->dF_dr[other] += K;
      J->dF_dv[kSelf] -= D;
      J->dF_dv[other] += D;
    }
    const HalfSegmentDrag d = Drag(u, t, g.L, sp.drag_normal, sp.drag_tangential, true);
    J->dF_dv[kSelf] += d.d_du;
    J->dF_dr[kSelf] += d.d_du * du_dr + sigma * d.d_dl;
    J->dF_dr[other] -= sigma * d.d_dl;
    // Added mass h = C1/2 L Pn a: dh/dl = C1/2 [a t^T - t a^T - (t.a) Pn].
    Mat3 H =
        0.5 * sp.added_mass_per_length * (a * t.transpose() - t * a.transpose() - t.dot(a) * Pn);
    if (sp.tangential_added_mass_per_length != 0.0) {
      // Tangential: h_t = C_t/2 L t t^T a, dh_t/dl = C_t/2 [(t.a) Pn + t a^T].
      H += 0.5 * sp.tangential_added_mass_per_length * (t.dot(a) * Pn + t * a.transpose());
    }
    J->dMa_dr[kSelf] += sigma * H;
    J->dMa_dr[other] -= sigma * H;
    if (water) {
      // Fluid inertia f = L/2 [c_n a + (c_t - c_n)(t.a) t] (FluidInertiaForce):
      // df/dl = 1/2 [c_n a t^T + (c_t - c_n)(t a^T Pn + (t.a) I)], as L t = l.
      const Vec3& aw = water->acceleration;
      const double cn = sp.displaced_mass_per_length + sp.added_mass_per_length;
      const double dc = sp.tangential_added_mass_per_length - sp.added_mass_per_length;
      const Mat3 df_dl =
          0.5 * (cn * aw * t.transpose() + dc * (t * (aw.transpose() * Pn) + t.dot(aw) * I));
      J->dF_dr[kSelf] +=
          sigma * df_dl + 0.5 * g.L * (cn * I + dc * t * t.transpose()) * water->d_acceleration;
      J->dF_dr[other] -= sigma * df_dl;
    }
  };
  if (has_above) add_segment(k, lp.sections[share.above], kAbove, -1.0);
  if (has_below) add_segment(k - 1, lp.sections[share.below], kBelow, +1.0);
  if (share.body >= 0) {
    AddBodyFluidJacobian(lp.bodies[share.body], u, du_dr, water ? &*water : nullptr,
                         &J->dF_dr[kSelf], &J->dF_dv[kSelf]);
  }

  if (seabed_.Below(r) > 0.0) {
    SeabedFrameDerivatives moving;  // how the frame turns and deepens with r
    const SeabedFrame frame = seabed_.Frame(r, &moving);
    const Vec3& n = frame.normal;
    const Mat3& Dn = moving.d_normal;
    double q, dq, s, ds;
    seabed_.Penetration(frame.penetration, &q, &dq);
    seabed_.DamperWeight(frame.penetration, &s, &ds);
    const double contact = share.contact;
    const double k_n = seabed_.stiffness * contact;
    const double c_n = seabed_.damping * contact;
    const double normal = k_n * q;
    const double vn = n.dot(v);
    // Spring and damper -X n, X = k_n q(delta) + c_n s(delta) (n . v).
    const Eigen::RowVector3d dX_dr = (k_n * dq + c_n * vn * ds) * moving.d_penetration.transpose() +
                                     c_n * s * (v.transpose() * Dn);
    J->dF_dr[kSelf] -= n * dX_dr + (normal + c_n * vn * s) * Dn;
    J->dF_dv[kSelf] -= c_n * s * n * n.transpose();
    if (normal > 0.0 && (share.friction_axial > 0.0 || share.friction_lateral > 0.0)) {
      const int next = has_above ? kAbove : kSelf;
      const int prev = has_below ? kBelow : kSelf;
      const Mat3 P = I - n * n.transpose();
      const Vec3 q_vec = pos_[has_above ? k + 1 : k] - pos_[has_below ? k - 1 : k];
      const Vec3 q_t = P * q_vec;
      const double qn = q_t.norm();
      const Vec3 v_t = P * v;
      const double rho =
          std::sqrt(v_t.squaredNorm() + seabed_.friction_velocity * seabed_.friction_velocity);
      // f = -(N / rho) A v_t with A = mu_l I + (mu_a - mu_l) th th^T; v_t and q_t turn
      // with the normal: d(P w)/dr = -(n . w) Dn - n (w^T Dn).
      Mat3 A = share.friction_lateral * I;
      Vec3 th = Vec3::Zero();
      if (qn > 1e-12) {
        th = q_t / qn;
        A += (share.friction_axial - share.friction_lateral) * th * th.transpose();
      }
      const Vec3 Av = A * v_t;
      const Mat3 dvt_dr = -vn * Dn - n * (v.transpose() * Dn);
      J->dF_dv[kSelf] +=
          -(normal / rho) * A * P + (normal / (rho * rho * rho)) * Av * v_t.transpose();
      J->dF_dr[kSelf] += -(k_n * dq / rho) * Av * moving.d_penetration.transpose() -
                         (normal / rho) * A * dvt_dr +
                         (normal / (rho * rho * rho)) * Av * (v_t.transpose() * dvt_dr);
      if (qn > 1e-12) {
        const Mat3 dF_dqt = -(normal / rho) * (share.friction_axial - share.friction_lateral) *
                            (th * v_t.transpose() + th.dot(v_t) * I) * (I - th * th.transpose()) /
                            qn;
        J->dF_dr[next] += dF_dqt * P;
        J->dF_dr[prev] -= dF_dqt * P;
        J->dF_dr[kSelf] += dF_dqt * (-n.dot(q_vec) * Dn - n * (q_vec.transpose() * Dn));
      }
    }
  }
}

void MooringSystem::Derivatives(const double* x, std::span<const PointKinematics> fairleads,
                                double* xdot, std::span<Vec3> forces) {
  for (auto& f : forces) f.setZero();
  for (int q = 0; q < num_points(); ++q) PointBodyLoad(q, x);
  for (const Chain& c : chains_) {
    GatherChain(c, x, fairleads);
    ComputeSegments(c);
    if (!forces.empty() && c.upper == EndCondition::kFairlead) {
      Vec3 F;
      NodeMass M;
      NodeForce(c, c.segments, &F, &M);
      forces[c.line] = F - M.Matrix() * fairleads[c.line].acceleration;
    }
    if (c.lower == EndCondition::kPoint) AddEndToPoint(c, 0, c.lower_point);
    if (c.upper == EndCondition::kPoint) AddEndToPoint(c, c.segments, c.upper_point);
    const int first = c.first_state_node();
    for (int k = first; k <= c.last_state_node(); ++k) {
      Vec3 F;
      NodeMass M;
      NodeForce(c, k, &F, &M);
      const Vec3 a = M.Solve(F);
      double* out = xdot + c.state_offset + 6 * (k - first);
      out[0] = vel_[k].x();
      out[1] = vel_[k].y();
      out[2] = vel_[k].z();
      out[3] = a.x();
      out[4] = a.y();
      out[5] = a.z();
    }
    if (!creep_.empty()) {
      // The creep element's dashpot carries the elastic tension less its spring's:
      // c de/dt = T - K e, for the stretch l0 e.
      const LineProperties& lp = lines_[c.line];
      for (int s = 0; s < c.segments; ++s) {
        const SegmentState& g = seg_[s];
        if (g.creep < 0) continue;
        const SectionProperties& sp = lp.SectionOf(c.first_node + s);
        const double strain = g.L / sp.segment_length - 1.0;
        const double carried =
            strain > 0.0 ? std::max(0.0, CreepTension(sp, strain, g.creep_strain)) : 0.0;
        xdot[g.creep] = sp.segment_length * (carried - CreepSpringsAt(sp, g.creep_strain).tension) /
                        sp.creep_damping;
      }
    }
  }
  for (int q = 0; q < num_points(); ++q) {
    const Vec3 a = PointAcceleration(q);
    double* out = xdot + 6 * q;
    for (int m = 0; m < 3; ++m) {
      out[m] = x[6 * q + 3 + m];
      out[3 + m] = a(m);
    }
  }
}

void MooringSystem::PointBodyLoad(int q, const double* x) {
  const PointBodyProperties& body = point_bodies_[q];
  const Vec3 r(x + 6 * q);
  const Vec3 v(x + 6 * q + 3);
  Vec3 u = v - current_.VelocityAt(time_, r);
  point_force_[q] = body.weight * kDown;
  if (waves_ != nullptr) {
    const WaterMotion water = waves_->At(time_, r, false);
    u -= water.velocity;
    point_force_[q] += BodyFluidForce(body, u, &water.acceleration);
  } else {
    point_force_[q] += BodyFluidForce(body, u, nullptr);
  }
  point_mass_[q] = (body.mass + body.added_mass) * Mat3::Identity();
}

void MooringSystem::AddEndToPoint(const Chain& c, int k, int point) {
  Vec3 F;
  NodeMass M;
  NodeForce(c, k, &F, &M);
  point_force_[point] += F;
  point_mass_[point] += M.Matrix();
}

void MooringSystem::PointLoads(const double* x, std::span<const PointKinematics> fairleads) {
  for (int q = 0; q < num_points(); ++q) PointBodyLoad(q, x);
  for (const Chain& c : chains_) {
    if (c.lower != EndCondition::kPoint && c.upper != EndCondition::kPoint) continue;
    GatherChain(c, x, fairleads);
    ComputeSegments(c);
    if (c.lower == EndCondition::kPoint) AddEndToPoint(c, 0, c.lower_point);
    if (c.upper == EndCondition::kPoint) AddEndToPoint(c, c.segments, c.upper_point);
  }
}

double MooringSystem::CreepSlope(const SegmentState& g, const SectionProperties& sp) const {
  if (settling_ || !sp.visco) return 0.0;
  const CreepPull pull = CreepPullAt(sp, g.L / sp.segment_length - 1.0, g.creep_strain);
  return pull.taut ? pull.d_tension_d_creep / sp.segment_length : 0.0;
}

double MooringSystem::CreepTension(const SectionProperties& sp, double strain,
                                   double creep_strain) const {
  return CreepSpringsAt(sp, creep_strain).dynamic * (strain - creep_strain);
}

void MooringSystem::CreepAtRest(double* x, std::span<const PointKinematics> fairleads) const {
  for (std::size_t i = 0; i < creep_.size(); ++i) {
    const CreepSegment& cs = creep_[i];
    const SectionProperties& sp = lines_[cs.line].SectionOf(cs.segment);
    const double L = (NodePosition(x, cs.line, cs.segment + 1, fairleads) -
                      NodePosition(x, cs.line, cs.segment, fairleads))
                         .norm();
    // At rest both springs carry T = EA_s e: the creep strain is T / K, with K at the mean
    // load T (EA_d = a + b T).
    const double strain = std::max(0.0, L / sp.segment_length - 1.0);
    double creep_stiffness = sp.creep_stiffness;
    if (sp.dynamic_stiffness_slope != 0.0) {
      const double dynamic =
          sp.dynamic_stiffness + sp.dynamic_stiffness_slope * sp.axial_stiffness * strain;
      creep_stiffness = sp.axial_stiffness * dynamic / (dynamic - sp.axial_stiffness);
    }
    x[creep_offset_ + i] = sp.segment_length * sp.axial_stiffness * strain / creep_stiffness;
  }
}

Vec3 MooringSystem::PointAcceleration(int q) const {
  // A point with nothing left on it and no mass of its own stays where it is.
  if (!(point_mass_[q].trace() > 0.0)) return Vec3::Zero();
  return point_mass_[q].inverse() * point_force_[q];
}

void MooringSystem::Jacobian(const double* x, std::span<const PointKinematics> fairleads,
                             double* values) {
  NodeJacobian J;
  // The points' accelerations first (their added mass's derivative needs them), and their
  // own bodies' force derivatives.
  const int np = num_points();
  std::vector<Vec3>& point_accel = point_accel_;
  std::vector<std::vector<Mat3>>& dR = point_dr_;
  std::vector<std::vector<Mat3>>& dV = point_dv_;
  std::vector<std::vector<Vec3>>& dQ = point_dq_;  // d F_point / d(creep stretch)
  auto block_of = [&](int q, int state) {
    const std::vector<int>& blocks = point_blocks_[q];
    return static_cast<int>(std::lower_bound(blocks.begin(), blocks.end(), state) - blocks.begin());
  };
  if (np > 0) {
    PointLoads(x, fairleads);
    for (int q = 0; q < np; ++q) {
      point_accel[q] = PointAcceleration(q);
      for (Mat3& m : dR[q]) m.setZero();
      for (Mat3& m : dV[q]) m.setZero();
      for (Vec3& d : dQ[q]) d.setZero();
      const Vec3 r(x + 6 * q);
      const Vec3 v(x + 6 * q + 3);
      std::optional<WaterMotion> water;
      if (waves_ != nullptr) water = waves_->At(time_, r, true);
      Vec3 u = v - current_.VelocityAt(time_, r);
      Mat3 du_dr = -current_.GradientAt(time_, r);
      if (water) {
        u -= water->velocity;
        du_dr -= water->d_velocity;
      }
      const int self = block_of(q, 6 * q);
      AddBodyFluidJacobian(point_bodies_[q], u, du_dr, water ? &*water : nullptr, &dR[q][self],
                           &dV[q][self]);
    }
  }
  // A line end's share of its point's force derivatives.
  auto add_end = [&](const Chain& c, bool lower) {
    const int q = lower ? c.lower_point : c.upper_point;
    NodeForceJacobian(c, lower ? 0 : c.segments, point_accel[q], &J);
    const int self = block_of(q, 6 * q);
    dR[q][self] += J.dF_dr[kSelf] - J.dMa_dr[kSelf];
    dV[q][self] += J.dF_dv[kSelf];
    // The end segment's creep: it pulls the point along t at its lower end, -t at its upper.
    const int end_segment = lower ? 0 : c.segments - 1;
    const SegmentState& g = seg_[end_segment];
    if (g.creep >= 0) {
      const std::vector<int>& creep = point_creep_[q];
      const auto at = std::lower_bound(creep.begin(), creep.end(), g.creep) - creep.begin();
      const double slope = CreepSlope(g, lines_[c.line].SectionOf(c.first_node + end_segment));
      dQ[q][at] += (lower ? slope : -slope) * g.t;
    }
    const int neighbour = EndNeighbourState(c, lower);
    if (neighbour < 0) return;
    const int slot = lower ? kAbove : kBelow;
    const int b = block_of(q, neighbour);
    dR[q][b] += J.dF_dr[slot] - J.dMa_dr[slot];
    dV[q][b] += J.dF_dv[slot];
  };
  for (const Chain& c : chains_) {
    GatherChain(c, x, fairleads);
    ComputeSegments(c);
    if (c.lower == EndCondition::kPoint) add_end(c, true);
    if (c.upper == EndCondition::kPoint) add_end(c, false);
    const int first = c.first_state_node();
    const int S = c.num_state_nodes();
    for (int i = 0; i < S; ++i) {
      const int k = first + i;
      const int row = c.state_offset + 6 * i;
      for (int comp = 0; comp < 3; ++comp) {  // r' = v
        double* v = values + pattern_.row_start[row + comp];
        v[0] = 0.0;
        v[1] = 1.0;
      }
      Vec3 F;
      NodeMass M;
      NodeForce(c, k, &F, &M);
      const Mat3 Minv = M.Matrix().inverse();
      const Vec3 a = Minv * F;
      NodeForceJacobian(c, k, a, &J);
      int points[2], slots[2];
      const int held = HeldPoints(c, i, points, slots);
      for (int comp = 0; comp < 3; ++comp) {
        double* v = values + pattern_.row_start[row + 3 + comp];
        for (int h = 0; h < held; ++h) {
          const int slot = slots[h];
          const Eigen::RowVector3d dr = Minv.row(comp) * (J.dF_dr[slot] - J.dMa_dr[slot]);
          const Eigen::RowVector3d dv = Minv.row(comp) * J.dF_dv[slot];
          for (int m = 0; m < 3; ++m) *v++ = dr(m);
          for (int m = 0; m < 3; ++m) *v++ = dv(m);
        }
        for (int j = std::max(0, i - 1); j <= std::min(S - 1, i + 1); ++j) {
          const int slot = j - i + 1;  // kBelow, kSelf, kAbove
          const Eigen::RowVector3d dr = Minv.row(comp) * (J.dF_dr[slot] - J.dMa_dr[slot]);
          const Eigen::RowVector3d dv = Minv.row(comp) * J.dF_dv[slot];
          for (int m = 0; m < 3; ++m) *v++ = dr(m);
          for (int m = 0; m < 3; ++m) *v++ = dv(m);
        }
        // The creep of the segments below and above: -T t below, T t above.
        const std::array<int, 2> creep = NodeCreepStates(c, k);
        for (int side = 0; side < 2; ++side) {
          if (creep[side] < 0) continue;
          const int s = side == 0 ? k - 1 : k;
          const double slope = CreepSlope(seg_[s], lines_[c.line].SectionOf(c.first_node + s));
          *v++ = Minv.row(comp).dot((side == 0 ? -slope : slope) * seg_[s].t);
        }
      }
    }
    // The creep rows: d(stretch)/dt = l0 (T_e - T_m) / c, T_e = EA_d (strain - e), T_m the
    // creep spring's tension K e (EA_d and K functions of e where the stiffness rises with
    // the mean load), e = stretch / l0.
    for (int s = 0; s < c.segments && !creep_.empty(); ++s) {
      const SegmentState& g = seg_[s];
      if (g.creep < 0) continue;
      const SectionProperties& sp = lines_[c.line].SectionOf(c.first_node + s);
      const CreepRow& plan = creep_rows_[g.creep - creep_offset_];
      const CreepPull pull = CreepPullAt(sp, g.L / sp.segment_length - 1.0, g.creep_strain);
      const bool taut = !settling_ && pull.taut;
      const double k = taut ? pull.springs.dynamic / sp.creep_damping : 0.0;
      double* v = values + pattern_.row_start[g.creep];
      const bool lower_first = plan.lower < plan.upper;
      for (const bool lower : {lower_first, !lower_first}) {
        if ((lower ? plan.lower : plan.upper) < 0) continue;
        const Vec3 d = (lower ? -k : k) * g.t;
        for (int m = 0; m < 3; ++m) *v++ = d(m);
      }
      *v = ((taut ? pull.d_tension_d_creep : 0.0) - pull.springs.d_tension) / sp.creep_damping;
    }
  }
  for (int q = 0; q < np; ++q) {
    const int row = 6 * q;
    for (int comp = 0; comp < 3; ++comp) {  // r' = v
      double* v = values + pattern_.row_start[row + comp];
      v[0] = 0.0;
      v[1] = 1.0;
    }
    const Mat3 Minv =
        point_mass_[q].trace() > 0.0 ? Mat3(point_mass_[q].inverse()) : Mat3(Mat3::Zero());
    for (int comp = 0; comp < 3; ++comp) {
      double* v = values + pattern_.row_start[row + 3 + comp];
      for (std::size_t b = 0; b < dR[q].size(); ++b) {
        const Eigen::RowVector3d dr = Minv.row(comp) * dR[q][b];
        const Eigen::RowVector3d dv = Minv.row(comp) * dV[q][b];
        for (int m = 0; m < 3; ++m) *v++ = dr(m);
        for (int m = 0; m < 3; ++m) *v++ = dv(m);
      }
      for (const Vec3& d : dQ[q]) *v++ = Minv.row(comp).dot(d);
    }
  }
}

void MooringSystem::FairleadForces(const double* x, std::span<const PointKinematics> fairleads,
                                   std::span<Vec3> forces) {
  for (auto& f : forces) f.setZero();
  for (const Chain& c : chains_) {
    if (c.upper != EndCondition::kFairlead) continue;
    forces[c.line] = UpperEndForce(c, x, fairleads, fairleads[c.line].acceleration);
  }
}

Vec3 MooringSystem::UpperEndForce(const Chain& c, const double* x,
                                  std::span<const PointKinematics> fairleads,
                                  const Vec3& acceleration) {
  GatherChain(c, x, fairleads);
  ComputeSegments(c);
  Vec3 F;
  NodeMass M;
  NodeForce(c, c.segments, &F, &M);
  // The node's equation M a = F + F_holder gives the line's force on its holder F - M a.
  return F - M.Matrix() * acceleration;
}

void MooringSystem::PointEndForces(const double* x, std::span<const PointKinematics> fairleads,
                                   std::span<Vec3> forces) {
  if (num_points() == 0) return;
  PointLoads(x, fairleads);
  for (const Chain& c : chains_) {
    if (c.upper != EndCondition::kPoint) continue;
    forces[c.line] = UpperEndForce(c, x, fairleads, PointAcceleration(c.upper_point));
  }
}

int MooringSystem::CouplingNode(int index) const {
  for (const Chain& c : chains_) {
    if (c.line != index || c.upper != EndCondition::kFairlead) continue;
    const int n = c.segments;
    if (n - 1 < c.first_state_node()) return -1;
    return c.state_offset + 6 * (n - 1 - c.first_state_node());
  }
  return -1;
}

FairleadCoupling MooringSystem::FairleadJacobian(const double* x,
                                                 std::span<const PointKinematics> fairleads,
                                                 int index) {
  const auto chain = std::find_if(chains_.begin(), chains_.end(), [&](const Chain& c) {
    return c.line == index && c.upper == EndCondition::kFairlead;
  });
  if (chain == chains_.end()) {
    throw Error("line " + std::to_string(index + 1) + " is not attached to its fairlead");
  }
  const Chain& c = *chain;
  const int n = c.segments;
  GatherChain(c, x, fairleads);
  ComputeSegments(c);
  FairleadCoupling out;
  NodeJacobian J;
  // Fairlead force F_n - M_n a_f: node n's force derivatives with its acceleration held.
  const Vec3& a_fairlead = fairleads[c.line].acceleration;
  NodeForceJacobian(c, n, a_fairlead, &J);
  out.J_force_node_pos = J.dF_dr[kBelow] - J.dMa_dr[kBelow];
  out.J_force_node_vel = J.dF_dv[kBelow];
  out.J_force_fairlead_pos = J.dF_dr[kSelf] - J.dMa_dr[kSelf];
  out.J_force_fairlead_vel = J.dF_dv[kSelf];
  if (n - 1 >= c.first_state_node()) {  // a one-segment chain has no free node
    Vec3 F;
    NodeMass M;
    NodeForce(c, n - 1, &F, &M);
    const Mat3 Minv = M.Matrix().inverse();
    NodeForceJacobian(c, n - 1, Minv * F, &J);
    out.node_state = c.state_offset + 6 * (n - 1 - c.first_state_node());
    out.J_accel_fairlead_pos = Minv * (J.dF_dr[kAbove] - J.dMa_dr[kAbove]);
    out.J_accel_fairlead_vel = Minv * J.dF_dv[kAbove];
  }
  // The top segment's creep: the fairlead node is its upper end (force -T t), and its rate
  // l0 (T_e - K e) / c grows with the fairlead's pull, EA_d / c along t.
  const SegmentState& top = seg_[n - 1];
  if (top.creep >= 0) {
    const SectionProperties& sp = lines_[c.line].SectionOf(c.first_node + n - 1);
    const double slope = CreepSlope(top, sp);
    out.creep_state = top.creep;
    out.J_force_creep = -slope * top.t;
    if (slope != 0.0) {
      out.J_creep_fairlead_pos =
          (CreepSpringsAt(sp, top.creep_strain).dynamic / sp.creep_damping) * top.t.transpose();
    }
  }
  return out;
}

int MooringSystem::CouplingCreep(int index) const {
  for (const Chain& c : chains_) {
    if (c.line != index || c.upper != EndCondition::kFairlead) continue;
    return CreepState(c.line, c.first_node + c.segments - 1);
  }
  return -1;
}

std::vector<LineLoad> MooringSystem::LineLoads(const double* x,
                                               std::span<const PointKinematics> fairleads) {
  std::vector<LineLoad> loads(lines_.size());
  std::vector<Vec3> forces(lines_.size());
  FairleadForces(x, fairleads, forces);
  for (size_t i = 0; i < lines_.size(); ++i) {
    loads[i].fairlead_force = forces[i];
    loads[i].upper_end_force = forces[i];
    loads[i].attached = attached(static_cast<int>(i));
  }
  if (num_points() > 0) {
    for (size_t i = 0; i < lines_.size(); ++i) forces[i] = loads[i].upper_end_force;
    PointEndForces(x, fairleads, forces);
    for (size_t i = 0; i < lines_.size(); ++i) loads[i].upper_end_force = forces[i];
  }
  // Grounded length: the seabed's share of the line's weight divided by the weight per
  // metre, which converges to the catenary's unstretched grounded length as n grows. A held
  // anchor on the seabed carries its half segment itself; it counts as grounded in the
  // proportion its neighbour is.
  for (const Chain& c : chains_) {
    GatherChain(c, x, fairleads);
    const LineProperties& lp = lines_[c.line];
    double grounded_fraction_of_node_1 = 0.0;
    for (int k = 0; k <= c.segments; ++k) {
      if (!(seabed_.Below(pos_[k]) > 0.0)) continue;
      const SeabedFrame frame = seabed_.Frame(pos_[k]);
      double q, dq;
      seabed_.Penetration(frame.penetration, &q, &dq);
      const NodeShare share = ShareOf(lp, c.first_node + k, k > 0, k < c.segments);
      // A buoyant stretch is not held up by the seabed.
      if (!(share.line_weight_per_length > 0.0)) continue;
      // On a slope the seabed carries the weight's normal component, w cos(slope) per metre.
      const double normal = seabed_.stiffness * share.contact * q;
      loads[c.line].grounded_length += normal / (share.line_weight_per_length * frame.normal.z());
      if (k == 1) {
        grounded_fraction_of_node_1 = std::min(
            1.0, normal / (share.line_weight_per_length * frame.normal.z() * share.length));
      }
    }
    if (c.lower == EndCondition::kAnchored && seabed_.Below(c.anchor) >= -1e-6) {
      loads[c.line].grounded_length +=
          0.5 * lp.SectionOf(c.first_node).segment_length * grounded_fraction_of_node_1;
    }
  }
  return loads;
}

double MooringSystem::MechanicalEnergy(const double* x,
                                       std::span<const PointKinematics> fairleads) {
  double energy = 0.0;
  for (const Chain& c : chains_) {
    const LineProperties& lp = lines_[c.line];
    GatherChain(c, x, fairleads);
    ComputeSegments(c);
    for (int s = 0; s < c.segments; ++s) {
      const SectionProperties& sp = lp.SectionOf(c.first_node + s);
      const double strain = seg_[s].L / sp.segment_length - 1.0;
      if (sp.visco) {  // both springs of the segment; the dashpot only dissipates
        const double e = seg_[s].creep_strain;
        const double elastic = strain > 0.0 ? std::max(0.0, strain - e) : 0.0;
        energy += sp.segment_length * (0.5 * CreepSpringsAt(sp, e).dynamic * elastic * elastic +
                                       CreepSpringEnergy(sp, e));
      } else if (strain > 0.0) {
        energy +=
            (sp.curve ? sp.curve->Energy(strain) : 0.5 * sp.axial_stiffness * strain * strain) *
            sp.segment_length;
      }
    }
    for (int k = c.first_state_node(); k <= c.last_state_node(); ++k) {
      Vec3 F;
      NodeMass mass;
      NodeForce(c, k, &F, &mass);
      const Mat3 M = mass.Matrix();
      const NodeShare share = ShareOf(lp, c.first_node + k, k > 0, k < c.segments);
      energy += 0.5 * vel_[k].dot(M * vel_[k]);
      energy -= share.weight * pos_[k].z();
      if (seabed_.Below(pos_[k]) > 0.0) {
        energy += seabed_.stiffness * share.contact *
                  seabed_.PenetrationEnergy(seabed_.Frame(pos_[k]).penetration);
      }
    }
    // The line's end nodes at free points move with them.
    for (const int k : {0, c.segments}) {
      const bool at_point =
          k == 0 ? c.lower == EndCondition::kPoint : c.upper == EndCondition::kPoint;
      if (!at_point) continue;
      Vec3 F;
      NodeMass mass;
      NodeForce(c, k, &F, &mass);
      const NodeShare share = ShareOf(lp, c.first_node + k, k > 0, k < c.segments);
      energy += 0.5 * vel_[k].dot(mass.Matrix() * vel_[k]) - share.weight * pos_[k].z();
      if (seabed_.Below(pos_[k]) > 0.0) {
        energy += seabed_.stiffness * share.contact *
                  seabed_.PenetrationEnergy(seabed_.Frame(pos_[k]).penetration);
      }
    }
  }
  for (int q = 0; q < num_points(); ++q) {
    const PointBodyProperties& body = point_bodies_[q];
    const Vec3 v(x + 6 * q + 3);
    energy += 0.5 * (body.mass + body.added_mass) * v.squaredNorm() - body.weight * x[6 * q + 2];
  }
  return energy;
}

Vec3 MooringSystem::NodePosition(const double* x, int line, int node,
                                 std::span<const PointKinematics> fairleads) const {
  for (const Chain& c : chains_) {
    if (c.line != line || node < c.first_node || node > c.first_node + c.segments) continue;
    const int k = node - c.first_node;
    if (k == 0 && c.lower == EndCondition::kAnchored) return c.anchor;
    if (k == c.segments && c.upper == EndCondition::kFairlead) return fairleads[line].position;
    if (k == 0 && c.lower == EndCondition::kPoint) return PointPosition(x, c.lower_point);
    if (k == c.segments && c.upper == EndCondition::kPoint) return PointPosition(x, c.upper_point);
    const double* p = x + c.state_offset + 6 * (k - c.first_state_node());
    return Vec3(p[0], p[1], p[2]);
  }
  throw Error("no node " + std::to_string(node) + " on line " + std::to_string(line + 1));
}

std::vector<double> MooringSystem::SegmentTensions(const double* x, int line,
                                                   std::span<const PointKinematics> fairleads) {
  std::vector<double> tensions(lines_.at(line).segments, 0.0);
  for (const Chain& c : chains_) {
    if (c.line != line) continue;
    GatherChain(c, x, fairleads);
    ComputeSegments(c);
    for (int s = 0; s < c.segments; ++s) tensions[c.first_node + s] = seg_[s].T;
  }
  return tensions;
}

void MooringSystem::CatenaryState(std::span<const Vec3> fairleads, double* x) const {
  for (int q = 0; q < num_points(); ++q) {
    for (int m = 0; m < 3; ++m) {
      x[6 * q + m] = point_start_[q](m);
      x[6 * q + 3 + m] = 0.0;
    }
  }
  for (const Chain& c : chains_) {
    if (c.lower == EndCondition::kFree || c.upper == EndCondition::kFree) {
      throw Error("catenary initial state needs intact lines");
    }
    const LineProperties& lp = lines_[c.line];
    const Vec3 lower = c.lower == EndCondition::kPoint ? point_start_[c.lower_point] : lp.anchor;
    const Vec3 upper =
        c.upper == EndCondition::kPoint ? point_start_[c.upper_point] : fairleads[c.line];
    Eigen::Matrix3Xd nodes;
    if (c.lower == EndCondition::kPoint) {
      nodes = SagPoints(lp, lower, upper, seabed_.surface);
    } else {
      try {
        nodes = StartNodes(c, lower, upper);
      } catch (const Error& e) {
        throw Error("line " + std::to_string(lp.id) + ": " + e.what());
      }
    }
    LayNodes(c, nodes, x);
  }
  if (!creep_.empty()) {
    std::vector<PointKinematics> held(lines_.size());
    for (std::size_t i = 0; i < lines_.size(); ++i) held[i].position = fairleads[i];
    CreepAtRest(x, held);
  }
}

double MooringSystem::SettleStatic(std::span<const Vec3> fairlead_positions, double* x) {
  std::vector<PointKinematics> fairleads(lines_.size());
  for (size_t i = 0; i < lines_.size(); ++i) fairleads[i].position = fairlead_positions[i];
  // At rest a visco-elastic segment has crept to its quasi-static stiffness: the lines settle
  // with it, and the creep is set to match.
  struct Settling {
    bool& flag;
    explicit Settling(bool& f) : flag(f) { flag = true; }
    ~Settling() { flag = false; }
  };
  double residual = 0.0;
  {
    const Settling settling(settling_);
    residual = SettleLinesAndPoints(fairleads, x);
  }
  CreepAtRest(x, fairleads);
  return residual;
}

Eigen::Matrix3Xd MooringSystem::StartNodes(const Chain& c, const Vec3& lower,
                                           const Vec3& upper) const {
  const LineProperties& lp = lines_[c.line];
  try {
    const CompositeLine line =
        RestingLineOf(lp, lower, upper, c.lower == EndCondition::kPoint, seabed_.surface);
    // Right below its anchor a line with no span lays its grounded nodes onto one another.
    if (c.upper == EndCondition::kPoint && line.lower_on_seabed &&
        !((upper - lower).head<2>().norm() > 1e-3 * lp.length)) {
      return SagPoints(lp, lower, upper, seabed_.surface);
    }
    if (line.Uniform()) {
      return SolveLineCatenary(line.sections.front(), lower, upper).NodePositions(c.segments);
    }
    return CompositeCatenaryPoints(line, lower, upper, NodeArcLengths(lp));
  } catch (const Error&) {
    // A line to or from a free point may not reach it as a catenary from the point's start
    // position; the static solve moves the point.
    if (c.upper != EndCondition::kPoint && c.lower != EndCondition::kPoint) throw;
    return SagPoints(lp, lower, upper, seabed_.surface);
  }
}

void MooringSystem::CatenaryPointStart(std::span<const PointKinematics> fairleads,
                                       double* x) const {
  const int np = num_points();
  Eigen::Matrix3Xd start(3, np);
  for (int q = 0; q < np; ++q) start.col(q) = Vec3(x[6 * q], x[6 * q + 1], x[6 * q + 2]);
  std::vector<NetworkLine> lines;
  std::vector<Vec3> anchors;
  std::vector<Vec3> held;  // the fairleads of lines up from points
  for (const Chain& c : chains_) {
    if (c.lower != EndCondition::kPoint && c.upper != EndCondition::kPoint) continue;
    if (c.lower == EndCondition::kFree || c.upper == EndCondition::kFree) return;
    const LineProperties& lp = lines_[c.line];
    NetworkLine line;
    line.id = lp.id;
    Vec3 lower = lp.anchor, upper = fairleads[c.line].position;
    if (c.lower == EndCondition::kPoint) {
      line.lower = {NetworkEnd::Kind::kPoint, c.lower_point};
      lower = start.col(c.lower_point);
    } else {
      line.lower = {NetworkEnd::Kind::kAnchor, static_cast<int>(anchors.size())};
      anchors.push_back(lp.anchor);
    }
    if (c.upper == EndCondition::kPoint) {
      line.upper = {NetworkEnd::Kind::kPoint, c.upper_point};
      upper = start.col(c.upper_point);
    } else {
      line.upper = {NetworkEnd::Kind::kFairlead, static_cast<int>(held.size())};
      held.push_back(upper);
    }
    line.line = RestingLineOf(lp, lower, upper, c.lower == EndCondition::kPoint, seabed_.surface);
    lines.push_back(std::move(line));
  }
  std::vector<double> weights;
  for (const PointBodyProperties& body : point_bodies_) weights.push_back(body.weight);
  Eigen::Matrix3Xd at(3, static_cast<Eigen::Index>(held.size()));
  for (std::size_t f = 0; f < held.size(); ++f) at.col(static_cast<Eigen::Index>(f)) = held[f];
  PointNetwork::Equilibrium rest;
  try {
    const PointNetwork network(std::move(lines), std::move(weights), std::move(anchors),
                               static_cast<int>(held.size()), start);
    rest = network.Solve(at, false);
  } catch (const Error&) {
    return;
  }
  if (!rest.converged) return;
  for (int q = 0; q < np; ++q) {
    const Vec3 p = rest.points.col(q);
    if (!(p.z() > 0.0)) return;  // afloat: SettleLinesAndPoints says so
    const double depth = seabed_.surface.DepthAt(p.x(), p.y());
    if (!(p.z() < depth)) {
      // A point has no contact with the seabed (as in MoorDyn): it would sink through it.
      std::ostringstream msg;
      msg << "mooring.points[" << q + 1 << "]: rests below the seabed (" << p.z()
          << " m deep where the seabed is " << depth
          << " m): a point has no contact with the seabed; shorten its lines, lighten it "
             "or give it buoyancy";
      throw InputError(msg.str());
    }
  }
  for (int q = 0; q < np; ++q) {
    for (int m = 0; m < 3; ++m) x[6 * q + m] = rest.points(m, q);
  }
  for (const Chain& c : chains_) {
    if (c.lower != EndCondition::kPoint && c.upper != EndCondition::kPoint) continue;
    const LineProperties& lp = lines_[c.line];
    const Vec3 lower =
        c.lower == EndCondition::kPoint ? Vec3(rest.points.col(c.lower_point)) : lp.anchor;
    const Vec3 upper = c.upper == EndCondition::kPoint ? Vec3(rest.points.col(c.upper_point))
                                                       : fairleads[c.line].position;
    LayNodes(c, StartNodes(c, lower, upper), x);
  }
}

double MooringSystem::SettleLinesAndPoints(std::span<const PointKinematics> fairleads, double* x) {
  const int np = num_points();
  if (np == 0) return SettleChains(fairleads, x);
  for (int q = 0; q < np; ++q) std::fill(x + 6 * q + 3, x + 6 * q + 6, 0.0);
  CatenaryPointStart(fairleads, x);
  // The points' tolerance, 1e-9 EA, is a hundred times the lines' own (1e-11 EA): the
  // settled lines' end forces carry noise of that order.
  double axial_stiffness = 0.0;
  for (const LineProperties& lp : lines_) {
    for (const SectionProperties& sp : lp.sections) {
      axial_stiffness = std::max(axial_stiffness, sp.axial_stiffness);
    }
  }
  const double tolerance = 1e-9 * axial_stiffness;
  const int n = 3 * np;
  VecX residual(n), trial(n);
  // The points' net force with the lines settled to the points' positions in x.
  double lines_residual = 0.0;
  auto balance = [&](VecX* R) {
    lines_residual = SettleChains(fairleads, x);
    PointLoads(x, fairleads);
    for (int q = 0; q < np; ++q) R->segment<3>(3 * q) = point_force_[q];
    return R->lpNorm<Eigen::Infinity>();
  };
  auto worst_point = [&](const VecX& R) {
    Eigen::Index i = 0;
    R.cwiseAbs().maxCoeff(&i);
    return std::to_string(i / 3 + 1);
  };
  auto check_afloat = [&]() {
    for (int q = 0; q < np; ++q) {
      if (x[6 * q + 2] < 0.0) {
        // The geometry given, not the numerics: a tether longer than the water is deep.
        throw InputError("mooring.points[" + std::to_string(q + 1) +
                         "]: rises above the water at rest: its buoyancy is more than its "
                         "lines hold down below the surface");
      }
    }
  };
  double norm = balance(&residual);
  std::vector<double> base(x, x + state_size_);
  MatX K(n, n);
  constexpr double kStep = 1e-3;  // [m], the finite difference
  // A point whose lines are all slack has no stiffness (a buoy on a slack pendant): a
  // Levenberg-Marquardt shift (K - mu I) then steps along its force.
  double shift = 0.0;
  bool fresh = false;  // whether K is the Jacobian at x
  for (int iteration = 0; norm > tolerance; ++iteration) {
    if (iteration == 200) {
      std::ostringstream msg;
      msg << "static equilibrium of free point " << worst_point(residual)
          << " did not converge: residual force " << norm << " N after 200 iterations";
      throw Error(msg.str());
    }
    if (!fresh) {
      base.assign(x, x + state_size_);
      for (int j = 0; j < n; ++j) {
        std::copy(base.begin(), base.end(), x);
        x[6 * (j / 3) + j % 3] += kStep;
        balance(&trial);
        K.col(j) = (trial - residual) / kStep;
      }
      std::copy(base.begin(), base.end(), x);
      fresh = true;
    }
    const auto raise_shift = [&]() {
      std::copy(base.begin(), base.end(), x);
      const double scale = K.diagonal().cwiseAbs().maxCoeff() + axial_stiffness * 1e-9;
      shift = shift == 0.0 ? 1e-6 * scale : 10.0 * shift;
      if (shift > 1e6 * scale) {
        std::ostringstream msg;
        msg << "static equilibrium of free point " << worst_point(residual)
            << " did not converge: residual force " << norm << " N and no step reduces it";
        throw Error(msg.str());
      }
    };
    const VecX step = (K - shift * MatX::Identity(n, n)).fullPivLu().solve(-residual);
    // As for the lines (SettleChains): phi(lambda) = F(x + lambda step) . step, minus the
    // potential energy's slope along the step, searched for its zero.
    const double phi0 = residual.dot(step);
    if (!step.allFinite() || !(phi0 > 0.0)) {
      raise_shift();
      continue;
    }
    const auto move_to = [&](double lambda) {
      std::copy(base.begin(), base.end(), x);
      for (int j = 0; j < n; ++j) x[6 * (j / 3) + j % 3] += lambda * step(j);
      try {
        return balance(&trial);
      } catch (const Error&) {  // the lines found no equilibrium there
        return std::numeric_limits<double>::infinity();
      }
    };
    trial = residual;  // the search's phi0
    const StepSearch search = SearchAlongStep(move_to, trial, step, tolerance, norm);
    const double accepted = search.accepted;
    double trial_norm = search.norm;
    if (accepted == 0.0) {
      raise_shift();
      continue;
    }
    if (search.evaluated_at != accepted) trial_norm = move_to(accepted);
    if (!std::isfinite(trial_norm)) {
      raise_shift();
      continue;
    }
    norm = trial_norm;
    residual = trial;
    fresh = false;
    if (accepted == 1.0) shift = shift / 10.0 < 1e-12 ? 0.0 : shift / 10.0;
    check_afloat();
  }
  return std::max(norm, lines_residual);
}

double MooringSystem::SettleChains(std::span<const PointKinematics> fairleads, double* x) {
  double worst = 0.0;
  NodeJacobian J;
  for (const Chain& c : chains_) {
    if (c.lower == EndCondition::kFree || c.upper == EndCondition::kFree) {
      throw Error("static equilibrium needs both ends of every chain held");
    }
    const LineProperties& lp = lines_[c.line];
    const int S = c.num_state_nodes();
    const int first = c.first_state_node();
    double* xc = x + c.state_offset;
    for (int i = 0; i < S; ++i) std::fill(xc + 6 * i + 3, xc + 6 * i + 6, 0.0);
    // Round-off floor of the node force balance is ~1e-15 EA; ask for far less than any
    // physical effect (1e-11 EA = 2 mN for the seed chain) but well above that floor.
    // (The stiffest section sets both scales.)
    double axial_stiffness = 0.0, segment_stiffness = 0.0;
    for (const SectionProperties& sp : lp.sections) {
      axial_stiffness = std::max(axial_stiffness, sp.axial_stiffness);
      segment_stiffness = std::max(segment_stiffness, sp.axial_stiffness / sp.segment_length);
    }
    const double tolerance = 1e-11 * axial_stiffness;
    // The Levenberg-Marquardt shift starts at a millionth of one segment's axial stiffness
    // and may grow to a million times it (then a step moves a node by less than a millionth
    // of the elastic stretch its residual force would cause: no progress is possible).
    const double min_shift = 1e-6 * segment_stiffness;
    const double max_shift = 1e6 * segment_stiffness;
    Eigen::VectorXd residual(3 * S);
    // The largest node force [N]; +inf for a state with a zero-length segment (two nodes
    // on top of each other: no tangent, no force).
    auto evaluate = [&]() {
      GatherChain(c, x, fairleads);
      try {
        ComputeSegments(c);
      } catch (const RecoverableStateError&) {
        return std::numeric_limits<double>::infinity();
      }
      for (int i = 0; i < S; ++i) {
        Vec3 F;
        NodeMass M;
        NodeForce(c, first + i, &F, &M);
        residual.segment<3>(3 * i) = F;
      }
      return residual.lpNorm<Eigen::Infinity>();
    };
    const auto fail = [&](const std::string& why) {
      std::ostringstream msg;
      msg << "static equilibrium of line " << lp.id << " did not converge: " << why;
      throw Error(msg.str());
    };
    double norm = evaluate();
    if (!std::isfinite(norm)) {
      GatherChain(c, x, fairleads);
      try {
        ComputeSegments(c);
      } catch (const RecoverableStateError& e) {
        throw Error("static equilibrium of line " + std::to_string(lp.id) +
                    ": the start state is degenerate (" + e.what() + ")");
      }
      fail("the node forces of the start state are not finite");
    }
    int iteration = 0;
    double shift = 0.0;
    Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
    std::vector<Eigen::Triplet<double>> triplets;
    std::vector<double> saved(6 * S);
    while (norm > tolerance) {
      if (++iteration > kMaxStaticIterations) {
        std::ostringstream why;
        why << "residual node force " << norm << " N after " << kMaxStaticIterations
            << " Newton iterations (tolerance " << tolerance << " N)";
        fail(why.str());
      }
      const auto raise_shift = [&]() {
        shift = std::max(min_shift, 10.0 * shift);
        if (shift > max_shift) {
          std::ostringstream why;
          why << "residual node force " << norm << " N and no step reduces it (iteration "
              << iteration << ")";
          fail(why.str());
        }
      };
      triplets.clear();
      for (int i = 0; i < S; ++i) {
        NodeForceJacobian(c, first + i, Vec3::Zero(), &J);
        for (int j = std::max(0, i - 1); j <= std::min(S - 1, i + 1); ++j) {
          const Mat3& B = J.dF_dr[j - i + 1];
          for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) triplets.emplace_back(3 * i + a, 3 * j + b, B(a, b));
          }
        }
        if (shift > 0.0) {
          for (int a = 0; a < 3; ++a) triplets.emplace_back(3 * i + a, 3 * i + a, -shift);
        }
      }
      Eigen::SparseMatrix<double> K(3 * S, 3 * S);
      K.setFromTriplets(triplets.begin(), triplets.end());
      solver.compute(K);
      if (solver.info() != Eigen::Success) {  // a node with no taut segment and no contact
        raise_shift();
        continue;
      }
      const Eigen::VectorXd step = solver.solve(-residual);
      // phi(lambda) = F(x + lambda step) . step is minus the slope of the potential energy
      // along the step: positive while the energy still falls.
      const double phi0 = residual.dot(step);
      if (!step.allFinite() || !(phi0 > 0.0)) {  // not downhill: lean toward F itself
        raise_shift();
        continue;
      }
      std::copy(xc, xc + 6 * S, saved.begin());
      const auto move_to = [&](double lambda) {
        for (int i = 0; i < S; ++i) {
          for (int m = 0; m < 3; ++m) xc[6 * i + m] = saved[6 * i + m] + lambda * step(3 * i + m);
        }
        return evaluate();
      };
      const StepSearch search = SearchAlongStep(move_to, residual, step, tolerance, norm);
      const double accepted = search.accepted;
      double trial = search.norm;
      if (accepted == 0.0) {  // no progress along this step
        std::copy(saved.begin(), saved.end(), xc);
        norm = evaluate();
        raise_shift();
        continue;
      }
      if (search.evaluated_at != accepted) trial = move_to(accepted);
      if (!std::isfinite(trial)) fail("the node forces are not finite");
      norm = trial;
      // A full step is Newton doing well: relax the shift toward plain Newton.
      if (accepted == 1.0) shift = shift / 10.0 < min_shift ? 0.0 : shift / 10.0;
    }
    worst = std::max(worst, norm);
  }
  return worst;
}

std::vector<double> MooringSystem::ApplyFailure(const LineFailure& failure, const double* x,
                                                std::span<const PointKinematics> fairleads) {
  if (failure.line < 0 || failure.line >= num_lines()) {
    throw InputError("failure: no line " + std::to_string(failure.line + 1));
  }
  std::vector<Chain> next;
  std::vector<int> source;  // old chain each new chain takes its nodes from
  auto keep = [&](const Chain& c, std::size_t ci) {
    next.push_back(c);
    source.push_back(static_cast<int>(ci));
  };
  bool applied = false;
  for (std::size_t ci = 0; ci < chains_.size(); ++ci) {
    const Chain& c = chains_[ci];
    if (c.line != failure.line || applied) {
      keep(c, ci);
      continue;
    }
    if (failure.mode == FailureMode::kNode) {
      const int k = failure.node - c.first_node;
      if (k <= 0 || k >= c.segments) {
        keep(c, ci);
        continue;
      }
      // Split at node k: both pieces get a free copy of it.
      Chain lower = c;
      lower.segments = k;
      lower.upper = EndCondition::kFree;
      Chain upper = c;
      upper.first_node = failure.node;
      upper.segments = c.segments - k;
      upper.lower = EndCondition::kFree;
      keep(lower, ci);
      keep(upper, ci);
      applied = true;
      continue;
    }
    // The fairlead or the anchor lets go: that held end becomes free.
    Chain freed = c;
    const bool at_fairlead = failure.mode == FailureMode::kFairlead;
    EndCondition& end = at_fairlead ? freed.upper : freed.lower;
    if (end == (at_fairlead ? EndCondition::kFairlead : EndCondition::kAnchored) ||
        end == EndCondition::kPoint) {
      end = EndCondition::kFree;
      applied = true;
    }
    keep(freed, ci);
  }
  if (!applied) {
    std::ostringstream msg;
    msg << "failure of line " << failure.line + 1 << ": ";
    if (failure.mode == FailureMode::kNode) {
      msg << "node " << failure.node << " is not an intact internal node (1.."
          << lines_[failure.line].segments - 1 << ")";
    } else {
      msg << (failure.mode == FailureMode::kFairlead ? "fairlead" : "anchor")
          << " is already detached";
    }
    throw InputError(msg.str());
  }

  const std::vector<Chain> old = chains_;
  const int old_creep_offset = creep_offset_;
  chains_ = next;
  Layout();
  std::vector<double> x_new(state_size_);
  std::copy(x, x + 6 * num_points(), x_new.begin());  // the points keep their states
  std::copy(x + old_creep_offset, x + old_creep_offset + creep_.size(),
            x_new.begin() + creep_offset_);  // and the segments their creep
  for (size_t ci = 0; ci < chains_.size(); ++ci) {
    const Chain& oc = old[source[ci]];
    GatherNodes(oc, x, fairleads);  // pos_/vel_ now hold the old chain's nodes
    const Chain& c = chains_[ci];
    for (int k = c.first_state_node(); k <= c.last_state_node(); ++k) {
      const int old_k = c.first_node + k - oc.first_node;
      double* p = x_new.data() + c.state_offset + 6 * (k - c.first_state_node());
      for (int m = 0; m < 3; ++m) {
        p[m] = pos_[old_k](m);
        p[3 + m] = vel_[old_k](m);
      }
    }
  }
  return x_new;
}

}  // namespace moorsim::mooring_fem
