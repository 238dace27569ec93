// The bytes of a saved state (the lines' or the plant's): numbers appended in the
// machine's own byte order, read back with every read checked against the end, so that a
// buffer cut short or damaged is an InputError naming what was being read.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/version.h"

namespace moorsim {

class StateWriter {
 public:
  template <typename T>
  void Put(const T& value) {
    const auto* b = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), b, b + sizeof(T));
  }
  void PutString(const std::string& text) {
    Put(static_cast<std::int64_t>(text.size()));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
  }
  void PutNumbers(std::span<const double> values) {
    Put(static_cast<std::int64_t>(values.size()));
    for (double v : values) Put(v);
  }
  /// The start of every saved state: an 8-character tag naming its kind, the format, the
  /// program's version and the model's fingerprint (StateReader::CheckHeader).
  void PutHeader(const char (&tag)[9], std::int64_t format, std::uint64_t fingerprint) {
    bytes_.insert(bytes_.end(), tag, tag + 8);
    Put(format);
    PutString(kVersion);
    Put(fingerprint);
  }
  /// The bytes PutHeader writes.
  static std::size_t HeaderSize() { return 8 + 8 + 8 + std::strlen(kVersion) + 8; }
  std::vector<std::uint8_t> Take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

class StateReader {
 public:
  /// `kind` names the state in messages ("lines state").
  StateReader(std::span<const std::uint8_t> bytes, std::string kind)
      : bytes_(bytes), kind_(std::move(kind)) {}

  template <typename T>
  T Get(const char* what) {
    Need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string GetString(std::size_t max_size, const char* what) {
    const auto size = Get<std::int64_t>(what);
    if (size < 0 || static_cast<std::uint64_t>(size) > max_size) Damaged(what);
    Need(static_cast<std::size_t>(size), what);
    std::string text(reinterpret_cast<const char*>(bytes_.data() + at_),
                     static_cast<std::size_t>(size));
    at_ += static_cast<std::size_t>(size);
    return text;
  }
  /// A count of items of `item_size` bytes each, no more than the bytes left can hold.
  std::size_t GetCount(std::size_t item_size, const char* what) {
    const auto count = Get<std::int64_t>(what);
    if (count < 0 || static_cast<std::uint64_t>(count) > remaining() / item_size) Damaged(what);
    return static_cast<std::size_t>(count);
  }
  /// Reads what StateWriter::PutHeader wrote and refuses a state of another kind, format,
  /// program version or model.
  void CheckHeader(const char (&tag)[9], std::int64_t format, std::uint64_t fingerprint) {
    for (int i = 0; i < 8; ++i) {
      if (Get<char>("tag") != tag[i]) Refuse("not a moorsim " + kind_);
    }
    const auto saved_format = Get<std::int64_t>("format");
    if (saved_format != format) {
      Refuse("format " + std::to_string(saved_format) + ", this program reads " +
             std::to_string(format));
    }
    const std::string version = GetString(256, "version");
    if (version != kVersion)
      Refuse("saved by moorsim " + version + ", this is moorsim " + kVersion);
    if (Get<std::uint64_t>("fingerprint") != fingerprint) {
      Refuse("saved from another model (" + std::string(what_differs_) + ")");
    }
  }
  /// What the fingerprint covers, for the message of a state from another model.
  void SetFingerprintMeaning(const char* what) { what_differs_ = what; }
  std::size_t remaining() const { return bytes_.size() - at_; }
  [[noreturn]] void Damaged(const char* what) const {
    throw InputError(kind_ + ": damaged (" + what + ")");
  }
  [[noreturn]] void Refuse(const std::string& why) const { throw InputError(kind_ + ": " + why); }

 private:
  void Need(std::size_t size, const char* what) const {
    if (remaining() < size) {
      throw InputError(kind_ + ": cut short at byte " + std::to_string(at_) + " (" + what + ")");
    }
  }
  std::span<const std::uint8_t> bytes_;
  std::string kind_;
  const char* what_differs_ = "its inputs differ";
  std::size_t at_ = 0;
};

}  // namespace moorsim
