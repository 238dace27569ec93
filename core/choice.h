// Configuration choices: an enum whose values a scenario, a campaign or an API call names
// in text ("locked", "klu", "passive"). Each such enum has one table, declared beside it,
// that names every value, in the order of the enum's values (0, 1, 2, ...), and a
// ChoicesOf overload that ChoiceNames and the others below find by argument-dependent
// lookup:
//
//   enum class TurretBearing { kLocked, kFree, kFriction };
//   inline constexpr std::string_view kTurretBearingNames[] = {"locked", "free", "friction"};
//   constexpr ChoiceInfo ChoicesOf(TurretBearing) { return {"turret bearing", kTurretBearingNames};
//   }
//
// The scenario loader parses the text once, through ParseChoice; the schema's list of
// accepted values, the messages and the echo of a default use the same table, so a value
// added to the enum and its table is known everywhere at once.
#pragma once

#include <concepts>
#include <cstddef>
#include <optional>
#include <span>
#include <string_view>
#include <type_traits>

namespace moorsim {

/// How messages name a choice ("turret bearing") and its values' names, in the enum's order.
struct ChoiceInfo {
  std::string_view noun;
  std::span<const std::string_view> names;
};

/// An enum with a ChoicesOf overload beside it.
template <class E>
concept Choice = std::is_enum_v<E> && requires(E value) {
  { ChoicesOf(value) } -> std::same_as<ChoiceInfo>;
};

/// Every accepted name of E, in the enum's order.
template <Choice E>
constexpr std::span<const std::string_view> ChoiceNames() {
  return ChoicesOf(E{}).names;
}

/// How messages name E ("turret bearing").
template <Choice E>
constexpr std::string_view ChoiceNoun() {
  return ChoicesOf(E{}).noun;
}

/// The name of `value`.
template <Choice E>
constexpr std::string_view ChoiceName(E value) {
  return ChoiceNames<E>()[static_cast<std::size_t>(value)];
}

/// The value named `name`, or nothing if no value has that name.
template <Choice E>
constexpr std::optional<E> ParseChoice(std::string_view name) {
  const std::span<const std::string_view> names = ChoiceNames<E>();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<E>(i);
  }
  return std::nullopt;
}

}  // namespace moorsim
