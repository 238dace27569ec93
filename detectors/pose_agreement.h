// Whether the pose agrees with the load cells: a check on the GNSS and the gyro together that
// their own readings cannot make.
//
// Each cell's expected reading is the intact model's tension with the vessel where the
// filter puts it (Evidence::tensions). If the filter puts the turret a few metres from where
// it is, every cell disagrees with its expectation in one pattern: the lines the estimate
// stretches too far read below it, the lines opposite above it. With u_k the horizontal
// direction of line k's pull and rho_k = 1 - measured_k / expected_k (its mean over `time`
// seconds, which averages out the wave-frequency tension), a pose error delta gives about
// rho_k = c u_k . delta, with c = (dT/dX) / T the same for lines alike. The check fits
// rho_k = u_k . a by least squares over the cells that count and judges the pose wrong when
// |a| exceeds `threshold`, the fit explains at least `explained` of sum rho_k^2, both for
// `hold` seconds. It is trusted again once |a| falls below half the threshold. Where no fit
// can be made (too few cells, below), and for twice `time` from the first sample (the means
// settling while the vessel and the filter do), the judgement stands.
//
// What it sees and what it leaves: a gyro that steps or drifts by 0.1 rad moves the turret
// estimate of the seed set-up (60 m from the reference point) by 6 m; on its chains
// c is about 0.6 % per metre, so |a| reaches about 0.04 where a healthy pose stays near
// 0.005. A slow GNSS drift of a metre or two stays below it. A line that parts takes its own
// cell far below its expectation and leaves the others near theirs: no pattern of this kind,
// and cells reading low are left out of the fit (they are the cells test's to judge). One
// faulty cell is one outlier, which the pattern explains only in part (an eighth to a
// quarter of it for eight lines around the turret). The lines must pull from at least three
// sides: the fit needs cells whose directions span the plane (at least `min_cells` cells,
// and the smaller eigenvalue of sum u_k u_k^T at least a quarter of their number).
//
// Which of the two is wrong: the filter places the point where the lines pull (the turret)
// from the GNSS position and the heading, at the lever r from the vessel's reference point.
// A heading error d_psi moves it by d_psi r rotated a quarter turn: across r, never along
// it. So a pose judged wrong by an error with a part along r of at least half its size
// (60 degrees or less from r) is the GNSS's; so is any, where the lines pull at the reference
// point. Across r, the GNSS and the gyro make the same pattern, and the verdict names the
// pose. The lever is read from the lines' loads at the filter's pose: each line's yaw moment
// is r x F_k (fitted over the cells that count). The sensor named is settled when the pose
// is judged wrong, and stands with the judgement.
#pragma once

#include <vector>

#include "core/types.h"
#include "detectors/detector.h"

namespace moorsim::detectors {

struct PoseAgreementOptions {
  /// [s] Time constant of each cell's mean residual, > 0.
  double time = 60.0;
  /// The pattern's amplitude |a| at which the pose disagrees with the cells, > 0.
  double threshold = 0.02;
  /// Least share of the residuals' squares the pattern must explain, in (0, 1].
  double explained = 0.7;
  /// [s] How long both must hold before the pose is judged wrong, >= 0.
  double hold = 20.0;
  /// Least number of cells in the fit, >= 3.
  int min_cells = 4;
};

class PoseAgreement {
 public:
  explicit PoseAgreement(const PoseAgreementOptions& options = {});

  void Reset();
  /// Takes a sample: `counts[k]` whether line k + 1's cell enters the fit (read, judged
  /// sound, not reading low). Without tension or load evidence the state stays as it was.
  /// Returns whether the pose disagrees with the cells after it.
  bool Update(const Evidence& evidence, const std::vector<bool>& counts);

  bool disagrees() const { return disagrees_; }
  /// While the pose disagrees: SensorId::Kind::kGnss where the pattern shows the GNSS
  /// wrong, else kPose (the GNSS or the gyro).
  SensorId::Kind culprit() const { return culprit_; }
  /// The latest fit's amplitude |a| (0 before the first fit).
  double amplitude() const { return amplitude_; }

 private:
  PoseAgreementOptions options_;
  VecX mean_;                     // per cell, the mean of rho_k; NaN until its first reading
  double t_ = 0.0, start_ = 0.0;  // the latest sample's time and the first's
  bool started_ = false;
  double amplitude_ = 0.0;
  double beyond_since_ = 0.0;
  bool beyond_ = false, disagrees_ = false;
  SensorId::Kind culprit_ = SensorId::Kind::kPose;
};

}  // namespace moorsim::detectors
