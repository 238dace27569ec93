// Load cells and the pose together, each checking the other, and the sensors judged as well
// as the lines: the detector to run where the vessel has fairlead load cells.
//
// Three sources of evidence, each with its own way of lying:
//  - the cells (detectors/cells.h) tell at once which line lost its load, but a cell that
//    dies, sticks or drifts tells the same of a line that still holds;
//  - the pose, through the force-deficit test (detectors/deficit.h), feels the lost load
//    whatever the cells read, but slower, and a position reference that jumps, freezes or
//    grows noisy moves it as a lost line would;
//  - the observers' sensor checks (detectors/sensor_monitor.h, Evidence::sensor_faults)
//    judge the GNSS, the gyro and frozen cells from their own readings;
//  - the cells judge the pose (detectors/pose_agreement.h): a GNSS or gyro error of a few
//    metres or a tenth of a radian, too small or too slow for the sensor checks, puts the
//    turret where every cell disagrees with its expectation in one pattern ("pose
//    disagrees", or "GNSS disagrees" where the pattern's direction can only be the GNSS's).
//    It judges while every cell reads true and no line is named; from then on its judgement
//    stands.
//
// The verdict, at every sample:
//  1. A cell that reads low and that the pose confirms (the cells test's rule) names its
//     line: the cells for speed, the pose to confirm.
//  2. While a pose sensor is judged faulty, or the pose disagrees with the cells, the pose
//     confirms nothing: a low cell that the other cells explain names its line after the
//     cells' hold, and no cell is declared faulty for want of the pose's confirmation.
//  3. The force-deficit test names a line only where that line's cell cannot speak: no cells
//     fitted, the cell judged faulty (it read low while the vessel felt nothing, or it is
//     frozen), or no reading from it. Where the line's cell reads true, the cell outweighs
//     the pose: a pose that says otherwise is a position reference in error.
//  4. A named line stays named while its cell reads low, or, named by the pose, while the
//     force-deficit alarm stands on it.
//  5. A cell declared faulty for want of the pose's confirmation, whose line the pose then
//     names, was right after all: it is not reported faulty while its line stays named.
// The sensors it judges faulty are the sensor checks' and the cells test's; a sensor judged
// faulty is reported as such, never as a parted line. Once a line is named, a cell judged
// noisy only from then on is not reported: the remaining lines carry more dynamic tension
// than their cells' usual noise level holds.
#pragma once

#include <string_view>

#include "detectors/cells.h"
#include "detectors/deficit.h"
#include "detectors/detector.h"
#include "detectors/pose_agreement.h"

namespace moorsim::detectors {

struct FusedOptions {
  /// The cells test's options, with three changes against a faulty cell that a wave-drift
  /// group seems to confirm (in a seaway the intact filter's bias wanders by the
  /// confirmation's 1.5 MN within minutes):
  ///  - a low cell waits only 60 s for the pose, so a faulty cell has fewer chances of a
  ///    false confirmation. A real parting shows in the bias within a minute; a line whose
  ///    cell was judged faulty is then the pose's to name, and the cell is cleared again;
  ///  - a cell that reads nothing (a dead cell, or a break at the fairlead) needs the bias
  ///    to show 60 % of the line's horizontal load, not half: a break's shift grows to the
  ///    whole load, a wander seldom reaches 60 % of it;
  ///  - a cell still reading more than half must be falling still (anchor_fall, cells.h).
  CellsOptions cells{.confirm_fraction = 0.6, .confirm_time = 60.0, .anchor_fall = 0.05};
  DeficitOptions pose;
  /// The check of the pose against the cells (detectors/pose_agreement.h).
  PoseAgreementOptions agreement;
};

class Fused final : public Detector {
 public:
  explicit Fused(const FusedOptions& options = {});
  std::string_view type() const override { return "fused"; }
  bool NeedsLoadEvidence() const override { return true; }
  void Reset(int hypotheses) override;
  Verdict Update(const Evidence& evidence) override;

 private:
  // Whether line k's cell (1-based) can speak for it: fitted, read, neither frozen nor
  // judged faulty (a cell judged noisy still speaks).
  bool CellSpeaks(const Evidence& evidence, int line) const;

  Cells cells_;
  Deficit pose_;
  PoseAgreement agreement_;
  std::vector<bool> counts_;  // per cell, whether it enters the pose agreement's fit
  int hypotheses_ = 0;
  int named_ = 0;  // the line named, 0 none
  bool named_by_pose_ = false;
  std::vector<int> noisy_when_named_;  // the cells judged noisy before the line was named
  Verdict verdict_;
};

}  // namespace moorsim::detectors
