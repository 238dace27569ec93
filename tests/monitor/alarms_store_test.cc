// The alarm list (monitor/alarms.h) as bridge alert management has it, the ALR and ACK
// sentences, and the store (monitor/store.h): what was written reads back exactly, across a
// reopening, and a store is not reused by another scenario.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/error.h"
#include "monitor/alarms.h"
#include "monitor/nmea.h"
#include "monitor/store.h"
#include "tests/cli/run_cli.h"

namespace moorsim::monitor {
namespace {

using ::testing::HasSubstr;

TEST(AlarmBoard, AnAlarmStaysListedUntilClearedAndAcknowledged) {
  AlarmBoard board;
  std::vector<AlarmChange> changes = board.Update({{6, "Mooring line 6 parted"}}, 100.0);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].kind, AlarmChange::Kind::kRaised);
  EXPECT_TRUE(board.Update({{6, "Mooring line 6 parted"}}, 101.0).empty());
  changes = board.Update({}, 102.0);
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0].kind, AlarmChange::Kind::kCleared);
  EXPECT_EQ(board.listed().size(), 1u);  // rectified, unacknowledged
  const std::optional<AlarmChange> ack = board.Acknowledge(6, 103.0, "bridge");
  ASSERT_TRUE(ack.has_value());
  EXPECT_EQ(ack->alarm.acknowledged_by, "bridge");
  EXPECT_TRUE(board.listed().empty());
  EXPECT_FALSE(board.Acknowledge(6, 104.0, "bridge").has_value());
  // Acknowledged while it holds: listed until it clears.
  board.Update({{101, "Heading stale"}}, 105.0);
  ASSERT_TRUE(board.Acknowledge(101, 106.0, "display").has_value());
  EXPECT_EQ(board.listed().size(), 1u);
  board.Update({}, 107.0);
  EXPECT_TRUE(board.listed().empty());
}

TEST(AlarmSentences, AnAlrIsAValidSentenceOfAtMost82CharactersAndAnAckNamesItsNumber) {
  Alarm alarm;
  alarm.number = 6;
  alarm.raised = 1796662649.5;  // 16:57:29.50 UTC
  alarm.text = "Mooring line 6 parted, says $everyone* " + std::string(80, 'x');
  const std::string alr = AlrSentence("MM", alarm);
  EXPECT_LE(alr.size(), kNmeaMaxLength);
  const NmeaParse parse = ParseNmea(alr);
  ASSERT_TRUE(parse.sentence.has_value()) << parse.detail;
  EXPECT_EQ(parse.sentence->talker, "MM");
  EXPECT_EQ(parse.sentence->type, "ALR");
  EXPECT_EQ(parse.sentence->fields[0], "165729.50");
  EXPECT_EQ(parse.sentence->fields[1], "006");
  EXPECT_EQ(parse.sentence->fields[2], "A");
  EXPECT_EQ(parse.sentence->fields[3], "V");
  EXPECT_THAT(parse.sentence->fields[4],
              ::testing::StartsWith("Mooring line 6 parted  says  everyone "));
  alarm.cleared = 1796662700.0;
  alarm.acknowledged = 1796662690.0;
  const NmeaParse cleared = ParseNmea(AlrSentence("MM", alarm));
  EXPECT_EQ(cleared.sentence->fields[2], "V");
  EXPECT_EQ(cleared.sentence->fields[3], "A");

  std::string why;
  EXPECT_EQ(AckNumber(*ParseNmea(NmeaText('$', "BRACK", {"006"})).sentence, &why), 6);
  EXPECT_FALSE(AckNumber(*ParseNmea(NmeaText('$', "BRACK", {"6x"})).sentence, &why));
  EXPECT_THAT(why, HasSubstr("ACK field 1 '6x'"));
}

TEST(Store, SamplesAlarmsAndAcknowledgementsReadBackAfterReopening) {
  const moorsim::testing::TempDirectory dir(::testing::TempDir());
  const std::string folder = (dir.path() / "store").string();
  StoreIdentity identity;
  identity.scenario_text = "name: a\n";
  const double now = 1796662000.25;
  {
    Store store(folder, identity, now);
    EXPECT_FALSE(store.resumed());
    EXPECT_EQ(store.epoch(), 1796662000.0);
    for (int k = 0; k < 3; ++k) {
      Sample sample;
      sample.index = k;
      sample.observation.t = k;
      sample.observation.pose = Vec3(0.1 * k, 1.0 / 3.0, -2.0);
      sample.observation.valid = {true, true, k != 1};
      sample.observation.tau_command = Vec3(1e5 / 3.0, 2, 3);
      if (k == 2) sample.observation.tensions = VecX::Constant(2, 1e6 / 7.0);
      if (k == 1) {  // cell 1 withheld
        sample.observation.tensions = VecX::Constant(2, 2e6 / 7.0);
        (*sample.observation.tensions)(0) = kNaN;
      }
      store.SampleTaken(sample, 1);
    }
    Alarm alarm;
    alarm.number = 6;
    alarm.text = "Mooring line 6 parted";
    alarm.raised = now + 1;
    alarm.id = store.Change({AlarmChange::Kind::kRaised, alarm});
    alarm.acknowledged = now + 2;
    alarm.acknowledged_by = "bridge";
    store.Change({AlarmChange::Kind::kAcknowledged, alarm});
  }
  Store store(folder, identity, now + 100);
  EXPECT_TRUE(store.resumed());
  EXPECT_EQ(store.epoch(), 1796662000.0);
  const std::vector<Alarm> listed = store.ListedAlarms();
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].number, 6);
  EXPECT_EQ(listed[0].acknowledged, now + 2);
  EXPECT_EQ(listed[0].acknowledged_by, "bridge");
  EXPECT_FALSE(listed[0].cleared.has_value());
  const std::vector<StoredSample> samples = ReadStoredSamples(folder, 0.0, 1e12);
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[1].observation.pose(1), 1.0 / 3.0);
  EXPECT_FALSE(samples[1].observation.valid[2]);
  EXPECT_EQ(samples[2].observation.tau_command(0), 1e5 / 3.0);
  ASSERT_TRUE(samples[2].observation.tensions.has_value());
  EXPECT_EQ((*samples[2].observation.tensions)(1), 1e6 / 7.0);
  ASSERT_TRUE(samples[1].observation.tensions.has_value());
  EXPECT_TRUE(std::isnan((*samples[1].observation.tensions)(0)));
  EXPECT_EQ((*samples[1].observation.tensions)(1), 2e6 / 7.0);
  EXPECT_FALSE(samples[0].observation.tensions.has_value());
  EXPECT_EQ(store.LastSegment(), 1);

  StoreIdentity other = identity;
  other.scenario_text = "name: b\n";
  try {
    Store wrong(folder, other, now);
    FAIL() << "another scenario's store was reused";
  } catch (const InputError& error) {
    EXPECT_THAT(error.what(), HasSubstr("the store of another scenario"));
  }
}

}  // namespace
}  // namespace moorsim::monitor

namespace moorsim::monitor {
namespace {

TEST(Store, RecordsPastTheirDaysAreDeletedAndTheRestKept) {
  const moorsim::testing::TempDirectory dir(::testing::TempDir());
  const std::filesystem::path folder = dir.path() / "store";
  std::filesystem::create_directories(folder);
  for (const char* name : {"record-2026-12-01.db", "record-2026-12-01.db-wal",
                           "record-2026-12-05.db", "record-2026-12-06.db", "monitor-notes.txt"}) {
    moorsim::testing::WriteWholeFile(folder / name, "x");
  }
  StoreIdentity identity;
  identity.scenario_text = "name: a\n";
  // 2026-12-07 12:00 UTC, two days kept: the 6th and the 7th.
  const Store store(folder.string(), identity, 1796644800.0, 2);
  EXPECT_FALSE(std::filesystem::exists(folder / "record-2026-12-01.db"));
  EXPECT_FALSE(std::filesystem::exists(folder / "record-2026-12-01.db-wal"));
  EXPECT_FALSE(std::filesystem::exists(folder / "record-2026-12-05.db"));
  EXPECT_TRUE(std::filesystem::exists(folder / "record-2026-12-06.db"));
  EXPECT_TRUE(std::filesystem::exists(folder / "record-2026-12-07.db"));
  EXPECT_TRUE(std::filesystem::exists(folder / "monitor-notes.txt"));
  EXPECT_TRUE(std::filesystem::exists(folder / "monitor.db"));
}

}  // namespace
}  // namespace moorsim::monitor
