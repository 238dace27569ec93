#include "detectors/pose_agreement.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "detectors/registry.h"

namespace moorsim::detectors {

namespace {
// [m] A lever shorter than this turns no heading error the cells can see into a position
// error (0.1 rad moves the turret 10 cm).
constexpr double kLeastLever = 1.0;
}  // namespace

PoseAgreement::PoseAgreement(const PoseAgreementOptions& options) : options_(options) {
  internal::Require(options.time > 0.0 && options.threshold > 0.0 && options.explained > 0.0 &&
                        options.explained <= 1.0 && options.hold >= 0.0 && options.min_cells >= 3,
                    "pose agreement", "valid options");
  Reset();
}

void PoseAgreement::Reset() {
  mean_.resize(0);
  started_ = false;
  amplitude_ = 0.0;
  beyond_ = disagrees_ = false;
  culprit_ = SensorId::Kind::kPose;
}

bool PoseAgreement::Update(const Evidence& evidence, const std::vector<bool>& counts) {
  if (!evidence.tensions || !evidence.load) return disagrees_;
  const TensionEvidence& cells = *evidence.tensions;
  const Eigen::Index n = cells.measured.size();
  internal::Require(static_cast<Eigen::Index>(counts.size()) == n, "pose agreement",
                    "a count flag per cell");
  const std::vector<Vec3>& pulls = evidence.load->line_load;  // pulls[k + 1]: line k + 1's
  if (mean_.size() != n) mean_ = VecX::Constant(n, kNaN);
  const double dt = started_ ? evidence.t - t_ : 0.0;
  if (!started_) start_ = evidence.t;
  t_ = evidence.t;
  started_ = true;
  const double weight = 1.0 - std::exp(-dt / options_.time);

  // Each counting cell's mean residual, and the normal equations of rho_k = u_k . a.
  Eigen::Matrix2d normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d right = Eigen::Vector2d::Zero();
  double total = 0.0;  // sum of the fitted means' squares
  int fitted = 0;
  // The lever of the lines' pull, from their yaw moments M_k = r x F_k = (F_y, -F_x) . r.
  Eigen::Matrix2d lever_normal = Eigen::Matrix2d::Zero();
  Eigen::Vector2d lever_right = Eigen::Vector2d::Zero();
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto line = static_cast<std::size_t>(k) + 1;
    const double expected = cells.expected(k);
    if (!counts[line - 1] || !(expected > 0.0) || line >= pulls.size()) continue;
    const double rho = 1.0 - cells.measured(k) / expected;
    if (!std::isfinite(rho)) continue;
    double& mean = mean_(k);
    mean = std::isfinite(mean) ? mean + weight * (rho - mean) : rho;
    const Eigen::Vector2d pull = pulls[line].head<2>();
    if (!(pull.norm() > 0.0)) continue;
    const Eigen::Vector2d u = pull.normalized();
    const Eigen::Vector2d row(u.y(), -u.x());  // the moment equation divided by |F_k|
    lever_normal += row * row.transpose();
    lever_right += row * pulls[line].z() / pull.norm();
    normal += u * u.transpose();
    right += u * mean;
    total += mean * mean;
    ++fitted;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> spread(normal, Eigen::EigenvaluesOnly);
  if (fitted < options_.min_cells || spread.eigenvalues()(0) < fitted / 4.0 ||
      evidence.t - start_ < 2.0 * options_.time) {
    return disagrees_;  // no fit, or the means still settling: the judgement stands
  }
  const Eigen::Vector2d a = normal.ldlt().solve(right);
  amplitude_ = a.norm();
  // The least-squares residual sum of squares is sum rho^2 - a . (U^T rho).
  const double explained = total > 0.0 ? a.dot(right) / total : 0.0;
  // Judged wrong on the pattern; trusted again only once its amplitude is down.
  const bool beyond = disagrees_
                          ? amplitude_ >= options_.threshold / 2.0
                          : explained >= options_.explained && amplitude_ >= options_.threshold;
  if (beyond && !beyond_) beyond_since_ = evidence.t;
  beyond_ = beyond;
  const bool was = disagrees_;
  disagrees_ = disagrees_ ? beyond : beyond && evidence.t - beyond_since_ >= options_.hold;
  if (disagrees_ && !was) {
    // The rows span the plane as the pulls do (rotated a quarter turn), so this solves.
    const Eigen::Vector2d lever = lever_normal.ldlt().solve(lever_right);
    const bool along = std::abs(a.dot(lever)) >= 0.5 * amplitude_ * lever.norm();
    culprit_ = lever.norm() < kLeastLever || along ? SensorId::Kind::kGnss : SensorId::Kind::kPose;
  }
  return disagrees_;
}

}  // namespace moorsim::detectors
