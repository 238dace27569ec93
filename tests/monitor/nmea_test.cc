// NMEA 0183 sentences (monitor/nmea.h): sentences as receivers, gyros and load-cell
// amplifiers write them decoded to the numbers they hold (their checksums computed here by
// an independent sum); every kind of damage a serial line or a network does to a line named
// as its fault; a million mutated and random lines neither crash nor hang the parser and the
// decoders.
#include "monitor/nmea.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>

namespace moorsim::monitor {
namespace {

// The sentence with its checksum, written the way the standard defines it (the XOR of the
// bytes between $ and *), independently of NmeaChecksum.
std::string WithChecksum(const std::string& body, char start = '$') {
  unsigned char sum = 0;
  for (std::size_t i = 0; i < body.size(); ++i) sum = sum ^ static_cast<unsigned char>(body[i]);
  char tail[4];
  std::snprintf(tail, sizeof tail, "*%02X", sum);
  return start + body + tail;
}

NmeaSentence Parsed(const std::string& line) {
  const NmeaParse p = ParseNmea(line);
  EXPECT_TRUE(p.sentence.has_value()) << line << ": " << p.detail;
  return p.sentence.value_or(NmeaSentence{});
}

TEST(Nmea, AKnownSentenceChecksAgainstItsPublishedChecksum) {
  // The GGA example that receivers' manuals print, checksum 47.
  const NmeaParse p =
      ParseNmea("$GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,*47\r\n");
  ASSERT_TRUE(p.sentence.has_value()) << p.detail;
  EXPECT_EQ(p.sentence->talker, "GP");
  EXPECT_EQ(p.sentence->type, "GGA");
  EXPECT_EQ(p.sentence->fields.size(), 14u);
  EXPECT_EQ(NmeaChecksum("GPGGA,123519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,"), 0x47u);
}

TEST(Nmea, GgaGnsAndRmcGiveTheFixInSignedDegrees) {
  std::string why;
  const std::optional<NmeaFix> gga = DecodeFix(
      Parsed(WithChecksum("GNGGA,071502.25,6027.58940,S,00520.12760,W,4,21,0.6,12.3,M,44.1,M,,")),
      &why);
  ASSERT_TRUE(gga.has_value()) << why;
  EXPECT_DOUBLE_EQ(*gga->time_of_day, 7 * 3600 + 15 * 60 + 2.25);
  EXPECT_DOUBLE_EQ(gga->latitude, -(60.0 + 27.58940 / 60.0));
  EXPECT_DOUBLE_EQ(gga->longitude, -(5.0 + 20.12760 / 60.0));
  EXPECT_EQ(gga->quality, 4);
  EXPECT_EQ(gga->satellites, 21);
  EXPECT_DOUBLE_EQ(*gga->hdop, 0.6);
  EXPECT_DOUBLE_EQ(*gga->altitude, 12.3);

  // GNS: a mode letter per constellation, the best taken (R: RTK fixed).
  const std::optional<NmeaFix> gns = DecodeFix(
      Parsed(WithChecksum("GNGNS,071502.00,6027.5894,N,00520.1276,E,ARN,18,0.7,12.3,44.1,,")),
      &why);
  ASSERT_TRUE(gns.has_value()) << why;
  EXPECT_EQ(gns->quality, 4);
  EXPECT_DOUBLE_EQ(gns->latitude, 60.0 + 27.5894 / 60.0);
  EXPECT_DOUBLE_EQ(gns->longitude, 5.0 + 20.1276 / 60.0);

  // RMC: valid (A) with its mode D; void (V) is quality 0 whatever the mode says.
  const std::optional<NmeaFix> rmc = DecodeFix(
      Parsed(WithChecksum("GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E,D")),
      &why);
  ASSERT_TRUE(rmc.has_value()) << why;
  EXPECT_EQ(rmc->quality, 2);
  EXPECT_DOUBLE_EQ(rmc->longitude, -(123.0 + 11.12 / 60.0));
  EXPECT_FALSE(rmc->satellites.has_value());
  const std::optional<NmeaFix> void_fix = DecodeFix(
      Parsed(WithChecksum("GPRMC,225446,V,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E,A")),
      &why);
  ASSERT_TRUE(void_fix.has_value()) << why;
  EXPECT_EQ(void_fix->quality, 0);
}

TEST(Nmea, HeadingsTransducersAndTheClockDecode) {
  std::string why;
  const std::optional<NmeaHeading> hdt =
      DecodeHeading(Parsed(WithChecksum("HEHDT,274.07,T")), &why);
  ASSERT_TRUE(hdt.has_value()) << why;
  EXPECT_DOUBLE_EQ(hdt->degrees, 274.07);
  EXPECT_FALSE(hdt->mode.has_value());
  const std::optional<NmeaHeading> ths =
      DecodeHeading(Parsed(WithChecksum("INTHS,360.00,E")), &why);
  ASSERT_TRUE(ths.has_value()) << why;
  EXPECT_DOUBLE_EQ(ths->degrees, 0.0);  // 360 is north
  EXPECT_EQ(ths->mode, 'E');

  const std::optional<std::vector<NmeaTransducer>> cells =
      DecodeTransducers(Parsed(WithChecksum("IIXDR,N,4.91E6,N,LINE1,N,4893000.5,N,LINE2")), &why);
  ASSERT_TRUE(cells.has_value()) << why;
  ASSERT_EQ(cells->size(), 2u);
  EXPECT_EQ((*cells)[0].type, 'N');
  EXPECT_DOUBLE_EQ((*cells)[0].value, 4.91e6);
  EXPECT_EQ((*cells)[1].name, "LINE2");
  EXPECT_EQ((*cells)[1].units, "N");

  const std::optional<NmeaClock> zda =
      DecodeClock(Parsed(WithChecksum("GPZDA,201530.00,04,07,2026,-03,30")), &why);
  ASSERT_TRUE(zda.has_value()) << why;
  EXPECT_DOUBLE_EQ(zda->time_of_day, 20 * 3600 + 15 * 60 + 30.0);
  EXPECT_EQ(zda->day, 4);
  EXPECT_EQ(zda->month, 7);
  EXPECT_EQ(zda->year, 2026);
  EXPECT_EQ(zda->zone_minutes, -(3 * 60 + 30));
}

TEST(Nmea, EveryKindOfDamageIsNamedAsItsFault) {
  const std::string good = WithChecksum("HEHDT,274.07,T");
  struct Case {
    std::string line;
    NmeaFault fault;
  } cases[] = {
      {"", NmeaFault::kEmpty},
      {"\r\n", NmeaFault::kEmpty},
      {good.substr(1), NmeaFault::kNoStart},
      {WithChecksum("HEHDT," + std::string(90, '1') + ",T"), NmeaFault::kTooLong},
      {WithChecksum("HEHDT,274.07\t,T"), NmeaFault::kBadCharacter},
      {WithChecksum("HEHDT,27\xb0,T"), NmeaFault::kBadCharacter},
      {"$HEHDT,274.07,T", NmeaFault::kNoChecksum},
      {good.substr(0, good.size() - 1), NmeaFault::kNoChecksum},
      {good.substr(0, good.size() - 2) + "G7", NmeaFault::kNoChecksum},
      {"$HEHDT,274.08,T" + good.substr(good.size() - 3), NmeaFault::kBadChecksum},
      {WithChecksum("HEHDT$274.07,T"), NmeaFault::kBadCharacter},
      {WithChecksum("HE*HDT,274.07,T"), NmeaFault::kBadCharacter},
      {WithChecksum("hehdt,274.07,T"), NmeaFault::kBadAddress},
      {WithChecksum("HEHD,274.07,T"), NmeaFault::kBadAddress},
      {WithChecksum(",274.07,T"), NmeaFault::kBadAddress},
  };
  for (const Case& c : cases) {
    const NmeaParse p = ParseNmea(c.line);
    EXPECT_FALSE(p.sentence.has_value()) << c.line;
    EXPECT_EQ(p.fault, c.fault) << c.line << ": " << p.detail;
    EXPECT_FALSE(p.detail.empty()) << c.line;
  }
  // A proprietary sentence parses (its fields are the maker's).
  const NmeaSentence proprietary = Parsed(WithChecksum("PGRME,15.0,M,45.0,M,25.0,M"));
  EXPECT_EQ(proprietary.talker, "P");
  EXPECT_EQ(proprietary.type, "GRME");
  // The checksum's digits in either case.
  std::string lower = WithChecksum("IIXDR,N,4.91E6,N,LINE1");
  for (std::size_t k = lower.size() - 2; k < lower.size(); ++k) {
    lower[k] = static_cast<char>(std::tolower(static_cast<unsigned char>(lower[k])));
  }
  EXPECT_TRUE(ParseNmea(lower).sentence.has_value()) << lower;
}

TEST(Nmea, ADecoderNamesTheFieldItCannotRead) {
  const struct {
    std::string body;
    std::string why;
  } cases[] = {
      {"GPGGA,123519,,,,,0,00,,,M,,M,,", "GGA field 2 '': no position (no fix)"},
      {"GPGGA,123519,4807.038,X,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",
       "GGA field 3 'X': not N or S"},
      {"GPGGA,123519,9107.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",
       "GGA field 2 '9107.038': beyond 90 deg"},
      {"GPGGA,123519,4867.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",
       "GGA field 2 '4867.038': not ddmm.mmmm"},
      {"GPGGA,123519,4807.038,N,1131.000,E,1,08,0.9,545.4,M,46.9,M,,",
       "GGA field 4 '1131.000': not dddmm.mmmm"},
      {"GPGGA,253519,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,",
       "GGA field 1 '253519': not a time hhmmss.ss"},
      {"GPGGA,123519,4807.038,N,01131.000,E,,08,0.9,545.4,M,46.9,M,,", "GGA field 6 '': empty"},
      {"GPGGA,123519,4807.038,N,01131.000,E,1,08,nan,545.4,M,46.9,M,,",
       "GGA field 8 'nan': not a number in [0, 100]"},
      {"GNGNS,071502.00,6027.5894,N,00520.1276,E,AX,18,0.7,12.3,44.1,,",
       "GNS field 6 'AX': not one or more mode letters"},
      {"HEHDT,-1,T", "HDT field 1 '-1': not a number in [0, 360]"},
      {"HEHDT,274.07,M", "HDT field 2 'M': not T (true)"},
      {"HEHDT,,T", "HDT field 1 '': empty"},
      {"INTHS,12.5,Q", "THS field 2 'Q': not a mode A, E, M, S or V"},
      {"IIXDR,N,4.91E6,N", "XDR field 4 '': XDR holds quadruplets of type, value, units and name"},
      {"IIXDR,N,4.91E6,N,", "XDR field 4 '': no transducer name"},
      {"IIXDR,N,lots,N,LINE1", "XDR field 2 'lots': not a number in [-1e+15, 1e+15]"},
      {"GPZDA,201530.00,32,07,2026,,", "ZDA field 2 '32': not a whole number in 1..31"},
  };
  for (const auto& c : cases) {
    const NmeaSentence s = Parsed(WithChecksum(c.body));
    std::string why;
    bool decoded = false;
    if (s.type == "GGA" || s.type == "GNS" || s.type == "RMC")
      decoded = DecodeFix(s, &why).has_value();
    if (s.type == "HDT" || s.type == "THS") decoded = DecodeHeading(s, &why).has_value();
    if (s.type == "XDR") decoded = DecodeTransducers(s, &why).has_value();
    if (s.type == "ZDA") decoded = DecodeClock(s, &why).has_value();
    EXPECT_FALSE(decoded) << c.body;
    EXPECT_EQ(why, c.why) << c.body;
  }
  EXPECT_THROW(DecodeHeading(Parsed(WithChecksum("GPZDA,201530.00,04,07,2026,,")), nullptr),
               std::invalid_argument);
}

// A million lines: valid sentences of every type mutated (bytes flipped, cut, repeated,
// fields dropped or emptied) and random bytes. Nothing crashes or hangs (the sanitizer
// build checks every read); every line is a sentence or a named fault.
TEST(Nmea, MutatedAndRandomLinesAreSentencesOrNamedFaults) {
  const std::vector<std::string> valid = {
      WithChecksum("GNGGA,071502.25,6027.58940,S,00520.12760,W,4,21,0.6,12.3,M,44.1,M,,"),
      WithChecksum("GNGNS,071502.00,6027.5894,N,00520.1276,E,ARN,18,0.7,12.3,44.1,,"),
      WithChecksum("GPRMC,225446,A,4916.45,N,12311.12,W,000.5,054.7,191194,020.3,E,D"),
      WithChecksum("HEHDT,274.07,T"),
      WithChecksum("INTHS,12.5,A"),
      WithChecksum("IIXDR,N,4.91E6,N,LINE1,N,4893000.5,N,LINE2"),
      WithChecksum("GPZDA,201530.00,04,07,2026,-03,30")};
  std::mt19937_64 random(20261207);
  const auto below = [&](std::size_t n) { return static_cast<std::size_t>(random() % n); };
  int sentences = 0, decoded = 0;
  constexpr int kLines = 1'000'000;
  for (int i = 0; i < kLines; ++i) {
    std::string line;
    if (i % 10 == 0) {
      line.resize(below(100));
      for (char& c : line) c = static_cast<char>(random());
    } else {
      line = valid[below(valid.size())];
      for (std::size_t m = 1 + below(3); m > 0 && !line.empty(); --m) {
        const std::size_t at = below(line.size());
        switch (below(5)) {
          case 0:
            line[at] = static_cast<char>(line[at] ^ (1 << below(8)));
            break;
          case 1:
            line.erase(at, 1 + below(8));
            break;
          case 2:
            line.insert(at, line.substr(below(line.size()), 1 + below(6)));
            break;
          case 3:
            line.insert(at, 1, ",*$!-."[below(6)]);
            break;
          default:
            line.resize(at);
        }
      }
      // Most flips break the checksum; now and then make it right again, so that the
      // decoders see damaged fields too.
      if (i % 3 == 0 && line.size() > 4 && line.find('*') != std::string::npos) {
        line = WithChecksum(line.substr(1, line.rfind('*') - 1), line[0]);
      }
    }
    const NmeaParse p = ParseNmea(line);
    ASSERT_EQ(p.sentence.has_value(), p.fault == NmeaFault::kNone) << line;
    if (!p.sentence) {
      ASSERT_FALSE(p.detail.empty()) << line;
      continue;
    }
    ++sentences;
    std::string why;
    const NmeaSentence& s = *p.sentence;
    bool ok = true;
    if (s.type == "GGA" || s.type == "GNS" || s.type == "RMC")
      ok = DecodeFix(s, &why).has_value();
    else if (s.type == "HDT" || s.type == "THS")
      ok = DecodeHeading(s, &why).has_value();
    else if (s.type == "XDR")
      ok = DecodeTransducers(s, &why).has_value();
    else if (s.type == "ZDA")
      ok = DecodeClock(s, &why).has_value();
    ASSERT_TRUE(ok || !why.empty()) << line;
    decoded += ok ? 1 : 0;
  }
  // The mutations reach both the parser's checks and the decoders'.
  EXPECT_GT(sentences, kLines / 20);
  EXPECT_GT(decoded, kLines / 50);
  EXPECT_LT(decoded, sentences);
}

}  // namespace
}  // namespace moorsim::monitor
