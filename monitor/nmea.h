// NMEA 0183 sentences (IEC 61162-1) as a vessel's position, heading, load-cell and clock
// feeds send them: one sentence checked and split (`$`, a talker and a sentence type, comma
// separated fields, `*` and the two hex digits of the checksum), then the fields of the
// sentences the monitor reads decoded into numbers: GGA, GNS and RMC (position), HDT and THS
// (true heading), XDR (transducers: the load cells), ZDA (date and time).
//
// A line that is not a sentence is never an exception: ParseNmea says which fault it has
// (NmeaFault), so that a feed counts its garbled sentences and goes on. The rules:
//   * a sentence starts with `$` (or `!`, encapsulated data) and ends with `*hh`, the XOR of
//     every character between them in two hex digits (either case): a sentence without a
//     checksum is refused, since nothing else tells a line cut on a serial line from a whole
//     one;
//   * at most 82 characters from `$` to the checksum (the standard's limit with CR LF);
//     characters outside printable ASCII are refused;
//   * the address is a two-letter talker (GP, GN, GL, HE, HC, II, ...: any) and a
//     three-letter type, or `P` and a proprietary code.
// A decoder refuses a sentence whose fields do not hold what its type needs, and says which
// field; an empty field the type allows to be empty (a fix without satellites counted, a
// THS without its mode) is left unset rather than read as 0.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/choice.h"

namespace moorsim::monitor {

/// Why a line is not a sentence that can be read.
enum class NmeaFault {
  kNone,
  kEmpty,         ///< an empty line (or only CR LF)
  kNoStart,       ///< it does not start with $ or !
  kTooLong,       ///< more than 82 characters
  kBadCharacter,  ///< a character outside printable ASCII, or a reserved one in a field
  kNoChecksum,    ///< no *hh at its end
  kBadChecksum,   ///< the checksum does not match the sentence
  kBadAddress,    ///< no talker and sentence type
  kBadField,      ///< a field the sentence's type needs is missing or not a number
};

inline constexpr std::string_view kNmeaFaultNames[] = {
    "none",        "empty",        "no start",    "too long", "bad character",
    "no checksum", "bad checksum", "bad address", "bad field"};
constexpr ChoiceInfo ChoicesOf(NmeaFault) { return {"NMEA fault", kNmeaFaultNames}; }

/// The longest sentence, from its start character to its checksum's last digit.
inline constexpr std::size_t kNmeaMaxLength = 82;

struct NmeaSentence {
  char start = '$';
  std::string talker;               ///< "GP", "HE", ...; "P" for a proprietary sentence
  std::string type;                 ///< "GGA", "HDT", ...; a proprietary sentence's code
  std::vector<std::string> fields;  ///< after the address, before the checksum
};

/// A line parsed: the sentence, or the fault and what was wrong (for the feed's log).
struct NmeaParse {
  std::optional<NmeaSentence> sentence;
  NmeaFault fault = NmeaFault::kNone;
  std::string detail;
};

/// Parses one line of a feed (a trailing CR, LF or CR LF is allowed).
NmeaParse ParseNmea(std::string_view line);

/// The checksum of a sentence's body (the characters between its start and `*`).
unsigned NmeaChecksum(std::string_view body);

/// A position fix (GGA, GNS, RMC): latitude north and longitude east positive [deg], the
/// time of day [s since 00:00 UTC] where given.
struct NmeaFix {
  std::optional<double> time_of_day;
  double latitude = 0.0;
  double longitude = 0.0;
  /// GGA's fix quality (0 invalid, 1 GPS, 2 DGPS, 4 RTK fixed, 5 RTK float, ...); GNS's
  /// and RMC's modes mapped onto it (N: 0, A: 1, D: 2, R: 4, F: 5, E: 6, M: 7, S: 8).
  int quality = 0;
  std::optional<int> satellites;
  std::optional<double> hdop;
  std::optional<double> altitude;  ///< above mean sea level [m] (GGA, GNS)
};

/// A true heading (HDT, THS) [deg, 0..360), and THS's mode (A autonomous, E estimated,
/// M manual, S simulator, V not valid).
struct NmeaHeading {
  double degrees = 0.0;
  std::optional<char> mode;
};

/// One XDR measurement: the transducer's type (`N` force, `P` pressure, `C` temperature,
/// ...), its value, units and name.
struct NmeaTransducer {
  char type = ' ';
  double value = 0.0;
  std::string units;
  std::string name;
};

/// ZDA: the time of day [s] and the date; the local zone's offset from UTC [min].
struct NmeaClock {
  double time_of_day = 0.0;
  int day = 0, month = 0, year = 0;
  std::optional<int> zone_minutes;
};

/// The decoders: the value, or nothing with `why` saying which field is wrong. A decoder
/// given another type's sentence is a contract error of the caller (std::invalid_argument).
std::optional<NmeaFix> DecodeFix(const NmeaSentence& sentence, std::string* why);
std::optional<NmeaHeading> DecodeHeading(const NmeaSentence& sentence, std::string* why);
std::optional<std::vector<NmeaTransducer>> DecodeTransducers(const NmeaSentence& sentence,
                                                             std::string* why);
std::optional<NmeaClock> DecodeClock(const NmeaSentence& sentence, std::string* why);

/// An NMEA TAG block (IEC 61162-450, NMEA 0183 v4) written before a sentence,
/// `\c:1733580000.25,s:GP01*hh\`: the time the sentence was received [s since 1970 UTC]
/// and its source, as a recorded log keeps them.
struct NmeaTags {
  std::optional<double> unix_time;  ///< c: (seconds; decimals allowed)
  std::string source;               ///< s:
};

/// Splits a leading TAG block off `line`: true with `tags` set and `line` left at the
/// sentence; true with nothing changed if the line has no TAG block; false with `why` for a
/// TAG block that is cut, has a wrong checksum or a `c:` that is not a time.
bool SplitTagBlock(std::string_view* line, NmeaTags* tags, std::string* why);

/// A sentence's text: `start`, the address and the fields joined by commas, `*` and the
/// checksum (no line end).
std::string NmeaText(char start, std::string_view address, const std::vector<std::string>& fields);
/// The UTC time of day of `unix_time` as a sentence's time field, "hhmmss.ss" (rounded to
/// the hundredth of a second).
std::string NmeaTimeOfDay(double unix_time);
/// A field (or a CSV cell) that is a whole finite number, or nothing.
std::optional<double> NmeaNumber(std::string_view text);

/// A TAG block with `c:` (UNIX time, to the microsecond) for a recorded log.
std::string NmeaTagBlock(double unix_time);

}  // namespace moorsim::monitor
