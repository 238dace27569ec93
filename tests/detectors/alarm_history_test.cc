// The alarm history: onsets, revisions and ends, and the questions a campaign asks of it.
#include "detectors/alarm_history.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/error.h"

namespace moorsim::detectors {
namespace {

using Kind = AlarmEvent::Kind;

/// Feeds (time, alarm, hypothesis) samples.
AlarmHistory Feed(const std::vector<std::tuple<double, bool, int>>& samples) {
  AlarmHistory h;
  for (const auto& [t, alarm, hypothesis] : samples) h.Update(t, alarm, hypothesis);
  return h;
}

TEST(AlarmHistory, RecordsOnsetsRevisionsAndEndsOnly) {
  const AlarmHistory h = Feed({{0, false, 4},  // no alarm: the named hypothesis is ignored
                               {1, false, 2},
                               {2, true, 3},  // onset on 3
                               {3, true, 3},
                               {4, true, 6},   // revision to 6
                               {5, false, 6},  // end
                               {6, false, 0},
                               {7, true, 6}});  // onset again
  const std::vector<AlarmEvent>& e = h.events();
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].kind, Kind::kOnset);
  EXPECT_EQ(e[0].time, 2.0);
  EXPECT_EQ(e[0].hypothesis, 3);
  EXPECT_EQ(e[1].kind, Kind::kRevision);
  EXPECT_EQ(e[1].time, 4.0);
  EXPECT_EQ(e[1].hypothesis, 6);
  EXPECT_EQ(e[2].kind, Kind::kEnd);
  EXPECT_EQ(e[2].time, 5.0);
  EXPECT_EQ(e[2].hypothesis, 0);
  EXPECT_EQ(e[3].kind, Kind::kOnset);
  EXPECT_TRUE(h.alarm());
  EXPECT_EQ(h.hypothesis(), 6);
  EXPECT_EQ(h.OnsetsBefore(7.0), 1);
  EXPECT_EQ(h.OnsetsBefore(7.5), 2);
  EXPECT_EQ(h.FirstOnset(0.0)->time, 2.0);
  EXPECT_EQ(h.FirstOnset(3.0)->time, 7.0);
  EXPECT_EQ(h.FirstOnset(3.0)->hypothesis, 6);
  EXPECT_FALSE(h.FirstOnset(7.5).has_value());
  EXPECT_EQ(AlarmEventName(Kind::kRevision), "revision");
}

// A line that parts under a standing false alarm raises no onset; the verdict names it when
// the alarm is revised, and that is when it is reported.
TEST(AlarmHistory, ALineThatPartsUnderAStandingAlarmIsReportedAtTheRevision) {
  const AlarmHistory h = Feed({{50, true, 3}, {100, true, 3}, {130, true, 6}, {200, true, 6}});
  EXPECT_EQ(h.FirstNamed(6, 100.0), 130.0);
  EXPECT_EQ(h.OnsetsBefore(100.0), 1);  // the false alarm, before the break
  EXPECT_FALSE(h.FirstNamed(8, 100.0).has_value());
  EXPECT_FALSE(h.FirstNamed(0, 100.0).has_value());  // intact is never "named"
}

TEST(AlarmHistory, AnAlarmStandingOnTheLineAtTheBreakNamesItThen) {
  const AlarmHistory h = Feed({{50, true, 6}, {100, true, 6}, {130, false, 0}});
  EXPECT_EQ(h.FirstNamed(6, 100.0), 100.0);
  EXPECT_FALSE(h.FirstNamed(6, 140.0).has_value());  // ended and never named again
  EXPECT_EQ(h.FirstNamed(6, 20.0), 50.0);            // from before: the onset
}

TEST(AlarmHistory, AlarmSecondsCountOpenAndClosedAlarms) {
  const AlarmHistory h = Feed({{10, true, 1}, {15, true, 2}, {20, false, 0}, {50, true, 4}});
  EXPECT_DOUBLE_EQ(h.AlarmSeconds(0.0, 100.0), 10.0 + 50.0);
  EXPECT_DOUBLE_EQ(h.AlarmSeconds(15.0, 55.0), 5.0 + 5.0);
  EXPECT_DOUBLE_EQ(h.AlarmSeconds(20.0, 50.0), 0.0);
  EXPECT_DOUBLE_EQ(AlarmHistory().AlarmSeconds(0.0, 10.0), 0.0);
}

TEST(AlarmHistory, TimeMustNotGoBack) {
  AlarmHistory h;
  h.Update(5.0, false, 0);
  h.Update(5.0, true, 1);  // the same instant is fine
  EXPECT_THROW(h.Update(4.0, false, 0), ContractError);
}

TEST(SensorFaultHistory, EachSpellOfEachSensorWithItsStartAndEnd) {
  SensorFaultHistory h;
  const SensorId cell3{.kind = SensorId::Kind::kCell, .line = 3};
  const SensorFinding cell3_low{.sensor = cell3, .symptom = SensorSymptom::kDisagrees};
  const SensorFinding gnss_jump{.sensor = {.kind = SensorId::Kind::kGnss},
                                .symptom = SensorSymptom::kJump};
  const SensorFinding gnss_noisy{.sensor = {.kind = SensorId::Kind::kGnss},
                                 .symptom = SensorSymptom::kNoisy};
  h.Update(1.0, {});
  h.Update(2.0, {cell3_low});
  h.Update(3.0, {cell3_low, gnss_jump});
  h.Update(4.0, {gnss_jump});
  h.Update(5.0, {cell3_low, gnss_jump});
  h.Update(6.0, {cell3_low, gnss_noisy});  // the same sensor, another symptom: a new spell
  ASSERT_EQ(h.spells().size(), 4u);
  EXPECT_EQ(h.spells()[0].sensor.Name(), "cell 3");
  EXPECT_EQ(h.spells()[0].since, 2.0);
  EXPECT_EQ(h.spells()[0].until, 4.0);
  EXPECT_EQ(h.spells()[1].sensor.Name(), "GNSS");
  EXPECT_EQ(SensorSymptomName(h.spells()[1].symptom), "jump");
  EXPECT_EQ(h.spells()[1].since, 3.0);
  EXPECT_EQ(h.spells()[1].until, 6.0);
  EXPECT_EQ(h.spells()[2].sensor, cell3);
  EXPECT_EQ(h.spells()[2].since, 5.0);
  EXPECT_FALSE(h.spells()[2].until);
  EXPECT_EQ(SensorSymptomName(h.spells()[3].symptom), "noisy");
  EXPECT_EQ(h.spells()[3].since, 6.0);
}

}  // namespace
}  // namespace moorsim::detectors
