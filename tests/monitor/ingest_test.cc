// From lines to samples (monitor/ingest.h), against what the harness writes for a known
// sample (monitor/harness.h): the pose comes back through latitude, longitude, the grid's
// north and the antenna's offset to within the sentences' resolution; a sample closes with
// the line that completes it; a missing heading is a dropout; a long silence suspends the
// detection and the next complete sample starts a segment; every bad line is counted by
// its fault.
#include "monitor/ingest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/angles.h"
#include "monitor/harness.h"
#include "monitor/nmea.h"
#include "tests/support/sanitized.h"

namespace moorsim::monitor {
namespace {

constexpr double kEpoch = 1796662000.0;

scenarios::MonitorConfig Config(bool thrust, bool cells) {
  scenarios::MonitorConfig c;
  c.latitude = 61.25;
  c.longitude = 1.75;
  c.grid_north = 20.0;
  c.antenna[0] = 40.0;
  c.antenna[1] = -5.0;
  scenarios::FeedConfig f;
  f.name = "ship";
  c.feeds.push_back(f);
  if (thrust) c.thrust = scenarios::ThrustConfig{"ship", {"TX", "TY", "TN"}};
  if (cells) {
    c.cells.push_back({"LC1", 1});
    c.cells.push_back({"LC2", 2, 1000.0, "kN"});
  }
  c.max_gap = 5.0;
  return c;
}

detectors::Observation Sample(double t) {
  detectors::Observation o;
  o.t = t;
  o.pose = Vec3(12.345 + t, -6.789, -2.35 + 0.01 * t);
  o.tau_command = Vec3(1.5e5, -2.5e4, 3.0e6);
  VecX tensions(2);
  tensions << 1.2345e6, 2.5e6;
  o.tensions = tensions;
  return o;
}

// The lines of the sample at t, as the harness sends them (1 ms after the instant).
std::vector<FeedLine> LinesOf(SentenceWriter& writer, const detectors::Observation& o) {
  std::vector<FeedLine> lines;
  const double stamp = kEpoch + o.t + 1e-3;
  for (const PlayedLine& l : writer.Lines(o, stamp)) lines.push_back({l.feed, l.text, stamp});
  return lines;
}

TEST(Ingest, APoseComesBackThroughLatitudeLongitudeGridAndAntenna) {
  const scenarios::MonitorConfig config = Config(true, true);
  SentenceWriter writer(config, Routing{0, 0, 0, 0});
  Ingest ingest(config, 2, 1.0, kEpoch);
  for (int k = 0; k < 3; ++k) {
    for (const FeedLine& line : LinesOf(writer, Sample(k))) ingest.Take(line);
    // Closed by its last line (the cells and the thrust complete it), not by the next one.
    const std::vector<monitor::Sample> samples = ingest.TakeSamples();
    ASSERT_EQ(samples.size(), 1u) << "k = " << k;
    const detectors::Observation& o = samples[0].observation;
    const detectors::Observation expected = Sample(k);
    EXPECT_EQ(samples[0].index, k);
    EXPECT_EQ(samples[0].starts_segment, k == 0);
    EXPECT_EQ(o.t, expected.t);
    EXPECT_TRUE(o.valid[0] && o.valid[1] && o.valid[2]);
    // 7 decimals of a minute: 0.19 mm of latitude; the heading to 1e-4 deg (40 m of
    // antenna arm turns 0.07 mm).
    EXPECT_NEAR(o.pose(0), expected.pose(0), 5e-4);
    EXPECT_NEAR(o.pose(1), expected.pose(1), 5e-4);
    EXPECT_NEAR(o.pose(2), expected.pose(2), 1e-4 * kDegree);
    EXPECT_NEAR((o.tau_command - expected.tau_command).norm(), 0.0, 0.1);
    ASSERT_TRUE(o.tensions.has_value());
    EXPECT_NEAR((*o.tensions)(0), 1.2345e6, 0.05);
    EXPECT_NEAR((*o.tensions)(1), 2.5e6, 50.0);  // kN to one decimal
  }
  EXPECT_EQ(ingest.channels()[kPositionChannel].detail, "GGA quality 1, 12 satellites, HDOP 0.8");
  EXPECT_EQ(ingest.channels()[kHeadingChannel].detail, "HDT");
}

TEST(Ingest, AMissingHeadingIsADropoutAndALongSilenceSuspendsTheDetection) {
  const scenarios::MonitorConfig config = Config(false, false);
  SentenceWriter writer(config, Routing{0, 0, 0, -1});
  Ingest ingest(config, 2, 1.0, kEpoch);
  const auto play = [&](double t, bool heading) {
    detectors::Observation o = Sample(t);
    o.valid[2] = heading;
    for (const FeedLine& line : LinesOf(writer, o)) ingest.Take(line);
  };
  play(0, true);
  play(1, false);  // the GGA alone: the interval waits for its heading
  EXPECT_EQ(ingest.TakeSamples().size(), 1u);
  play(2, true);  // its first line closes interval 1 without a heading
  std::vector<monitor::Sample> samples = ingest.TakeSamples();
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_TRUE(samples[0].observation.valid[0]);
  EXPECT_FALSE(samples[0].observation.valid[2]);
  EXPECT_TRUE(samples[1].observation.valid[2]);
  // Nothing from 3 s to 10 s: dropouts up to max_gap (5 s), then suspended.
  ingest.Advance(kEpoch + 10.5, kEpoch + 10.5);
  samples = ingest.TakeSamples();
  ASSERT_EQ(samples.size(), 5u);  // 3, 4, 5, 6, 7 (7 - 2 = 5 s without either)
  EXPECT_FALSE(ingest.active());
  for (const monitor::Sample& s : samples) EXPECT_FALSE(s.observation.valid[0]);
  play(12, true);
  samples = ingest.TakeSamples();
  ASSERT_EQ(samples.size(), 1u);
  EXPECT_TRUE(samples[0].starts_segment);
  EXPECT_EQ(samples[0].index, 12);
  EXPECT_TRUE(ingest.active());
}

TEST(Ingest, AStaleCellIsWithheldAloneAndNotWaitedFor) {
  scenarios::MonitorConfig config = Config(false, true);
  config.stale_after = 2.5;
  SentenceWriter writer(config, Routing{0, 0, 0, -1});
  Ingest ingest(config, 2, 1.0, kEpoch, Waits{.cells = true, .thrust = false});
  // Cell 2 reads at 0 and 1 s, then falls silent; cell 1 reads until 8 s.
  std::vector<monitor::Sample> samples;
  for (int k = 0; k < 12; ++k) {
    detectors::Observation o = Sample(k);
    if (k >= 2) (*o.tensions)(1) = kNaN;  // the harness sends nothing for it
    if (k >= 9) (*o.tensions)(0) = kNaN;
    for (const FeedLine& line : LinesOf(writer, o)) ingest.Take(line);
    // A sample closes with its own last line, except while a silent cell is still waited
    // for (not yet stale: samples 2, 3 for cell 2; 9, 10 for cell 1), when the next
    // interval's first line closes it.
    const std::size_t before = samples.size();
    for (monitor::Sample& s : ingest.TakeSamples()) samples.push_back(std::move(s));
    const std::size_t expected = (k == 2 || k == 9) ? 0 : (k == 4 || k == 11) ? 2 : 1;
    EXPECT_EQ(samples.size() - before, expected) << "k = " << k;
  }
  ASSERT_EQ(samples.size(), 12u);
  for (int k = 0; k < 12; ++k) {
    const detectors::Observation& o = samples[static_cast<std::size_t>(k)].observation;
    SCOPED_TRACE("sample " + std::to_string(k));
    EXPECT_EQ(o.t, k);
    if (k == 11) {  // both stale: no tensions
      EXPECT_FALSE(o.tensions.has_value());
      continue;
    }
    ASSERT_TRUE(o.tensions.has_value());
    EXPECT_NEAR((*o.tensions)(0), 1.2345e6, 0.05);  // held while not stale
    if (k < 4) {
      EXPECT_NEAR((*o.tensions)(1), 2.5e6, 50.0);  // held while not stale
    } else {
      EXPECT_TRUE(std::isnan((*o.tensions)(1)));  // withheld alone
    }
  }
}

TEST(Ingest, EveryBadLineIsCountedByItsFault) {
  const scenarios::MonitorConfig config = Config(false, true);
  Ingest ingest(config, 2, 1.0, kEpoch);
  const double t = kEpoch + 0.5;
  const std::string gga = NmeaText('$', "GPGGA",
                                   {"120000.00", "6115.0000000", "N", "00145.0000000", "E", "1",
                                    "12", "0.8", "0.0", "M", "0.0", "M", "", ""});
  std::string corrupted = gga;
  corrupted[10] = '9';
  const std::vector<std::string> lines = {
      corrupted,                                // bad checksum
      "$GPGGA,120000.00,6115.0000000,N",        // no checksum
      NmeaText('$', "GPGGA", {"1200", "x"}),    // bad field
      NmeaText('$', "GPGSV", {"1", "1", "0"}),  // not read
      NmeaText('$', "GPGGA",
               {"120000.00", "6115.0000000", "N", "00145.0000000", "E", "0", "0", "", "", "", "",
                "", "", ""}),                            // no fix
      NmeaText('$', "IIXDR", {"N", "5.0", "N", "LC2"}),  // wrong units
      std::string(300, 'x'),
  };
  for (const std::string& line : lines) ingest.Take({0, line, t});
  const FeedCounts& counts = ingest.feeds()[0];
  EXPECT_EQ(counts.faults.at("bad checksum"), 1);
  EXPECT_EQ(counts.faults.at("no checksum"), 1);
  EXPECT_EQ(counts.faults.at("bad field"), 1);
  EXPECT_EQ(counts.faults.at("no start"), 1);
  EXPECT_EQ(counts.ignored, 1);
  EXPECT_EQ(ingest.channels()[kPositionChannel].rejected, 1);
  EXPECT_EQ(ingest.channels()[3].rejected, 1);  // LC2
  EXPECT_EQ(ingest.channels()[kPositionChannel].readings, 0);
  EXPECT_TRUE(ingest.TakeSamples().empty());
}

TEST(LineSplitter, LinesEndAtCrOrLfAndAnOverlongOneIsCutOffAndCounted) {
  LineSplitter splitter;
  std::vector<std::string> lines;
  const auto take = [&](std::string line) { lines.push_back(std::move(line)); };
  const std::string bytes = "$A*00\r\n$B*00\r\r\n" + std::string(1000, 'y') + "\n$C";
  EXPECT_EQ(splitter.Take(bytes.data(), bytes.size(), take), 1);
  EXPECT_EQ(lines, (std::vector<std::string>{"$A*00", "$B*00"}));
  splitter.End(take);
  EXPECT_EQ(lines.back(), "$C");
}

}  // namespace
}  // namespace moorsim::monitor

namespace moorsim::monitor {
namespace {

// A million lines (a hundred thousand under the sanitizers): the sentences of a moving
// vessel, each mutated (a character changed, dropped or doubled, the line cut, bytes of
// noise) or left whole, through the ingest. Nothing throws; every line is used, ignored or
// a counted fault; every sample is finite and on the clock.
TEST(Ingest, AMillionMutatedLinesAreAllCountedAndTheSamplesStaySane) {
  constexpr long kLines = moorsim::testing::CaseCount(1000000, 100000);
  const scenarios::MonitorConfig config = Config(true, true);
  SentenceWriter writer(config, Routing{0, 0, 0, 0});
  Ingest ingest(config, 2, 1.0, kEpoch);
  std::mt19937_64 random(55);
  long lines = 0, samples = 0;
  double last_t = -1.0;
  for (int k = 0; lines < kLines; ++k) {
    for (FeedLine line : LinesOf(writer, Sample(k % 50))) {
      line.stamp = kEpoch + k + 1e-3;
      std::string& t = line.text;
      switch (random() % 6) {
        case 0:
          t[random() % t.size()] = static_cast<char>(random() & 0xff);
          break;
        case 1:
          t.erase(random() % t.size(), 1);
          break;
        case 2:
          t.resize(random() % t.size());
          break;
        case 3: {
          const std::size_t at = random() % t.size();
          t.insert(at, 1, t[at]);
          break;
        }
        case 4:
          for (char& c : t) c = static_cast<char>(random() & 0xff);
          break;
        default:
          break;  // whole
      }
      if (t.empty()) continue;
      ingest.Take(line);
      ++lines;
      for (const monitor::Sample& s : ingest.TakeSamples()) {
        ++samples;
        const detectors::Observation& o = s.observation;
        ASSERT_GT(o.t, last_t);
        last_t = o.t;
        ASSERT_EQ(o.t, static_cast<double>(s.index));
        for (int i = 0; i < 3; ++i) {
          if (o.valid[i]) {
            ASSERT_TRUE(std::isfinite(o.pose(i))) << i;
          }
        }
        ASSERT_TRUE(o.tau_command.allFinite());
        if (o.tensions) {  // a withheld cell is NaN; at least one reads
          ASSERT_FALSE(o.tensions->array().isInf().any());
          ASSERT_TRUE(o.tensions->array().isFinite().any());
        }
      }
    }
  }
  const FeedCounts& counts = ingest.feeds()[0];
  EXPECT_EQ(counts.sentences + counts.ignored + counts.Faults(), lines);
  EXPECT_GT(counts.Faults(), lines / 2);
  EXPECT_GT(samples, lines / 40);  // a sixth of the fixes and headings are whole
}

}  // namespace
}  // namespace moorsim::monitor
