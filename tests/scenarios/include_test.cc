// Scenarios that start from another (`base: other.yaml`): what is merged, what is replaced,
// where errors point, and the bad includes (a cycle, a base that does not exist).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "scenarios/load.h"
#include "scenarios/strict_yaml.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::scenarios {
namespace {

namespace fs = std::filesystem;

const std::string kLibraryDir = MOORSIM_SOURCE_DIR "/scenarios/library/";

void WriteScenario(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

std::string IncludeErrorOf(const fs::path& path) {
  try {
    LoadScenario(path.string());
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(Include, TheThesisVariantsAreTheBaseWithTheirOwnChanges) {
  const Scenario base = LoadScenario(kLibraryDir + "thesis_no_failure.yaml");
  const Scenario line6 = LoadScenario(kLibraryDir + "thesis_line6.yaml");
  const Scenario line7_current = LoadScenario(kLibraryDir + "thesis_line7_current.yaml");
  // Named by their own files, not by the base.
  EXPECT_EQ(base.name, "thesis_no_failure");
  EXPECT_EQ(line6.name, "thesis_line6");
  EXPECT_EQ(line7_current.name, "thesis_line7_current");
  // Their own keys...
  EXPECT_EQ(base.failure.line, 0);
  EXPECT_EQ(line6.failure.line, 6);
  EXPECT_EQ(line6.failure.time, 400.0);
  EXPECT_EQ(line7_current.failure.line, 7);  // from thesis_line7.yaml, its base
  EXPECT_EQ(line7_current.failure.time, 300.0);
  EXPECT_TRUE(base.mooring.current.speed.empty());
  ASSERT_EQ(line7_current.mooring.current.speed.size(), 1u);
  EXPECT_EQ(line7_current.mooring.current.speed[0], 0.1);
  // ...merged into the base's maps: the waves stay beside the added current.
  EXPECT_TRUE(line7_current.environment.waves.enabled);
  EXPECT_EQ(line7_current.environment.waves.significant_height, 2.5);
  EXPECT_EQ(line7_current.mooring.lines.size(), 8u);
  EXPECT_EQ(line7_current.vessel->hydrodynamics, base.vessel->hydrodynamics);
  ASSERT_EQ(line7_current.detectors.size(), base.detectors.size());
  // Where values came from: the failure in thesis_line7.yaml, the rest in the base.
  EXPECT_EQ(line7_current.origins.at("failure"), kLibraryDir + "thesis_line7.yaml");
  EXPECT_EQ(line7_current.origins.at("mooring"), kLibraryDir + "thesis_no_failure.yaml");
  EXPECT_EQ(line7_current.origins.count("environment.current"), 0u);  // its own
}

TEST(Include, ListsAndValuesAreReplacedWholeAndNullRemoves) {
  const fs::path dir = moorsim::testing::FreshDirectory("include_replace");
  WriteScenario(dir / "v.yaml", "base: " + kLibraryDir +
                                    "thesis_line6.yaml\n"
                                    "detectors: [{type: glr}]\n"
                                    "failure: ~\n"
                                    "mooring: {defaults: {segments: 20}}\n"
                                    "simulation: {duration: 50}\n");
  const Scenario s = LoadScenario((dir / "v.yaml").string());
  ASSERT_EQ(s.detectors.size(), 1u);  // the list replaced, not appended to
  EXPECT_EQ(s.detectors[0].type, "glr");
  EXPECT_EQ(s.failure.line, 0);  // removed
  EXPECT_FALSE(s.marks.contains("failure"));
  EXPECT_EQ(s.simulation.duration, 50.0);
  EXPECT_EQ(s.simulation.seed, 1u);  // the rest of the base's simulation block stays
  // The lines say segments: 50 each in the base; defaults apply only where a line is silent.
  EXPECT_EQ(s.mooring.defaults.segments, 20);
  EXPECT_EQ(s.mooring.lines[0].Segments(), 50);
}

TEST(Include, ErrorsPointIntoTheFileWhereTheValueWasWritten) {
  const fs::path dir = moorsim::testing::FreshDirectory("include_errors");
  std::ifstream in(kLibraryDir + "thesis_no_failure.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string base = text.str();
  base.replace(base.find("mass: 1.0041e8"), 14, "mass: -1.0e8");
  base.replace(base.find("../../data/fpso_wamit/fpso"), 26,
               MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso");
  WriteScenario(dir / "bases" / "base.yaml", base);
  WriteScenario(dir / "case.yaml", "base: bases/base.yaml\nsimulation: {duration: -5}\n");
  const std::size_t at = base.find("-1.0e8");
  const auto line = 1 + std::count(base.begin(), base.begin() + static_cast<long>(at), '\n');
  const auto column = at - base.rfind('\n', at);
  // Ordered by file, then position.
  EXPECT_EQ(IncludeErrorOf(dir / "case.yaml"),
            (dir / "bases" / "base.yaml").string() + ":" + std::to_string(line) + ":" +
                std::to_string(column) + ": vessel.mass: -1e+08 kg must be > 0\n" +
                (dir / "case.yaml").string() + ":2:24: simulation.duration: -5 s must be > 0");
}

TEST(Include, RelativePathsInABaseElsewhereStayRelativeToTheBase) {
  const fs::path dir = moorsim::testing::FreshDirectory("include_paths");
  // The library's base names its WAMIT data relative to scenarios/library/.
  WriteScenario(dir / "deep" / "er" / "case.yaml",
                "base: " + kLibraryDir + "thesis_no_failure.yaml\n");
  const Scenario s = LoadScenario((dir / "deep" / "er" / "case.yaml").string());
  EXPECT_EQ(fs::weakly_canonical(s.vessel->hydrodynamics + ".1"),
            fs::weakly_canonical(MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso.1"));
}

TEST(Include, TheResolvedTextIsTheWholeScenarioAndLoadsAlone) {
  const Scenario s = LoadScenario(kLibraryDir + "thesis_line8_current.yaml");
  EXPECT_EQ(s.text.find("base:"), std::string::npos) << s.text;
  EXPECT_NE(s.text.find("line_types:"), std::string::npos);
  // Read back under the same name (outputs record the text; `detect` re-reads it).
  const Scenario again = ParseScenario(s.text, s.source_path);
  EXPECT_EQ(again.name, s.name);
  EXPECT_EQ(again.failure.line, 8);
  EXPECT_EQ(again.mooring.current.speed, s.mooring.current.speed);
  EXPECT_EQ(again.vessel->hydrodynamics, s.vessel->hydrodynamics);
  EXPECT_EQ(again.detectors.size(), s.detectors.size());
  EXPECT_EQ(again.mooring.lines[5].anchor, s.mooring.lines[5].anchor);
  EXPECT_EQ(again.text, s.text);  // no base left to merge: the text as given
}

TEST(Include, BadIncludesAreOneLocatedLine) {
  const fs::path dir = moorsim::testing::FreshDirectory("include_bad");
  WriteScenario(dir / "a.yaml", "# first\nbase: b.yaml\n");
  WriteScenario(dir / "b.yaml", "base: c.yaml\n");
  WriteScenario(dir / "c.yaml", "name: c\nbase: a.yaml\n");
  EXPECT_EQ(IncludeErrorOf(dir / "a.yaml"), (dir / "c.yaml").string() +
                                                ":2:7: base: 'a.yaml' includes itself: a.yaml -> "
                                                "b.yaml -> c.yaml -> a.yaml");
  WriteScenario(dir / "self.yaml", "base: self.yaml\n");
  EXPECT_EQ(IncludeErrorOf(dir / "self.yaml"), (dir / "self.yaml").string() +
                                                   ":1:7: base: 'self.yaml' includes itself: "
                                                   "self.yaml -> self.yaml");
  WriteScenario(dir / "missing.yaml", "base: nothere.yaml\n");
  EXPECT_EQ(IncludeErrorOf(dir / "missing.yaml"), (dir / "missing.yaml").string() +
                                                      ":1:7: base: 'nothere.yaml': no such file (" +
                                                      (dir / "nothere.yaml").string() + ")");
  WriteScenario(dir / "list.yaml", "base: [a.yaml]\n");
  EXPECT_EQ(IncludeErrorOf(dir / "list.yaml"),
            (dir / "list.yaml").string() + ":1:7: base: [a.yaml] must be a file name (a scenario)");
  // A second base (yaml-cpp keeps both; one was silently ignored), also in a base.
  WriteScenario(dir / "two.yaml", "base: " + kLibraryDir + "thesis_line6.yaml\nbase: b.yaml\n");
  EXPECT_EQ(IncludeErrorOf(dir / "two.yaml"),
            (dir / "two.yaml").string() + ":2:1: duplicate key 'base'");
  WriteScenario(dir / "dup_base.yaml", "base: " + kLibraryDir +
                                           "thesis_line6.yaml\nsimulation: {duration: 5, "
                                           "duration: 6}\n");
  WriteScenario(dir / "on_dup.yaml", "base: dup_base.yaml\n");
  EXPECT_EQ(IncludeErrorOf(dir / "on_dup.yaml"),
            (dir / "dup_base.yaml").string() + ":2:27: simulation: duplicate key 'duration'");
  WriteScenario(dir / "broken.yaml", "mooring: [\n");
  WriteScenario(dir / "on_broken.yaml", "base: broken.yaml\n");
  const std::string error = IncludeErrorOf(dir / "on_broken.yaml");
  EXPECT_EQ(error.rfind((dir / "broken.yaml").string() + ":", 0), 0u) << error;
  EXPECT_NE(error.find("YAML syntax error"), std::string::npos) << error;
}

// Every file of a chain of bases is held while the chain is read: each must cost what it
// holds, not the 4 MiB limit a file may reach.
TEST(Include, AFileReadHoldsItsTextNotTheSizeLimit) {
  const fs::path dir = moorsim::testing::FreshDirectory("include_memory");
  WriteScenario(dir / "small.yaml", "name: small\n");
  const std::string text =
      strict_yaml::ReadInputFile((dir / "small.yaml").string(), 4 << 20, "scenario");
  EXPECT_EQ(text, "name: small\n");
  // 64 KiB: the chunk the file is read in; the limit itself would be 4 MiB.
  EXPECT_LE(text.capacity(), std::size_t{1} << 17);
}

TEST(Include, AChainOfBasesLongerThan32FilesIsOneLocatedLine) {
  const fs::path dir = moorsim::testing::FreshDirectory("include_deep");
  // Appended, not `"s" + std::to_string(i)`: GCC 12 at -O3 warns falsely about the latter.
  const auto name = [](int i) { return std::string("s").append(std::to_string(i)) + ".yaml"; };
  for (int i = 0; i < 40; ++i) WriteScenario(dir / name(i), "base: " + name(i + 1) + "\n");
  const std::string error = IncludeErrorOf(dir / "s0.yaml");
  const std::string at = (dir / "s31.yaml").string() + ":1:7: ";
  EXPECT_EQ(error.substr(0, at.size()), at) << error;
  EXPECT_EQ(error.substr(std::min(at.size(), error.size())),
            "base: 's32.yaml': more than 32 files in the chain of bases (s0.yaml -> ... -> "
            "s31.yaml)");
}

}  // namespace
}  // namespace moorsim::scenarios
