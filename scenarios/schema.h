// The input formats' schema: every key a scenario or a campaign file may hold, with its
// kind, unit, description, physical range, choices and default. It is the one list of keys:
// the loader takes the known keys, the required keys, the ranges and the choices of every
// block from here while it reads (strict_yaml::Reader), and `moorsim schema` writes the same
// tables as a JSON Schema for editors (JsonSchema). Checks that relate several values (a
// line that must reach its fairlead, waves too steep for their period, ...) stay in the
// loader's Validate(); the schema has no place for them.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace moorsim::scenarios::schema {

/// The largest coordinate of a point on the vessel, body frame [m] (fairleads, thrusters).
inline constexpr double kMaxBodyCoordinate = 1000.0;

/// What a key holds.
enum class Kind {
  kNumber,    ///< a finite number
  kInteger,   ///< a whole number (int)
  kCount,     ///< a non-negative whole number (64-bit: seeds)
  kBoolean,   ///< true or false
  kString,    ///< text
  kVector,    ///< three numbers [x, y, z]
  kMap,       ///< a map with the keys of `block`
  kList,      ///< a list whose entries are maps with the keys of `block`, or scalars of `item`
  kValue,     ///< any YAML value (campaign values, written into a scenario as given)
  kValueMap,  ///< a map from key paths to any YAML values (campaign `set`)
};

/// One end of a key's range.
struct Bound {
  double value = 0.0;
  bool exclusive = false;
  /// Where the bound comes from, shown in messages after the rule ("" = nothing to add).
  std::string_view why;
};

struct Block;

/// One key of a block.
struct Key {
  std::string_view name;
  Kind kind = Kind::kNumber;
  /// SI unit of the value ("" for a pure number or text); degrees under *_deg keys.
  std::string_view unit;
  std::string_view description;
  bool required = false;
  std::optional<Bound> minimum;
  std::optional<Bound> maximum;
  /// Messages give the whole range ("must be in [1, 10]") instead of the side broken.
  bool interval = false;
  /// For strings: the accepted values, and how messages name them ("linear solver":
  /// "unknown linear solver 'lu' (known: block, klu)").
  std::span<const std::string_view> choices;
  std::string_view choice_noun;
  /// JSON text of the default, read from the spec structs (scenario.h), or null when the
  /// default depends on other values (the description says how).
  std::string (*default_json)() = nullptr;
  /// kMap: its keys; kList: each entry's keys (null for a list of scalars).
  const Block* block = nullptr;
  /// kList of scalars: their kind.
  Kind item = Kind::kNumber;
  /// kList: fewest and most entries (0 = no limit on the most).
  int min_items = 0;
  int max_items = 0;
};

/// The keys of one map, sorted by name.
struct Block {
  std::string_view description;
  std::span<const Key> keys;
  /// Keys not in `keys` are accepted as numbers (a detector's parameters).
  bool open_numbers = false;
  /// The key, or null.
  const Key* Find(std::string_view name) const;
};

/// The scenario file's top level and the campaign file's.
const Block& Scenario();
const Block& Campaign();

/// `root` as a JSON Schema (draft-07) document, pretty-printed; `title` names the format.
std::string JsonSchema(const Block& root, std::string_view title);

/// Every key of `root` as a Markdown table (key path, kind, unit, range, default, what it
/// is), for the documentation: the same table the loader checks against.
std::string MarkdownTable(const Block& root);

/// The nearest name to `name` among the block's keys within a small edit distance (a
/// likely misspelling), or "".
std::string NearestKey(const Block& block, std::string_view name);

/// Optimal-string-alignment distance (insertions, deletions, substitutions and swaps of
/// neighbours) between two words.
int EditDistance(std::string_view a, std::string_view b);

}  // namespace moorsim::scenarios::schema
