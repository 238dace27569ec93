// A followed log through the rotations `tail -F` follows: copy-and-truncate, a rewrite in
// place (shorter or longer than what was read), rename-and-create, a file moved away and
// one put back. Each step is taken between two reads, so the tests are deterministic.
#include "simulation/followed_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/scratch_directory.h"

namespace moorsim::simulation {
namespace {

namespace fs = std::filesystem;

void Write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}
void Append(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary | std::ios::app) << text;
}

// What one look at the file gives: the lines it has now and the rotations met on the way.
struct Read {
  std::vector<std::string> lines;
  std::vector<std::string> events;  // "truncated", "rewritten:3" (with dropped bytes), ...
};

// Reads until the follower has waited at the end of the file a few times (a stop that
// comes after three looks), so a rotation made before the call is always seen.
Read ReadNow(FollowedFile& file) {
  Read read;
  for (;;) {
    int looks = 0;
    std::string line;
    const bool more = file.Next(
        &line, [&] { return ++looks > 3; },
        [&](Rotation rotation, std::size_t dropped) {
          std::string event = RotationName(rotation);
          if (dropped > 0) event.append(":").append(std::to_string(dropped));
          read.events.push_back(event);
        });
    if (!more) return read;
    read.lines.push_back(line);
  }
}

using Lines = std::vector<std::string>;

TEST(FollowedFile, ALineWrittenInTwoPartsComesWhole) {
  const fs::path log = moorsim::testing::FreshDirectory("follow_split") / "log.csv";
  Write(log, "time,x\n0,1");
  FollowedFile file(log.string(), 1);
  std::string line;
  const auto never = [] { return false; };
  const auto no_rotation = [](Rotation, std::size_t) { FAIL() << "no rotation expected"; };
  ASSERT_TRUE(file.Next(&line, never, no_rotation));
  EXPECT_EQ(line, "time,x");
  Append(log, ".5\n1,2\n");
  ASSERT_TRUE(file.Next(&line, never, no_rotation));
  EXPECT_EQ(line, "0,1.5");
  ASSERT_TRUE(file.Next(&line, never, no_rotation));
  EXPECT_EQ(line, "1,2");
}

TEST(FollowedFile, CopyAndTruncateIsFollowedFromTheStart) {
  const fs::path log = moorsim::testing::FreshDirectory("follow_truncate") / "log.csv";
  Write(log, "time,x\n0,1\n1,2\n");
  FollowedFile file(log.string(), 1);
  EXPECT_EQ(ReadNow(file).lines, (Lines{"time,x", "0,1", "1,2"}));
  Write(log, "");  // logrotate's copytruncate
  Append(log, "2,3\n");
  const Read after = ReadNow(file);
  EXPECT_EQ(after.events, (Lines{"truncated"}));
  EXPECT_EQ(after.lines, (Lines{"2,3"}));
  // Nothing more happens until the file changes again.
  EXPECT_EQ(ReadNow(file).events, Lines{});
  Append(log, "3,4\n");
  EXPECT_EQ(ReadNow(file).lines, (Lines{"3,4"}));
}

TEST(FollowedFile, AFileRewrittenLongerIsReadFromItsStartNotTheOldOffset) {
  const fs::path log = moorsim::testing::FreshDirectory("follow_rewrite") / "log.csv";
  Write(log, "time,x\n0,1\n1,2\n");
  FollowedFile file(log.string(), 1);
  EXPECT_EQ(ReadNow(file).lines.size(), 3u);
  Write(log, "time,x\n10,11\n11,12\n12,13\n13,14\n");
  const Read after = ReadNow(file);
  EXPECT_EQ(after.events, (Lines{"rewritten"}));
  EXPECT_EQ(after.lines, (Lines{"time,x", "10,11", "11,12", "12,13", "13,14"}));
}

TEST(FollowedFile, AnUnfinishedLineCutOffByATruncationIsDroppedAndCounted) {
  const fs::path log = moorsim::testing::FreshDirectory("follow_partial") / "log.csv";
  Write(log, "time,x\n0,1\n1,");
  FollowedFile file(log.string(), 1);
  std::string line;
  const auto never = [] { return false; };
  const auto no_rotation = [](Rotation, std::size_t) { FAIL() << "no rotation expected"; };
  ASSERT_TRUE(file.Next(&line, never, no_rotation));
  ASSERT_TRUE(file.Next(&line, never, no_rotation));
  EXPECT_EQ(line, "0,1");
  Write(log, "2,3\n");
  const Read after = ReadNow(file);
  EXPECT_EQ(after.events, (Lines{"truncated:2"}));
  EXPECT_EQ(after.lines, (Lines{"2,3"}));
}

TEST(FollowedFile, RenameAndCreateReadsTheOldFileToItsEndThenTheNewOne) {
  const fs::path dir = moorsim::testing::FreshDirectory("follow_rename");
  const fs::path log = dir / "log.csv";
  Write(log, "time,x\n0,1\n");
  FollowedFile file(log.string(), 1);
  EXPECT_EQ(ReadNow(file).lines.size(), 2u);
  Append(log, "1,2\n");  // written just before the rotation
  fs::rename(log, dir / "log.csv.1");
  Write(log, "time,x\n2,3\n");
  const Read after = ReadNow(file);
  EXPECT_EQ(after.lines, (Lines{"1,2", "time,x", "2,3"}));
  EXPECT_EQ(after.events, (Lines{"replaced"}));
}

TEST(FollowedFile, AFileMovedAwayIsStillReadUntilANewOneAppears) {
  const fs::path dir = moorsim::testing::FreshDirectory("follow_missing");
  const fs::path log = dir / "log.csv";
  Write(log, "time,x\n0,1\n");
  FollowedFile file(log.string(), 1);
  EXPECT_EQ(ReadNow(file).lines.size(), 2u);
  fs::rename(log, dir / "moved.csv");
  EXPECT_EQ(ReadNow(file).events, (Lines{"missing"}));
  EXPECT_EQ(ReadNow(file).events, Lines{});  // said once
  Append(dir / "moved.csv", "1,2\n");
  EXPECT_EQ(ReadNow(file).lines, (Lines{"1,2"}));
  Write(log, "time,x\n2,3\n");
  const Read after = ReadNow(file);
  EXPECT_EQ(after.events, (Lines{"replaced"}));
  EXPECT_EQ(after.lines, (Lines{"time,x", "2,3"}));
}

TEST(FollowedFile, AtTheStopTheLastLineWithoutItsNewlineCounts) {
  const fs::path log = moorsim::testing::FreshDirectory("follow_stop") / "log.csv";
  Write(log, "time,x\n0,1");
  FollowedFile file(log.string(), 1);
  EXPECT_EQ(ReadNow(file).lines, (Lines{"time,x", "0,1"}));
}

}  // namespace
}  // namespace moorsim::simulation
