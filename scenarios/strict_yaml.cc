#include "scenarios/strict_yaml.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <set>
#include <system_error>
#include <tuple>

#include "core/error.h"
#include "core/format.h"

namespace moorsim::scenarios::strict_yaml {

// ---------------------------------------------------------------------------------------
// Message building, shared by the parser and Validate().

std::string Fixed(double value, int decimals) {
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed, decimals);
  return std::string(buffer, result.ptr);
}

std::string Significant(double value, int digits) {
  char buffer[32];
  const auto result =
      std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, digits);
  return std::string(buffer, result.ptr);
}

std::string WithUnit(double value, std::string_view unit) {
  return unit.empty() ? FormatNumber(value) : FormatNumber(value) + " " + std::string(unit);
}

std::string DoubleQuoted(std::string_view text) {
  std::string quoted = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        quoted += "\\\"";
        break;
      case '\\':
        quoted += "\\\\";
        break;
      case '\n':
        quoted += "\\n";
        break;
      case '\r':
        quoted += "\\r";
        break;
      case '\t':
        quoted += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          quoted += "\\x" + HexByte(static_cast<unsigned char>(c)).substr(2);
        } else {
          quoted += c;
        }
    }
  }
  return quoted + "\"";
}

std::string OneLine(std::string_view text) {
  std::string line;
  for (const char c : text) {
    if (c == '\n') {
      line += "\\n";
    } else if (c == '\r') {
      line += "\\r";
    } else {
      line += c;
    }
  }
  return line;
}

std::string JoinSorted(std::vector<std::string> words) {
  std::sort(words.begin(), words.end());
  std::string joined;
  for (const std::string& word : words) {
    joined += (joined.empty() ? "" : ", ") + word;
  }
  return joined.empty() ? "none" : joined;
}

[[noreturn]] void ThrowAt(const std::string& file, SourceMark mark, const std::string& path,
                          const std::string& what) {
  std::string message = file;
  if (mark.line > 0) {
    // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on ":" + std::string&&.
    message.append(":").append(std::to_string(mark.line));
    message.append(":").append(std::to_string(mark.column));
  }
  message += ": ";
  if (!path.empty()) message += path + ": ";
  throw InputError(message + what);
}

SourceMark ToSourceMark(const YAML::Mark& mark) {
  if (mark.is_null()) return {};
  return {mark.line + 1, mark.column + 1};  // yaml-cpp counts from 0, editors from 1
}

// List indices in key paths are 1-based (mooring.lines[3] is the third entry): the project
// numbers lines from 1 in everything a user reads, and the path should match the id.
std::string ItemPath(const std::string& list_path, std::size_t index) {
  return list_path + "[" + std::to_string(index + 1) + "]";
}

std::string KeyPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

double Radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// ---------------------------------------------------------------------------------------
// Text encoding: scenario files and --set values are UTF-8 (the run's outputs record them
// in JSON, which is UTF-8 only).

// Length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no overlong forms, no
// surrogates, nothing above U+10FFFF), or 0 if the byte there does not start one.
std::size_t Utf8SequenceLength(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) {
    return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u;
  };
  const unsigned lead = byte(i);
  const auto continuation = [&](std::size_t k, unsigned low = 0x80, unsigned high = 0xBF) {
    return byte(k) >= low && byte(k) <= high;
  };
  if (lead < 0x80) return 1;
  if (lead >= 0xC2 && lead <= 0xDF) return continuation(i + 1) ? 2 : 0;
  if (lead >= 0xE0 && lead <= 0xEF) {
    const unsigned low = lead == 0xE0 ? 0xA0 : 0x80;   // no overlong forms
    const unsigned high = lead == 0xED ? 0x9F : 0xBF;  // no surrogates
    return continuation(i + 1, low, high) && continuation(i + 2) ? 3 : 0;
  }
  if (lead >= 0xF0 && lead <= 0xF4) {
    const unsigned low = lead == 0xF0 ? 0x90 : 0x80;   // no overlong forms
    const unsigned high = lead == 0xF4 ? 0x8F : 0xBF;  // nothing above U+10FFFF
    return continuation(i + 1, low, high) && continuation(i + 2) && continuation(i + 3) ? 4 : 0;
  }
  return 0;
}

// Offset of the first byte that is not part of well-formed UTF-8, if any.
std::optional<std::size_t> FirstInvalidUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = Utf8SequenceLength(text, i);
    if (length == 0) return i;
    i += length;
  }
  return std::nullopt;
}

std::string HexByte(unsigned char byte) {
  static constexpr char kDigits[] = "0123456789ABCDEF";
  return std::string("0x") + kDigits[byte >> 4] + kDigits[byte & 0xF];
}

// The text with every byte outside well-formed UTF-8 written as \xNN, so a message that
// quotes it is UTF-8 itself.
std::string EscapeInvalidUtf8(std::string_view text) {
  std::string shown;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t length = Utf8SequenceLength(text, i);
    if (length == 0) {
      shown += "\\x" + HexByte(static_cast<unsigned char>(text[i])).substr(2);
      ++i;
    } else {
      shown.append(text.substr(i, length));
      i += length;
    }
  }
  return shown;
}

// "not valid UTF-8 (byte 0xE9); ...": the message tail for the bad byte at `offset`.
std::string InvalidUtf8(std::string_view text, std::size_t offset) {
  return "not valid UTF-8 (byte " + HexByte(static_cast<unsigned char>(text[offset])) +
         "); save the file as UTF-8";
}

// 1-based line and column (in bytes, as yaml-cpp counts them) of byte `offset`.
SourceMark MarkOfOffset(std::string_view text, std::size_t offset) {
  const std::size_t line_start =
      offset == 0 ? std::string_view::npos : text.rfind('\n', offset - 1);
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n');
  const std::size_t column =
      line_start == std::string_view::npos ? offset + 1 : offset - line_start;
  return {static_cast<int>(line), static_cast<int>(column)};
}

// ---------------------------------------------------------------------------------------
// YAML tags. A tag changes how a value reads (`!!str 1.0041e8` is text that yaml-cpp still
// converts to a number; `!!binary`, `!foo` are not numbers at all), so none is accepted.
// yaml-cpp gives a plain scalar the tag "?" and a quoted or block scalar "!"; an explicit
// non-specific tag (`! 5`) is also "!", told apart by the '!' written at the node (after an
// anchor, if any).

// The tag as the user wrote it ("!!str" for "tag:yaml.org,2002:str"), or nothing.
std::optional<std::string> ExplicitTag(const YAML::Node& node, const std::string* text) {
  const std::string& tag = node.Tag();
  if (tag.empty() || tag == "?") return std::nullopt;
  if (tag != "!") {
    constexpr std::string_view kCore = "tag:yaml.org,2002:";
    if (tag.compare(0, kCore.size(), kCore) == 0) return "!!" + tag.substr(kCore.size());
    if (tag[0] == '!') return tag;
    return "!<" + tag + ">";
  }
  const YAML::Mark mark = node.Mark();
  if (text == nullptr || mark.is_null() || mark.pos < 0 ||
      static_cast<std::size_t>(mark.pos) >= text->size()) {
    return std::nullopt;
  }
  std::size_t i = static_cast<std::size_t>(mark.pos);
  if ((*text)[i] == '&') {  // an anchor first: skip its name and the blanks after it
    while (i < text->size() && (*text)[i] != ' ' && (*text)[i] != '\t' && (*text)[i] != '\n') ++i;
    while (i < text->size() && ((*text)[i] == ' ' || (*text)[i] == '\t')) ++i;
  }
  if (i < text->size() && (*text)[i] == '!') return std::string("!");
  return std::nullopt;
}

// Throws InputError `prefix`: tagged value ... for the first tagged node in a --set value.
void CheckOverrideUntagged(const YAML::Node& node, const std::string& text,
                           const std::string& prefix) {
  if (const std::optional<std::string> tag = ExplicitTag(node, &text)) {
    throw InputError(prefix + ": tagged value '" + *tag +
                     "' (tags are not accepted; write the plain value)");
  }
  if (node.IsMap()) {
    for (const auto& entry : node) {
      CheckOverrideUntagged(entry.first, text, prefix);
      CheckOverrideUntagged(entry.second, text, prefix);
    }
  } else if (node.IsSequence()) {
    for (const auto& item : node) CheckOverrideUntagged(item, text, prefix);
  }
}

// ---------------------------------------------------------------------------------------
// Strict reading of one YAML node at a key path.

bool UnderPath(const std::string& path, const std::string& prefix) {
  if (prefix.empty()) return true;
  return path == prefix ||
         (path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0 &&
          (path[prefix.size()] == '.' || path[prefix.size()] == '['));
}

std::vector<KeyStep> SplitKeyPath(const std::string& path) {
  const auto fail = [&](const std::string& what) { throw InputError(what); };
  const auto empty_key = [&] {
    fail("empty key in '" + path + "' (one '.' between keys, none before '[')");
  };
  std::vector<KeyStep> steps;
  std::size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '[') {
      if (steps.empty()) fail("'" + path + "' starts with a list index (e.g. mooring.lines[1])");
      const std::size_t close = path.find(']', i);
      const char* first = path.data() + i + 1;
      const char* last = path.data() + (close == std::string::npos ? i + 1 : close);
      int index = 0;
      const auto [end, error] = std::from_chars(first, last, index);
      if (close == std::string::npos || error != std::errc() || end != last || index < 1) {
        fail("bad list index in '" + path + "' (lists count from 1)");
      }
      if (*first == '0') {
        fail("bad list index in '" + path + "' (write [" + std::to_string(index) + "])");
      }
      steps.push_back({"", index});
      i = close + 1;
      if (i < path.size() && path[i] != '.' && path[i] != '[') {
        fail("'" + path + "': '.' or '[' must follow ']'");
      }
      continue;
    }
    if (path[i] == '.') {
      if (steps.empty()) empty_key();
      ++i;
    }
    const std::size_t stop = std::min(path.find_first_of(".[", i), path.size());
    if (stop == i) empty_key();
    steps.push_back({path.substr(i, stop - i), 0});
    i = stop;
  }
  if (steps.empty()) empty_key();
  return steps;
}

namespace {

// Offset of the first text after a document-end marker (a line "..."), other than blanks
// and comments, if any. yaml-cpp drops what follows the marker when it is not a document
// (a directive such as "%YAML 1.2"); a second document it reports.
std::optional<std::size_t> TextAfterDocumentEnd(std::string_view text) {
  bool ended = false;
  for (std::size_t line = 0; line < text.size();) {
    const std::size_t end = std::min(text.find('\n', line), text.size());
    std::size_t i = line;
    if (!ended && text.substr(line, 3) == "..." &&
        (end == line + 3 ||
         std::string_view(" \t\r").find(text[line + 3]) != std::string_view::npos)) {
      ended = true;
      i += 3;
    }
    if (ended) {
      while (i < end && std::string_view(" \t\r").find(text[i]) != std::string_view::npos) ++i;
      if (i < end && text[i] != '#') return i;
    }
    line = end + 1;
  }
  return std::nullopt;
}

// Every map's keys once (a second occurrence is an error there) and at most
// kMaxDocumentValues values in all, an alias counted as all it stands for: yaml-cpp shares
// an aliased node, so nested aliases cost nothing to read but multiply every later walk
// over the document.
void CheckStructure(const YAML::Node& node, const std::string& path, const std::string& file,
                    std::size_t& values) {
  if (++values > kMaxDocumentValues) {
    ThrowAt(file, ToSourceMark(node.Mark()), path,
            "aliases expand the document to more than " + std::to_string(kMaxDocumentValues) +
                " values (write the values out)");
  }
  if (node.IsMap()) {
    std::set<std::string> keys;
    for (const auto& entry : node) {
      if (!entry.first.IsScalar()) {  // the reader rejects it where it is read
        CheckStructure(entry.first, path, file, values);
        CheckStructure(entry.second, path, file, values);
        continue;
      }
      const std::string& name = entry.first.Scalar();
      if (!keys.insert(name).second) {
        ThrowAt(file, ToSourceMark(entry.first.Mark()), path, "duplicate key '" + name + "'");
      }
      CheckStructure(entry.second, KeyPath(path, name), file, values);
    }
  } else if (node.IsSequence()) {
    std::size_t i = 0;
    for (const YAML::Node& item : node) CheckStructure(item, ItemPath(path, i++), file, values);
  }
}

}  // namespace

YAML::Node LoadDocument(const std::string& text, const std::string& file, std::string_view what,
                        std::string_view expected) {
  // Bytes that are not UTF-8 would pass as text and stop the JSON writer after the run.
  if (const std::optional<std::size_t> bad = FirstInvalidUtf8(text)) {
    ThrowAt(file, MarkOfOffset(text, *bad), "", InvalidUtf8(text, *bad));
  }
  const std::string kind(what);
  try {
    const std::vector<YAML::Node> documents = YAML::LoadAll(text);
    if (documents.empty() || documents[0].IsNull()) {
      ThrowAt(file, {}, "",
              "the " + kind + " is empty (expected a map with '" + std::string(expected) + "')");
    }
    if (const std::optional<std::size_t> after = TextAfterDocumentEnd(text)) {
      ThrowAt(
          file, MarkOfOffset(text, *after), "",
          "text after the document-end marker '...' (a " + kind + " file holds one YAML document)");
    }
    if (documents.size() > 1) {
      ThrowAt(file, ToSourceMark(documents[1].Mark()), "",
              "a " + kind + " file holds one YAML document; this is a second one");
    }
    std::size_t values = 0;
    CheckStructure(documents[0], "", file, values);
    return documents[0];
  } catch (const YAML::ParserException& error) {
    ThrowAt(file, ToSourceMark(error.mark), "", "YAML syntax error: " + error.msg);
  }
}

namespace {

const ParseContext::Origin* DeepestOrigin(const ParseContext& context, const std::string& path) {
  return DeepestUnder(context.origins, path,
                      [](const ParseContext::Origin& o) -> const std::string& { return o.path; });
}

}  // namespace

const std::string& ParseContext::FileOf(const std::string& path) const {
  const Origin* origin = DeepestOrigin(*this, path);
  return origin ? origin->file : file;
}

const std::string* ParseContext::TextOf(const std::string& path) const {
  const Origin* origin = DeepestOrigin(*this, path);
  return origin ? origin->text : text;
}

void ParseContext::Record(const std::string& message) const {
  if (std::find(errors->begin(), errors->end(), message) == errors->end()) {
    errors->push_back(message);
  }
}

// Whether `path` is an overridden key path or lies under one.
bool Overridden(const ParseContext& context, const std::string& path) {
  for (const std::string& o : context.overridden) {
    if (UnderPath(path, o)) return true;
  }
  return false;
}

// One InputError for all the messages (one located line each, ordered by file and
// position); nothing for none.
void ThrowCollected(std::vector<std::string> errors) {
  if (errors.empty()) return;
  // "<file>:<line>:<col>: ..." sorts by file, then numerically by line and column.
  const auto key = [](const std::string& message) {
    std::size_t colon = message.find(": ");
    const std::string head = message.substr(0, colon);
    int line = 0, column = 0;
    const std::size_t second = head.rfind(':');
    const std::size_t first = second == std::string::npos ? second : head.rfind(':', second - 1);
    if (first != std::string::npos &&
        std::from_chars(head.data() + first + 1, head.data() + second, line).ec == std::errc() &&
        std::from_chars(head.data() + second + 1, head.data() + head.size(), column).ec ==
            std::errc()) {
      return std::tuple(head.substr(0, first), line, column);
    }
    return std::tuple(head, 0, 0);
  };
  std::stable_sort(errors.begin(), errors.end(),
                   [&](const std::string& a, const std::string& b) { return key(a) < key(b); });
  std::string joined;
  for (const std::string& error : errors) joined += (joined.empty() ? "" : "\n") + error;
  throw InputError(joined);
}

// ---------------------------------------------------------------------------------------
// Keys and values against the schema.

std::string Reader::KeyName(const YAML::Node& key) const {
  const SourceMark key_mark = ToSourceMark(key.Mark());
  if (!key.IsScalar())
    ThrowAt(context_->FileOf(path_), key_mark, path_, "keys must be plain names");
  if (!overridden_) {
    const std::string child = KeyPath(path_, key.Scalar());
    if (const std::optional<std::string> tag = ExplicitTag(key, context_->TextOf(child))) {
      ThrowAt(context_->FileOf(child), key_mark, path_,
              "tagged key '" + *tag + "' (tags are not accepted; write the plain name)");
    }
  }
  return key.Scalar();
}

void Reader::FailAtKey(const YAML::Node& key, const std::string& name,
                       const std::string& what) const {
  ThrowAt(context_->FileOf(KeyPath(path_, name)), ToSourceMark(key.Mark()), path_, what);
}

std::vector<std::string> Reader::Keys() const {
  CheckUntagged("the plain map");
  std::vector<std::string> keys;
  for (const auto& entry : node_) {
    const std::string name = KeyName(entry.first);
    if (std::find(keys.begin(), keys.end(), name) != keys.end()) {
      FailAtKey(entry.first, name, "duplicate key '" + name + "'");
    }
    keys.push_back(name);
  }
  return keys;
}

Reader Reader::Needed(std::string_view key) const {
  if (std::optional<Reader> child = Find(key)) return *child;
  if (block_ != nullptr && node_.IsMap()) {
    for (const auto& entry : node_) {
      const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : std::string();
      if (block_->Find(name) == nullptr && schema::NearestKey(*block_, name) == key) {
        throw AlreadyReported();  // by CheckKeys, as the key it meant
      }
    }
  }
  Fail("required key '" + std::string(key) + "' is missing");
}

void Reader::CheckKeys() const {
  if (block_ == nullptr) throw ContractError("CheckKeys at '" + path_ + "' without a schema");
  CheckUntagged("the plain map");
  if (!node_.IsMap()) Fail(Describe(node_) + " must be a map");
  context_->checked.insert(path_);
  std::vector<std::string> seen, suggested;
  for (const auto& entry : node_) {
    context_->Attempt([&] {
      const std::string name = KeyName(entry.first);
      if (block_->Find(name) == nullptr && !block_->open_numbers) {
        const std::string nearest = schema::NearestKey(*block_, name);
        suggested.push_back(nearest);
        std::vector<std::string> known;
        for (const schema::Key& key : block_->keys) known.emplace_back(key.name);
        FailAtKey(entry.first, name,
                  "unknown key '" + name + "' " +
                      (nearest.empty() ? "(known: " + JoinSorted(known) + ")"
                                       : "(did you mean '" + nearest + "'?)"));
      }
      if (std::find(seen.begin(), seen.end(), name) != seen.end()) {
        FailAtKey(entry.first, name, "duplicate key '" + name + "'");
      }
      seen.push_back(name);
    });
  }
  // A required key that an unknown key's message already suggests is not missing twice.
  for (const schema::Key& key : block_->keys) {
    if (key.required && std::find(seen.begin(), seen.end(), key.name) == seen.end() &&
        std::find(suggested.begin(), suggested.end(), key.name) == suggested.end()) {
      context_->Attempt([&] { Fail("required key '" + std::string(key.name) + "' is missing"); });
    }
  }
}

Reader Reader::Under(const YAML::Node& value, std::string path, SourceMark mark,
                     const schema::Key* key) const {
  Reader child(*context_, value, std::move(path), mark, key ? key->block : nullptr);
  child.key_ = key;
  return child;
}

std::optional<Reader> Reader::Find(std::string_view key) const {
  const schema::Key* known = nullptr;
  if (block_ != nullptr) {
    known = block_->Find(key);
    if (known == nullptr && !block_->open_numbers) {
      throw ContractError("the loader reads '" + KeyPath(path_, key) +
                          "', which the schema does not list");
    }
  }
  for (const auto& entry : node_) {
    if (entry.first.IsScalar() && entry.first.Scalar() == key) {
      // yaml-cpp puts an empty value's mark on the next token, possibly lines later;
      // the key is where the user looks.
      const YAML::Mark& mark = entry.second.IsNull() ? entry.first.Mark() : entry.second.Mark();
      return Under(entry.second, KeyPath(path_, key), ToSourceMark(mark), known);
    }
  }
  return std::nullopt;
}

std::vector<Reader> Reader::Items() const {
  CheckUntagged("the plain list");
  if (!node_.IsSequence()) Fail(Describe(node_) + " must be a list");
  std::vector<Reader> items;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    items.push_back(Under(node_[i], ItemPath(path_, i), ToSourceMark(node_[i].Mark()), key_));
  }
  return items;
}

void Reader::CheckRange(double value) const {
  if (key_ == nullptr || (!key_->minimum && !key_->maximum)) return;
  const std::optional<schema::Bound>& low = key_->minimum;
  const std::optional<schema::Bound>& high = key_->maximum;
  const bool below = low && (low->exclusive ? !(value > low->value) : !(value >= low->value));
  const bool above = high && (high->exclusive ? !(value < high->value) : !(value <= high->value));
  if (!below && !above) return;
  const auto why = [](std::string_view text) {
    return text.empty() ? std::string() : " (" + std::string(text) + ")";
  };
  if (key_->kind == schema::Kind::kInteger) {
    const auto whole = [](double v) { return std::to_string(static_cast<long long>(v)); };
    const std::string shown = whole(value);
    if (low && high) Fail(shown + " must be in " + whole(low->value) + ".." + whole(high->value));
    Fail(shown +
         (below ? " must be >= " + whole(low->value) : " must be <= " + whole(high->value)));
  }
  const std::string shown = WithUnit(value, key_->unit);
  if (key_->interval && low && high) {
    Fail(shown + " must be in " + (low->exclusive ? "(" : "[") + FormatNumber(low->value) + ", " +
         FormatNumber(high->value) + (high->exclusive ? ")" : "]") +
         why(high->why.empty() ? low->why : high->why));
  }
  if (below) {
    Fail(shown + " must be " + (low->exclusive ? "> " : ">= ") + FormatNumber(low->value) +
         why(low->why));
  }
  Fail(shown + " must be " + (high->exclusive ? "< " : "<= ") + FormatNumber(high->value) +
       why(high->why));
}

void Reader::CheckChoice(const std::string& value) const {
  if (key_ == nullptr || key_->choices.empty()) return;
  if (std::find(key_->choices.begin(), key_->choices.end(), value) != key_->choices.end()) return;
  Fail("unknown " + std::string(key_->choice_noun) + " '" + value +
       "' (known: " + JoinSorted({key_->choices.begin(), key_->choices.end()}) + ")");
}

std::string Describe(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Scalar:
      // Tag "!" is yaml-cpp's mark of a quoted scalar; show the quotes so "must be a
      // number" makes sense for "0.08".
      return node.Tag() == "!" ? "\"" + node.Scalar() + "\"" : node.Scalar();
    case YAML::NodeType::Sequence: {
      // A short list of scalars reads best as written: "[0, 20] must be a list of 3 ...".
      std::string shown = "[";
      for (std::size_t i = 0; i < node.size(); ++i) {
        if (!node[i].IsScalar() || i == 6) return "a list";
        shown += (i > 0 ? ", " : "") + Describe(node[i]);
      }
      return shown + "]";
    }
    case YAML::NodeType::Map:
      return "a map";
    default:
      return "an empty value";
  }
}

template <>
double Reader::As<double>() const {
  const double value = Decode<double>("a number", "the plain number");
  if (!std::isfinite(value)) Fail(Describe(node_) + " must be a finite number");
  CheckRange(value);
  return value;
}

template <>
int Reader::As<int>() const {
  const int value = Decode<int>("an integer", "the plain integer");
  CheckRange(value);
  return value;
}

template <>
bool Reader::As<bool>() const {
  return Decode<bool>("true or false", "true or false");
}

template <>
std::string Reader::As<std::string>() const {
  return PlainText();
}

std::string Reader::PlainText() const {
  CheckUntagged("the plain text");
  if (!node_.IsScalar()) Fail(Describe(node_) + " must be a string");
  CheckChoice(node_.Scalar());
  return node_.Scalar();
}

template <>
std::uint64_t Reader::As<std::uint64_t>() const {
  CheckUntagged("the plain integer");
  if (!node_.IsScalar() || node_.Tag() == "!" || node_.Scalar().empty() ||
      node_.Scalar()[0] == '-') {
    Fail(Describe(node_) + " must be a non-negative integer");
  }
  return Decode<std::uint64_t>("a non-negative integer", "the plain integer");
}

template <>
Vec3 Reader::As<Vec3>() const {
  CheckUntagged("the plain list");
  if (!node_.IsSequence() || node_.size() != 3) {
    Fail(Describe(node_) + " must be a list of 3 numbers [x, y, z]");
  }
  const std::vector<Reader> items = Items();
  return Vec3(items[0].As<double>(), items[1].As<double>(), items[2].As<double>());
}
std::string ReadInputFile(const std::string& path, std::size_t max_bytes, std::string_view what) {
  const std::string kind(what);
  std::error_code ignored;
  if (std::filesystem::is_directory(path, ignored)) {
    throw InputError(path + ": is a directory, not a " + kind + " file");
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    const std::error_code error(errno, std::generic_category());
    throw InputError(path + ": cannot open the " + kind + " file: " + error.message());
  }
  // Read in chunks: the text holds what the file has, not the limit (every included file
  // of a scenario is held while the chain is read).
  std::string text;
  std::array<char, 1 << 16> chunk{};
  while (text.size() <= max_bytes) {
    file.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    text.append(chunk.data(), static_cast<std::size_t>(file.gcount()));
    if (!file) break;
  }
  if (file.bad()) throw InputError(path + ": cannot read the " + kind + " file");
  if (text.size() > max_bytes) {
    throw InputError(path + ": larger than " + std::to_string(max_bytes >> 20) + " MiB, not a " +
                     kind + " file");
  }
  return text;
}

}  // namespace moorsim::scenarios::strict_yaml
