#include "io/compare.h"

#include <fnmatch.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <set>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "core/format.h"
#include "core/types.h"
#include "io/csv_table.h"
#include "io/hdf5_reader.h"

namespace moorsim::output {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// An integer of any 64-bit type, signed or not, kept exactly (a double holds 2^53 at most;
/// seeds use all 64 bits).
struct ExactInteger {
  bool negative = false;
  std::uint64_t magnitude = 0;
  bool operator==(const ExactInteger&) const = default;
  double ToDouble() const {
    return negative ? -static_cast<double>(magnitude) : static_cast<double>(magnitude);
  }
  std::string ToString() const { return (negative ? "-" : "") + std::to_string(magnitude); }
};

/// One channel of one output, read whole.
struct Channel {
  bool text = false;
  bool integer = false;  ///< numbers that are all whole, exactly in `integers`
  std::vector<std::size_t> dims;
  std::size_t columns = 1;  ///< values per row (the product of all but the first dimension)
  std::vector<double> numbers;
  std::vector<ExactInteger> integers;
  std::vector<std::string> texts;
  std::vector<std::string> column_names;  ///< one per column, or none
  std::size_t size() const { return text ? texts.size() : numbers.size(); }
};

using Channels = std::map<std::string, Channel>;

/// The two outputs' channels and how to name a row in the report.
struct Outputs {
  Channels a, b;
  /// csv: "run N" for each row of every channel; HDF5: empty (rows named by index and time).
  std::vector<std::string> row_names;
  /// A difference the channels cannot show: the csv "run" column's set of runs.
  std::optional<ChannelDifference> runs_difference;
};

std::string Quoted(const std::string& text) { return "'" + text + "'"; }

std::string Shape(const std::vector<std::size_t>& dims) {
  if (dims.empty()) return "scalar";
  std::string text;
  for (std::size_t i = 0; i < dims.size(); ++i)
    text += (i > 0 ? "x" : "") + std::to_string(dims[i]);
  return text;
}

bool Matches(const std::string& pattern, const std::string& name) {
  return fnmatch(pattern.c_str(), name.c_str(), 0) == 0;
}

// ---------------------------------------------------------------------------------------
// Reading the outputs.

enum class InputKind { kRun, kCampaign, kOtherHdf5, kCsv };

struct Input {
  std::string path;
  InputKind kind = InputKind::kOtherHdf5;
};

const char* KindName(InputKind kind) {
  switch (kind) {
    case InputKind::kRun:
      return "a run (run.h5)";
    case InputKind::kCampaign:
      return "a campaign (campaign.h5)";
    case InputKind::kOtherHdf5:
      return "an HDF5 file";
    case InputKind::kCsv:
      return "a CSV table";
  }
  return "?";
}

Input Resolve(const std::string& given) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::status(given, error);
  if (!fs::exists(status)) throw InputError(given + ": no such file or directory");
  Input input{given, InputKind::kOtherHdf5};
  if (fs::is_directory(status)) {
    for (const char* name : {"run.h5", "runs.csv"}) {
      const fs::path inside = fs::path(given) / name;
      if (fs::is_regular_file(inside, error)) return Resolve(inside.string());
    }
    throw InputError(given + ": a directory without run.h5 or runs.csv");
  }
  if (!std::ifstream(given, std::ios::binary)) throw InputError(given + ": cannot read it");
  if (LooksLikeHdf5(given)) {
    const Hdf5Reader file(given);
    if (file.Has("/runs")) input.kind = InputKind::kCampaign;
    if (file.Has("/time")) input.kind = InputKind::kRun;
    return input;
  }
  if (fs::path(given).extension() == ".csv") {
    input.kind = InputKind::kCsv;
    return input;
  }
  throw InputError(given + ": neither an HDF5 file nor a .csv table");
}

std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> items;
  for (std::size_t begin = 0;;) {
    const std::size_t comma = text.find(',', begin);
    items.push_back(text.substr(begin, comma == std::string::npos ? comma : comma - begin));
    if (comma == std::string::npos) return items;
    begin = comma + 1;
  }
}

Channels ReadHdf5(const std::string& path) {
  const Hdf5Reader file(path);
  Channels channels;
  for (const DatasetInfo& info : file.ListDatasets()) {
    if (info.element == ElementClass::kOther) continue;  // nothing moorsim writes
    Channel c;
    c.dims = info.dims;
    for (std::size_t i = 1; i < c.dims.size(); ++i) c.columns *= c.dims[i];
    if (info.element == ElementClass::kString) {
      c.text = true;
      c.texts = file.ReadStrings(info.path);
    } else {
      c.numbers = file.ReadArray(info.path).values;
      if (info.element == ElementClass::kSignedInteger) {
        c.integer = true;
        for (const std::int64_t v : file.ReadSignedIntegers(info.path)) {
          // The magnitude of INT64_MIN does not fit an int64_t: negate in unsigned arithmetic.
          c.integers.push_back(
              {v < 0, v < 0 ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v)});
        }
      } else if (info.element == ElementClass::kUnsignedInteger) {
        c.integer = true;
        for (const std::uint64_t v : file.ReadUnsignedIntegers(info.path)) {
          c.integers.push_back({false, v});
        }
      }
    }
    // Column names are a convenience of the report and the patterns: a file whose
    // attribute is of another type or length simply has none.
    if (file.HasAttribute(info.path, "columns")) {
      try {
        std::vector<std::string> names = SplitCommas(file.StringAttribute(info.path, "columns"));
        if (names.size() == c.columns) c.column_names = std::move(names);
      } catch (const InputError&) {
      }
    }
    channels.emplace(info.path, std::move(c));
  }
  return channels;
}

std::optional<ExactInteger> ParseInteger(const std::string& text) {
  const bool negative = !text.empty() && text[0] == '-';
  const char* begin = text.data() + (negative ? 1 : 0);
  const char* end = text.data() + text.size();
  ExactInteger value{negative, 0};
  if (begin == end || *begin < '0' || *begin > '9') return std::nullopt;
  const auto result = std::from_chars(begin, end, value.magnitude);
  if (result.ec != std::errc() || result.ptr != end) return std::nullopt;
  if (value.magnitude == 0) value.negative = false;  // "-0" is 0
  return value;
}

std::optional<double> ParseDouble(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto result = std::from_chars(text.data(), end, value);
  if (text.empty() || result.ec != std::errc() || result.ptr != end) return std::nullopt;
  return value;
}

/// A runs.csv with its rows by run index; throws for a table that is not one.
struct CampaignTable {
  CsvTable table;
  std::map<std::string, std::size_t> column;  ///< header name -> index
  std::map<std::int64_t, std::size_t> row;    ///< run index -> row
};

CampaignTable ReadCampaignTable(const std::string& path) {
  CampaignTable t{ReadCsvTable(path), {}, {}};
  for (std::size_t i = 0; i < t.table.header.size(); ++i) {
    if (!t.column.emplace(t.table.header[i], i).second) {
      throw InputError(path + ":1: column " + Quoted(t.table.header[i]) + " twice");
    }
  }
  const auto run = t.column.find("run");
  if (run == t.column.end()) {
    throw InputError(path + ": no 'run' column (not a runs.csv of moorsim batch)");
  }
  for (std::size_t r = 0; r < t.table.rows.size(); ++r) {
    const std::string& text = t.table.rows[r][run->second];
    const std::string where = path + ":" + std::to_string(t.table.row_lines[r]) + ": run ";
    const std::optional<ExactInteger> index = ParseInteger(text);
    if (!index || index->negative ||
        index->magnitude > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max())) {
      throw InputError(where + Quoted(text) + " is not a run index (a whole number >= 0)");
    }
    const auto key = static_cast<std::int64_t>(index->magnitude);
    const auto [first, inserted] = t.row.emplace(key, r);
    if (!inserted) {
      throw InputError(where + text + " again (first on line " +
                       std::to_string(t.table.row_lines[first->second]) + ")");
    }
  }
  return t;
}

std::string RunList(const std::vector<std::int64_t>& runs) {
  std::string text = runs.size() == 1 ? "run " : "runs ";
  for (std::size_t i = 0; i < runs.size() && i < 5; ++i) {
    text += (i > 0 ? ", " : "") + std::to_string(runs[i]);
  }
  if (runs.size() > 5) text += ", ... (" + std::to_string(runs.size()) + ")";
  return text;
}

/// Both tables as channels over the runs they share, in run order.
Outputs ReadCampaignTables(const std::string& path_a, const std::string& path_b) {
  const CampaignTable a = ReadCampaignTable(path_a);
  const CampaignTable b = ReadCampaignTable(path_b);
  Outputs outputs;
  std::vector<std::int64_t> common, only_a, only_b;
  for (const auto& [run, row] : a.row) (b.row.count(run) ? common : only_a).push_back(run);
  for (const auto& [run, row] : b.row) {
    if (!a.row.count(run)) only_b.push_back(run);
  }
  for (const std::int64_t run : common) outputs.row_names.push_back("run " + std::to_string(run));
  if (!only_a.empty() || !only_b.empty()) {
    ChannelDifference d;
    d.channel = "run";
    d.kind = ChannelDifference::Kind::kShape;
    if (!only_a.empty()) d.detail = RunList(only_a) + " only in A";
    if (!only_b.empty())
      d.detail += (d.detail.empty() ? "" : "; ") + RunList(only_b) + " only in B";
    d.excess = kInfinity;
    d.difference = kInfinity;
    outputs.runs_difference = d;
  }

  std::set<std::string> names;
  for (const std::string& name : a.table.header) names.insert(name);
  for (const std::string& name : b.table.header) names.insert(name);
  for (const std::string& name : names) {
    // The cells of both tables at the common runs, so that both get the same kind.
    std::vector<const std::string*> cells_a, cells_b;
    const auto collect = [&](const CampaignTable& t, std::vector<const std::string*>& cells) {
      const auto column = t.column.find(name);
      if (column == t.column.end()) return false;
      for (const std::int64_t run : common)
        cells.push_back(&t.table.rows[t.row.at(run)][column->second]);
      return true;
    };
    const bool in_a = collect(a, cells_a);
    const bool in_b = collect(b, cells_b);
    bool integer = true, numbers = true;
    for (const auto* cells : {&cells_a, &cells_b}) {
      for (const std::string* cell : *cells) {
        integer = integer && ParseInteger(*cell).has_value();
        numbers = numbers && (cell->empty() || ParseDouble(*cell).has_value());
      }
    }
    const auto make = [&](const std::vector<const std::string*>& cells) {
      Channel c;
      c.dims = {cells.size()};
      c.text = !numbers;
      c.integer = integer;
      for (const std::string* cell : cells) {
        if (c.text) {
          c.texts.push_back(*cell);
        } else if (integer) {
          c.integers.push_back(*ParseInteger(*cell));
          c.numbers.push_back(c.integers.back().ToDouble());
        } else {
          c.numbers.push_back(cell->empty() ? kNaN : *ParseDouble(*cell));
        }
      }
      return c;
    };
    if (in_a) outputs.a.emplace(name, make(cells_a));
    if (in_b) outputs.b.emplace(name, make(cells_b));
  }
  return outputs;
}

// ---------------------------------------------------------------------------------------
// Comparing.

struct Tolerance {
  double rtol = 0.0;
  double atol = 0.0;
};

/// The tolerance of each column of channel `name`.
std::vector<Tolerance> ColumnTolerances(const CompareOptions& options, const std::string& name,
                                        const Channel& channel, bool integer) {
  std::vector<Tolerance> tolerances;
  for (std::size_t column = 0; column < channel.columns; ++column) {
    Tolerance t = integer ? Tolerance{} : Tolerance{options.rtol, options.atol};
    const std::string column_name =
        channel.column_names.empty() ? "" : name + "/" + channel.column_names[column];
    for (const ToleranceRule& rule : options.rules) {
      if (!Matches(rule.pattern, name) &&
          (column_name.empty() || !Matches(rule.pattern, column_name))) {
        continue;
      }
      (rule.kind == ToleranceRule::Kind::kRelative ? t.rtol : t.atol) = rule.value;
    }
    tolerances.push_back(t);
  }
  return tolerances;
}

/// The time of row `row` of channel `name`: its group's own time table (the detection input
/// has one), else the run's, from the reference where it has one; none if neither has as
/// many rows as the channel.
std::optional<double> RowTime(const Outputs& outputs, const std::string& name,
                              const Channel& channel, std::size_t row) {
  const std::string group = name.substr(0, name.rfind('/'));
  for (const std::string& time : {group + "/time", std::string("/time")}) {
    if (time == name) return std::nullopt;
    for (const Channels* channels : {&outputs.b, &outputs.a}) {
      const auto found = channels->find(time);
      if (found == channels->end()) continue;
      const Channel& t = found->second;
      if (!t.text && t.dims.size() == 1 && t.dims[0] == channel.dims[0]) return t.numbers[row];
    }
  }
  return std::nullopt;
}

/// "row 12 (t = 6 s), column 3 (line3)" for HDF5, "run 7" for csv.
std::string ElementName(const Outputs& outputs, const std::string& name, const Channel& channel,
                        std::size_t row, std::size_t column) {
  if (!outputs.row_names.empty()) return outputs.row_names[row];
  if (channel.dims.empty()) return "";
  std::string text = "row " + std::to_string(row);
  if (const std::optional<double> t = RowTime(outputs, name, channel, row)) {
    text += " (t = " + FormatNumber(*t) + " s)";
  }
  if (channel.dims.size() > 1) {
    text += ", column " + std::to_string(column);
    if (!channel.column_names.empty()) text += " (" + channel.column_names[column] + ")";
  }
  return text;
}

std::optional<ChannelDifference> CompareChannel(const Outputs& outputs, const std::string& name,
                                                const CompareOptions& options) {
  const auto in_a = outputs.a.find(name);
  const auto in_b = outputs.b.find(name);
  ChannelDifference d;
  d.channel = name;
  d.excess = kInfinity;
  d.difference = kInfinity;
  if (in_b == outputs.b.end()) {
    d.kind = ChannelDifference::Kind::kOnlyInA;
    d.detail = "only in A";
    return d;
  }
  if (in_a == outputs.a.end()) {
    d.kind = ChannelDifference::Kind::kOnlyInB;
    d.detail = "only in B";
    return d;
  }
  const Channel& a = in_a->second;
  const Channel& b = in_b->second;
  if (a.text != b.text) {
    d.kind = ChannelDifference::Kind::kType;
    d.detail = std::string(a.text ? "text" : "numbers") + " in A, " +
               (b.text ? "text" : "numbers") + " in B";
    return d;
  }
  if (a.dims != b.dims) {
    d.kind = ChannelDifference::Kind::kShape;
    d.detail = "shape " + Shape(a.dims) + " in A, " + Shape(b.dims) + " in B";
    return d;
  }
  const bool integer = a.integer && b.integer;
  const Channel& named = b.column_names.empty() ? a : b;
  const std::vector<Tolerance> tolerances = ColumnTolerances(options, name, named, integer);
  d.values = b.size();
  d.excess = 0.0;
  d.difference = 0.0;
  std::optional<std::size_t> worst;
  std::string values_text;
  for (std::size_t i = 0; i < d.values; ++i) {
    const std::size_t column = i % b.columns;
    const Tolerance& t = tolerances[column];
    double difference = kInfinity, allowed = 0.0, x = kNaN, y = kNaN;
    bool differs = false;
    if (b.text) {
      differs = a.texts[i] != b.texts[i];
    } else if (integer && t.rtol == 0.0 && t.atol == 0.0) {
      x = a.numbers[i];
      y = b.numbers[i];
      differs = !(a.integers[i] == b.integers[i]);
      difference = std::abs(x - y);
    } else {
      x = a.numbers[i];
      y = b.numbers[i];
      allowed = t.atol + (t.rtol > 0.0 ? t.rtol * std::abs(y) : 0.0);  // no 0 * inf
      if (std::isnan(x) || std::isnan(y)) {
        differs = std::isnan(x) != std::isnan(y);
      } else if (x != y) {
        difference = std::abs(x - y);  // infinite if either is
        differs = std::isinf(difference) || difference > allowed;
      }
    }
    if (!differs) continue;
    ++d.values_differing;
    const double excess = allowed > 0.0 ? difference / allowed : kInfinity;
    if (worst && std::tie(excess, difference) <= std::tie(d.excess, d.difference)) continue;
    worst = i;
    d.row = i / b.columns;
    d.column = column;
    d.a = x;
    d.b = y;
    d.difference = difference;
    d.allowed = allowed;
    d.excess = excess;
    if (b.text) {
      values_text = "a \"" + a.texts[i] + "\", b \"" + b.texts[i] + "\"";
    } else if (integer && t.rtol == 0.0 && t.atol == 0.0) {
      values_text = "a " + a.integers[i].ToString() + ", b " + b.integers[i].ToString() +
                    " (compared exactly)";
    } else if (std::isnan(x) || std::isnan(y)) {
      values_text = "a " + FormatNumber(x) + ", b " + FormatNumber(y) + " (NaN in one only)";
    } else {
      values_text = "a " + FormatNumber(x) + ", b " + FormatNumber(y) + ", |a-b| " +
                    FormatNumber(difference) + " > allowed " + FormatNumber(allowed);
    }
  }
  if (!worst) return std::nullopt;
  const std::string element = ElementName(outputs, name, b, d.row, d.column);
  d.detail = (element.empty() ? "" : element + ": ") + values_text + " (" +
             std::to_string(d.values_differing) + " of " + std::to_string(d.values) +
             (d.values == 1 ? " value differs)" : " values differ)");
  return d;
}

/// Throws for a pattern that matches nothing: certainly a typo, which would otherwise pass
/// silently with the default tolerance.
void CheckPatternsMatch(const Outputs& outputs, const CompareOptions& options,
                        const std::string& files) {
  std::set<std::string> names, names_and_columns;
  for (const Channels* channels : {&outputs.a, &outputs.b}) {
    for (const auto& [name, channel] : *channels) {
      names.insert(name);
      names_and_columns.insert(name);
      for (const std::string& column : channel.column_names) {
        names_and_columns.insert(name + "/" + column);
      }
    }
  }
  names_and_columns.insert(names.begin(), names.end());
  const auto any = [](const std::set<std::string>& set, const std::string& pattern) {
    return std::any_of(set.begin(), set.end(),
                       [&](const std::string& name) { return Matches(pattern, name); });
  };
  for (const ToleranceRule& rule : options.rules) {
    if (!any(names_and_columns, rule.pattern)) {
      throw OptionError(rule.option, rule.given + ": matches no channel of " + files);
    }
  }
  for (const std::string& pattern : options.ignore) {
    if (!any(names, pattern)) {
      throw OptionError("ignore", " " + Quoted(pattern) + ": matches no channel of " + files);
    }
  }
}

bool Ignored(const CompareOptions& options, const std::string& name) {
  return std::any_of(options.ignore.begin(), options.ignore.end(),
                     [&](const std::string& pattern) { return Matches(pattern, name); });
}

}  // namespace

void AddTolerance(CompareOptions& options, ToleranceRule::Kind kind, const std::string& text) {
  const std::string option = kind == ToleranceRule::Kind::kRelative ? "rtol" : "atol";
  const std::string given = " " + Quoted(text);
  if (text.empty()) throw OptionError(option, given + ": empty value");
  const std::size_t equals = text.rfind('=');
  const std::string pattern = equals == std::string::npos ? "" : text.substr(0, equals);
  const std::string value_text = equals == std::string::npos ? text : text.substr(equals + 1);
  if (equals != std::string::npos && pattern.empty()) {
    throw OptionError(option, given + ": no pattern before '=' (PATTERN=VALUE or VALUE)");
  }
  const std::optional<double> value = ParseDouble(value_text);
  if (!value) throw OptionError(option, given + ": " + Quoted(value_text) + " is not a number");
  if (!std::isfinite(*value)) {
    throw OptionError(option, given + ": " + Quoted(value_text) + " is not a finite number");
  }
  if (*value < 0.0)
    throw OptionError(option, given + ": " + value_text + " is negative (a tolerance is >= 0)");
  if (equals == std::string::npos) {
    (kind == ToleranceRule::Kind::kRelative ? options.rtol : options.atol) = *value;
    return;
  }
  options.rules.push_back({kind, pattern, *value, option, given});
}

Comparison CompareOutputs(const std::string& a, const std::string& b,
                          const CompareOptions& options) {
  const Input input_a = Resolve(a);
  const Input input_b = Resolve(b);
  const bool csv_a = input_a.kind == InputKind::kCsv;
  const bool csv_b = input_b.kind == InputKind::kCsv;
  const bool run_and_campaign =
      (input_a.kind == InputKind::kRun && input_b.kind == InputKind::kCampaign) ||
      (input_a.kind == InputKind::kCampaign && input_b.kind == InputKind::kRun);
  if (csv_a != csv_b || run_and_campaign) {
    throw InputError(input_a.path + " is " + KindName(input_a.kind) + " but " + input_b.path +
                     " is " + KindName(input_b.kind) + " (compare like with like)");
  }
  Outputs outputs;
  if (csv_a) {
    outputs = ReadCampaignTables(input_a.path, input_b.path);
  } else {
    outputs.a = ReadHdf5(input_a.path);
    outputs.b = ReadHdf5(input_b.path);
  }
  CheckPatternsMatch(outputs, options, input_a.path + " or " + input_b.path);

  Comparison comparison;
  comparison.a = input_a.path;
  comparison.b = input_b.path;
  std::set<std::string> names;
  for (const auto& [name, channel] : outputs.a) names.insert(name);
  for (const auto& [name, channel] : outputs.b) names.insert(name);
  for (const std::string& name : names) {
    if (Ignored(options, name)) {
      ++comparison.ignored;
      continue;
    }
    ++comparison.channels;
    std::optional<ChannelDifference> d;
    if (name == "run" && outputs.runs_difference) {
      d = outputs.runs_difference;
    } else {
      d = CompareChannel(outputs, name, options);
    }
    if (d) comparison.differences.push_back(std::move(*d));
  }
  std::stable_sort(comparison.differences.begin(), comparison.differences.end(),
                   [](const ChannelDifference& x, const ChannelDifference& y) {
                     using K = ChannelDifference::Kind;
                     return std::make_tuple(x.kind != K::kValues, x.excess, x.difference) >
                            std::make_tuple(y.kind != K::kValues, y.excess, y.difference);
                   });
  return comparison;
}

void PrintComparison(const Comparison& comparison, std::size_t show, std::ostream& out,
                     const std::string& more_hint) {
  const std::size_t n = comparison.differences.size();
  for (std::size_t i = 0; i < n && i < show; ++i) {
    out << comparison.differences[i].channel << ": " << comparison.differences[i].detail << "\n";
  }
  if (n > show) out << "(" << n - show << " more not shown" << more_hint << ")\n";
  if (n == 0) {
    out << "all " << comparison.channels << " channels within tolerance";
  } else {
    out << n << " of " << comparison.channels << " channels differ";
  }
  if (comparison.ignored > 0) out << " (" << comparison.ignored << " ignored)";
  out << "\n";
}

}  // namespace moorsim::output
