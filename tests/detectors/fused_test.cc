// The fused detector (detectors/fused.h) on synthetic evidence: four lines whose loads of
// 4.5 MN point at their anchors 90 degrees apart, a cell on each reading 6 MN as the intact
// model expects, and an intact filter's bias with a slowly varying disturbance (0.3 MN, 60 s)
// that a parted line shifts by minus its load (with a 10 s lag). Each rule of the file
// comment is checked where it decides: a cell the pose confirms names its line as the cells
// test does; while a pose sensor is judged faulty a low cell decides alone; a dead cell the
// vessel did not feel is a faulty cell, not a line; where a line's cell is frozen the pose
// speaks for it; where a line's cell reads true the pose's claim (a position reference in
// error) names nothing; a pose the cells show wrong is named, and a low cell then decides
// alone; a cell judged noisy still outweighs the pose, and one judged noisy only after a line
// is named is not reported; a cell declared faulty before the pose felt its line go is
// cleared when the pose names the line; a cell still reading more than half is confirmed
// only while its reading falls (an anchor let go), not while it reads a steady share (a
// gain error).
#include "detectors/fused.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "core/random.h"
#include "tests/detectors/evidence_support.h"

namespace moorsim::detectors::fused_test {
namespace {

constexpr int kLines = 4;
constexpr double kExpected = 6.0e6;  // [N] every cell's intact reading

// What happens to the plant and its sensors in a test.
struct Story {
  int parted = 0;  // the line that parts, at `part_time`
  double part_time = std::numeric_limits<double>::infinity();
  double lag_time = 10.0;          // [s] the bias's lag behind the lost load
  Vec3 bias_error = Vec3::Zero();  // added to the bias from `error_time` to `error_end`
  double error_time = std::numeric_limits<double>::infinity();
  double error_end = std::numeric_limits<double>::infinity();
  std::function<void(double, VecX&)> cells = [](double, VecX&) {};  // cell faults
  std::function<std::vector<SensorFinding>(double)> findings = [](double) {
    return std::vector<SensorFinding>{};
  };
};

class Plant {
 public:
  explicit Plant(Story story)
      : story_(std::move(story)),
        x_(RandomStream::Derive(11, "fused.x")),
        y_(RandomStream::Derive(11, "fused.y")) {
    evidence_.hypotheses.resize(kLines + 1);
    evidence_.load.emplace();
    evidence_.load->line_load.push_back(Vec3::Zero());
    for (int k = 1; k <= kLines; ++k)
      evidence_.load->line_load.push_back(testing::QuarterLineLoad(k));
    evidence_.tensions.emplace();
    evidence_.tensions->expected = VecX::Constant(kLines, kExpected);
  }
  const Evidence& Sample(double t) {
    const double decay = std::exp(-1.0 / 60.0);
    disturbance_ = decay * disturbance_ +
                   3e5 * std::sqrt(1 - decay * decay) * Vec3(x_.Normal(), y_.Normal(), 0.0);
    const Vec3 lost =
        t >= story_.part_time ? testing::QuarterLineLoad(story_.parted) : Vec3::Zero();
    lag_ += (lost - lag_) * (1.0 - std::exp(-1.0 / story_.lag_time));
    evidence_.t = t;
    evidence_.load->bias =
        disturbance_ - lag_ +
        (t >= story_.error_time && t < story_.error_end ? story_.bias_error : Vec3::Zero());
    VecX cells = VecX::Constant(kLines, kExpected);
    if (t >= story_.part_time) cells(story_.parted - 1) = 0.0;
    story_.cells(t, cells);
    evidence_.tensions->measured = cells;
    evidence_.sensor_faults = story_.findings(t);
    return evidence_;
  }

 private:
  Story story_;
  RandomStream x_, y_;
  Vec3 disturbance_ = Vec3::Zero(), lag_ = Vec3::Zero();
  Evidence evidence_;
};

struct Outcome {
  std::optional<double> alarm;  // the first alarm
  int hypothesis = 0;           // named at the first alarm
  Verdict last;
};

Outcome RunStory(Detector& detector, const Story& story, double seconds) {
  detector.Reset(kLines + 1);
  Plant plant(story);
  Outcome out;
  for (double t = 0; t <= seconds; t += 1.0) {
    out.last = detector.Update(plant.Sample(t));
    if (out.last.alarm && !out.alarm) {
      out.alarm = t;
      out.hypothesis = out.last.hypothesis;
    }
  }
  return out;
}

bool Lists(const Verdict& v, SensorId sensor, SensorSymptom symptom) {
  return std::find(v.faulty_sensors.begin(), v.faulty_sensors.end(),
                   SensorFinding{.sensor = sensor, .symptom = symptom}) != v.faulty_sensors.end();
}

constexpr SensorId kGnss{.kind = SensorId::Kind::kGnss};

// The sensor checks' findings for a story: `sensor` judged `symptom` from t0 on.
std::function<std::vector<SensorFinding>(double)> FindingFrom(double t0, SensorId sensor,
                                                              SensorSymptom symptom) {
  return [=](double t) {
    return t >= t0 ? std::vector<SensorFinding>{{.sensor = sensor, .symptom = symptom}}
                   : std::vector<SensorFinding>{};
  };
}

TEST(Fused, ACellThePoseConfirmsNamesItsLineAsTheCellsTestDoes) {
  Story story;
  story.parted = 2;
  story.part_time = 400;
  Fused fused;
  Cells cells;
  const Outcome f = RunStory(fused, story, 900);
  const Outcome c = RunStory(cells, story, 900);
  ASSERT_TRUE(f.alarm.has_value());
  EXPECT_EQ(f.alarm, c.alarm);
  EXPECT_GT(*f.alarm, 400.0);
  EXPECT_LT(*f.alarm, 420.0);
  EXPECT_EQ(f.hypothesis, 2);
  EXPECT_TRUE(f.last.alarm);  // and stays named
  EXPECT_EQ(f.last.hypothesis, 2);
  EXPECT_TRUE(f.last.faulty_sensors.empty());
}

TEST(Fused, WhileTheGnssIsJudgedFaultyALowCellDecidesAlone) {
  // The receiver jumped at 300 s (the sensor checks say so) and the bias shows nothing of
  // line 2's parting at 400 s: the cells test waits for a confirmation that cannot come;
  // the fused detector names line 2 after the cells' hold.
  Story story;
  story.parted = 2;
  story.part_time = 400;
  story.error_time = 400;
  story.bias_error = testing::QuarterLineLoad(2);  // cancels the lost load: the pose feels nothing
  story.findings = FindingFrom(300, kGnss, SensorSymptom::kJump);
  Fused fused;
  Cells cells;
  const Outcome f = RunStory(fused, story, 900);
  ASSERT_TRUE(f.alarm.has_value());
  // The window's mean (10 samples) falls below 0.75 with the third zero, plus the 3 s hold.
  EXPECT_EQ(*f.alarm, 405.0);
  EXPECT_EQ(f.hypothesis, 2);
  EXPECT_TRUE(f.last.alarm);
  EXPECT_TRUE(Lists(f.last, kGnss, SensorSymptom::kJump));
  EXPECT_FALSE(RunStory(cells, story, 900).alarm.has_value());
}

TEST(Fused, ADeadCellTheVesselDidNotFeelIsAFaultyCellNotALine) {
  Story story;
  story.cells = [](double t, VecX& cells) {
    if (t >= 400) cells(2) = 0.0;  // cell 3 dies
  };
  Fused fused;
  const Outcome f = RunStory(fused, story, 900);
  EXPECT_FALSE(f.alarm.has_value());
  // Declared faulty once it has waited confirm_time (60 s) for the pose.
  EXPECT_TRUE(
      Lists(f.last, SensorId{.kind = SensorId::Kind::kCell, .line = 3}, SensorSymptom::kDisagrees));
}

TEST(Fused, ACellDeclaredFaultyBeforeThePoseFeltItsLineGoIsClearedWhenThePoseNamesIt) {
  // Line 2's anchor lets go at 400 s: its cell falls to the hanging chain's 70 % at once,
  // while the bias feels the load leave over minutes (a 240 s lag). The cell waits 60 s
  // for a confirmation that comes too late and is declared faulty; the force-deficit test
  // then names line 2, and the cell, right after all, is no longer reported.
  Story story;
  story.parted = 2;
  story.part_time = 400;
  story.lag_time = 240;
  story.cells = [](double t, VecX& cells) {
    if (t >= 400) cells(1) = 0.7 * kExpected;
  };
  const SensorId cell2{.kind = SensorId::Kind::kCell, .line = 2};
  Fused fused;
  fused.Reset(kLines + 1);
  Plant plant(story);
  std::optional<double> declared, named;
  Verdict last;
  for (double t = 0; t <= 900; t += 1.0) {
    last = fused.Update(plant.Sample(t));
    if (!declared && Lists(last, cell2, SensorSymptom::kDisagrees)) declared = t;
    if (!named && last.alarm) named = t;
  }
  ASSERT_TRUE(declared.has_value());
  ASSERT_TRUE(named.has_value());
  EXPECT_LT(*declared, *named);
  EXPECT_EQ(last.hypothesis, 2);
  EXPECT_TRUE(last.alarm);
  EXPECT_FALSE(Lists(last, cell2, SensorSymptom::kDisagrees));
}

TEST(Fused, ACellReadingASteadyShareIsNotConfirmedByAWaveDriftGroup) {
  // Cell 3 reads 70 % of its line from 400 s (a gain error), and from 430 s to 460 s a
  // wave-drift group moves the bias by 2 MN as losing line 3 would: enough for the
  // confirmation, so without the fall rule the cells name line 3 within the group. The
  // line holds and the cell's share is steady: the fused detector names nothing. (Up to
  // 465 s, before the cell has waited confirm_time: from then on the line is the pose's to
  // name, and the force-deficit test has felt the group too.)
  Story story;
  story.cells = [](double t, VecX& cells) {
    if (t >= 400) cells(2) *= 0.7;
  };
  story.error_time = 430;
  story.error_end = 460;
  story.bias_error = -2.0e6 * testing::QuarterLineLoad(3).normalized();
  Fused fused;
  EXPECT_FALSE(RunStory(fused, story, 465).alarm.has_value());
  FusedOptions without;
  without.cells.anchor_fall = 0.0;
  Fused unruled(without);
  const Outcome u = RunStory(unruled, story, 465);
  ASSERT_TRUE(u.alarm.has_value());
  EXPECT_GE(*u.alarm, 430.0);
  EXPECT_LT(*u.alarm, 460.0);
  EXPECT_EQ(u.hypothesis, 3);
}

TEST(Fused, AnAnchorReleaseWhoseCellKeepsFallingIsNamedByTheCells) {
  // Line 2's anchor lets go at 400 s: its cell falls to 72 % at once and on to 55 % over
  // the next 100 s as the chain is dragged, while the bias feels the load leave (10 s lag).
  // The cell is confirmed once its mean is 0.05 below its highest of the low spell: about
  // 45 s after the release.
  Story story;
  story.parted = 2;
  story.part_time = 400;
  story.cells = [](double t, VecX& cells) {
    if (t >= 400) cells(1) = (0.72 - 0.17 * std::min(t - 400, 100.0) / 100.0) * kExpected;
  };
  Fused fused;
  const Outcome f = RunStory(fused, story, 900);
  ASSERT_TRUE(f.alarm.has_value());
  EXPECT_EQ(f.hypothesis, 2);
  EXPECT_GT(*f.alarm, 430.0);
  EXPECT_LT(*f.alarm, 460.0);
  EXPECT_TRUE(f.last.faulty_sensors.empty());
}

TEST(Fused, ThePoseSpeaksForALineWhoseCellIsFrozen) {
  // Cell 2 froze at 300 s (the sensor checks withhold it: NaN) and line 2 parts at 700 s.
  Story story;
  story.parted = 2;
  story.part_time = 700;
  story.cells = [](double t, VecX& cells) {
    if (t >= 300) cells(1) = std::numeric_limits<double>::quiet_NaN();
  };
  const SensorId cell2{.kind = SensorId::Kind::kCell, .line = 2};
  story.findings = FindingFrom(300, cell2, SensorSymptom::kFrozen);
  Fused fused;
  Cells cells;
  const Outcome f = RunStory(fused, story, 1500);
  ASSERT_TRUE(f.alarm.has_value());
  EXPECT_GT(*f.alarm, 700.0);
  EXPECT_LT(*f.alarm, 760.0);  // the force-deficit test's time (within a minute)
  EXPECT_EQ(f.hypothesis, 2);
  EXPECT_TRUE(f.last.alarm);
  EXPECT_TRUE(Lists(f.last, cell2, SensorSymptom::kFrozen));
  EXPECT_FALSE(RunStory(cells, story, 1500).alarm.has_value());  // the cells alone cannot see it
}

TEST(Fused, ANoisyCellStillSpeaksForItsLine) {
  // Cell 2 is judged noisy from 300 s (its readings 100 kN noisier, their mean true), and
  // from 700 s the bias shifts as if line 2 had parted (a position reference in error): the
  // noisy cell still outweighs the pose, where a frozen one would leave line 2 to it.
  Story story;
  story.error_time = 700;
  story.bias_error = -testing::QuarterLineLoad(2);
  RandomStream noise(RandomStream::Derive(11, "fused.cell"));
  story.cells = [&noise](double t, VecX& cells) {
    if (t >= 300) cells(1) += 1e5 * noise.Normal();
  };
  const SensorId cell2{.kind = SensorId::Kind::kCell, .line = 2};
  story.findings = FindingFrom(300, cell2, SensorSymptom::kNoisy);
  Fused fused;
  const Outcome f = RunStory(fused, story, 1500);
  EXPECT_FALSE(f.alarm.has_value());
  EXPECT_TRUE(Lists(f.last, cell2, SensorSymptom::kNoisy));  // named, as a sensor
}

TEST(Fused, ACellJudgedNoisyOnlyAfterALineIsNamedIsNotReported) {
  // Line 2 parts at 400 s. Cell 4 is judged noisy from 300 s, cell 3 only from 600 s (the
  // remaining lines' tensions grow livelier than their cells' usual level): cell 4 is
  // reported, cell 3 is not.
  Story story;
  story.parted = 2;
  story.part_time = 400;
  const SensorId cell3{.kind = SensorId::Kind::kCell, .line = 3};
  const SensorId cell4{.kind = SensorId::Kind::kCell, .line = 4};
  story.findings = [&](double t) {
    std::vector<SensorFinding> found;
    if (t >= 300) found.push_back({.sensor = cell4, .symptom = SensorSymptom::kNoisy});
    if (t >= 600) found.push_back({.sensor = cell3, .symptom = SensorSymptom::kNoisy});
    return found;
  };
  Fused fused;
  const Outcome f = RunStory(fused, story, 900);
  ASSERT_TRUE(f.alarm.has_value());
  EXPECT_EQ(f.hypothesis, 2);
  EXPECT_TRUE(f.last.alarm);
  EXPECT_TRUE(Lists(f.last, cell4, SensorSymptom::kNoisy));
  EXPECT_FALSE(Lists(f.last, cell3, SensorSymptom::kNoisy));
}

TEST(Fused, ACellReadingTrueOutweighsAPoseThatSaysItsLineParted) {
  // From 700 s the bias shifts as if line 2 had parted (a position reference in error, not
  // caught by the checks); cell 2 reads its 6 MN throughout.
  Story story;
  story.error_time = 700;
  story.bias_error = -testing::QuarterLineLoad(2);
  Deficit deficit;
  const Outcome d = RunStory(deficit, story, 1500);
  ASSERT_TRUE(d.alarm.has_value());  // the pose alone names line 2
  EXPECT_EQ(d.hypothesis, 2);
  Fused fused;
  EXPECT_FALSE(RunStory(fused, story, 1500).alarm.has_value());
}

TEST(Fused, APoseTheCellsShowWrongIsNamedAndALowCellThenDecidesAlone) {
  // From 300 s the pose is 6 m off (a GNSS drift that its own checks miss): every cell reads
  // 0.6 % per metre of it off its expectation, in the pattern of a misplaced turret. The
  // lines here pull at the vessel's reference point, where no heading error moves them, so
  // the pattern names the GNSS. Line 2 parts at 700 s, and the bias shows nothing of it.
  Story story;
  story.cells = [](double t, VecX& cells) {
    if (t < 300) return;
    for (int k = 0; k < kLines; ++k) {
      const Vec3 pull = testing::QuarterLineLoad(k + 1).normalized();
      cells(k) *= 1.0 - 0.006 * (3.0 * pull.x() + 5.2 * pull.y());
    }
  };
  const SensorId gnss{.kind = SensorId::Kind::kGnss};
  Fused fused;
  const Outcome intact = RunStory(fused, story, 1500);
  EXPECT_FALSE(intact.alarm.has_value());
  EXPECT_TRUE(Lists(intact.last, gnss, SensorSymptom::kDisagrees));
  story.parted = 2;
  story.part_time = 700;
  story.error_time = 700;
  story.bias_error = testing::QuarterLineLoad(2);  // cancels the lost load
  const Outcome f = RunStory(fused, story, 1500);
  ASSERT_TRUE(f.alarm.has_value());
  EXPECT_EQ(*f.alarm, 705.0);  // the cells' window and hold, as with a GNSS judged faulty
  EXPECT_EQ(f.hypothesis, 2);
  Cells cells;
  EXPECT_FALSE(RunStory(cells, story, 1500).alarm.has_value());
}

TEST(Fused, WithoutCellsItIsTheForceDeficitTest) {
  Story story;
  story.parted = 3;
  story.part_time = 700;
  Fused fused;
  Deficit deficit;
  const auto without_cells = [](Detector& d, const Story& s) {
    d.Reset(kLines + 1);
    Plant plant(s);
    std::optional<double> first;
    for (double t = 0; t <= 1500; t += 1.0) {
      Evidence e = plant.Sample(t);
      e.tensions.reset();
      const Verdict v = d.Update(e);
      if (v.alarm && !first) first = t;
    }
    return first;
  };
  const std::optional<double> f = without_cells(fused, story);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f, without_cells(deficit, story));
}

}  // namespace
}  // namespace moorsim::detectors::fused_test
