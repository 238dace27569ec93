// The schema tables (scenarios/schema.h) and what the loader does with them: defaults that
// obey their own ranges, the nearest-key suggestion, every error of a file at once.
#include "scenarios/schema.h"

#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bad_input_cases.h"
#include "core/error.h"
#include "scenarios/load.h"

namespace moorsim::scenarios {
namespace {

using schema::Block;
using schema::Key;
using schema::Kind;

// Calls `visit` for every key of `block` and the blocks under it, with its key path
// ("mooring.lines[].length").
void ForEachKey(const Block& block, const std::string& path,
                const std::function<void(const Key&, const std::string&)>& visit,
                std::set<const Block*> seen = {}) {
  if (!seen.insert(&block).second) return;
  for (const Key& key : block.keys) {
    const std::string here = (path.empty() ? "" : path + ".") + std::string(key.name);
    visit(key, here);
    if (key.block != nullptr) {
      ForEachKey(*key.block, here + (key.kind == Kind::kList ? "[]" : ""), visit, seen);
    }
  }
}

bool Within(const Key& key, double value) {
  if (key.minimum &&
      (key.minimum->exclusive ? !(value > key.minimum->value) : !(value >= key.minimum->value))) {
    return false;
  }
  if (key.maximum &&
      (key.maximum->exclusive ? !(value < key.maximum->value) : !(value <= key.maximum->value))) {
    return false;
  }
  return true;
}

TEST(Schema, EveryDefaultObeysItsKeysRangeKindAndChoices) {
  int defaults = 0;
  for (const Block* root : {&schema::Scenario(), &schema::Campaign()}) {
    ForEachKey(*root, "", [&](const Key& key, const std::string& path) {
      if (key.default_json == nullptr) return;
      ++defaults;
      const nlohmann::json value = nlohmann::json::parse(key.default_json());
      switch (key.kind) {
        case Kind::kNumber:
          ASSERT_TRUE(value.is_number()) << path;
          EXPECT_TRUE(Within(key, value.get<double>())) << path << " default " << value;
          break;
        case Kind::kInteger:
        case Kind::kCount:
          ASSERT_TRUE(value.is_number_integer()) << path;
          EXPECT_TRUE(Within(key, value.get<double>())) << path << " default " << value;
          break;
        case Kind::kBoolean:
          EXPECT_TRUE(value.is_boolean()) << path;
          break;
        case Kind::kString:
          ASSERT_TRUE(value.is_string()) << path;
          if (!key.choices.empty()) {
            EXPECT_NE(std::find(key.choices.begin(), key.choices.end(), value.get<std::string>()),
                      key.choices.end())
                << path << " default " << value;
          }
          break;
        case Kind::kVector:
          ASSERT_TRUE(value.is_array() && value.size() == 3) << path;
          for (const auto& element : value) {
            EXPECT_TRUE(Within(key, element.get<double>())) << path << " default " << value;
          }
          break;
        default:
          ADD_FAILURE() << path << ": a default on a " << static_cast<int>(key.kind) << " key";
      }
    });
  }
  EXPECT_GT(defaults, 80);  // the scenario's optional numbers, switches and choices
}

TEST(Schema, BlocksAreSortedWithUniqueNamesAndDescribed) {
  for (const Block* root : {&schema::Scenario(), &schema::Campaign()}) {
    ForEachKey(*root, "", [&](const Key& key, const std::string& path) {
      EXPECT_FALSE(key.description.empty()) << path;
      EXPECT_EQ(key.choices.empty(), key.choice_noun.empty()) << path;
      if (key.kind == Kind::kMap) {
        EXPECT_NE(key.block, nullptr) << path;
      }
      if (key.minimum && key.maximum) {
        EXPECT_LT(key.minimum->value, key.maximum->value) << path;
      }
    });
    std::function<void(const Block&)> sorted = [&](const Block& block) {
      for (std::size_t i = 1; i < block.keys.size(); ++i) {
        EXPECT_LT(block.keys[i - 1].name, block.keys[i].name) << block.description;
      }
    };
    sorted(*root);
    ForEachKey(*root, "", [&](const Key& key, const std::string&) {
      if (key.block) sorted(*key.block);
    });
  }
}

TEST(Schema, JsonSchemaHasEveryKeyWithItsRangeAndDefault) {
  const nlohmann::json root = nlohmann::json::parse(schema::JsonSchema(schema::Scenario(), "t"));
  EXPECT_EQ(root["$schema"], "http://json-schema.org/draft-07/schema#");
  // A file with a base may leave anything out; a whole file must have its required keys.
  EXPECT_EQ(root["if"]["required"], nlohmann::json({"base"}));
  EXPECT_EQ(root["definitions"]["override"].count("required"), 0u);
  const nlohmann::json& s = root["definitions"]["whole"];
  EXPECT_EQ(s["required"], nlohmann::json({"mooring"}));
  EXPECT_EQ(s["additionalProperties"], false);
  const nlohmann::json& depth =
      s["properties"]["mooring"]["properties"]["water"]["properties"]["depth"];
  EXPECT_EQ(depth["type"], "number");
  EXPECT_EQ(depth["exclusiveMinimum"], 0.0);
  EXPECT_EQ(depth["maximum"], 12000.0);
  EXPECT_NE(depth["description"].get<std::string>().find("[m]"), std::string::npos);
  const nlohmann::json& solver = s["properties"]["solver"]["properties"];
  EXPECT_EQ(solver["rtol"]["default"], 1e-4);
  EXPECT_EQ(solver["linear_solver"]["enum"], nlohmann::json({"block", "klu"}));
  const nlohmann::json& lines = s["properties"]["mooring"]["properties"]["lines"];
  EXPECT_EQ(lines["type"], "array");
  EXPECT_EQ(lines["items"]["properties"]["fairlead"]["maxItems"], 3);
  // A detector entry takes any number besides its listed keys.
  EXPECT_EQ(s["properties"]["detectors"]["items"]["additionalProperties"]["type"], "number");
}

TEST(Schema, MarkdownTableHasARowPerKeyWithRangeAndDefault) {
  const std::string table = schema::MarkdownTable(schema::Scenario());
  int rows = 0, keys = 0;
  for (char c : table) rows += c == '\n';
  ForEachKey(schema::Scenario(), "", [&](const Key&, const std::string&) { ++keys; });
  EXPECT_EQ(rows, keys + 2);  // the header and its rule
  EXPECT_NE(table.find("| `mooring.water.depth` (required) | number | m | (0, 12000] (the deepest "
                       "ocean is 11 km) |  | Water depth"),
            std::string::npos)
      << table;
  EXPECT_NE(table.find("| `solver.linear_solver` | choice |  | block, klu | `\"block\"` |"),
            std::string::npos);
  EXPECT_NE(table.find("| `mooring.lines[].segments` | integer |  | [2, 10000] |"),
            std::string::npos);
}

TEST(Schema, NearestKeyCatchesTyposAndMissingUnitSuffixes) {
  const Block& water = *schema::Scenario().Find("mooring")->block->Find("water")->block;
  EXPECT_EQ(schema::NearestKey(water, "dept"), "depth");
  EXPECT_EQ(schema::NearestKey(water, "detph"), "depth");  // a swap is one edit
  EXPECT_EQ(schema::NearestKey(water, "densty"), "density");
  EXPECT_EQ(schema::NearestKey(water, "salinity"), "");  // nothing close
  const Block& current = *schema::Scenario().Find("mooring")->block->Find("current")->block;
  EXPECT_EQ(schema::NearestKey(current, "direction"), "direction_deg");
  EXPECT_EQ(schema::EditDistance("kitten", "sitting"), 3);
  EXPECT_EQ(schema::EditDistance("ab", "ba"), 1);
  EXPECT_EQ(schema::EditDistance("", "abc"), 3);
}

std::string AllErrorsOf(const std::string& text) {
  try {
    ParseScenario(text, "test.yaml");
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

std::vector<std::string> MessageLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

using test_cases::Edit;
using test_cases::kBase;
using test_cases::PositionOf;

TEST(AllErrors, EveryProblemOfTheFileOnItsOwnLineInFileOrder) {
  std::string text = Edit(kBase, "- name: chain", "diameter: 0.08", "diameter: -0.08");
  text = Edit(text, "", "depth: 1000}", "dept: 1000}");
  text = Edit(text, "solver:", "rtol: 1.0e-4", "rtol: 2");
  text = Edit(text, "- id: 2", "type: wire", "type: [wire]");
  const std::vector<std::string> lines = MessageLines(AllErrorsOf(text));
  ASSERT_EQ(lines.size(), 4u) << AllErrorsOf(text);
  // The misspelt required key: suggested, not also reported missing.
  EXPECT_EQ(lines[0], "test.yaml:" + PositionOf(text, "", "dept") +
                          ": mooring.water: unknown key 'dept' (did you mean 'depth'?)");
  EXPECT_EQ(lines[1], "test.yaml:" + PositionOf(text, "- name: chain", "-0.08") +
                          ": mooring.line_types[1].diameter: -0.08 m must be > 0");
  EXPECT_EQ(lines[2], "test.yaml:" + PositionOf(text, "- id: 2", "[wire]") +
                          ": mooring.lines[2].type: [wire] must be a string");
  EXPECT_EQ(lines[3],
            "test.yaml:" + PositionOf(text, "solver:", "2") + ": solver.rtol: 2 must be in (0, 1)");
}

TEST(AllErrors, ChecksBetweenValuesWaitForValuesThatRead) {
  // A line too short (a check between values) is not reported while a value does not read:
  // with a bad value in the file, such checks would run on a stand-in.
  std::string text = Edit(kBase, "- id: 3", "length: 2250", "length: 100");
  EXPECT_EQ(MessageLines(AllErrorsOf(text)).size(), 1u);
  text = Edit(text, "", "depth: 1000}", "depth: deep}");
  EXPECT_EQ(AllErrorsOf(text), "test.yaml:" + PositionOf(text, "", "deep") +
                                   ": mooring.water.depth: deep must be a number");
}

TEST(AllErrors, IndependentChecksBetweenValuesAreAllReported) {
  std::string text = Edit(kBase, "- id: 3", "length: 2250", "length: 100");
  text = Edit(text, "simulation:", "duration: 1000", "duration: 10");
  const std::vector<std::string> lines = MessageLines(AllErrorsOf(text));
  ASSERT_EQ(lines.size(), 3u) << AllErrorsOf(text);
  EXPECT_NE(lines[0].find("mooring.lines[3].length: 100 m is shorter"), std::string::npos);
  EXPECT_NE(lines[1].find("sensors.tension_cells.faults[1].time"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("failure.time"), std::string::npos) << lines[2];
}

TEST(AllErrors, TheSameMistakeTwiceIsTwoLines) {
  std::string text = Edit(kBase, "- name: chain", "drag_normal: 0.3", "drag_normal: -1");
  text = Edit(text, "- name: wire", "drag_normal: 1.2", "drag_normal: -1");
  const std::vector<std::string> lines = MessageLines(AllErrorsOf(text));
  ASSERT_EQ(lines.size(), 2u) << AllErrorsOf(text);
  EXPECT_NE(lines[0].find("line_types[1].drag_normal"), std::string::npos);
  EXPECT_NE(lines[1].find("line_types[2].drag_normal"), std::string::npos);
}

}  // namespace
}  // namespace moorsim::scenarios
