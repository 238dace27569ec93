// The load-cell test (detectors/cells.h) on synthetic evidence: a parted line's cell falls
// and the intact filter's bias moves by that line's load (the alarm names it, at once
// without confirmation, once the bias agrees with it); a drifting cell on a line that holds
// moves no bias (a plain threshold on the cells raises a false alarm; asking for a fall,
// or for the pose to confirm, declares the cell faulty and raises none); a faulty cell
// that reads true again re-arms.
#include "detectors/cells.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "tests/detectors/evidence_support.h"

namespace moorsim::detectors {
namespace {

constexpr int kCellLines = 4;
constexpr double kPretension = 6.0e6;  // [N] every cell's expected reading

// One sample at time t: cell readings `measured` and the intact filter's bias `bias`.
Evidence CellEvidence(double t, const std::vector<double>& measured, const Vec3& bias) {
  Evidence e;
  e.t = t;
  e.hypotheses.resize(kCellLines + 1);
  LoadEvidence load;
  load.bias = bias;
  load.line_load.push_back(Vec3::Zero());
  for (int k = 1; k <= kCellLines; ++k) load.line_load.push_back(testing::QuarterLineLoad(k));
  e.load = load;
  TensionEvidence cells;
  cells.measured = Eigen::Map<const VecX>(measured.data(), kCellLines);
  cells.expected = VecX::Constant(kCellLines, kPretension);
  e.tensions = cells;
  return e;
}

// Runs `detector` through `seconds` of 1 Hz samples from `t0`; `reading(t)` gives the
// cells, `bias(t)` the bias. Returns the first time the alarm stands (nullopt if never)
// and leaves the last verdict in *last.
template <typename Reading, typename Bias>
std::optional<double> FirstAlarm(Cells& detector, double t0, double seconds, Reading reading,
                                 Bias bias, Verdict* last) {
  std::optional<double> first;
  for (double t = t0; t < t0 + seconds; t += 1.0) {
    *last = detector.Update(CellEvidence(t, reading(t), bias(t)));
    if (last->alarm && !first) first = t;
  }
  return first;
}

std::vector<double> Healthy(double) { return std::vector<double>(kCellLines, kPretension); }

TEST(Cells, APartedLinesCellNamesItOnceThePoseAgrees) {
  // Line 2 parts at 100 s: its cell reads zero from then on; the bias settles by -load of
  // line 2 over 20 s (the intact filter's lag).
  const auto reading = [](double t) {
    std::vector<double> r = Healthy(t);
    if (t >= 100) r[1] = 0.0;
    return r;
  };
  const auto bias = [](double t) -> Vec3 {
    const double share = std::clamp((t - 100) / 20.0, 0.0, 1.0);
    return -share * testing::QuarterLineLoad(2);
  };
  for (const bool confirm : {false, true}) {
    SCOPED_TRACE(confirm ? "confirmed" : "cells alone");
    CellsOptions options;
    options.confirm = confirm;
    Cells detector(options);
    detector.Reset(kCellLines + 1);
    Verdict last;
    const std::optional<double> alarm = FirstAlarm(detector, 0, 300, reading, bias, &last);
    ASSERT_TRUE(alarm.has_value());
    // The window's mean (10 samples) falls below 0.75 with the third zero: 102 s, plus the
    // 3 s hold. Confirmed: the bias must move
    // max(0.5 x 1.0 x 4.5 MN, 1.5 MN) = 2.25 MN toward line 2's load: half-way, at 110 s.
    EXPECT_EQ(*alarm, confirm ? 110.0 : 105.0);
    EXPECT_TRUE(last.alarm);
    EXPECT_EQ(last.hypothesis, 2);
    EXPECT_NEAR(last.score[2], 1.0, 1e-12);  // the whole reading is gone
    EXPECT_EQ(last.score[1], 0.0);
    EXPECT_EQ(detector.cell_faults(), 0);
  }
}

TEST(Cells, ADriftingCellOnALineThatHoldsIsAFaultNotAFailure) {
  // Cell 3 drifts down 10 kN/s from 50 s; nothing moves the vessel (the bias wanders 0.5 MN).
  const auto reading = [](double t) {
    std::vector<double> r = Healthy(t);
    if (t >= 50) r[2] -= 1.0e4 * (t - 50);
    return r;
  };
  const auto bias = [](double t) -> Vec3 { return Vec3(5e5 * std::sin(t / 40), 0.0, 0.0); };
  CellsOptions alone;
  alone.confirm = false;
  alone.fall_time = 0.0;  // the plain threshold on the reading
  Cells cells_alone(alone);
  cells_alone.Reset(kCellLines + 1);
  Verdict last;
  // Alone: low once 25 % of 6 MN = 1.5 MN has drifted off in the window's mean: a false
  // alarm on line 3 about 200 s after the drift began.
  const std::optional<double> false_alarm = FirstAlarm(cells_alone, 0, 600, reading, bias, &last);
  ASSERT_TRUE(false_alarm.has_value());
  EXPECT_NEAR(*false_alarm, 50 + 150 + 4.5 + 3, 2.0);
  EXPECT_EQ(last.hypothesis, 3);

  // Cells alone but asking for a fall (the default fall_time, 30 s): 10 kN/s takes 30 s to
  // lose 5 % of the reading, so when the cell first reads low it is a drift: a fault.
  alone.fall_time = CellsOptions{}.fall_time;
  Cells falls_only(alone);
  falls_only.Reset(kCellLines + 1);
  EXPECT_FALSE(FirstAlarm(falls_only, 0, 600, reading, bias, &last).has_value());
  EXPECT_EQ(falls_only.cell_faults(), 1);

  Cells confirmed;  // the defaults: confirm 1, fall_time 30 s
  confirmed.Reset(kCellLines + 1);
  EXPECT_FALSE(FirstAlarm(confirmed, 0, 600, reading, bias, &last).has_value());
  EXPECT_FALSE(last.alarm);
  EXPECT_EQ(confirmed.cell_faults(), 1);
  // Repaired (reads true again): it re-arms and a real break of its line is then named.
  const auto repaired_then_parted = [](double t) {
    std::vector<double> r = Healthy(t);
    if (t >= 700) r[2] = 0.0;
    return r;
  };
  const auto parted_bias = [](double t) -> Vec3 {
    return -std::clamp((t - 700) / 20.0, 0.0, 1.0) * testing::QuarterLineLoad(3);
  };
  const std::optional<double> alarm =
      FirstAlarm(confirmed, 600, 200, repaired_then_parted, parted_bias, &last);
  ASSERT_TRUE(alarm.has_value());
  EXPECT_EQ(*alarm, 710.0);
  EXPECT_EQ(last.hypothesis, 3);
}

// A bridle: line 1 runs from its anchor to an apex, lines 3 and 4 from the apex to the
// vessel (legs), line 2 is a plain line. Intact cells read 4, 6, 3 and 3 MN. With line 1
// parted the model has no expectation for the legs (the apex then reaches no anchor);
// with a leg parted its twin takes the bridle's load. Line 1's loss moves the vessel by
// 3.9 MN; a leg's barely does (0.3 MN, nearly along line 1's).
constexpr int kBridleCells = 4;
const VecX kBridleIntact = (VecX(4) << 4e6, 6e6, 3e6, 3e6).finished();

Evidence BridleEvidence(double t, const std::vector<double>& measured, const Vec3& bias) {
  Evidence e;
  e.t = t;
  e.hypotheses.resize(kBridleCells + 1);
  LoadEvidence load;
  load.bias = bias;
  load.line_load = {Vec3::Zero(), Vec3(3.9e6, 0.0, 0.0), Vec3(0.0, 4.5e6, 0.0),
                    Vec3(0.3e6, 0.1e6, 0.0), Vec3(0.3e6, -0.1e6, 0.0)};
  e.load = load;
  TensionEvidence cells;
  cells.measured = Eigen::Map<const VecX>(measured.data(), kBridleCells);
  cells.expected = kBridleIntact;
  const double none = std::nan("");
  cells.expected_if_parted.setConstant(kBridleCells, kBridleCells, none);
  cells.expected_if_parted.col(0) << 0.0, 6e6, none, none;
  cells.expected_if_parted.col(2) << 4e6, 6e6, 0.0, 6e6;
  cells.expected_if_parted.col(3) << 4e6, 6e6, 6e6, 0.0;
  e.tensions = cells;
  return e;
}

// The intact readings until 100 s, `after` from then on.
auto ReadingFrom100(std::vector<double> after) {
  return [after](double t) {
    return t >= 100
               ? after
               : std::vector<double>(kBridleIntact.data(), kBridleIntact.data() + kBridleCells);
  };
}

struct BridleRun {
  std::optional<double> first_alarm;
  int first_line = 0;
  Verdict last;
  int cell_faults = 0;
};

template <typename Reading, typename Bias>
BridleRun RunBridle(bool confirm, Reading reading, Bias bias) {
  CellsOptions options;
  options.confirm = confirm;
  Cells detector(options);
  detector.Reset(kBridleCells + 1);
  BridleRun run;
  for (double t = 0; t < 400; t += 1.0) {
    run.last = detector.Update(BridleEvidence(t, reading(t), bias(t)));
    if (run.last.alarm && !run.first_alarm) {
      run.first_alarm = t;
      run.first_line = run.last.hypothesis;
    }
  }
  run.cell_faults = detector.cell_faults();
  return run;
}

// The anchor line parts at 100 s: its cell and both legs' read low at once. The legs'
// partings would leave their twins the load, which the cells deny: the alarm names line
// 1 once the pose agrees (its 1.95 MN at 110 s), though a leg's 1.5 MN floor is reached
// first (108 s).
TEST(Cells, WhereLinesMeetTheOtherCellsTellWhichLineParted) {
  const auto reading = ReadingFrom100({0.0, 6e6, 0.3e6, 0.3e6});
  const auto bias = [](double t) -> Vec3 {
    return -std::clamp((t - 100) / 20.0, 0.0, 1.0) * Vec3(3.9e6, 0.0, 0.0);
  };
  const BridleRun run = RunBridle(true, reading, bias);
  ASSERT_TRUE(run.first_alarm.has_value());
  EXPECT_EQ(*run.first_alarm, 110.0);
  EXPECT_EQ(run.first_line, 1);
  EXPECT_EQ(run.last.hypothesis, 1);
  EXPECT_EQ(run.cell_faults, 0);
}

// A leg parts at 100 s: its cell reads zero and its twin's doubles, which no faulty cell
// does: the cells corroborate each other and name it without the pose (which hardly
// moves), at the hold's end.
TEST(Cells, ALegsTwinCorroboratesItsParting) {
  const auto reading = ReadingFrom100({4e6, 6e6, 0.0, 6e6});
  const auto still = [](double) { return Vec3::Zero(); };
  for (const bool confirm : {false, true}) {
    SCOPED_TRACE(confirm ? "confirmed" : "cells alone");
    const BridleRun run = RunBridle(confirm, reading, still);
    ASSERT_TRUE(run.first_alarm.has_value());
    EXPECT_EQ(*run.first_alarm, 105.0);
    EXPECT_EQ(run.first_line, 3);
    EXPECT_EQ(run.cell_faults, 0);
  }
}

// A leg's cell goes dead at 100 s on an intact bridle: its twin reads as it would with the
// leg intact, so nothing is named, with or without the pose; after confirm_time (180 s)
// with no other cell low it is a faulty cell.
TEST(Cells, ALegsDeadCellIsDeniedByItsTwin) {
  const auto reading = ReadingFrom100({4e6, 6e6, 0.0, 3e6});
  const auto still = [](double) { return Vec3::Zero(); };
  for (const bool confirm : {false, true}) {
    SCOPED_TRACE(confirm ? "confirmed" : "cells alone");
    const BridleRun run = RunBridle(confirm, reading, still);
    EXPECT_FALSE(run.first_alarm.has_value());
    EXPECT_EQ(run.cell_faults, 1);
  }
}

TEST(Cells, WithoutCellReadingsNothingChangesAndBadOptionsAreRefused) {
  Cells detector;
  detector.Reset(kCellLines + 1);
  Evidence e = CellEvidence(0.0, Healthy(0), Vec3::Zero());
  e.tensions.reset();
  const Verdict v = detector.Update(e);
  EXPECT_FALSE(v.alarm);
  EXPECT_EQ(v.score, std::vector<double>(kCellLines + 1, 0.0));
  CellsOptions bad;
  bad.drop = 1.0;
  EXPECT_THROW(Cells{bad}, InputError);
  bad = CellsOptions{};
  bad.window = 0;
  EXPECT_THROW(Cells{bad}, InputError);
}

}  // namespace
}  // namespace moorsim::detectors
