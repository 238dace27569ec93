// Campaign files: the expansion into runs (order, grid and zip, ranges, seeds, draws) and
// one test per input rule, each asserting the whole message with its position.
#include "scenarios/campaign.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <string>
#include <utility>

#include "core/error.h"

namespace moorsim::scenarios {
namespace {

// Campaign texts are named as if they sat in scenarios/campaigns/, so the scenario path
// resolves to the library.
const std::string kSource = std::string(MOORSIM_SOURCE_DIR) + "/scenarios/campaigns/test.yaml";
const std::string kScenario =
    std::string(MOORSIM_SOURCE_DIR) + "/scenarios/library/thesis_no_failure.yaml";

const std::string kCampaign = R"(name: test
scenario: ../library/thesis_no_failure.yaml
seed: 11
set:
  simulation.duration: 300
blocks:
  - name: failures
    set: {failure.mode: fairlead}
    factors:
      - {key: failure.line, values: [1, 2, 3]}
      - {key: "environment.current.profile[1].speed", range: {from: 0, to: 0.2, step: 0.1}}
      - {key: failure.time, uniform: [100, 200]}
    seeds: 2
  - name: intact
    factors:
      - {key: controller.type, choice: [pi, observer_pid]}
      - {key: environment.waves.hs, normal: {mean: 2.5, std_dev: 0.5, min: 2, max: 3}}
    seeds: {from: 5, to: 7}
)";

std::string CampaignErrorOf(const std::string& text) {
  try {
    ParseCampaign(text, kSource);
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return std::string("not an InputError: ") + error.what();
  }
  return "(no error)";
}

// "file:line:col: " of the first occurrence of `needle` in `text` (1-based).
std::string At(const std::string& text, const std::string& needle) {
  const std::size_t offset = text.find(needle);
  EXPECT_NE(offset, std::string::npos) << needle;
  const std::size_t line_start = text.rfind('\n', offset);
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(offset), '\n');
  const std::size_t column = line_start == std::string::npos ? offset + 1 : offset - line_start;
  return kSource + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(Campaign, ExpandsBlocksInOrderGridLastFactorFastestSeedsInnermost) {
  const Campaign c = ParseCampaign(kCampaign, kSource);
  EXPECT_EQ(c.name, "test");
  EXPECT_EQ(c.scenario_path, kScenario);
  EXPECT_EQ(c.seed, 11u);
  ASSERT_EQ(c.blocks.size(), 2u);
  EXPECT_EQ(c.blocks[0].Points(), 9);  // 3 lines x 3 speeds
  EXPECT_EQ(c.blocks[0].SeedsPerPoint(), 2);
  EXPECT_EQ(c.blocks[1].Points(), 1);
  EXPECT_EQ(c.blocks[1].SeedsPerPoint(), 3);
  EXPECT_EQ(c.NumRuns(), 9 * 2 + 3);
  EXPECT_EQ(c.FactorKeys(),
            (std::vector<std::string>{"failure.line", "environment.current.profile[1].speed",
                                      "failure.time", "controller.type", "environment.waves.hs"}));

  // Run 0: line 1, speed 0, first seed; run 1: its second seed; run 2: speed 0.1.
  const CampaignRun r0 = MakeCampaignRun(c, 0);
  const CampaignRun r1 = MakeCampaignRun(c, 1);
  const CampaignRun r2 = MakeCampaignRun(c, 2);
  const CampaignRun r7 = MakeCampaignRun(c, 7);
  EXPECT_EQ(r0.factors[0].second, "1");
  EXPECT_EQ(r0.factors[1].second, "0");
  EXPECT_EQ(r1.factors[1].second, "0");
  EXPECT_EQ(r2.factors[1].second, "0.1");
  EXPECT_EQ(r7.factors[0].second, "2");  // point 3: line 2, speed 0
  EXPECT_EQ(r7.factors[1].second, "0");
  EXPECT_EQ(MakeCampaignRun(c, 17).factors[1].second, "0.2");
  EXPECT_EQ(r0.seed, DerivedRunSeed(11, 0));
  EXPECT_NE(r0.seed, r1.seed);
  // The overrides: campaign set, block set, factors, seed last.
  EXPECT_EQ(r0.overrides.front(), "simulation.duration=300");
  EXPECT_EQ(r0.overrides[1], "failure.mode=fairlead");
  EXPECT_EQ(r0.overrides[2], "failure.line=1");
  EXPECT_EQ(r0.overrides.back(), "simulation.seed=" + std::to_string(r0.seed));
  EXPECT_EQ(r0.block, 0);

  // The intact block: explicit seeds 5, 6, 7; draws within their bounds.
  for (int k = 0; k < 3; ++k) {
    const CampaignRun r = MakeCampaignRun(c, 18 + k);
    EXPECT_EQ(r.block, 1);
    EXPECT_EQ(r.seed, 5u + static_cast<unsigned>(k));
    EXPECT_TRUE(r.factors[0].second == "pi" || r.factors[0].second == "observer_pid");
    const double hs = std::stod(r.factors[1].second);
    EXPECT_GE(hs, 2.0);
    EXPECT_LE(hs, 3.0);
  }
  EXPECT_THROW(MakeCampaignRun(c, 21), InputError);
  EXPECT_THROW(MakeCampaignRun(c, -1), InputError);
}

TEST(Campaign, DrawsDependOnlyOnTheCampaignSeedTheRunAndTheKey) {
  const Campaign c = ParseCampaign(kCampaign, kSource);
  std::set<std::string> times;
  for (int i = 0; i < 18; ++i) {
    const CampaignRun a = MakeCampaignRun(c, i);
    const CampaignRun b = MakeCampaignRun(c, i);  // again: the same values
    EXPECT_EQ(a.overrides, b.overrides);
    const double t = std::stod(a.factors[2].second);
    EXPECT_GE(t, 100.0);
    EXPECT_LT(t, 200.0);
    // The text reads back as the same double, so the command repeats the run exactly.
    EXPECT_EQ(std::stod(a.factors[2].second), t);
    times.insert(a.factors[2].second);
  }
  EXPECT_EQ(times.size(), 18u);  // one draw per run
  const Campaign other = ParseCampaign(Replace(kCampaign, "seed: 11", "seed: 12"), kSource);
  EXPECT_NE(MakeCampaignRun(other, 0).factors[2].second, MakeCampaignRun(c, 0).factors[2].second);
  EXPECT_NE(MakeCampaignRun(other, 0).seed, MakeCampaignRun(c, 0).seed);
}

TEST(Campaign, ZipTakesTheIthValueOfEveryList) {
  const std::string text = R"(scenario: ../library/thesis_no_failure.yaml
seed: 1
blocks:
  - name: pairs
    combine: zip
    factors:
      - {key: failure.line, values: [1, 2, 3]}
      - {key: failure.time, values: [100, 200, 300]}
    seeds: 1
)";
  const Campaign c = ParseCampaign(text, kSource);
  EXPECT_EQ(c.name, "test");  // the file's stem
  ASSERT_EQ(c.NumRuns(), 3);
  for (int i = 0; i < 3; ++i) {
    const CampaignRun r = MakeCampaignRun(c, i);
    EXPECT_EQ(r.factors[0].second, std::to_string(i + 1));
    EXPECT_EQ(r.factors[1].second, std::to_string(100 * (i + 1)));
  }
}

TEST(Campaign, FollowsAddsToAnEarlierFactorsValue) {
  // The vessel's heading into the waves: the wave direction drawn or listed, the heading
  // 180 deg from it (plus a uniform offset), reduced to [-180, 180); the initial heading
  // equal to the setpoint.
  const std::string text = R"(scenario: ../library/thesis_no_failure.yaml
seed: 3
blocks:
  - name: drawn
    factors:
      - {key: environment.waves.direction_toward_deg, uniform: [0, 360]}
      - {key: controller.setpoint.heading_deg, follows: environment.waves.direction_toward_deg,
         add: [160, 200], modulo: 360}
      - {key: vessel.initial_pose.heading_deg, follows: controller.setpoint.heading_deg}
    seeds: 200
  - name: listed
    factors:
      - {key: environment.waves.direction_toward_deg, values: [10, 350]}
      - {key: controller.setpoint.heading_deg, follows: environment.waves.direction_toward_deg,
         add: 180, modulo: 360}
    seeds: 1
)";
  const Campaign c = ParseCampaign(text, kSource);
  ASSERT_EQ(c.NumRuns(), 202);
  double least = 180.0, most = -180.0;
  for (int i = 0; i < 200; ++i) {
    const CampaignRun r = MakeCampaignRun(c, i);
    ASSERT_EQ(r.factors.size(), 3u);
    const double toward = std::stod(r.factors[0].second);
    const double heading = std::stod(r.factors[1].second);
    EXPECT_GE(heading, -180.0);
    EXPECT_LT(heading, 180.0);
    // The offset from "into the waves" (toward + 180) wrapped to [-180, 180).
    const double offset = std::remainder(heading - toward - 180.0, 360.0);
    EXPECT_GE(offset, -20.0 - 1e-9);
    EXPECT_LT(offset, 20.0 + 1e-9);
    least = std::min(least, offset);
    most = std::max(most, offset);
    EXPECT_EQ(r.factors[2].second, r.factors[1].second);
    EXPECT_EQ(r.overrides[2], "vessel.initial_pose.heading_deg=" + r.factors[1].second);
  }
  EXPECT_LT(least, -15.0);  // a draw per run over the whole interval
  EXPECT_GT(most, 15.0);
  EXPECT_EQ(MakeCampaignRun(c, 200).factors[1].second, "-170");
  EXPECT_EQ(MakeCampaignRun(c, 201).factors[1].second, "170");
}

TEST(Campaign, FollowsTurnsAPointWithTheHeading) {
  // A turret 60 m ahead of the reference point kept over the field origin: the reference
  // point at -60 (cos psi, sin psi), psi the drawn heading; the sum of the two squares is
  // 60^2 whatever the draw.
  const std::string text = R"(scenario: ../library/thesis_no_failure.yaml
seed: 5
blocks:
  - name: turned
    factors:
      - {key: controller.setpoint.heading_deg, uniform: [-180, 180]}
      - {key: controller.setpoint.x, follows: controller.setpoint.heading_deg, function: cos,
         scale: -60}
      - {key: controller.setpoint.y, follows: controller.setpoint.heading_deg, function: sin,
         scale: -60, add: [0, 1]}
    seeds: 50
)";
  const Campaign c = ParseCampaign(text, kSource);
  for (int i = 0; i < 50; ++i) {
    const CampaignRun r = MakeCampaignRun(c, i);
    const double psi = std::stod(r.factors[0].second) * std::numbers::pi / 180.0;
    const double x = std::stod(r.factors[1].second);
    const double y = std::stod(r.factors[2].second);
    EXPECT_NEAR(x, -60.0 * std::cos(psi), 1e-12);
    const double drawn = y + 60.0 * std::sin(psi);  // the uniform add
    EXPECT_GE(drawn, -1e-12);
    EXPECT_LT(drawn, 1.0 + 1e-12);
  }
}

TEST(Campaign, CommandRepeatsTheRunWithQuotedValues) {
  const std::string text = R"(scenario: ../library/thesis_no_failure.yaml
seed: 3
set: {environment.wind: {speed: 15, direction_from_deg: 90}}
blocks:
  - {name: one, seeds: 1}
)";
  const Campaign c = ParseCampaign(text, kSource);
  const CampaignRun r = MakeCampaignRun(c, 0);
  EXPECT_EQ(r.overrides[0], "environment.wind={speed: 15, direction_from_deg: 90}");
  EXPECT_EQ(r.Command(c, ""), "moorsim run " + kScenario +
                                  " --set 'environment.wind={speed: 15, direction_from_deg: 90}'"
                                  " --seed " +
                                  std::to_string(r.seed));
  // A list written in block style (a campaign's `detectors:`) still goes on one line.
  const std::string block_list = R"(scenario: ../library/thesis_no_failure.yaml
seed: 3
set:
  detectors:
    - {type: glr}
    - type: deficit
      label: fast
      thresholds:
        - 1
        - 2
blocks:
  - {name: one, seeds: 1}
)";
  const Campaign listed = ParseCampaign(block_list, kSource);
  EXPECT_EQ(MakeCampaignRun(listed, 0).overrides[0],
            "detectors=[{type: glr}, {type: deficit, label: fast, thresholds: [1, 2]}]");
  EXPECT_EQ(ShellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(ShellQuote(""), "''");
  EXPECT_EQ(ShellQuote("a/b.yaml"), "a/b.yaml");
}

// A transient block naming its intact block: each run is matched to the intact run of its
// seed and the intact block's factor values, and parts its own failure.line.
const std::string kTransient = R"(scenario: ../library/thesis_no_failure.yaml
seed: 4
blocks:
  - name: storm
    design: {condition: intact}
    factors: [{key: environment.waves.hs, values: [3, 5]}]
    seeds: {from: 10, to: 12}
  - name: parted
    design: {condition: transient, intact: storm}
    set: {failure.mode: fairlead}
    factors:
      - {key: failure.line, values: [4, 7]}
      - {key: environment.waves.hs, values: [5]}
    seeds: {from: 11, to: 12}
)";

TEST(Campaign, ATransientRunTakesItsInstantFromTheIntactRunOfItsSeedAndValues) {
  const Campaign c = ParseCampaign(kTransient, kSource);
  ASSERT_EQ(c.NumRuns(), 10);
  EXPECT_FALSE(TransientSourceOf(c, MakeCampaignRun(c, 4)));  // an intact run
  // Runs 6..9: line 4 at seeds 11, 12; line 7 at seeds 11, 12; all at hs 5, the intact
  // block's second point (runs 3..5, seeds 10..12).
  const std::int64_t expected_intact[] = {4, 5, 4, 5};
  const int expected_line[] = {4, 4, 7, 7};
  for (int k = 0; k < 4; ++k) {
    CampaignRun run = MakeCampaignRun(c, 6 + k);
    const std::optional<TransientSource> source = TransientSourceOf(c, run);
    ASSERT_TRUE(source);
    EXPECT_EQ(source->intact_run, expected_intact[k]);
    EXPECT_EQ(source->line, expected_line[k]);
    const CampaignRun intact = MakeCampaignRun(c, source->intact_run);
    EXPECT_EQ(intact.seed, run.seed);
    EXPECT_EQ(intact.factors.at(0).second, "5");
    // The instant goes just before the seed, so the run's command repeats it.
    SetFailureTime(run, 1234.6);
    EXPECT_EQ(run.overrides.at(run.overrides.size() - 2), "failure.time=1234.6");
    EXPECT_NE(
        run.Command(c, "").find("--set failure.time=1234.6 --seed " + std::to_string(run.seed)),
        std::string::npos);
  }
}

struct CampaignError {
  const char* name;
  std::string text;
  std::string at;  // where the message points (searched in text); empty = no position
  std::string message;
};

std::vector<CampaignError> Errors() {
  const std::string& b = kCampaign;
  const std::string kSeedRule =
      "every run's simulation.seed is its own seed, which would replace this value; vary seeds "
      "with the block's `seeds` (a count or {from: A, to: B})";
  const std::string kBaseRule =
      "a campaign cannot set the scenario's base (it is read before any override); name "
      "another scenario in `scenario:`";
  return {
      {"UnknownTopKey", Replace(b, "seed: 11", "seed: 11\nseeds: 3"), "seeds: 3",
       "unknown key 'seeds' (did you mean 'seed'?)"},
      {"MissingSeed", Replace(b, "seed: 11\n", ""), "name: test", "required key 'seed' is missing"},
      {"NegativeSeed", Replace(b, "seed: 11", "seed: -1"), "-1",
       "seed: -1 must be a non-negative integer"},
      {"NoScenarioFile", Replace(b, "thesis_no_failure.yaml", "nothing.yaml"),
       "../library/nothing.yaml",
       "scenario: '../library/nothing.yaml': no scenario file at " +
           std::string(MOORSIM_SOURCE_DIR) + "/scenarios/library/nothing.yaml"},
      {"NoBlocks", Replace(b, b.substr(b.find("blocks:")), "blocks: []\n"), "[]",
       "blocks: an empty list (a campaign has at least one block)"},
      {"DuplicateBlock", Replace(b, "name: intact", "name: failures"),
       "failures\n    factors:\n      - {key: controller",
       "blocks[2].name: duplicate block name 'failures'"},
      {"BadBlockName", Replace(b, "name: intact", "name: no good"), "no good",
       "blocks[2].name: 'no good' must be letters, digits, '_' or '-'"},
      {"TwoKinds", Replace(b, "values: [1, 2, 3]}", "values: [1, 2, 3], uniform: [1, 2]}"),
       "{key: failure.line",
       "blocks[1].factors[1]: give exactly one of values, range, uniform, normal, choice, "
       "follows"},
      {"NoKind", Replace(b, "{key: failure.line, values: [1, 2, 3]}", "{key: failure.line}"),
       "{key: failure.line}",
       "blocks[1].factors[1]: give exactly one of values, range, uniform, normal, choice, "
       "follows"},
      {"FollowsNothing",
       Replace(b, "{key: failure.time, uniform: [100, 200]}",
               "{key: failure.time, follows: failure.nothing}"),
       "failure.nothing",
       "blocks[1].factors[3].follows: 'failure.nothing' is not a factor listed "
       "above it in this block"},
      {"FollowsLater",
       Replace(b, "{key: failure.line, values: [1, 2, 3]}",
               "{key: failure.line, follows: failure.time}"),
       "failure.time}",
       "blocks[1].factors[1].follows: 'failure.time' is not a factor listed "
       "above it in this block"},
      {"FollowsText",
       Replace(b, "{key: environment.waves.hs, normal",
               "{key: failure.line, follows: controller.type}\n      - {key: environment.waves.hs, "
               "normal"),
       "controller.type}",
       "blocks[2].factors[2].follows: 'controller.type' has the value 'pi', "
       "not a number to add to"},
      {"AddAlone", Replace(b, "uniform: [100, 200]}", "uniform: [100, 200], add: 5}"), "5}",
       "blocks[1].factors[3].add: add goes with follows"},
      {"AddTriple",
       Replace(b, "{key: failure.time, uniform: [100, 200]}",
               "{key: failure.time, follows: failure.line, add: [1, 2, 3]}"),
       "[1, 2, 3]}\n    seeds",
       "blocks[1].factors[3].add: [1, 2, 3] must be a number or [low, high]"},
      {"ModuloZero",
       Replace(b, "{key: failure.time, uniform: [100, 200]}",
               "{key: failure.time, follows: failure.line, modulo: 0}"),
       "0}", "blocks[1].factors[3].modulo: 0 must be > 0"},
      {"FunctionUnknown",
       Replace(b, "{key: failure.time, uniform: [100, 200]}",
               "{key: failure.time, follows: failure.line, function: tan}"),
       "tan}", "blocks[1].factors[3].function: unknown function 'tan' (known: cos, sin)"},
      {"ScaleAlone", Replace(b, "uniform: [100, 200]}", "uniform: [100, 200], scale: 2}"), "2}",
       "blocks[1].factors[3].scale: scale goes with follows"},
      {"ScaleNotFinite",
       Replace(b, "{key: failure.time, uniform: [100, 200]}",
               "{key: failure.time, follows: failure.line, scale: .inf}"),
       ".inf}", "blocks[1].factors[3].scale: .inf must be a finite number"},
      {"EmptyValues", Replace(b, "values: [1, 2, 3]", "values: []"), "[]",
       "blocks[1].factors[1].values: an empty list"},
      {"TwiceVaried", Replace(b, "failure.time, uniform", "failure.line, uniform"),
       "failure.line, uniform",
       "blocks[1].factors[3].key: 'failure.line' is varied twice in this block"},
      {"BadKey", Replace(b, "key: failure.line", "key: 'failure line'"), "'failure line'",
       "blocks[1].factors[1].key: 'failure line' is not a key path (e.g. failure.line)"},
      {"RangeStep", Replace(b, "step: 0.1", "step: 0"), "0}",
       "blocks[1].factors[2].range.step: 0 must be > 0"},
      {"RangeBackwards", Replace(b, "to: 0.2", "to: -1"), "-1",
       "blocks[1].factors[2].range.to: -1 must be >= from (0)"},
      {"RangeHuge", Replace(b, "step: 0.1", "step: 1e-9"), "{from: 0",
       "blocks[1].factors[2].range: gives 200000001 values, more than 100000"},
      {"UniformBounds", Replace(b, "uniform: [100, 200]", "uniform: [200, 100]"), "100]",
       "blocks[1].factors[3].uniform[2]: 100 must be > low (200)"},
      {"UniformNotPair", Replace(b, "uniform: [100, 200]", "uniform: [100]"), "[100]",
       "blocks[1].factors[3].uniform: [100] must be [low, high]"},
      {"NormalStd", Replace(b, "std_dev: 0.5", "std_dev: 0"), "0, min",
       "blocks[2].factors[2].normal.std_dev: 0 must be > 0"},
      {"NormalWindowFar", Replace(b, "min: 2, max: 3", "min: 5, max: 6"), "{mean: 2.5",
       "blocks[2].factors[2].normal: [min, max] lies more than 3 standard deviations from the "
       "mean"},
      {"ZipLengths",
       Replace(Replace(b, "seeds: 2\n", "combine: zip\n    seeds: 2\n"), "to: 0.2", "to: 0.1"),
       "{key: \"environment",
       "blocks[1].factors: combine: zip needs lists of one length: "
       "'environment.current.profile[1].speed' has 2 values, 'failure.line' 3"},
      {"Combine", Replace(b, "seeds: 2\n", "combine: cross\n    seeds: 2\n"), "cross",
       "blocks[1].combine: unknown combination 'cross' (known: grid, zip)"},
      {"SeedsZero", Replace(b, "seeds: 2", "seeds: 0"), "0\n  - name: intact",
       "blocks[1].seeds: 0 must be in [1, 10000000] (or {from: A, to: B})"},
      {"SeedsBackwards", Replace(b, "{from: 5, to: 7}", "{from: 7, to: 5}"), "5}",
       "blocks[2].seeds.to: 5 must be >= from (7)"},
      {"SeedsMissing", Replace(b, "    seeds: 2\n", ""), "name: failures",
       "blocks[1]: required key 'seeds' is missing"},
      {"SetNotMap", Replace(b, "simulation.duration: 300", "- 300"), "- 300",
       "set: [300] must be a map of key paths to values"},
      {"Tagged", Replace(b, "seed: 11", "seed: !!str 11"), "!!str",
       "seed: tagged value '!!str' (tags are not accepted; write the plain integer)"},
      {"Syntax", Replace(b, "seeds: 2", "seeds: [2"), "", ""},
      // The run's seed replaces simulation.seed: a factor or set on it would change nothing
      // while runs.csv showed its values.
      {"SeedFactor", Replace(b, "key: failure.time", "key: simulation.seed"),
       "simulation.seed, uniform", "blocks[1].factors[3].key: 'simulation.seed': " + kSeedRule},
      {"SeedSet", Replace(b, "simulation.duration: 300", "simulation.seed: 4"), "simulation.seed",
       "set: 'simulation.seed': " + kSeedRule},
      {"SeedInSimulationMap",
       Replace(b, "set: {failure.mode: fairlead}", "set: {simulation: {duration: 9, seed: 4}}"),
       "simulation: {", "blocks[1].set: 'simulation': " + kSeedRule},
      // One key, one spelling: a second spelling would pass the twice-varied check.
      {"EmptyKeyInPath", Replace(b, "key: failure.time", "key: failure..time"), "failure..time",
       "blocks[1].factors[3].key: empty key in 'failure..time' (one '.' between keys, none "
       "before '[')"},
      {"ZeroPaddedIndex", Replace(b, "profile[1].speed", "profile[01].speed"), "\"environment",
       "blocks[1].factors[2].key: bad list index in 'environment.current.profile[01].speed' "
       "(write [1])"},
      {"DotBeforeIndex", Replace(b, "profile[1].speed", "profile.[1].speed"), "\"environment",
       "blocks[1].factors[2].key: empty key in 'environment.current.profile.[1].speed' (one '.' "
       "between keys, none before '[')"},
      {"SetKeyEmptyPart", Replace(b, "simulation.duration: 300", "simulation..duration: 300"),
       "simulation..duration",
       "set: empty key in 'simulation..duration' (one '.' between keys, none before '[')"},
      {"OverlappingFactors", Replace(b, "key: failure.time", "key: failure"), "failure, uniform",
       "blocks[1].factors[3].key: 'failure' overlaps 'failure.line', varied above in this block "
       "(each value is varied once)"},
      // The base is read before any override applies.
      {"BaseSet", Replace(b, "simulation.duration: 300", "base: other.yaml"), "base: other",
       "set: 'base': " + kBaseRule},
      {"BaseFactor", Replace(b, "key: failure.time", "key: base"), "base, uniform",
       "blocks[1].factors[3].key: 'base': " + kBaseRule},
      {"DuplicateKey", Replace(b, "seed: 11", "seed: 11\nseed: 12"), "seed: 12",
       "duplicate key 'seed'"},
      {"DuplicateKeyInValue",
       Replace(b, "simulation.duration: 300", "environment.wind: {speed: 1, speed: 2}"), "speed: 2",
       "set.environment.wind: duplicate key 'speed'"},
      {"TextAfterDocumentEnd", b + "...\n%YAML 1.2\n", "%YAML",
       "text after the document-end marker '...' (a campaign file holds one YAML document)"},
      {"SecondDocument", b + "---\nseed: 3\n", "seed: 3\n",
       "a campaign file holds one YAML document; this is a second one"},
      {"WeibullOverSeeds",
       Replace(b, "seeds: {from: 5, to: 7}",
               "design: {method: weibull}\n    seeds: {from: 5, to: 7}"),
       "weibull}",
       "blocks[2].design.method: weibull fits one long run per point: give the block one seed "
       "(and its runs the length the fit needs)"},
      {"WeibullTransient",
       Replace(kTransient, "condition: transient,", "condition: transient, method: weibull,"),
       "weibull,",
       "blocks[2].design.method: a transient's maxima come after its failure: fit them over "
       "seeds (gumbel)"},
      // A transient block that takes its instants from an intact block.
      {"IntactOnAnIntactBlock", Replace(kTransient, "condition: transient", "condition: damaged"),
       "storm}\n    set",
       "blocks[2].design.intact: only a transient block takes its instants from an intact block"},
      {"IntactNotABlock", Replace(kTransient, "intact: storm", "intact: storms"), "storms}",
       "blocks[2].design.intact: 'storms' is not a block of this campaign"},
      {"IntactNotIntact", Replace(kTransient, "condition: intact", "condition: damaged"),
       "storm}\n    set",
       "blocks[2].design.intact: block 'storm' is not an intact one (design: {condition: "
       "intact})"},
      {"IntactDerivedSeeds", Replace(kTransient, "seeds: {from: 10, to: 12}", "seeds: 3"),
       "storm}\n    set",
       "blocks[2].design.intact: runs are matched by seed: give this block and 'storm' explicit "
       "seeds (seeds: {from: A, to: B})"},
      {"IntactSeedsOutside", Replace(kTransient, "from: 11, to: 12", "from: 11, to: 13"),
       "storm}\n    set",
       "blocks[2].design.intact: seeds 11..13: block 'storm' has seeds 10..12 only"},
      {"IntactDrawnFactor", Replace(kTransient, "values: [3, 5]", "uniform: [3, 5]"),
       "storm}\n    set",
       "blocks[2].design.intact: 'storm' draws 'environment.waves.hs': runs are matched by "
       "listed values (values or range)"},
      {"IntactFactorNotListed",
       Replace(kTransient, "      - {key: environment.waves.hs, values: [5]}\n", ""),
       "storm}\n    set",
       "blocks[2].design.intact: 'storm' varies 'environment.waves.hs': list its values in this "
       "block too"},
      {"IntactValueNotThere", Replace(kTransient, "values: [5]", "values: [5, 6]"),
       "storm}\n    set",
       "blocks[2].design.intact: 'environment.waves.hs' = 6: block 'storm' does not list it"},
      {"TransientWithoutLine",
       Replace(kTransient, "      - {key: failure.line, values: [4, 7]}\n", ""), "storm}\n    set",
       "blocks[2].design.intact: the line each run parts: give failure.line (set or listed "
       "values)"},
      {"TransientWithTime", Replace(kTransient, "failure.mode: fairlead", "failure.time: 9"),
       "storm}\n    set",
       "blocks[2].design.intact: failure.time is set: the runs take it from block 'storm'"},
  };
}

TEST(Campaign, EveryErrorAtOnceOnePerBlock) {
  // A misspelt top-level key, a bad seed and a problem in each block: four lines in file
  // order. A block stops at its first problem (its factors build on each other).
  std::string text = Replace(kCampaign, "seed: 11", "seed: -11\nseeds: 3");
  text = Replace(text, "uniform: [100, 200]", "uniform: [200, 100]");
  text = Replace(text, "std_dev: 0.5, min", "std_dev: 0, min");
  text = Replace(text, "seeds: {from: 5, to: 7}", "seeds: {from: 5, to: 7, by: 1}");
  const std::string error = CampaignErrorOf(text);
  EXPECT_EQ(error, At(text, "-11") + "seed: -11 must be a non-negative integer\n" +
                       At(text, "seeds: 3") + "unknown key 'seeds' (did you mean 'seed'?)\n" +
                       At(text, "100]") +
                       "blocks[1].factors[3].uniform[2]: 100 must be > low (200)\n" +
                       At(text, "0, min") + "blocks[2].factors[2].normal.std_dev: 0 must be > 0");
}

TEST(Campaign, EveryRuleIsOneLocatedLine) {
  for (const CampaignError& e : Errors()) {
    SCOPED_TRACE(e.name);
    const std::string error = CampaignErrorOf(e.text);
    if (e.message.empty()) {  // only that it is located in the file
      EXPECT_EQ(error.rfind(kSource + ":", 0), 0u) << error;
      continue;
    }
    std::string expected = e.message;
    if (!e.at.empty()) expected = At(e.text, e.at) + e.message;
    EXPECT_EQ(error, expected);
    EXPECT_EQ(error.find('\n'), std::string::npos);
  }
}

TEST(Campaign, MissingFileAndNotUtf8) {
  try {
    LoadCampaign("/nonexistent/campaign.yaml");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "/nonexistent/campaign.yaml: cannot open the campaign file: No such file or directory");
  }
  const std::string bad = Replace(kCampaign, "name: test", "name: t\xE9st");
  EXPECT_EQ(CampaignErrorOf(bad),
            kSource + ":1:8: not valid UTF-8 (byte 0xE9); save the file as UTF-8");
}

// Aliases that multiply (each level ten of the one below: 10^9 values) are refused while
// the file is read, not expanded into every run's overrides.
TEST(Campaign, NestedAliasesAreOneLocatedLine) {
  std::string text = "scenario: ../library/thesis_no_failure.yaml\nseed: 3\nlol:\n";
  text += "  - &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level < 9; ++level) {
    const std::string below = "*a" + std::to_string(level - 1);
    text += "  - &a" + std::to_string(level) + " [";
    for (int k = 0; k < 10; ++k) text += (k ? ", " : "") + below;
    text += "]\n";
  }
  text += "blocks:\n  - {name: one, factors: [{key: failure.time, values: [*a8]}], seeds: 1}\n";
  const std::string error = CampaignErrorOf(text);
  EXPECT_EQ(error.rfind(kSource + ":", 0), 0u) << error;
  EXPECT_NE(error.find("aliases expand the document to more than 1048576 values"),
            std::string::npos)
      << error;
  EXPECT_EQ(error.find('\n'), std::string::npos) << error;
}

// An alias used as the library's campaigns use it (one factor list for several blocks).
TEST(Campaign, AFlatAliasStillReads) {
  const std::string text = R"(scenario: ../library/thesis_no_failure.yaml
seed: 3
blocks:
  - {name: one, factors: &f [{key: failure.line, values: [1, 2]}], seeds: 1}
  - {name: two, factors: *f, seeds: 1}
)";
  const Campaign c = ParseCampaign(text, kSource);
  EXPECT_EQ(c.NumRuns(), 4);
  EXPECT_EQ(MakeCampaignRun(c, 3).factors[0].second, "2");
}

// The normal draws of a window that holds a fair share of the mass are the rejection
// draws campaigns have always had (these values were drawn before a narrow window got its
// own method).
TEST(Campaign, NormalDrawsOfAWideWindowAreUnchanged) {
  const Campaign c = ParseCampaign(kCampaign, kSource);
  std::vector<std::string> hs;
  for (int k = 0; k < 3; ++k) hs.push_back(MakeCampaignRun(c, 18 + k).factors[1].second);
  EXPECT_EQ(hs, (std::vector<std::string>{"2.8512641718530163", "2.362985694831704",
                                          "2.394294163934284"}));
}

// A window narrow enough that rejection would take ~10^9 draws per value (within the
// 3-sigma guard) draws at once, inside the window, the same value every time.
TEST(Campaign, NormalDrawOfANarrowWindowFinishes) {
  const std::string text = Replace(kCampaign, "normal: {mean: 2.5, std_dev: 0.5, min: 2, max: 3}",
                                   "normal: {mean: 0, std_dev: 1, min: 2.9, max: 2.9000001}");
  const Campaign c = ParseCampaign(text, kSource);
  for (int k = 0; k < 3; ++k) {
    const std::string value = MakeCampaignRun(c, 18 + k).factors[1].second;
    const double x = std::stod(value);
    EXPECT_GE(x, 2.9);
    EXPECT_LE(x, 2.9000001);
    EXPECT_EQ(MakeCampaignRun(c, 18 + k).factors[1].second, value);
  }
  // Upper tail, mirrored: the same window below the mean.
  const Campaign lower = ParseCampaign(
      Replace(text, "min: 2.9, max: 2.9000001", "min: -2.9000001, max: -2.9"), kSource);
  const double y = std::stod(MakeCampaignRun(lower, 18).factors[1].second);
  EXPECT_GE(y, -2.9000001);
  EXPECT_LE(y, -2.9);
}

// The inverted draws follow the truncated normal law: their mean is the law's,
// (phi(a) - phi(b)) / (Phi(b) - Phi(a)), within a few standard errors.
TEST(Campaign, NormalDrawOfASmallWindowHasTheTruncatedLawsMean) {
  const std::string text =
      Replace(Replace(kCampaign, "normal: {mean: 2.5, std_dev: 0.5, min: 2, max: 3}",
                      "normal: {mean: 0, std_dev: 1, min: 2.6, max: 3.5}"),
              "seeds: {from: 5, to: 7}", "seeds: 400");
  const Campaign c = ParseCampaign(text, kSource);
  double sum = 0.0;
  for (int k = 0; k < 400; ++k) sum += std::stod(MakeCampaignRun(c, 18 + k).factors[1].second);
  const auto pdf = [](double z) {
    return std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi);
  };
  const auto cdf = [](double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); };
  const double mean = (pdf(2.6) - pdf(3.5)) / (cdf(3.5) - cdf(2.6));  // about 2.83
  // The law's standard deviation here is below 0.25: 0.05 is over 4 standard errors.
  EXPECT_NEAR(sum / 400, mean, 0.05);
}

}  // namespace
}  // namespace moorsim::scenarios

namespace moorsim::scenarios {
namespace {

// Every campaign of the library (scenarios/campaigns/, and the training campaigns in its
// training/ folder) reads, names its base scenario in the library and expands into runs
// (each run's draws made): a campaign file edited, moved or generated wrong fails here, not
// in the middle of a batch.
TEST(Campaign, EveryLibraryCampaignReadsAndExpands) {
  const std::filesystem::path root =
      std::filesystem::path(MOORSIM_SOURCE_DIR) / "scenarios/campaigns";
  // The least number of campaigns each folder holds, so that a folder read empty fails.
  for (const auto& [folder, least] : {std::pair{root, 8}, std::pair{root / "training", 10}}) {
    SCOPED_TRACE(folder.string());
    int campaigns = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
      if (entry.path().extension() != ".yaml") continue;
      SCOPED_TRACE(entry.path().string());
      const Campaign campaign = LoadCampaign(entry.path().string());
      EXPECT_TRUE(std::filesystem::exists(campaign.scenario_path)) << campaign.scenario_path;
      ASSERT_GT(campaign.NumRuns(), 0);
      for (std::int64_t i = 0; i < campaign.NumRuns(); ++i) {
        EXPECT_FALSE(MakeCampaignRun(campaign, i).overrides.empty());
      }
      ++campaigns;
    }
    EXPECT_GE(campaigns, least);
  }
}

}  // namespace
}  // namespace moorsim::scenarios
