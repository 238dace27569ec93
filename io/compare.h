// Comparing two outputs channel by channel, for regression suites (`moorsim compare`): two
// HDF5 files (run.h5 of `moorsim run`, campaign.h5 of `moorsim batch`) or two campaign
// tables (runs.csv). B is the reference.
//
// Channels. In an HDF5 file every numeric or string dataset is a channel, named by its path
// ("/mooring/fairlead_tension"); attributes (the program version, the scenario's text and
// path, units) are not compared. In a runs.csv every column is a channel named by its header
// ("dht.delay"), rows matched by their run index (the "run" column), whatever their order.
//
// A channel differs if it is in one output only, if its shape or its kind (numbers, text)
// differs, or if an element differs:
//  - floats: |a - b| > atol + rtol |b|; NaN equals NaN only, +-inf only itself;
//  - integers (HDF5 integer datasets; csv columns of whole numbers only): exactly, unless a
//    tolerance pattern matches the channel;
//  - text (HDF5 string datasets, other csv columns): exactly.
// An empty field of a numeric csv column reads as NaN.
#pragma once

#include <cstddef>
#include <iosfwd>
#include <string>
#include <vector>

namespace moorsim::output {

/// A tolerance for the channels that a glob pattern (fnmatch(3): '*', '?', '[...]'; '*'
/// also matches '/') matches. A pattern is matched against the channel's name and against
/// "<name>/<column>" for each column an HDF5 table names in its "columns" attribute
/// ("/vessel/pose_true/psi"), so one column can have a tolerance of its own.
struct ToleranceRule {
  enum class Kind { kRelative, kAbsolute };
  Kind kind = Kind::kAbsolute;
  std::string pattern;
  double value = 0.0;  ///< >= 0
  std::string option;  ///< "rtol" or "atol", for messages (OptionError)
  std::string given;   ///< the value as given, after the option's name: " '/mooring/*=2e3'"
};

struct CompareOptions {
  /// The tolerances of float channels that no rule matches.
  double rtol = 1e-9;
  double atol = 0.0;
  /// In the order given: the last rule of a kind that matches an element sets that
  /// element's tolerance of that kind.
  std::vector<ToleranceRule> rules;
  /// Glob patterns of channels left out (matched against the channel's name only).
  std::vector<std::string> ignore;
};

/// Reads a --rtol or --atol value: "VALUE" sets the default, "PATTERN=VALUE" adds a rule.
/// Throws InputError "<flag> '<text>': ..." for an empty pattern or a value that is not a
/// finite number >= 0.
void AddTolerance(CompareOptions& options, ToleranceRule::Kind kind, const std::string& text);

/// One channel that differs, at its worst element.
struct ChannelDifference {
  enum class Kind {
    kOnlyInA,
    kOnlyInB,
    kShape,   ///< dimensions (HDF5) or the set of runs (csv "run" column) differ
    kType,    ///< numbers in one, text in the other
    kValues,  ///< same shape, an element outside its tolerance
  };
  std::string channel;
  Kind kind = Kind::kValues;
  /// What differs, one line without the channel's name: "row 12 (t = 6 s), column 3
  /// (line3): a 1.5, b 1.25, |a-b| 0.25 > allowed 0.1 (3 of 80 values differ)".
  std::string detail;
  /// The worst element (kValues): its row and flattened column, the values (NaN for text),
  /// |a - b| (infinite for NaN against a number) and the tolerance atol + rtol |b|.
  std::size_t row = 0;
  std::size_t column = 0;
  double a = 0.0;
  double b = 0.0;
  double difference = 0.0;
  double allowed = 0.0;
  /// difference / allowed; infinite where nothing was allowed, for text and structure.
  double excess = 0.0;
  std::size_t values_differing = 0;
  std::size_t values = 0;
};

struct Comparison {
  std::string a;  ///< the files compared (a directory resolved to its run.h5 or runs.csv)
  std::string b;
  std::size_t channels = 0;  ///< in either output, ignored ones excluded
  std::size_t ignored = 0;
  /// Worst first: structural differences, then by excess, then by |a - b|.
  std::vector<ChannelDifference> differences;
};

/// Compares output `a` with the reference `b` (files, or directories holding run.h5 or
/// runs.csv). Throws InputError naming the file or the flag for bad input: a missing file,
/// one that is neither HDF5 nor a CSV table, two outputs of different kinds, a csv without
/// a "run" column or with a run index twice, a rule or ignore pattern that matches no
/// channel of either output.
Comparison CompareOutputs(const std::string& a, const std::string& b,
                          const CompareOptions& options);

/// The report: one line per differing channel (at most `show`, worst first; the rest
/// counted, with `more_hint` after the count: how to see them), then "N of M channels
/// differ" or "all M channels within tolerance".
void PrintComparison(const Comparison& comparison, std::size_t show, std::ostream& out,
                     const std::string& more_hint = "");

}  // namespace moorsim::output
