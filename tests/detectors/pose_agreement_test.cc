// The pose's agreement with the load cells (detectors/pose_agreement.h) on synthetic cells:
// eight lines pulling toward anchors 45 degrees apart, each cell expecting 6 MN and reading
// it with 10 kN of white noise and a wave-frequency swing of 2 % (12 s period, its own
// phase per line). A pose error delta makes line k read 6 MN x (1 - c u_k . delta) with
// c = 0.6 % per metre. Checked: a healthy pose is never judged wrong; a 6 m error (a gyro
// off by 0.1 rad, 60 m from the turret) is, within the mean's rise and the hold, and trusted
// again once it goes; an error along the hull, which no heading error makes, is named the
// GNSS's, one across it either sensor's; nothing is judged while the means settle; a 1 m
// error is not; one faulty cell is not a pose error; cells reading low are left out; too
// few cells, or cells pulling along one axis, judge nothing.
#include "detectors/pose_agreement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "core/random.h"

namespace moorsim::detectors::pose_agreement_test {
namespace {

constexpr int kLines = 8;
constexpr double kExpected = 6.0e6;   // [N]
constexpr double kPerMetre = 0.006;   // c: relative tension change per metre
constexpr double kCellNoise = 1.0e4;  // [N]
constexpr double kWaveSwing = 0.02;   // relative amplitude of the wave-frequency tension
constexpr double kWavePeriod = 12.0;  // [s]
// [m] The turret, 60 m ahead of the reference point of a vessel heading 150 degrees: a gyro
// error of 0.1 rad moves the filter's turret by {3.0, 5.2} m, across the hull.
const Eigen::Vector2d kLever(-52.0, 30.0);

Eigen::Vector2d Pull(int line) {  // 1-based
  const double angle = (line - 1) * std::numbers::pi / 4;
  return {std::cos(angle), std::sin(angle)};
}

class Cells {
 public:
  explicit Cells(const Eigen::Vector2d& lever = kLever)
      : noise_(RandomStream::Derive(5, "pose_agreement.cells")) {
    evidence_.load.emplace();
    evidence_.load->line_load.push_back(Vec3::Zero());
    for (int k = 1; k <= kLines; ++k) {
      const Eigen::Vector2d force = 4.5e6 * Pull(k);
      const double moment = lever.x() * force.y() - lever.y() * force.x();
      evidence_.load->line_load.push_back(Vec3(force.x(), force.y(), moment));
    }
    evidence_.tensions.emplace();
    evidence_.tensions->expected = VecX::Constant(kLines, kExpected);
    evidence_.tensions->measured = VecX::Constant(kLines, kExpected);
  }
  /// The cells at time t with the pose estimate off by `error` [m]; `gain` multiplies each
  /// reading (a faulty cell's gain).
  const Evidence& Sample(double t, const Eigen::Vector2d& error, const VecX& gain) {
    evidence_.t = t;
    for (int k = 0; k < kLines; ++k) {
      const double wave = kWaveSwing * std::sin(2 * std::numbers::pi * t / kWavePeriod + k);
      evidence_.tensions->measured(k) =
          gain(k) * kExpected * (1.0 - kPerMetre * Pull(k + 1).dot(error) + wave) +
          kCellNoise * noise_.Normal();
    }
    return evidence_;
  }

 private:
  RandomStream noise_;
  Evidence evidence_;
};

struct Outcome {
  std::optional<double> judged, cleared;           // first time judged wrong, then trusted again
  double largest = 0.0;                            // the largest amplitude seen
  SensorId::Kind culprit = SensorId::Kind::kPose;  // the sensor named when judged
};

// 0..seconds at 1 Hz; the pose is off by `error` during [from, to).
Outcome RunPose(const Eigen::Vector2d& error, double from, double to, double seconds,
                const VecX& gain = VecX::Ones(kLines),
                std::vector<bool> counts = std::vector<bool>(kLines, true),
                const Eigen::Vector2d& lever = kLever) {
  Cells cells(lever);
  PoseAgreement agreement;
  Outcome out;
  for (double t = 0; t <= seconds; t += 1.0) {
    const Eigen::Vector2d e = t >= from && t < to ? error : Eigen::Vector2d::Zero();
    const bool wrong = agreement.Update(cells.Sample(t, e, gain), counts);
    if (wrong && !out.judged) {
      out.judged = t;
      out.culprit = agreement.culprit();
    }
    if (!wrong && out.judged && !out.cleared) out.cleared = t;
    if (t > 120) out.largest = std::max(out.largest, agreement.amplitude());
  }
  return out;
}

TEST(PoseAgreement, AHealthyPoseIsNeverJudgedWrong) {
  const Outcome out = RunPose(Eigen::Vector2d::Zero(), 0, 0, 3000);
  EXPECT_FALSE(out.judged.has_value());
  EXPECT_LT(out.largest, 0.005);
}

TEST(PoseAgreement, ASixMetreErrorIsJudgedWithinAMinuteAndTrustedAgainWhenItGoes) {
  // |a| = 0.036 at the full error: the 60 s mean reaches the 0.02 threshold after
  // 60 ln(1 / (1 - 0.02 / 0.036)) = 49 s, then the 20 s hold.
  const Outcome out = RunPose({3.0, 5.2}, 400, 1000, 1600);
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_GT(*out.judged, 460.0);
  EXPECT_LT(*out.judged, 480.0);
  ASSERT_TRUE(out.cleared.has_value());
  EXPECT_GT(*out.cleared, 1000.0);  // half the threshold: 60 ln(2 x 0.036 / 0.02) = 77 s
  EXPECT_LT(*out.cleared, 1100.0);
}

TEST(PoseAgreement, AnErrorAlongTheHullIsTheGnssAcrossItEitherSensor) {
  // Across the lever (a gyro's 0.1 rad, or the GNSS): the pose.
  Outcome out = RunPose({3.0, 5.2}, 400, 1000, 1600);
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_EQ(out.culprit, SensorId::Kind::kPose);
  // Along it, which no heading error makes: the GNSS; so at 50 degrees from it.
  out = RunPose({-5.2, 3.0}, 400, 1000, 1600);
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_EQ(out.culprit, SensorId::Kind::kGnss);
  const Eigen::Vector2d across(3.0, 5.2), along(-5.2, 3.0);
  const double angle = 50.0 * std::numbers::pi / 180.0;
  out = RunPose((std::cos(angle) * along + std::sin(angle) * across).normalized() * 6.0, 400, 1000,
                1600);
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_EQ(out.culprit, SensorId::Kind::kGnss);
  // 70 degrees from it: either.
  const double steep = 70.0 * std::numbers::pi / 180.0;
  out = RunPose((std::cos(steep) * along + std::sin(steep) * across).normalized() * 6.0, 400, 1000,
                1600);
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_EQ(out.culprit, SensorId::Kind::kPose);
  // Lines that pull at the reference point: no heading error moves them, so the GNSS.
  out = RunPose({3.0, 5.2}, 400, 1000, 1600, VecX::Ones(kLines), std::vector<bool>(kLines, true),
                Eigen::Vector2d::Zero());
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_EQ(out.culprit, SensorId::Kind::kGnss);
}

TEST(PoseAgreement, NothingIsJudgedWhileTheMeansSettle) {
  // An error there from the first sample: judged once the means have run twice their time
  // (120 s) and the hold (20 s) has passed.
  const Outcome out = RunPose({3.0, 5.2}, 0, 3000, 1000);
  ASSERT_TRUE(out.judged.has_value());
  EXPECT_EQ(*out.judged, 140.0);
}

TEST(PoseAgreement, AMetreIsWithinTheCellsModelError) {
  EXPECT_FALSE(RunPose({1.0, 0.0}, 400, 3000, 3000).judged.has_value());
}

TEST(PoseAgreement, OneFaultyCellIsNoPoseError) {
  VecX gain = VecX::Ones(kLines);
  gain(2) = 0.8;  // cell 3 reads 20 % low (not low enough for the cells test)
  const Outcome out = RunPose(Eigen::Vector2d::Zero(), 0, 0, 2000, gain);
  EXPECT_FALSE(out.judged.has_value());
  EXPECT_GT(out.largest, 0.02);  // the fit sees it, but explains only a quarter of it
}

TEST(PoseAgreement, CellsLeftOutAndCellsOnOneSideJudgeNothing) {
  // Line 1's cell reads low (a parted line; left out): the other seven still judge.
  std::vector<bool> counts(kLines, true);
  counts[0] = false;
  VecX gain = VecX::Ones(kLines);
  gain(0) = 0.0;
  EXPECT_TRUE(RunPose({3.0, 5.2}, 400, 3000, 1000, gain, counts).judged.has_value());
  EXPECT_FALSE(RunPose(Eigen::Vector2d::Zero(), 0, 0, 2000, gain, counts).judged.has_value());
  // Lines 1, 2, 5 and 6 only: their pulls lie near one axis (22.5 degrees), so the fit
  // across it is ill-posed and nothing is judged, however large the error.
  counts.assign(kLines, false);
  counts[0] = counts[1] = counts[4] = counts[5] = true;
  EXPECT_FALSE(RunPose({3.0, 5.2}, 400, 3000, 1000, VecX::Ones(kLines), counts).judged.has_value());
  // Three cells are too few.
  counts.assign(kLines, false);
  counts[0] = counts[2] = counts[4] = true;
  EXPECT_FALSE(RunPose({3.0, 5.2}, 400, 3000, 1000, VecX::Ones(kLines), counts).judged.has_value());
}

}  // namespace
}  // namespace moorsim::detectors::pose_agreement_test
