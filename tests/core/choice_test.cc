// Tests of the configuration choices' tables (core/choice.h): names and values map both
// ways, and an unknown name is none (the loader's message lists the names sorted:
// tests/scenarios).
#include "core/choice.h"

#include <gtest/gtest.h>

#include <optional>
#include <string_view>

namespace moorsim {
namespace {

enum class Hold { kZeroOrder, kFirstOrder, kNone };
constexpr std::string_view kHoldNames[] = {"zero_order", "first_order", "none"};
constexpr ChoiceInfo ChoicesOf(Hold) { return {"hold", kHoldNames}; }

TEST(Choice, NamesAndValuesMapBothWays) {
  for (const Hold h : {Hold::kZeroOrder, Hold::kFirstOrder, Hold::kNone}) {
    EXPECT_EQ(ParseChoice<Hold>(ChoiceName(h)), h);
  }
  EXPECT_EQ(ChoiceName(Hold::kFirstOrder), "first_order");
  EXPECT_EQ(ChoiceNames<Hold>().size(), 3u);
  EXPECT_EQ(ChoiceNoun<Hold>(), "hold");
}

TEST(Choice, AnUnknownNameIsNone) {
  EXPECT_EQ(ParseChoice<Hold>("second_order"), std::nullopt);
  EXPECT_EQ(ParseChoice<Hold>(""), std::nullopt);
  EXPECT_EQ(ParseChoice<Hold>("None"), std::nullopt);  // names are case-sensitive
}

// Usable where the schema's tables are built: at compile time.
static_assert(ParseChoice<Hold>("none") == Hold::kNone);
static_assert(ChoiceName(Hold::kZeroOrder) == "zero_order");

}  // namespace
}  // namespace moorsim
