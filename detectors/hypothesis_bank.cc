#include "detectors/hypothesis_bank.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/seabed.h"

namespace moorsim::detectors {
namespace internal {
namespace {

/// Step of the central difference that gives the node slopes [m]. The solver's span
/// residual is ~1e-12 L ~ 2e-9 m, so the rounding part of the slope error is ~1e-7
/// relative; the truncation part, H''' step^2 / 6, is smaller still.
constexpr double kSlopeStep = 1e-2;

std::string LineKey(int line_id) { return "mooring.lines[" + std::to_string(line_id) + "]"; }

// "intact", "line 6", "lines 2+5".
std::string FailedLabel(const std::vector<int>& failed) {
  if (failed.empty()) return "intact";
  std::string label = failed.size() == 1 ? "line " : "lines ";
  for (std::size_t i = 0; i < failed.size(); ++i) {
    if (i > 0) label += "+";
    label += std::to_string(failed[i]);
  }
  return label;
}

[[noreturn]] void ThrowOption(const std::string& key, double value, const std::string& rule) {
  std::ostringstream out;
  out.precision(10);
  out << key << " = " << value << ": " << rule;
  throw InputError(out.str());
}

// H and V at the fairlead [N].
std::pair<double, double> Tensions(const mooring_fem::CompositeLine& line, double span,
                                   double height) {
  if (line.Uniform()) {
    const auto s = mooring_fem::SolveCatenary(line.sections.front(), span, height);
    return {s.horizontal_tension, s.vertical_tension};
  }
  const auto s = mooring_fem::SolveCompositeCatenary(line, span, height);
  return {s.horizontal_tension, s.vertical_tension};
}

bool Solvable(const mooring_fem::CompositeLine& line, double span, double height) {
  try {
    Tensions(line, span, height);
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace
}  // namespace internal

// ---------------------------------------------------------------------------------------
// LineForceTable

LineForceTable::LineForceTable(int line_id, const mooring_fem::CompositeLine& line,
                               const Vec3& anchor, const Vec3& fairlead_body, double fairlead_depth,
                               const LineForceTableOptions& options)
    : line_id_(line_id),
      line_(line),
      anchor_(anchor),
      fairlead_body_(fairlead_body),
      fairlead_depth_(fairlead_depth) {
  using internal::ThrowOption;
  const std::string key = internal::LineKey(line_id);
  if (!(std::isfinite(options.span_margin) && options.span_margin >= 0.0)) {
    ThrowOption("hypothesis_bank.table.span_margin", options.span_margin,
                "must be finite and >= 0");
  }
  if (!(std::isfinite(options.span_step) && options.span_step > 0.0)) {
    ThrowOption("hypothesis_bank.table.span_step", options.span_step, "must be finite and > 0");
  }
  if (line.sections.empty()) throw InputError(key + ": the line has no section");
  double length = 0.0;
  for (const mooring_fem::CatenaryLineProperties& section : line.sections) {
    if (!(std::isfinite(section.length) && section.length > 0.0)) {
      ThrowOption(key + ".length", section.length, "must be finite and > 0");
    }
    if (!(std::isfinite(section.weight_per_length) &&
          (section.weight_per_length > 0.0 || !line.Uniform()))) {
      ThrowOption(key + ".weight_per_length", section.weight_per_length,
                  "must be finite and > 0 (a line heavier than the water it displaces)");
    }
    if (!(std::isfinite(section.axial_stiffness) && section.axial_stiffness > 0.0)) {
      ThrowOption(key + ".axial_stiffness", section.axial_stiffness, "must be finite and > 0");
    }
    length += section.length;
  }
  if (!anchor.allFinite() || !fairlead_body.allFinite()) {
    throw InputError(key + ": anchor and fairlead must be finite");
  }
  if (!(std::isfinite(fairlead_depth) && fairlead_depth < anchor.z())) {
    std::ostringstream out;
    out << key << ": fairlead depth " << fairlead_depth
        << " m must be above the anchor (z = " << anchor.z() << " m, NED)";
    throw InputError(out.str());
  }

  const double h = height();
  nominal_span_ = (anchor.head<2>() - fairlead_body.head<2>()).norm();
  const double reach = options.span_margin + fairlead_body.head<2>().norm();
  if (!internal::Solvable(line, nominal_span_, h)) {
    std::ostringstream out;
    out << key << ": the catenary has no solution at the neutral pose (span " << nominal_span_
        << " m, height " << h << " m, length " << length << " m)";
    throw InputError(out.str());
  }
  span_min_ = std::max(nominal_span_ - reach, 2.0 * internal::kSlopeStep);
  span_max_ = nominal_span_ + reach;
  if (!internal::Solvable(line, span_max_ + internal::kSlopeStep, h)) {
    // Largest reachable span by bisection, then 1 m short of it so that the slope's
    // difference step and rounding stay inside.
    double lo = nominal_span_;
    double hi = span_max_ + internal::kSlopeStep;
    while (hi - lo > 1e-3) {
      const double mid = 0.5 * (lo + hi);
      (internal::Solvable(line, mid, h) ? lo : hi) = mid;
    }
    span_max_ = std::max(nominal_span_, lo - 1.0);
  }
  span_min_ = std::min(span_min_, span_max_);

  const int intervals =
      std::max(1, static_cast<int>(std::ceil((span_max_ - span_min_) / options.span_step)));
  step_ = (span_max_ - span_min_) / intervals;
  if (!(step_ > 0.0)) step_ = 1.0;  // degenerate range: a single point, extrapolated
  const int nodes = intervals + 1;
  h_.resize(nodes);
  dh_.resize(nodes);
  v_.resize(nodes);
  dv_.resize(nodes);
  try {
    for (int i = 0; i < nodes; ++i) {
      const double s = i == intervals ? span_max_ : span_min_ + i * step_;
      const auto mid = internal::Tensions(line, s, h);
      const auto plus = internal::Tensions(line, s + internal::kSlopeStep, h);
      const auto minus = internal::Tensions(line, s - internal::kSlopeStep, h);
      h_[i] = mid.first;
      v_[i] = mid.second;
      dh_[i] = (plus.first - minus.first) / (2.0 * internal::kSlopeStep);
      dv_[i] = (plus.second - minus.second) / (2.0 * internal::kSlopeStep);
    }
  } catch (const Error& error) {
    throw InputError(key + ": tabulating the catenary failed: " + error.what());
  }
}

double LineForceTable::Interpolate(const std::vector<double>& values,
                                   const std::vector<double>& slopes, double span,
                                   double* d_dspan) const {
  const int last = static_cast<int>(values.size()) - 1;
  double value = 0.0;
  double slope = 0.0;
  if (span <= span_min_) {
    value = values[0] + slopes[0] * (span - span_min_);
    slope = slopes[0];
  } else if (span >= span_max_) {
    value = values[last] + slopes[last] * (span - span_max_);
    slope = slopes[last];
  } else {
    const double u = (span - span_min_) / step_;
    const int i = std::min(static_cast<int>(u), last - 1);
    const double t = u - i;
    const double t2 = t * t;
    const double t3 = t2 * t;
    // Cubic Hermite basis on [0, 1] and its derivative.
    const double h00 = 2.0 * t3 - 3.0 * t2 + 1.0;
    const double h10 = t3 - 2.0 * t2 + t;
    const double h01 = -2.0 * t3 + 3.0 * t2;
    const double h11 = t3 - t2;
    const double d00 = 6.0 * t2 - 6.0 * t;
    const double d10 = 3.0 * t2 - 4.0 * t + 1.0;
    const double d01 = -d00;
    const double d11 = 3.0 * t2 - 2.0 * t;
    const double y0 = values[i];
    const double y1 = values[i + 1];
    const double m0 = slopes[i] * step_;
    const double m1 = slopes[i + 1] * step_;
    value = h00 * y0 + h10 * m0 + h01 * y1 + h11 * m1;
    slope = (d00 * y0 + d10 * m0 + d01 * y1 + d11 * m1) / step_;
  }
  if (value < 0.0) {  // a slack line pushes nothing
    value = 0.0;
    slope = 0.0;
  }
  if (d_dspan != nullptr) *d_dspan = slope;
  return value;
}

double LineForceTable::HorizontalTension(double span, double* d_dspan) const {
  return Interpolate(h_, dh_, span, d_dspan);
}

double LineForceTable::VerticalTension(double span, double* d_dspan) const {
  return Interpolate(v_, dv_, span, d_dspan);
}

// ---------------------------------------------------------------------------------------
// QuasiStaticMooring

QuasiStaticMooring::QuasiStaticMooring(std::vector<std::shared_ptr<const LineForceTable>> lines,
                                       std::optional<TurretModel> turret,
                                       std::vector<AttachedNetwork> networks)
    : lines_(std::move(lines)), turret_(turret), networks_(std::move(networks)) {
  for (const AttachedNetwork& attached : networks_) {
    if (attached.network == nullptr ||
        attached.fairlead_body.size() !=
            static_cast<std::size_t>(attached.network->num_fairleads()) ||
        attached.fairlead_depth.size() != attached.fairlead_body.size()) {
      throw Error("QuasiStaticMooring: a network without its fairleads");
    }
  }
  if (turret_ && !(turret_->centre.allFinite() && std::isfinite(turret_->heading))) {
    throw InputError("hypothesis_bank.turret: centre and heading must be finite");
  }
  for (const auto& line : lines_) {
    if (line == nullptr) throw Error("QuasiStaticMooring: null line table");
  }
}

namespace internal {
namespace {

// The fairlead's offset r from (x, y) and the lever of its force (QuasiStaticMooring).
void FairleadOffset(const std::optional<TurretModel>& turret, const Eigen::Vector2d& rb,
                    const Vec3& eta, Eigen::Vector2d* r, Eigen::Vector2d* lever) {
  const double c = std::cos(eta.z());
  const double s = std::sin(eta.z());
  if (turret) {
    const Eigen::Vector2d& centre = turret->centre;
    *lever = Eigen::Vector2d(c * centre.x() - s * centre.y(), s * centre.x() + c * centre.y());
    const double ct = std::cos(turret->heading), st = std::sin(turret->heading);
    const Eigen::Vector2d arm = rb - centre;
    *r = *lever + Eigen::Vector2d(ct * arm.x() - st * arm.y(), st * arm.x() + ct * arm.y());
  } else {
    *r = Eigen::Vector2d(c * rb.x() - s * rb.y(), s * rb.x() + c * rb.y());  // R rb
    *lever = *r;
  }
}

// The network's fairleads in the Earth frame with the vessel at eta; their levers too.
Eigen::Matrix3Xd NetworkFairleads(const std::optional<TurretModel>& turret,
                                  const AttachedNetwork& attached, const Vec3& eta,
                                  Eigen::Matrix2Xd* levers = nullptr) {
  const int nf = static_cast<int>(attached.fairlead_body.size());
  Eigen::Matrix3Xd fairleads(3, nf);
  if (levers != nullptr) levers->resize(2, nf);
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector2d r, lever;
    FairleadOffset(turret, attached.fairlead_body[static_cast<std::size_t>(f)].head<2>(), eta, &r,
                   &lever);
    fairleads.col(f) << eta.x() + r.x(), eta.y() + r.y(),
        attached.fairlead_depth[static_cast<std::size_t>(f)];
    if (levers != nullptr) levers->col(f) = lever;
  }
  return fairleads;
}

}  // namespace
}  // namespace internal

void QuasiStaticMooring::FairleadOffset(const Eigen::Vector2d& fairlead_body, const Vec3& eta,
                                        Eigen::Vector2d* r, Eigen::Vector2d* lever) const {
  internal::FairleadOffset(turret_, fairlead_body, eta, r, lever);
}

int QuasiStaticMooring::IndexOf(int line_id) const {
  for (int i = 0; i < num_lines(); ++i) {
    if (lines_[static_cast<std::size_t>(i)]->line_id() == line_id) return i;
  }
  return -1;
}

Vec3 QuasiStaticMooring::NetworkLoad(const Vec3& eta, Mat3* J_load_eta) const {
  Vec3 load = Vec3::Zero();
  if (J_load_eta != nullptr) J_load_eta->setZero();
  Eigen::Matrix2Xd levers;
  for (const AttachedNetwork& attached : networks_) {
    const Eigen::Matrix3Xd fairleads = internal::NetworkFairleads(turret_, attached, eta, &levers);
    const mooring_fem::PointNetwork::Equilibrium eq =
        attached.network->Solve(fairleads, J_load_eta != nullptr);
    const int nf = static_cast<int>(fairleads.cols());
    for (int f = 0; f < nf; ++f) {
      const Eigen::Vector2d force = eq.fairlead_forces.col(f).head<2>();
      const Eigen::Vector2d lever = levers.col(f);
      load += Vec3(force.x(), force.y(), lever.x() * force.y() - lever.y() * force.x());
      if (J_load_eta == nullptr) continue;
      // dF_f/deta = sum_g dF_f/dp_g [I, dp_g/dpsi], dp_g/dpsi = perp(lever_g).
      Eigen::Matrix<double, 2, 3> dF = Eigen::Matrix<double, 2, 3>::Zero();
      for (int g = 0; g < nf; ++g) {
        const Eigen::Matrix2d block = eq.d_horizontal.block<2, 2>(2 * f, 2 * g);
        dF.leftCols<2>() += block;
        dF.col(2) += block * Eigen::Vector2d(-levers(1, g), levers(0, g));
      }
      Mat3& J = *J_load_eta;
      J.topRows<2>() += dF;
      for (int k = 0; k < 3; ++k) J(2, k) += lever.x() * dF(1, k) - lever.y() * dF(0, k);
      // The lever turns with the hull: d lever/dpsi = perp(lever).
      J(2, 2) += -lever.y() * force.y() - lever.x() * force.x();
    }
  }
  return load;
}

double QuasiStaticMooring::LineTension(int index, const Vec3& eta) const {
  const LineForceTable& table = *lines_[index];
  Eigen::Vector2d r, lever;
  FairleadOffset(table.fairlead_body().head<2>(), eta, &r, &lever);
  const double span = (table.anchor().head<2>() - eta.head<2>() - r).norm();
  return std::hypot(table.HorizontalTension(span), table.VerticalTension(span));
}

void QuasiStaticMooring::UpperTensions(const Vec3& eta, Eigen::Ref<VecX> by_line) const {
  const auto set = [&](int id, double tension) {
    if (id >= 1 && id <= by_line.size()) by_line(id - 1) = tension;
  };
  for (int i = 0; i < num_lines(); ++i) set(lines_[i]->line_id(), LineTension(i, eta));
  for (const AttachedNetwork& attached : networks_) {
    const mooring_fem::PointNetwork::Equilibrium eq =
        attached.network->Solve(internal::NetworkFairleads(turret_, attached, eta), false);
    const std::vector<mooring_fem::NetworkLine>& lines = attached.network->lines();
    for (std::size_t l = 0; l < lines.size(); ++l) set(lines[l].id, eq.upper_tension[l]);
  }
}

Vec3 QuasiStaticMooring::LineLoad(int index, const Vec3& eta, Mat3* J_load_eta) const {
  const LineForceTable& table = *lines_[index];
  Eigen::Vector2d r, lever;
  FairleadOffset(table.fairlead_body().head<2>(), eta, &r, &lever);
  const Eigen::Vector2d dr_dpsi(-lever.y(), lever.x());                    // = d lever / d psi
  const Eigen::Vector2d d = table.anchor().head<2>() - eta.head<2>() - r;  // fairlead->anchor
  const double span = d.norm();
  if (J_load_eta != nullptr) J_load_eta->setZero();
  if (!(span > 0.0)) return Vec3::Zero();
  const Eigen::Vector2d u = d / span;
  double dh = 0.0;
  const double h = table.HorizontalTension(span, J_load_eta != nullptr ? &dh : nullptr);
  const Eigen::Vector2d force = h * u;
  const double moment = lever.x() * force.y() - lever.y() * force.x();
  if (J_load_eta != nullptr) {
    // dF/dp with p the fairlead; dp/d(x, y) = I, dp/dpsi = dr_dpsi.
    const Eigen::Matrix2d uu = u * u.transpose();
    const Eigen::Matrix2d dF_dp = -dh * uu - (h / span) * (Eigen::Matrix2d::Identity() - uu);
    Mat3& J = *J_load_eta;
    J.topLeftCorner<2, 2>() = dF_dp;
    const Eigen::Vector2d dF_dpsi = dF_dp * dr_dpsi;
    J.block<2, 1>(0, 2) = dF_dpsi;
    // Mz = lever x F: d/d(x, y) = lever x dF/d(x, y); d/dpsi = dlever/dpsi x F + lever x
    // dF/dpsi.
    for (int k = 0; k < 2; ++k) J(2, k) = lever.x() * dF_dp(1, k) - lever.y() * dF_dp(0, k);
    J(2, 2) = dr_dpsi.x() * force.y() - dr_dpsi.y() * force.x() + lever.x() * dF_dpsi.y() -
              lever.y() * dF_dpsi.x();
  }
  return Vec3(force.x(), force.y(), moment);
}

Vec3 QuasiStaticMooring::Load(const Vec3& eta, Mat3* J_load_eta) const {
  Vec3 load = Vec3::Zero();
  if (J_load_eta != nullptr) J_load_eta->setZero();
  Mat3 J_line;
  for (int i = 0; i < num_lines(); ++i) {
    load += LineLoad(i, eta, J_load_eta != nullptr ? &J_line : nullptr);
    if (J_load_eta != nullptr) *J_load_eta += J_line;
  }
  if (!networks_.empty()) {
    load += NetworkLoad(eta, J_load_eta != nullptr ? &J_line : nullptr);
    if (J_load_eta != nullptr) *J_load_eta += J_line;
  }
  return load;
}

Vec3 QuasiStaticMooring::LoadBody(const Vec3& eta, Mat3* J_load_eta) const {
  Mat3 J_earth;
  const Vec3 earth = Load(eta, J_load_eta != nullptr ? &J_earth : nullptr);
  const double c = std::cos(eta.z());
  const double s = std::sin(eta.z());
  // R^T F: X = c Fx + s Fy, Y = -s Fx + c Fy.
  const Vec3 body(c * earth.x() + s * earth.y(), -s * earth.x() + c * earth.y(), earth.z());
  if (J_load_eta != nullptr) {
    Mat3& J = *J_load_eta;
    J.row(0) = c * J_earth.row(0) + s * J_earth.row(1);
    J.row(1) = -s * J_earth.row(0) + c * J_earth.row(1);
    J.row(2) = J_earth.row(2);
    J(0, 2) += -s * earth.x() + c * earth.y();
    J(1, 2) += -c * earth.x() - s * earth.y();
  }
  return body;
}

// ---------------------------------------------------------------------------------------
// Models

LowFrequencyModel SeedLowFrequencyModel() {
  constexpr double kMass = 1.0041e8;      // [kg]
  constexpr double kA11 = 7.9427e6;       // [kg]
  constexpr double kA22 = 6.4432e7;       // [kg]
  constexpr double kA66 = 1.4513e11;      // [kg m^2]
  constexpr double kYawRadius = 54.0;     // [m]
  const Vec3 periods(50.0, 100.0, 20.0);  // [s]
  LowFrequencyModel model;
  model.mass =
      Vec3(kMass + kA11, kMass + kA22, kMass * kYawRadius * kYawRadius + kA66).asDiagonal();
  model.damping = model.mass.diagonal().cwiseQuotient(periods).asDiagonal();
  return model;
}

Mat3 MooringDampingMatrix(const Mat3& stiffness, const Mat3& mass, const Vec3& ratio) {
  for (int i = 0; i < 3; ++i) {
    if (!(std::isfinite(ratio(i)) && ratio(i) >= 0.0)) {
      internal::ThrowOption("mooring_damping_ratio[" + std::to_string(i + 1) + "]", ratio(i),
                            "must be finite and >= 0");
    }
  }
  Mat3 damping = Mat3::Zero();
  for (int i = 0; i < 3; ++i) {
    damping(i, i) =
        2.0 * ratio(i) * std::sqrt(std::max(stiffness(i, i), 0.0) * std::max(mass(i, i), 0.0));
  }
  return damping;
}

// ---------------------------------------------------------------------------------------
// HypothesisBank

HypothesisBank::HypothesisBank(const mooring_fem::MooringParameters& spec,
                               const HypothesisBankOptions& options) {
  if (spec.lines.empty()) throw InputError("mooring.lines: the bank needs at least one line");
  if (!std::isfinite(options.moored_heave)) {
    internal::ThrowOption("hypothesis_bank.moored_heave", options.moored_heave, "must be finite");
  }
  if (!options.reference_pose.allFinite()) {
    throw InputError("hypothesis_bank.reference_pose: must be finite");
  }
  reference_pose_ = options.reference_pose;
  turret_ = options.turret;
  const mooring_fem::SeabedSurface seabed(spec.seabed, spec.water.depth);
  for (const mooring_fem::LineParameters& line_spec : spec.lines) {
    if (line_spec.lower_point >= 0 || line_spec.upper_point >= 0) {
      tables_.push_back(nullptr);  // in a network
      network_lines_.push_back(line_spec.id);
      continue;
    }
    const mooring_fem::LineProperties p = mooring_fem::MakeLineProperties(spec, line_spec);
    // The seabed's rise from the anchor toward the fairlead with the vessel at the
    // reference pose (a turret's rotation moves the fairlead too little to matter).
    const Vec3 fairlead = mooring_fem::FairleadPosition(
        {reference_pose_.x(), reference_pose_.y(), reference_pose_.z()}, p.fairlead_body);
    tables_.push_back(std::make_shared<const LineForceTable>(
        p.id, mooring_fem::CatenaryLineOf(p, seabed.RiseAlong(p.anchor, fairlead)), p.anchor,
        p.fairlead_body, p.fairlead_body.z() + options.moored_heave, options.table));
  }
  const int n = num_lines();
  std::vector<std::vector<int>> failed_sets = {{}};
  for (int k = 1; k <= n; ++k) failed_sets.push_back({k});
  if (options.include_pairs) {
    for (int i = 1; i <= n; ++i) {
      for (int j = i + 1; j <= n; ++j) failed_sets.push_back({i, j});
    }
  }
  if (!network_lines_.empty()) BuildNetworks(spec, options, failed_sets);
  for (std::vector<int>& failed : failed_sets) Add(std::move(failed));
}

const LineForceTable& HypothesisBank::table(int index) const {
  const std::shared_ptr<const LineForceTable>& table = tables_.at(index);
  if (table == nullptr) {
    throw Error("line " + std::to_string(index + 1) +
                " ends at a free point: its load is its network's");
  }
  return *table;
}

void HypothesisBank::BuildNetworks(const mooring_fem::MooringParameters& spec,
                                   const HypothesisBankOptions& options,
                                   const std::vector<std::vector<int>>& failed_sets) {
  const mooring_fem::SeabedSurface seabed(spec.seabed, spec.water.depth);
  const int np = static_cast<int>(spec.points.size());
  std::vector<mooring_fem::LineProperties> props;
  for (const mooring_fem::LineParameters& line_spec : spec.lines) {
    props.push_back(mooring_fem::MakeLineProperties(spec, line_spec));
  }
  const auto& point_of = [&](int id) {
    const mooring_fem::LineProperties& p = props[static_cast<std::size_t>(id - 1)];
    return p.lower_point >= 0 ? p.lower_point : p.upper_point;
  };

  // A network: the lines of one connected set of points that reaches both an anchor and
  // the vessel (a set that reaches no anchor only hangs from the vessel: no horizontal
  // load; one that reaches no fairlead does not load the vessel at all).
  struct Unique {
    std::vector<int> ids;     // its lines, ascending
    std::vector<int> points;  // global indices, in local order
    std::shared_ptr<mooring_fem::PointNetwork> direct;
    AttachedNetwork attached;
  };
  std::vector<Unique> uniques;
  std::vector<std::vector<int>> set_networks;  // per failed set: indices into uniques
  std::vector<Vec3> rest(spec.points.size());
  for (int p = 0; p < np; ++p) rest[static_cast<std::size_t>(p)] = spec.points[p].position;
  const double weight_per_kg = spec.water.gravity;

  for (std::size_t set = 0; set < failed_sets.size(); ++set) {
    const std::vector<int>& failed = failed_sets[set];
    std::vector<int> intact;
    for (int id : network_lines_) {
      if (std::find(failed.begin(), failed.end(), id) == failed.end()) intact.push_back(id);
    }
    // Union-find over the points.
    std::vector<int> parent(static_cast<std::size_t>(np));
    for (int p = 0; p < np; ++p) parent[static_cast<std::size_t>(p)] = p;
    const auto root = [&](int p) {
      while (parent[static_cast<std::size_t>(p)] != p) p = parent[static_cast<std::size_t>(p)];
      return p;
    };
    for (int id : intact) {
      const mooring_fem::LineProperties& lp = props[static_cast<std::size_t>(id - 1)];
      if (lp.lower_point >= 0 && lp.upper_point >= 0) {
        parent[static_cast<std::size_t>(root(lp.lower_point))] = root(lp.upper_point);
      }
    }
    std::vector<int> networks;
    for (int r = 0; r < np; ++r) {
      if (root(r) != r) continue;
      std::vector<int> ids;
      bool anchored = false, attached = false;
      for (int id : intact) {
        if (root(point_of(id)) != r) continue;
        ids.push_back(id);
        const mooring_fem::LineProperties& lp = props[static_cast<std::size_t>(id - 1)];
        anchored = anchored || lp.lower_point < 0;
        attached = attached || lp.upper_point < 0;
      }
      if (!anchored || !attached) continue;
      const auto found = std::find_if(uniques.begin(), uniques.end(),
                                      [&](const Unique& u) { return u.ids == ids; });
      if (found != uniques.end()) {
        networks.push_back(static_cast<int>(found - uniques.begin()));
        continue;
      }
      // A new network, solved straight from the catenaries at the reference pose.
      Unique u;
      u.ids = ids;
      std::vector<int> local(static_cast<std::size_t>(np), -1);
      std::vector<mooring_fem::NetworkLine> lines;
      std::vector<Vec3> anchors;
      const auto point_end = [&](int p) {
        if (local[static_cast<std::size_t>(p)] < 0) {
          local[static_cast<std::size_t>(p)] = static_cast<int>(u.points.size());
          u.points.push_back(p);
        }
        return mooring_fem::NetworkEnd{mooring_fem::NetworkEnd::Kind::kPoint,
                                       local[static_cast<std::size_t>(p)]};
      };
      for (int id : ids) {
        const mooring_fem::LineProperties& lp = props[static_cast<std::size_t>(id - 1)];
        mooring_fem::NetworkLine line;
        line.id = id;
        if (lp.lower_point >= 0) {
          line.lower = point_end(lp.lower_point);
        } else {
          line.lower = {mooring_fem::NetworkEnd::Kind::kAnchor, static_cast<int>(anchors.size())};
          anchors.push_back(lp.anchor);
        }
        if (lp.upper_point >= 0) {
          line.upper = point_end(lp.upper_point);
        } else {
          line.upper = {mooring_fem::NetworkEnd::Kind::kFairlead,
                        static_cast<int>(u.attached.fairlead_body.size())};
          u.attached.fairlead_body.push_back(lp.fairlead_body);
          u.attached.fairlead_depth.push_back(lp.fairlead_body.z() + options.moored_heave);
        }
        // Where the line runs at the start: from its anchor or lower point to its upper
        // point or fairlead (the vessel at the origin).
        const Vec3 lower =
            lp.lower_point >= 0 ? rest[static_cast<std::size_t>(lp.lower_point)] : lp.anchor;
        const Vec3 upper =
            lp.upper_point >= 0 ? rest[static_cast<std::size_t>(lp.upper_point)] : lp.fairlead_body;
        line.line = mooring_fem::RestingLineOf(lp, lower, upper, lp.lower_point >= 0, seabed);
        lines.push_back(std::move(line));
      }
      std::vector<double> weights;
      Eigen::Matrix3Xd start(3, static_cast<Eigen::Index>(u.points.size()));
      for (std::size_t k = 0; k < u.points.size(); ++k) {
        const mooring_fem::FreePoint& point = spec.points[static_cast<std::size_t>(u.points[k])];
        weights.push_back((point.body.mass - spec.water.density * point.body.volume) *
                          weight_per_kg);
        start.col(static_cast<Eigen::Index>(k)) = rest[static_cast<std::size_t>(u.points[k])];
      }
      const int nf = static_cast<int>(u.attached.fairlead_body.size());
      u.direct = std::make_shared<mooring_fem::PointNetwork>(std::move(lines), std::move(weights),
                                                             std::move(anchors), nf, start);
      std::string where = "lines";
      for (int id : ids) where += " " + std::to_string(id);
      if (!failed.empty()) where += " (" + internal::FailedLabel(failed) + " failed)";
      mooring_fem::PointNetwork::Equilibrium eq;
      eq.points = start;
      try {
        eq = u.direct->Solve(internal::NetworkFairleads(turret_, u.attached, reference_pose_),
                             false);
      } catch (const Error&) {
        eq.converged = false;
      }
      // A point that sinks to the seabed (or below its anchors, where no catenary reaches)
      // is outside the model; so is one that finds no rest at all.
      for (std::size_t k = 0; k < u.points.size(); ++k) {
        const Vec3 q = eq.points.col(static_cast<Eigen::Index>(k));
        if (q.z() > seabed.DepthAt(q.x(), q.y()) - (eq.converged ? 1e-2 : 1.0)) {
          throw InputError("mooring.points[" + std::to_string(u.points[k] + 1) + "]" +
                           ": sinks to the seabed; the detectors' quasi-static model holds "
                           "free points in the water");
        }
      }
      if (!eq.converged) {
        throw InputError(
            "mooring.points: the detectors' quasi-static model finds no rest for the "
            "free points of " +
            where + " with the vessel at its reference pose");
      }
      for (std::size_t k = 0; k < u.points.size(); ++k) {
        if (set == 0) rest[static_cast<std::size_t>(u.points[k])] = eq.points.col(k);
      }
      *u.direct = u.direct->WithTables(
          std::vector<std::shared_ptr<const mooring_fem::LineEndTable>>(u.ids.size()), eq.points);
      networks.push_back(static_cast<int>(uniques.size()));
      uniques.push_back(std::move(u));
    }
    set_networks.push_back(std::move(networks));
  }

  // Where each line's ends go with the vessel offset up to the tables' margin and turned,
  // in every network it is in: the range of its end-tension table.
  struct Extent {
    double chord_min = 1e300, chord_max = -1e300, angle_min = 1e300, angle_max = -1e300;
  };
  std::vector<Extent> extent(spec.lines.size());
  const double margin = options.table.span_margin;
  std::vector<Vec3> poses = {reference_pose_, reference_pose_ + Vec3(0.0, 0.0, 0.1),
                             reference_pose_ - Vec3(0.0, 0.0, 0.1)};
  for (double radius : {0.5 * margin, margin}) {
    for (int k = 0; k < 8; ++k) {
      const double angle = k * std::numbers::pi / 4.0;
      poses.push_back(reference_pose_ +
                      Vec3(radius * std::cos(angle), radius * std::sin(angle), 0.0));
    }
  }
  for (const Unique& u : uniques) {
    for (const Vec3& pose : poses) {
      const Eigen::Matrix3Xd fairleads = internal::NetworkFairleads(turret_, u.attached, pose);
      mooring_fem::PointNetwork::Equilibrium eq;
      try {
        eq = u.direct->Solve(fairleads, false);
      } catch (const Error&) {
        continue;
      }
      if (!eq.converged) continue;
      for (const mooring_fem::NetworkLine& line : u.direct->lines()) {
        const auto end = [&](const mooring_fem::NetworkEnd& e) -> Vec3 {
          if (e.kind == mooring_fem::NetworkEnd::Kind::kPoint) return eq.points.col(e.index);
          if (e.kind == mooring_fem::NetworkEnd::Kind::kFairlead) return fairleads.col(e.index);
          return props[static_cast<std::size_t>(line.id - 1)].anchor;
        };
        const Vec3 a = end(line.lower), b = end(line.upper);
        Extent& x = extent[static_cast<std::size_t>(line.id - 1)];
        const double span = (b - a).head<2>().norm(), height = a.z() - b.z();
        const double chord = std::hypot(span, height), angle = std::atan2(height, span);
        x.chord_min = std::min(x.chord_min, chord);
        x.chord_max = std::max(x.chord_max, chord);
        x.angle_min = std::min(x.angle_min, angle);
        x.angle_max = std::max(x.angle_max, angle);
      }
    }
  }
  std::vector<std::shared_ptr<const mooring_fem::LineEndTable>> tables(spec.lines.size());
  for (const Unique& u : uniques) {
    for (const mooring_fem::NetworkLine& line : u.direct->lines()) {
      std::shared_ptr<const mooring_fem::LineEndTable>& table =
          tables[static_cast<std::size_t>(line.id - 1)];
      if (table != nullptr) continue;
      const Extent& x = extent[static_cast<std::size_t>(line.id - 1)];
      std::string problem;
      // Padded by a quarter of the range, at least 2 m and 0.02 rad; less where the
      // catenary has no solution that far out.
      for (double pad : {1.0, 0.5, 0.25, 0.0}) {
        const double pc = pad * std::max(0.25 * (x.chord_max - x.chord_min), 2.0);
        const double pa = pad * std::max(0.25 * (x.angle_max - x.angle_min), 0.02);
        mooring_fem::LineEndTable::Range range;
        range.chord_min = std::max(x.chord_min - pc, 0.1);
        range.chord_max = std::max(x.chord_max + pc, range.chord_min + 0.1);
        range.angle_min = std::max(x.angle_min - pa, line.line.lower_on_seabed ? 1e-3 : -1.5);
        range.angle_max = std::min(std::max(x.angle_max + pa, range.angle_min + 1e-3), 1.57);
        try {
          table = std::make_shared<const mooring_fem::LineEndTable>(line.line, range,
                                                                    options.table.network_step);
          break;
        } catch (const Error& e) {
          problem = e.what();
        }
      }
      if (table == nullptr) {
        throw InputError(internal::LineKey(line.id) +
                         ": the detectors' quasi-static model cannot tabulate its end "
                         "tensions: " +
                         problem);
      }
    }
  }
  for (Unique& u : uniques) {
    std::vector<std::shared_ptr<const mooring_fem::LineEndTable>> own;
    for (const mooring_fem::NetworkLine& line : u.direct->lines()) {
      own.push_back(tables[static_cast<std::size_t>(line.id - 1)]);
    }
    u.attached.network = std::make_shared<const mooring_fem::PointNetwork>(
        u.direct->WithTables(own, u.direct->rest()));
  }
  networks_.clear();
  for (const std::vector<int>& set : set_networks) {
    std::vector<AttachedNetwork> attached;
    for (int k : set) attached.push_back(uniques[static_cast<std::size_t>(k)].attached);
    networks_.push_back(std::move(attached));
  }
}

void HypothesisBank::Add(std::vector<int> failed) {
  std::vector<std::shared_ptr<const LineForceTable>> intact;
  for (const auto& table : tables_) {
    if (table != nullptr &&
        std::find(failed.begin(), failed.end(), table->line_id()) == failed.end()) {
      intact.push_back(table);
    }
  }
  std::vector<AttachedNetwork> networks;
  if (hypotheses_.size() < networks_.size()) networks = networks_[hypotheses_.size()];
  Hypothesis hypothesis;
  hypothesis.failed = std::move(failed);
  hypothesis.mooring = QuasiStaticMooring(std::move(intact), turret_, std::move(networks));
  Mat3 J;
  hypothesis.mooring.Load(reference_pose_, &J);
  hypothesis.stiffness = -J;
  hypotheses_.push_back(std::move(hypothesis));
}

std::string HypothesisBank::Label(int h) const {
  return internal::FailedLabel(hypotheses_.at(h).failed);
}

int HypothesisBank::Find(std::span<const int> lines) const {
  std::vector<int> wanted(lines.begin(), lines.end());
  std::sort(wanted.begin(), wanted.end());
  for (int h = 0; h < size(); ++h) {
    if (hypotheses_[h].failed == wanted) return h;
  }
  return -1;
}

Mat3 HypothesisBank::MooringDamping(int h, const Mat3& mass, const Vec3& ratio) const {
  return MooringDampingMatrix(stiffness(h), mass, ratio);
}

}  // namespace moorsim::detectors
