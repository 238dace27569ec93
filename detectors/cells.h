// Fairlead load cells as evidence (Evidence::tensions), checked against the vessel's pose.
//
// A load cell tells at once which line has lost its load: a fairlead break takes the
// reading to zero, an anchor release to the weight of the chain left hanging (on the seed
// mooring 6.4 -> 4.5 MN within 4 s). A cell that is stuck or drifts tells the same story
// about a line that is still holding, which is why operators have learned to distrust
// them and why position-only detection exists. This test uses both: the cells say which
// line, the pose says whether the vessel lost that line's load.
//
// Per line k and sample, the ratio f_k = measured_k / expected_k of the cell's reading to
// the intact model's quasi-static tension at the filter's pose; its mean over the last
// `window` samples is fbar_k. The cell reads low while fbar_k < 1 - drop; the reading's
// deficit is d_k = 1 - fbar_k (score[k]).
//
//  - A line parts in seconds: a fairlead break takes the whole reading at once, an anchor
//    release 29 % within 4 s. A cell that drifts loses its reading over minutes. So a cell
//    that begins to read low counts only if `fall_time` seconds earlier it still read
//    within drop / 2 of its expectation (fbar then >= 1 - drop / 2); one that fell slower
//    is a faulty cell at once (cell_faults()). On the seed mooring a drift faster than
//    about 25 kN/s (drop / 2 of 6 MN in 30 s) still looks like a fall. fall_time = 0: off.
//  - Cells alone (confirm = 0): an alarm naming line k once its cell has read low for
//    `hold` seconds (the lowest ratio wins when several do).
//  - Confirmed by the pose (confirm = 1): besides, the intact filter's bias must have
//    moved as losing line k would move it. A parted line is, to the intact filter, a steady
//    force: its bias settles by -line_load[k] (Evidence::load). With b0 the bias `window`
//    samples before the cell began to read low and l_k the horizontal part of
//    line_load[k], the shift toward the lost load is z_k = -(b - b0) . l_k / |l_k|; the
//    alarm needs z_k >= max(confirm_fraction d_k |l_k|, confirm_floor) (the floor keeps the
//    wave-drift wander of the bias from confirming a faulty cell), for `confirm_hold`
//    seconds on end (a wander crosses the line and falls back). A cell that reads low for
//    `confirm_time` seconds without the pose agreeing is declared faulty and ignored until
//    it reads within drop / 2 of its expectation again; cell_faults() counts them.
//  - A cell that still reads more than half its expectation (anchor_fall > 0): a parted
//    line whose cell reads that much let go at its anchor, and its chain, dragged as the
//    vessel drifts off, keeps unloading while the intact model expects ever more of it at
//    the new pose; a faulty cell on a line that holds (a gain or step error) reads a steady
//    share of what the model expects wherever the vessel goes, and a wave-drift group can
//    move the bias as far as the confirmation asks. So such a cell is confirmed only while
//    its fbar_k is anchor_fall below its highest since the window held only readings of the
//    low spell. On the seed mooring at Hs 6 m an anchor release's fbar falls from 0.72 to
//    0.60 within 40 s, a gain or step fault's stays within 0.03 of its level.
//
// Where lines meet at free points (TensionEvidence::expected_if_parted) a parted line
// changes its network's other cells too: a bridle's anchor line parting slackens both
// legs, a leg parting leaves its twin the whole load. A low cell names its line only where
// that line's parting explains every other cell within drop of its (intact) expectation;
// the legs' cells then wait for the anchor line's. Where the other cells also read what
// they would not with the line intact (the twin leg's rise), they corroborate the parting
// and the pose need not: a leg's loss barely moves the vessel, and one faulty cell cannot
// move another.
//
// Pairs: scored 0, never named. Without tension or load evidence a sample leaves the state
// as it was. A stuck cell on the line that then parts keeps reading its old load: this test
// cannot see that break (run a pose-only detector beside it; the campaign in
// benchmarks/README.md shows the cost).
#pragma once

#include <deque>
#include <limits>
#include <string_view>
#include <vector>

#include "detectors/detector.h"

namespace moorsim::detectors {

struct CellsOptions {
  /// Samples in the ratio's moving mean, >= 1.
  int window = 10;
  /// Fraction of the expected reading a cell must lose to read low, in (0, 1).
  double drop = 0.25;
  /// [s] How long a cell must read low before the alarm, >= 0.
  double hold = 3.0;
  /// Whether the pose must confirm (1) or the cells decide alone (0).
  bool confirm = true;
  /// Share of the horizontal load the cell says is lost that the bias must show, >= 0.
  double confirm_fraction = 0.5;
  /// [N] Least bias shift that confirms, >= 0.
  double confirm_floor = 1.5e6;
  /// [s] How long a low cell waits for the pose before it is declared faulty, > 0.
  double confirm_time = 180.0;
  /// [s] How long the bias must keep showing the lost load before it confirms, >= 0
  /// (0: the first sample that shows it).
  double confirm_hold = 0.0;
  /// A cell still reading more than half its expectation is confirmed only while its
  /// ratio's mean is this much below its highest of the low spell, >= 0 (0: off).
  double anchor_fall = 0.0;
  /// [s] A cell must have read true this long before it reads low (a fall, not a drift);
  /// >= 0, 0 = any.
  double fall_time = 30.0;
};

class Cells final : public Detector {
 public:
  explicit Cells(const CellsOptions& options = {});
  std::string_view type() const override { return "cells"; }
  bool NeedsLoadEvidence() const override { return true; }
  void Reset(int hypotheses) override;
  Verdict Update(const Evidence& evidence) override;
  /// Update() without the copy: the verdict stays valid until the next Step/Reset.
  const Verdict& Step(const Evidence& evidence);

  /// Cells declared faulty so far (each time a low cell went unconfirmed for
  /// confirm_time).
  int cell_faults() const { return cell_faults_; }

  /// Whether the pose can be trusted to confirm (the fused detector clears it while a pose
  /// sensor is judged faulty): while it cannot, a low cell is not declared faulty for want
  /// of confirmation, and its confirm_time runs from when the pose is trusted again.
  /// Call before Update(). True by default.
  void SetPoseTrusted(bool trusted) { pose_trusted_ = trusted; }
  /// After Update(): the hypothesis of the lowest cell that has read low for `hold` and is
  /// explained by the other cells, but that the pose has not confirmed; 0 if none.
  int unconfirmed() const { return unconfirmed_; }
  /// After Update(): whether line k's cell (1-based) is reading low, or judged faulty.
  bool reads_low(int line) const { return lines_.at(static_cast<std::size_t>(line - 1)).low; }
  bool judged_faulty(int line) const {
    return lines_.at(static_cast<std::size_t>(line - 1)).faulty;
  }
  int num_cells() const { return static_cast<int>(lines_.size()); }

 private:
  struct Line {
    std::deque<double> ratios;                    // the last `window` ratios
    std::deque<std::pair<double, double>> means;  // (t, fbar) over the last fall_time
    bool low = false;
    double low_since = 0.0;
    Vec3 bias_before = Vec3::Zero();  // b0: the bias `window` samples before the low began
    bool confirmed = false;           // the pose agreed during this low spell
    bool agreeing = false;            // the bias shows the lost load now
    double agree_since = 0.0;
    int low_samples = 0;       // samples since the low began
    double settled_max = 0.0;  // the highest mean of a window all from the low spell
    bool faulty = false;
  };

  // What the other cells say of line k's parting (where lines meet at free points;
  // elsewhere they neither deny nor corroborate it): explained, each reads within drop (of
  // its intact expectation) of what it should with k parted; corroborated, besides, one of
  // them reads what it would not with k intact.
  struct OtherCells {
    bool explained = true, corroborated = false;
  };
  OtherCells ReadOtherCells(const TensionEvidence& cells, int k) const;

  CellsOptions options_;
  int hypotheses_ = 0;
  std::vector<Line> lines_;
  std::deque<Vec3> bias_history_;  // the last window + 1 biases
  int cell_faults_ = 0;
  bool pose_trusted_ = true;
  double trusted_since_ = -std::numeric_limits<double>::infinity();
  int unconfirmed_ = 0;
  Verdict verdict_;
};

}  // namespace moorsim::detectors
