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
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/choice.h"
#include "core/error.h"
#include "core/types.h"
#include "scenarios/scenario.h"
#include "scenarios/schema.h"

namespace moorsim::scenarios::strict_yaml {

// Message building.

/// Fixed-point with `decimals` decimals.
std::string Fixed(double value, int decimals);
/// `digits` significant digits.
std::string Significant(double value, int digits);
/// FormatNumber(value) followed by the unit, if any.
std::string WithUnit(double value, std::string_view unit);
/// The words sorted and joined by ", " ("none" for no words).
std::string JoinSorted(std::vector<std::string> words);
/// `text` as a YAML double-quoted scalar that reads back as exactly `text`: quotes and
/// backslashes escaped, and so are control characters (a newline in a folder's name would
/// otherwise be folded into a space).
std::string DoubleQuoted(std::string_view text);
/// `text` for a YAML comment: line breaks written as \n and \r, so that it stays one line.
std::string OneLine(std::string_view text);
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

/// Whether `path` is `prefix` or lies under it ("a.b[2]" lies under "a.b" and "a").
bool UnderPath(const std::string& path, const std::string& prefix);

/// One step of a key path: a map key, or a list entry (`index`, from 1) when `key` is empty.
struct KeyStep {
  std::string key;
  int index = 0;
};
/// "a.b[2].c" as steps. Every key path has one spelling, so the same key is never taken
/// for two: an empty key (`a..b`, `.a`, `a.`, `a.[2]`), a list index that is not a plain
/// number from 1 (`[0]`, `[01]`, `[x]`), text right after `]` or a path that starts with an
/// index is an InputError (its message names the path, without a location).
std::vector<KeyStep> SplitKeyPath(const std::string& path);

/// How many values (scalars, lists and maps, an alias counted as all it stands for) an
/// input document may hold: hundreds of times what a scenario or campaign writes out, so
/// only aliases that multiply (nested or repeated) reach it.
inline constexpr std::size_t kMaxDocumentValues = std::size_t{1} << 20;

/// The one YAML document of an input file's text (`what`: "scenario", "campaign"), or a
/// located InputError: text that is not UTF-8, a syntax error, no document (`expected`
/// says what it should hold), a second document or any text after the document-end marker
/// `...`, a key twice in one map (at the second), or aliases that expand the document past
/// kMaxDocumentValues values.
YAML::Node LoadDocument(const std::string& text, const std::string& file, std::string_view what,
                        std::string_view expected);

/// The entry of `entries` whose key path (`path_of(entry)`) `path` lies under most deeply,
/// or null: where a value was written, from the subtrees taken from other files.
template <class Range, class PathOf>
auto DeepestUnder(const Range& entries, const std::string& path, PathOf path_of)
    -> decltype(&*std::begin(entries)) {
  decltype(&*std::begin(entries)) found = nullptr;
  for (const auto& entry : entries) {
    const std::string& prefix = path_of(entry);
    if (UnderPath(path, prefix) && (found == nullptr || prefix.size() > path_of(*found).size())) {
      found = &entry;
    }
  }
  return found;
}

/// Thrown, when collecting errors, where the problem has been recorded already (a missing
/// required key that CheckKeys reported): it ends the value's reading and records nothing.
class AlreadyReported : public InputError {
 public:
  AlreadyReported() : InputError("(reported)") {}
};

/// What every Reader of one document shares.
struct ParseContext {
  std::string file;
  std::map<std::string, SourceMark>* marks =
      nullptr;                          // filled with the position of every node read
  std::vector<std::string> overridden;  // key paths set from the command line
  const std::string* text = nullptr;    // the YAML text the marks point into
  /// Values written in another file (a scenario's base): the key path under which every
  /// value comes from `file`, whose text the marks there point into. The deepest wins.
  struct Origin {
    std::string path;
    std::string file;
    const std::string* text = nullptr;
  };
  std::vector<Origin> origins;
  /// Null: the first error is thrown. Otherwise every error is collected here, one located
  /// line each, and reading goes on with the next value (Reader::Attempt).
  std::vector<std::string>* errors = nullptr;
  /// Maps whose keys CheckKeys has checked (and whose missing required keys it reported).
  mutable std::set<std::string> checked;

  /// The file and text the value at `path` was written in.
  const std::string& FileOf(const std::string& path) const;
  const std::string* TextOf(const std::string& path) const;
  /// Runs `body`; when collecting, an InputError it throws is recorded (once) and false
  /// returned instead.
  template <class Body>
  bool Attempt(Body&& body) const {
    if (errors == nullptr) {
      body();
      return true;
    }
    try {
      body();
      return true;
    } catch (const AlreadyReported&) {
      return false;
    } catch (const InputError& error) {
      Record(error.what());
      return false;
    }
  }
  void Record(const std::string& message) const;
};

/// Throws one InputError holding every collected message (one located line each, ordered by
/// file, line and column); nothing for none.
void ThrowCollected(std::vector<std::string> errors);

/// Whether `path` is an overridden key path or lies under one.
bool Overridden(const ParseContext& context, const std::string& path);

/// One node at a key path, read strictly (see the top of this file).
class Reader {
 public:
  /// `block`: the schema of this map (its known and required keys), or null for a value
  /// read without one.
  Reader(const ParseContext& context, YAML::Node node, std::string path, SourceMark mark,
         const schema::Block* block = nullptr)
      : context_(&context),
        node_(std::move(node)),
        path_(std::move(path)),
        mark_(mark),
        block_(block) {
    // A value from --set has no place in the file: messages name the key path only.
    overridden_ = Overridden(*context_, path_);
    if (overridden_) mark_ = {};
    (*context_->marks)[path_] = mark_;
  }

  SourceMark mark() const { return mark_; }
  /// The file this value was written in.
  const std::string& File() const { return context_->FileOf(path_); }
  bool IsMap() const { return node_.IsMap(); }
  bool IsList() const { return node_.IsSequence(); }
  std::string Text() const { return Describe(node_); }
  /// The keys of a map, in order; duplicate keys and non-scalar keys are errors.
  std::vector<std::string> Keys() const;

  [[noreturn]] void Fail(const std::string& what) const {
    ThrowAt(context_->FileOf(path_), mark_, path_, what);
  }
  /// Fails at the key `key` of this map (the path shown is this map's).
  [[noreturn]] void FailAtKey(const YAML::Node& key, const std::string& what) const {
    FailAtKey(key, key.Scalar(), what);
  }

  /// Requires a map whose keys are all in the schema's block, each at most once, with
  /// every required key present. An unknown key's message suggests the nearest known one.
  /// When collecting errors, every problem is recorded and the known keys stay readable.
  void CheckKeys() const;

  /// The value under `key` of this map (CheckKeys first), or nothing if the key is absent.
  std::optional<Reader> Find(std::string_view key) const;

  Reader Child(std::string_view key) const {
    std::optional<Reader> child = Find(key);
    if (!child) {
      const schema::Key* known = block_ ? block_->Find(key) : nullptr;
      if (context_->errors != nullptr && known != nullptr && known->required &&
          context_->checked.contains(path_)) {
        throw AlreadyReported();  // by CheckKeys
      }
      Fail("required key '" + std::string(key) + "' is missing");
    }
    return *child;
  }

  /// The value under `key`, which this map needs in the form it is written in though its
  /// schema does not always require it (e.g. one of two forms). Missing, it is reported
  /// like a missing required key: once, and not when an unknown key's message (CheckKeys)
  /// suggested it already.
  Reader Needed(std::string_view key) const;

  std::vector<Reader> Items() const;

  /// Runs `body` for each entry of this list; when collecting errors, an entry that fails
  /// is recorded and the next one read.
  template <class Body>
  void ForEachItem(Body&& body) const {
    const std::vector<Reader> items = Items();
    for (std::size_t i = 0; i < items.size(); ++i) {
      context_->Attempt([&] { body(items[i], i); });
    }
  }

  /// Runs `body`; when collecting errors, records what it throws (see ParseContext).
  template <class Body>
  bool Attempt(Body&& body) const {
    return context_->Attempt(std::forward<Body>(body));
  }

  /// The value as a T: a number, a flag, a text, a vector, or a configuration choice (an
  /// enum with a table of names, core/choice.h) parsed from its name.
  template <class T>
  T As() const {
    static_assert(Choice<T>, "Reader::As: no conversion to this type");
    const std::string name = PlainText();
    if (const std::optional<T> value = ParseChoice<T>(name)) return *value;
    const std::span<const std::string_view> known = ChoiceNames<T>();
    Fail("unknown " + std::string(ChoiceNoun<T>()) + " '" + name +
         "' (known: " + JoinSorted({known.begin(), known.end()}) + ")");
  }

  /// Rejects an explicit tag on this value (`!!str 5`, `!foo`, `! 5`); `plain` says what
  /// to write instead ("the plain number", "true or false", ...).
  void CheckUntagged(std::string_view plain) const {
    // A --set value was checked, with its own text, when it was applied.
    if (overridden_) return;
    if (const std::optional<std::string> tag = ExplicitTag(node_, context_->TextOf(path_))) {
      Fail("tagged value '" + *tag + "' (tags are not accepted; write " + std::string(plain) + ")");
    }
  }

  /// A key the schema marks required (a ContractError otherwise: the schema and the loader
  /// must agree). When collecting errors, a bad value is recorded and T{} returned.
  template <class T>
  T Required(std::string_view key) const {
    if (block_ != nullptr) {
      const schema::Key* known = block_->Find(key);
      if (known == nullptr || !known->required) {
        throw ContractError("the loader requires '" + KeyPath(path_, key) +
                            "' but the schema does not");
      }
    }
    T value{};
    context_->Attempt([&] { value = Child(key).As<T>(); });
    return value;
  }

  /// The value if the key is present (and readable, when collecting errors).
  template <class T>
  std::optional<T> Maybe(std::string_view key) const {
    std::optional<T> value;
    context_->Attempt([&] {
      if (std::optional<Reader> child = Find(key)) value = child->As<T>();
    });
    return value;
  }

  /// Overwrites `field` (which holds the default) if the key is present.
  template <class T>
  void Optional(std::string_view key, T& field) const {
    if (std::optional<T> value = Maybe<T>(key)) field = *value;
  }

 private:
  // A key's name, checked: a plain scalar without a tag. Throws at the key.
  std::string KeyName(const YAML::Node& key) const;
  // Where the key `name` of this map was written.
  [[noreturn]] void FailAtKey(const YAML::Node& key, const std::string& name,
                              const std::string& what) const;
  // The reader of a value under `key` (this map's schema entry for it, if any).
  Reader Under(const YAML::Node& value, std::string path, SourceMark mark,
               const schema::Key* key) const;

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

  // The value as text (As<std::string>), checked against the schema's choices.
  std::string PlainText() const;
  // The schema's range and choices for a value of the key this reader is under.
  void CheckRange(double value) const;
  void CheckChoice(const std::string& value) const;

  const ParseContext* context_;
  YAML::Node node_;
  std::string path_;
  SourceMark mark_;
  bool overridden_ = false;
  const schema::Block* block_ = nullptr;  // this map's keys
  const schema::Key* key_ = nullptr;      // the key this value (or list entry) is under
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
