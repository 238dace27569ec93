#include "monitor/nmea.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/format.h"

namespace moorsim::monitor {
namespace {

NmeaParse Fault(NmeaFault fault, std::string detail) {
  NmeaParse parse;
  parse.fault = fault;
  parse.detail = std::move(detail);
  return parse;
}

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

std::optional<int> Whole(std::string_view text) {
  if (text.empty()) return std::nullopt;
  int value = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

// Reads a sentence's fields for a decoder, saying which one is wrong.
class Fields {
 public:
  Fields(const NmeaSentence& sentence, std::string* why) : s_(sentence), why_(why) {}

  bool Fail(std::size_t k, const std::string& what) {
    if (why_ != nullptr) {
      *why_ =
          s_.type + " field " + std::to_string(k + 1) + " '" + std::string(Text(k)) + "': " + what;
    }
    return false;
  }
  std::string_view Text(std::size_t k) const {
    return k < s_.fields.size() ? std::string_view(s_.fields[k]) : std::string_view();
  }
  bool Empty(std::size_t k) const { return Text(k).empty(); }

  // hhmmss(.ss) as seconds of the day; empty: nothing.
  bool TimeOfDay(std::size_t k, std::optional<double>* out) {
    const std::string_view t = Text(k);
    if (t.empty()) return true;
    const std::optional<int> h = t.size() >= 6 ? Whole(t.substr(0, 2)) : std::nullopt;
    const std::optional<int> m = t.size() >= 6 ? Whole(t.substr(2, 2)) : std::nullopt;
    const std::optional<double> s = t.size() >= 6 ? NmeaNumber(t.substr(4)) : std::nullopt;
    if (!h || !m || !s || *h < 0 || *h > 23 || *m < 0 || *m > 59 || *s < 0.0 || *s >= 61.0 ||
        t[4] == '-' || t[4] == '+') {
      return Fail(k, "not a time hhmmss.ss");
    }
    *out = 3600.0 * *h + 60.0 * *m + *s;
    return true;
  }

  // (d)ddmm.mmmm and its hemisphere in the next field, as signed degrees.
  bool Angle(std::size_t k, int degree_digits, char positive, char negative, double limit,
             double* out) {
    const std::string_view t = Text(k);
    const std::string_view h = Text(k + 1);
    const std::size_t dot = t.find('.');
    const std::size_t whole = dot == std::string_view::npos ? t.size() : dot;
    if (whole != static_cast<std::size_t>(degree_digits) + 2) {
      return Fail(k, "not " + std::string(degree_digits == 2 ? "ddmm.mmmm" : "dddmm.mmmm"));
    }
    const std::optional<int> degrees = Whole(t.substr(0, degree_digits));
    const std::optional<double> minutes = NmeaNumber(t.substr(degree_digits));
    if (!degrees || !minutes || *degrees < 0 || *minutes < 0.0 || *minutes >= 60.0 ||
        t[degree_digits] == '-' || t[degree_digits] == '+') {
      return Fail(k, "not " + std::string(degree_digits == 2 ? "ddmm.mmmm" : "dddmm.mmmm"));
    }
    const double value = *degrees + *minutes / 60.0;
    if (value > limit) return Fail(k, "beyond " + FormatNumber(limit) + " deg");
    if (h.size() != 1 || (h[0] != positive && h[0] != negative)) {
      return Fail(k + 1, std::string("not ") + positive + " or " + negative);
    }
    *out = h[0] == positive ? value : -value;
    return true;
  }

  bool Position(std::size_t k, NmeaFix* fix) {
    if (Empty(k) && Empty(k + 2)) return Fail(k, "no position (no fix)");
    return Angle(k, 2, 'N', 'S', 90.0, &fix->latitude) &&
           Angle(k + 2, 3, 'E', 'W', 180.0, &fix->longitude);
  }

  bool OptionalNumber(std::size_t k, std::optional<double>* out, double low, double high) {
    if (Empty(k)) return true;
    const std::optional<double> v = NmeaNumber(Text(k));
    if (!v || *v < low || *v > high) {
      return Fail(k, "not a number in [" + FormatNumber(low) + ", " + FormatNumber(high) + "]");
    }
    *out = v;
    return true;
  }
  bool OptionalWhole(std::size_t k, std::optional<int>* out, int low, int high) {
    if (Empty(k)) return true;
    const std::optional<int> v = Whole(Text(k));
    if (!v || *v < low || *v > high) {
      return Fail(k, "not a whole number in " + std::to_string(low) + ".." + std::to_string(high));
    }
    *out = v;
    return true;
  }
  bool RequiredNumber(std::size_t k, double* out, double low, double high) {
    std::optional<double> v;
    if (Empty(k)) return Fail(k, "empty");
    if (!OptionalNumber(k, &v, low, high)) return false;
    *out = *v;
    return true;
  }
  bool RequiredWhole(std::size_t k, int* out, int low, int high) {
    std::optional<int> v;
    if (Empty(k)) return Fail(k, "empty");
    if (!OptionalWhole(k, &v, low, high)) return false;
    *out = *v;
    return true;
  }

 private:
  const NmeaSentence& s_;
  std::string* why_;
};

// GNS's and RMC's mode letters as GGA's quality.
std::optional<int> QualityOfMode(char mode) {
  switch (mode) {
    case 'N':
      return 0;
    case 'A':
      return 1;
    case 'D':
      return 2;
    case 'P':
      return 3;
    case 'R':
      return 4;
    case 'F':
      return 5;
    case 'E':
      return 6;
    case 'M':
      return 7;
    case 'S':
      return 8;
    default:
      return std::nullopt;
  }
}

void RequireType(const NmeaSentence& s, std::initializer_list<std::string_view> types,
                 const char* decoder) {
  if (std::find(types.begin(), types.end(), s.type) == types.end()) {
    throw std::invalid_argument(std::string(decoder) + " given a " + s.type + " sentence");
  }
}

}  // namespace

std::optional<double> NmeaNumber(std::string_view text) {
  if (text.empty()) return std::nullopt;
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string NmeaTimeOfDay(double unix_time) {
  const double day = unix_time - 86400.0 * std::floor(unix_time / 86400.0);
  const long centis = std::lround(day * 100.0) % 8640000L;
  char text[16];
  std::snprintf(text, sizeof text, "%02ld%02ld%02ld.%02ld", centis / 360000, centis / 6000 % 60,
                centis / 100 % 60, centis % 100);
  return text;
}

unsigned NmeaChecksum(std::string_view body) {
  unsigned sum = 0;
  for (const char c : body) sum ^= static_cast<unsigned char>(c);
  return sum;
}

std::string NmeaText(char start, std::string_view address, const std::vector<std::string>& fields) {
  std::string body(address);
  for (const std::string& field : fields) body += ',' + field;
  static constexpr char kHex[] = "0123456789ABCDEF";
  const unsigned sum = NmeaChecksum(body);
  return std::string(1, start) + body + '*' + kHex[sum >> 4] + kHex[sum & 15];
}

std::string NmeaTagBlock(double unix_time) {
  char text[48];
  std::snprintf(text, sizeof text, "c:%.6f", unix_time);
  static constexpr char kHex[] = "0123456789ABCDEF";
  const unsigned sum = NmeaChecksum(text);
  return std::string("\\") + text + '*' + kHex[sum >> 4] + kHex[sum & 15] + '\\';
}

bool SplitTagBlock(std::string_view* line, NmeaTags* tags, std::string* why) {
  if (line->empty() || line->front() != '\\') return true;
  const std::size_t end = line->find('\\', 1);
  const std::string_view block = line->substr(1, end == std::string_view::npos ? 0 : end - 1);
  const std::size_t star = block.rfind('*');
  const auto fail = [&](const std::string& what) {
    if (why != nullptr) *why = "TAG block: " + what;
    return false;
  };
  if (end == std::string_view::npos || end > 100) return fail("no closing backslash");
  if (star == std::string_view::npos || star + 3 != block.size()) return fail("no *hh checksum");
  const int high = HexDigit(block[star + 1]), low = HexDigit(block[star + 2]);
  const std::string_view body = block.substr(0, star);
  if (high < 0 || low < 0) return fail("no *hh checksum");
  if (NmeaChecksum(body) != static_cast<unsigned>(16 * high + low)) return fail("bad checksum");
  NmeaTags found;
  for (std::size_t from = 0; from < body.size();) {
    const std::size_t comma = std::min(body.find(',', from), body.size());
    const std::string_view tag = body.substr(from, comma - from);
    if (tag.size() < 2 || tag[1] != ':') return fail("'" + std::string(tag) + "' is not k:value");
    if (tag[0] == 'c') {
      const std::optional<double> time = NmeaNumber(tag.substr(2));
      if (!time || *time < 0.0 || *time > 1e11) {
        return fail("c: '" + std::string(tag.substr(2)) + "' is not a UNIX time in seconds");
      }
      found.unix_time = time;
    } else if (tag[0] == 's') {
      found.source = std::string(tag.substr(2));
    }
    from = comma + 1;
  }
  *tags = std::move(found);
  line->remove_prefix(end + 1);
  return true;
}

NmeaParse ParseNmea(std::string_view line) {
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.remove_suffix(1);
  if (line.empty()) return Fault(NmeaFault::kEmpty, "an empty line");
  if (line.front() != '$' && line.front() != '!') {
    return Fault(NmeaFault::kNoStart, "does not start with $ or !");
  }
  if (line.size() > kNmeaMaxLength) {
    return Fault(NmeaFault::kTooLong, std::to_string(line.size()) + " characters, more than " +
                                          std::to_string(kNmeaMaxLength));
  }
  for (std::size_t i = 0; i < line.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(line[i]);
    if (c < 0x20 || c > 0x7e || (i > 0 && (c == '$' || c == '!'))) {
      return Fault(NmeaFault::kBadCharacter,
                   "character " + std::to_string(i + 1) + " (code " + std::to_string(c) + ")");
    }
  }
  const std::size_t star = line.rfind('*');
  if (star == std::string_view::npos || star + 3 != line.size()) {
    return Fault(NmeaFault::kNoChecksum, "no *hh at its end");
  }
  const int high = HexDigit(line[star + 1]), low = HexDigit(line[star + 2]);
  const std::string_view body = line.substr(1, star - 1);
  if (high < 0 || low < 0) return Fault(NmeaFault::kNoChecksum, "no *hh at its end");
  if (body.find('*') != std::string_view::npos) {
    return Fault(NmeaFault::kBadCharacter, "a * before the checksum");
  }
  const unsigned expected = static_cast<unsigned>(16 * high + low);
  if (NmeaChecksum(body) != expected) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    const unsigned sum = NmeaChecksum(body);
    return Fault(NmeaFault::kBadChecksum, std::string("checksum ") + kHex[expected >> 4] +
                                              kHex[expected & 15] + ", the sentence's is " +
                                              kHex[sum >> 4] + kHex[sum & 15]);
  }
  NmeaSentence s;
  s.start = line.front();
  const std::size_t comma = body.find(',');
  const std::string_view address = body.substr(0, comma);
  const bool letters = !address.empty() && std::all_of(address.begin(), address.end(), [](char c) {
    return std::isupper(static_cast<unsigned char>(c)) ||
           std::isdigit(static_cast<unsigned char>(c));
  });
  if (!letters || address.size() < 2 || (address.front() != 'P' && address.size() != 5)) {
    return Fault(NmeaFault::kBadAddress,
                 "address '" + std::string(address) + "' is not a talker and a sentence type");
  }
  if (address.front() == 'P') {
    s.talker = "P";
    s.type = std::string(address.substr(1));
  } else {
    s.talker = std::string(address.substr(0, 2));
    s.type = std::string(address.substr(2));
  }
  if (comma != std::string_view::npos) {
    for (std::size_t from = comma + 1;;) {
      const std::size_t next = body.find(',', from);
      s.fields.emplace_back(body.substr(from, next - from));
      if (next == std::string_view::npos) break;
      from = next + 1;
    }
  }
  NmeaParse parse;
  parse.sentence = std::move(s);
  return parse;
}

std::optional<NmeaFix> DecodeFix(const NmeaSentence& s, std::string* why) {
  RequireType(s, {"GGA", "GNS", "RMC"}, "DecodeFix");
  Fields f(s, why);
  NmeaFix fix;
  if (s.type == "GGA") {
    // time, lat, N/S, lon, E/W, quality, satellites, HDOP, altitude, M, ...
    if (!f.TimeOfDay(0, &fix.time_of_day) || !f.Position(1, &fix) ||
        !f.RequiredWhole(5, &fix.quality, 0, 9) || !f.OptionalWhole(6, &fix.satellites, 0, 99) ||
        !f.OptionalNumber(7, &fix.hdop, 0.0, 100.0) ||
        !f.OptionalNumber(8, &fix.altitude, -1e4, 1e5)) {
      return std::nullopt;
    }
    return fix;
  }
  if (s.type == "GNS") {
    // time, lat, N/S, lon, E/W, mode (a letter per constellation), satellites, HDOP,
    // altitude, ...: the best mode of any constellation.
    if (!f.TimeOfDay(0, &fix.time_of_day) || !f.Position(1, &fix)) return std::nullopt;
    const std::string_view modes = f.Text(5);
    if (modes.empty() || !std::all_of(modes.begin(), modes.end(),
                                      [](char m) { return QualityOfMode(m).has_value(); })) {
      f.Fail(5, "not one or more mode letters");
      return std::nullopt;
    }
    // The best of the constellations' modes: RTK fixed, float, differential, precise,
    // autonomous, then estimated, manual, simulated; none without a fix.
    constexpr std::string_view kBestFirst = "RFDPAEMS";
    std::size_t best = kBestFirst.size();
    for (const char m : modes) best = std::min(best, kBestFirst.find(m));
    fix.quality = best < kBestFirst.size() ? *QualityOfMode(kBestFirst[best]) : 0;
    if (!f.OptionalWhole(6, &fix.satellites, 0, 99) ||
        !f.OptionalNumber(7, &fix.hdop, 0.0, 100.0) ||
        !f.OptionalNumber(8, &fix.altitude, -1e4, 1e5)) {
      return std::nullopt;
    }
    return fix;
  }
  // RMC: time, status A/V, lat, N/S, lon, E/W, speed, course, date, variation, E/W, mode
  if (!f.TimeOfDay(0, &fix.time_of_day)) return std::nullopt;
  const std::string_view status = f.Text(1);
  if (status != "A" && status != "V") {
    f.Fail(1, "not A or V");
    return std::nullopt;
  }
  if (!f.Position(2, &fix)) return std::nullopt;
  fix.quality = status == "A" ? 1 : 0;
  const std::string_view mode = f.Text(11);
  if (!mode.empty()) {
    const std::optional<int> q = mode.size() == 1 ? QualityOfMode(mode[0]) : std::nullopt;
    if (!q) {
      f.Fail(11, "not a mode letter");
      return std::nullopt;
    }
    if (status == "A") fix.quality = *q;
  }
  return fix;
}

std::optional<NmeaHeading> DecodeHeading(const NmeaSentence& s, std::string* why) {
  RequireType(s, {"HDT", "THS"}, "DecodeHeading");
  Fields f(s, why);
  NmeaHeading heading;
  if (!f.RequiredNumber(0, &heading.degrees, 0.0, 360.0)) return std::nullopt;
  if (heading.degrees == 360.0) heading.degrees = 0.0;
  if (s.type == "HDT") {
    if (f.Text(1) != "T") {
      f.Fail(1, "not T (true)");
      return std::nullopt;
    }
    return heading;
  }
  const std::string_view mode = f.Text(1);
  if (!mode.empty()) {
    if (mode.size() != 1 || std::string_view("AEMSV").find(mode[0]) == std::string_view::npos) {
      f.Fail(1, "not a mode A, E, M, S or V");
      return std::nullopt;
    }
    heading.mode = mode[0];
  }
  return heading;
}

std::optional<std::vector<NmeaTransducer>> DecodeTransducers(const NmeaSentence& s,
                                                             std::string* why) {
  RequireType(s, {"XDR"}, "DecodeTransducers");
  Fields f(s, why);
  if (s.fields.empty() || s.fields.size() % 4 != 0) {
    f.Fail(s.fields.size(), "XDR holds quadruplets of type, value, units and name");
    return std::nullopt;
  }
  std::vector<NmeaTransducer> out;
  for (std::size_t k = 0; k < s.fields.size(); k += 4) {
    NmeaTransducer t;
    if (f.Text(k).size() != 1) {
      f.Fail(k, "not a transducer type letter");
      return std::nullopt;
    }
    t.type = f.Text(k)[0];
    if (!f.RequiredNumber(k + 1, &t.value, -1e15, 1e15)) return std::nullopt;
    t.units = std::string(f.Text(k + 2));
    t.name = std::string(f.Text(k + 3));
    if (t.name.empty()) {
      f.Fail(k + 3, "no transducer name");
      return std::nullopt;
    }
    out.push_back(std::move(t));
  }
  return out;
}

std::optional<NmeaClock> DecodeClock(const NmeaSentence& s, std::string* why) {
  RequireType(s, {"ZDA"}, "DecodeClock");
  Fields f(s, why);
  NmeaClock clock;
  std::optional<double> time;
  if (!f.TimeOfDay(0, &time)) return std::nullopt;
  if (!time) {
    f.Fail(0, "empty");
    return std::nullopt;
  }
  clock.time_of_day = *time;
  std::optional<int> zone_hours, zone_minutes;
  if (!f.RequiredWhole(1, &clock.day, 1, 31) || !f.RequiredWhole(2, &clock.month, 1, 12) ||
      !f.RequiredWhole(3, &clock.year, 1980, 9999) || !f.OptionalWhole(4, &zone_hours, -13, 13) ||
      !f.OptionalWhole(5, &zone_minutes, 0, 59)) {
    return std::nullopt;
  }
  if (zone_hours || zone_minutes) {
    const int h = zone_hours.value_or(0);
    clock.zone_minutes = 60 * h + (h < 0 ? -1 : 1) * zone_minutes.value_or(0);
  }
  return clock;
}

}  // namespace moorsim::monitor
