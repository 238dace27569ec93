// Strict reading of YAML for moorsim's input files (scenarios and campaigns): a Reader that
// walks a yaml-cpp node at a key path, accepts only the kinds and keys asked for, rejects
// tags, duplicate keys and unknown keys, and reports every problem as one moorsim::InputError
// line "<file>:<line>:<col>: <key.path>: <what>" (1-based line, column and list indices).
// Internal to the scenarios library (yaml-cpp is its private dependency); load.cc and
// campaign.cc build on it.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/types.h"
#include "scenarios/scenario.h"

namespace moorsim::scenarios::strict_yaml {

// Message building.

/// Shortest text that reads back as the same double ("-0.08", "1800", "2.5e-05").
std::string Number(double value);
/// Fixed-point with `decimals` decimals.
std::string Fixed(double value, int decimals);
/// `digits` significant digits.
std::string Significant(double value, int digits);
/// Number(value) followed by the unit, if any.
std::string WithUnit(double value, std::string_view unit);
/// The words sorted and joined by ", " ("none" for no words).
std::string JoinSorted(std::vector<std::string> words);
/// Throws InputError "<file>:<line>:<col>: <path>: <what>" (no line:col for an empty mark,
/// no path for an empty one).
[[noreturn]] void ThrowAt(const std::string& file, SourceMark mark, const std::string& path,
                          const std::string& what);
/// yaml-cpp's 0-based mark as 1-based line and column (empty for a null mark).
SourceMark ToSourceMark(const YAML::Mark& mark);
/// "list[i+1]": key paths count list entries from 1.
std::string ItemPath(const std::string& list_path, std::size_t index);
/// "parent.key" ("key" at the root).
std::string KeyPath(const std::string& parent, std::string_view key);
double Radians(double degrees);

// Text encoding: input files and --set values are UTF-8 (outputs record them in JSON).

/// Offset of the first byte that is not part of well-formed UTF-8, if any.
std::optional<std::size_t> FirstInvalidUtf8(std::string_view text);
/// "0xE9".
std::string HexByte(unsigned char byte);
/// The text with every byte outside well-formed UTF-8 written as \xNN.
std::string EscapeInvalidUtf8(std::string_view text);
/// "not valid UTF-8 (byte 0xE9); save the file as UTF-8" for the bad byte at `offset`.
std::string InvalidUtf8(std::string_view text, std::size_t offset);
/// 1-based line and column (in bytes, as yaml-cpp counts them) of byte `offset`.
SourceMark MarkOfOffset(std::string_view text, std::size_t offset);

// Tags.

/// The tag as the user wrote it ("!!str" for "tag:yaml.org,2002:str"), or nothing.
std::optional<std::string> ExplicitTag(const YAML::Node& node, const std::string* text);
/// Throws InputError "`prefix`: tagged value ..." for the first tagged node in a --set value.
void CheckOverrideUntagged(const YAML::Node& node, const std::string& text,
                           const std::string& prefix);

/// A value as an error message shows it: a scalar as written (quoted if it was), a short
/// list of scalars as "[a, b]", else "a list", "a map" or "an empty value".
std::string Describe(const YAML::Node& node);

/// Reads a small input file whole, as bytes; stops at `max_bytes` so a device or a wrong
/// file (/dev/zero) is an error instead of a read that never ends. `what` names the kind
/// of file in messages ("scenario"). Throws InputError.
std::string ReadInputFile(const std::string& path, std::size_t max_bytes, std::string_view what);

/// What every Reader of one document shares.
struct ParseContext {
  std::string file;
  std::map<std::string, SourceMark>* marks;  // filled with the position of every node read
  std::vector<std::string> overridden;       // key paths set from the command line
  const std::string* text = nullptr;         // the YAML text the marks point into
};

/// Whether `path` is an overridden key path or lies under one.
bool Overridden(const ParseContext& context, const std::string& path);

/// One node at a key path, read strictly (see the top of this file).
class Reader {
 public:
  Reader(const ParseContext& context, YAML::Node node, std::string path, SourceMark mark)
      : context_(&context), node_(std::move(node)), path_(std::move(path)), mark_(mark) {
    // A value from --set has no place in the file: messages name the key path only.
    overridden_ = Overridden(*context_, path_);
    if (overridden_) mark_ = {};
    (*context_->marks)[path_] = mark_;
  }

  SourceMark mark() const { return mark_; }
  bool IsMap() const { return node_.IsMap(); }
  bool IsList() const { return node_.IsSequence(); }
  std::string Text() const { return Describe(node_); }
  /// The keys of a map, in order; duplicate keys and non-scalar keys are errors.
  std::vector<std::string> Keys() const {
    CheckUntagged("the plain map");
    std::vector<std::string> keys;
    for (const auto& entry : node_) {
      const SourceMark key_mark = ToSourceMark(entry.first.Mark());
      if (!entry.first.IsScalar())
        ThrowAt(context_->file, key_mark, path_, "keys must be plain names");
      CheckKeyUntagged(entry.first, key_mark);
      const std::string& name = entry.first.Scalar();
      if (std::find(keys.begin(), keys.end(), name) != keys.end()) {
        ThrowAt(context_->file, key_mark, path_, "duplicate key '" + name + "'");
      }
      keys.push_back(name);
    }
    return keys;
  }

  [[noreturn]] void Fail(const std::string& what) const {
    ThrowAt(context_->file, mark_, path_, what);
  }

  /// Requires a map whose keys are all in `known`, each at most once.
  void CheckKeys(std::vector<std::string_view> known) const {
    CheckUntagged("the plain map");
    if (!node_.IsMap()) Fail(Describe(node_) + " must be a map");
    std::vector<std::string> seen;
    for (const auto& entry : node_) {
      const YAML::Node& key = entry.first;
      const SourceMark key_mark = ToSourceMark(key.Mark());
      if (!key.IsScalar()) ThrowAt(context_->file, key_mark, path_, "keys must be plain names");
      CheckKeyUntagged(key, key_mark);
      const std::string& name = key.Scalar();
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        ThrowAt(context_->file, key_mark, path_,
                "unknown key '" + name + "' (known: " +
                    JoinSorted(std::vector<std::string>(known.begin(), known.end())) + ")");
      }
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
        ThrowAt(context_->file, key_mark, path_, "duplicate key '" + name + "'");
      }
      seen.push_back(name);
    }
  }

  /// The value under `key` of this map (CheckKeys first), or nothing if the key is absent.
  std::optional<Reader> Find(std::string_view key) const {
    for (const auto& entry : node_) {
      if (entry.first.IsScalar() && entry.first.Scalar() == key) {
        // yaml-cpp puts an empty value's mark on the next token, possibly lines later;
        // the key is where the user looks.
        const YAML::Mark& mark = entry.second.IsNull() ? entry.first.Mark() : entry.second.Mark();
        return Reader(*context_, entry.second, KeyPath(path_, key), ToSourceMark(mark));
      }
    }
    return std::nullopt;
  }

  Reader Child(std::string_view key) const {
    std::optional<Reader> child = Find(key);
    if (!child) Fail("required key '" + std::string(key) + "' is missing");
    return *child;
  }

  std::vector<Reader> Items() const {
    CheckUntagged("the plain list");
    if (!node_.IsSequence()) Fail(Describe(node_) + " must be a list");
    std::vector<Reader> items;
    for (std::size_t i = 0; i < node_.size(); ++i) {
      items.emplace_back(*context_, node_[i], ItemPath(path_, i), ToSourceMark(node_[i].Mark()));
    }
    return items;
  }

  template <class T>
  T As() const;

  /// Rejects an explicit tag on this value (`!!str 5`, `!foo`, `! 5`); `plain` says what
  /// to write instead ("the plain number", "true or false", ...).
  void CheckUntagged(std::string_view plain) const {
    // A --set value was checked, with its own text, when it was applied.
    if (overridden_) return;
    if (const std::optional<std::string> tag = ExplicitTag(node_, context_->text)) {
      Fail("tagged value '" + *tag + "' (tags are not accepted; write " + std::string(plain) + ")");
    }
  }

  template <class T>
  T Required(std::string_view key) const {
    return Child(key).As<T>();
  }

  template <class T>
  std::optional<T> Maybe(std::string_view key) const {
    if (std::optional<Reader> child = Find(key)) return child->As<T>();
    return std::nullopt;
  }

  /// Overwrites `field` (which holds the default) if the key is present.
  template <class T>
  void Optional(std::string_view key, T& field) const {
    if (std::optional<T> value = Maybe<T>(key)) field = *value;
  }

 private:
  void CheckKeyUntagged(const YAML::Node& key, SourceMark key_mark) const {
    if (overridden_) return;
    if (const std::optional<std::string> tag = ExplicitTag(key, context_->text)) {
      ThrowAt(context_->file, key_mark, path_,
              "tagged key '" + *tag + "' (tags are not accepted; write the plain name)");
    }
  }

  // A plain scalar (not quoted) that yaml-cpp's own conversion accepts.
  template <class T>
  T Decode(const char* expected, std::string_view plain) const {
    CheckUntagged(plain);
    T value{};
    if (!node_.IsScalar() || node_.Tag() == "!" || !YAML::convert<T>::decode(node_, value)) {
      Fail(Describe(node_) + " must be " + expected);
    }
    return value;
  }

  const ParseContext* context_;
  YAML::Node node_;
  std::string path_;
  SourceMark mark_;
  bool overridden_ = false;
};

template <>
double Reader::As<double>() const;
template <>
int Reader::As<int>() const;
template <>
bool Reader::As<bool>() const;
template <>
std::string Reader::As<std::string>() const;
template <>
std::uint64_t Reader::As<std::uint64_t>() const;
template <>
Vec3 Reader::As<Vec3>() const;

}  // namespace moorsim::scenarios::strict_yaml
