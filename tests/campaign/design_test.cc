// A campaign's design checks (campaign/design.h) on rows made here with known numbers: the
// MPM is the Gumbel fit of the seeds' maxima, the check the standard's, a damaged point
// leaves its parted line out, a transient one takes the maxima after the failure, and the
// fatigue life is the probability-weighted damage rate's inverse.
#include "campaign/design.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/design_tension.h"
#include "analysis/extremes.h"
#include "campaign/batch.h"
#include "core/format.h"
#include "scenarios/campaign.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::simulation {
namespace {

const char kCampaign[] = R"(name: design
scenario: seed_tapm.yaml
seed: 1
design: {standard: api_rp_2sk, offset_limit: 50, service_life: 20, fatigue_factor: 3}
blocks:
  - name: storm
    design: {condition: intact}
    seeds: 10
  - name: damaged
    design: {condition: damaged}
    set: {failure.time: 0, simulation.statistics_from: 600}
    factors: [{key: failure.line, values: [1, 2]}]
    seeds: 10
  - name: calm
    design: {probability: 0.7}
    seeds: 2
  - name: rough
    design: {probability: 0.3}
    seeds: 2
  - name: other
    seeds: 1
)";

// A row of run `run` in `block`: two lines, line k's largest top tension `top[k]`.
nlohmann::json Row(std::int64_t run, const std::string& block, std::vector<double> top,
                   int failure_line, double damage_top, double offset) {
  nlohmann::json lines = nlohmann::json::array();
  for (std::size_t k = 0; k < top.size(); ++k) {
    lines.push_back({{"line", k + 1},
                     {"type", "chain"},
                     {"minimum_breaking_load", 6.0e6},
                     {"max_top_tension", top[k]},
                     {"mean_top_tension", 2.0e6},
                     {"max_top_tension_after_failure", top[k] * 0.9},
                     {"top_damage", damage_top * (k + 1)},
                     {"touchdown_type", "wire"},
                     {"touchdown_damage", nullptr}});
  }
  nlohmann::json failure = nullptr;
  if (failure_line > 0) failure = {{"line", failure_line}, {"time", 0}, {"mode", "fairlead"}};
  return {{"run", run},
          {"block", block},
          {"status", "ok"},
          {"factors", nlohmann::json::object()},
          {"failure", failure},
          {"design", {{"duration", 3600.0}, {"lines", lines}, {"max_offset", offset}}}};
}

TEST(DesignChecks, TheTablesAreTheFitsTheStandardAndTheWeightedDamage) {
  const scenarios::Campaign campaign = scenarios::ParseCampaign(kCampaign, "design.yaml", false);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto gumbel = [&](double mu, double beta) {
    return mu - beta * std::log(-std::log(u(random)));
  };
  std::vector<nlohmann::json> rows;
  std::vector<double> line1, offsets;
  std::int64_t run = 0;
  for (int s = 0; s < 10; ++s, ++run) {
    const double t1 = gumbel(3.0e6, 2.0e5), o = gumbel(30.0, 3.0);
    line1.push_back(t1);
    offsets.push_back(o);
    rows.push_back(Row(run, "storm", {t1, gumbel(2.5e6, 1e5)}, 0, 0.0, o));
  }
  for (int line = 1; line <= 2; ++line) {
    for (int s = 0; s < 10; ++s, ++run) {
      rows.push_back(
          Row(run, "damaged", {gumbel(3.5e6, 2e5), gumbel(3.5e6, 2e5)}, line, 0.0, 40.0));
    }
  }
  for (int s = 0; s < 2; ++s, ++run) rows.push_back(Row(run, "calm", {1e6, 1e6}, 0, 1e-6, 5.0));
  for (int s = 0; s < 2; ++s, ++run) rows.push_back(Row(run, "rough", {2e6, 2e6}, 0, 1e-4, 9.0));
  rows.push_back(Row(run, "other", {1e6, 1e6}, 0, 0.0, 1.0));

  const nlohmann::json checks = DesignChecks(campaign, rows);
  ASSERT_TRUE(checks.is_object());
  const nlohmann::json& extremes = checks.at("extremes");
  // storm: two lines; damaged: two points, each without its parted line.
  ASSERT_EQ(extremes.size(), 4u);
  const nlohmann::json& storm1 = extremes.at(0);
  EXPECT_EQ(storm1.at("block"), "storm");
  EXPECT_EQ(storm1.at("line"), 1);
  const analysis::GumbelFit fit = analysis::FitGumbel(line1);
  EXPECT_DOUBLE_EQ(storm1.at("mpm").at("value").get<double>(), fit.Mpm().value);
  EXPECT_DOUBLE_EQ(storm1.at("mpm").at("lower").get<double>(), fit.Mpm().lower);
  const analysis::DesignCheck check =
      analysis::CheckLine({fit.Mpm().value, 2.0e6, 6.0e6}, analysis::DesignStandard::kApiRp2sk,
                          analysis::DesignCondition::kIntact);
  EXPECT_DOUBLE_EQ(storm1.at("check").at("safety_factor").get<double>(), check.safety_factor);
  EXPECT_EQ(storm1.at("check").at("pass").get<bool>(), check.pass);
  EXPECT_EQ(storm1.at("run_indices").size(), 10u);
  EXPECT_EQ(extremes.at(2).at("block"), "damaged");
  EXPECT_EQ(extremes.at(2).at("parted_line"), 1);
  EXPECT_EQ(extremes.at(2).at("line"), 2);
  EXPECT_EQ(extremes.at(3).at("parted_line"), 2);
  EXPECT_EQ(extremes.at(3).at("line"), 1);
  EXPECT_EQ(extremes.at(3).at("check").at("required_factor"), 1.25);
  // Offsets: one per point, against the limit.
  const nlohmann::json& offset = checks.at("offsets").at(0);
  EXPECT_DOUBLE_EQ(offset.at("mpm").at("value").get<double>(),
                   analysis::FitGumbel(offsets).Mpm().value);
  EXPECT_EQ(offset.at("limit"), 50.0);
  // Fatigue: 0.7 x 1e-6 / 3600 s + 0.3 x 1e-4 / 3600 s per second, for line 1's top.
  const nlohmann::json& fatigue = checks.at("fatigue");
  EXPECT_DOUBLE_EQ(fatigue.at("probability").get<double>(), 1.0);
  const double year = 365.25 * 86400.0;
  const double annual = (0.7 * 1e-6 + 0.3 * 1e-4) / 3600.0 * year;
  const nlohmann::json& line1_fatigue = fatigue.at("lines").at(0);
  EXPECT_NEAR(line1_fatigue.at("top").at("annual_damage").get<double>(), annual, 1e-12 * annual);
  EXPECT_NEAR(line1_fatigue.at("top").at("life_years").get<double>(), 1.0 / annual, 1e-9);
  EXPECT_EQ(line1_fatigue.at("top").at("pass").get<bool>(), 1.0 / annual >= 60.0);
  EXPECT_TRUE(line1_fatigue.at("touchdown").at("annual_damage").is_null());
  EXPECT_EQ(line1_fatigue.at("touchdown").at("note"), "no T-N curve (fatigue) for its line type");
  // Line 2's damage per run is twice line 1's.
  EXPECT_NEAR(fatigue.at("lines").at(1).at("top").at("annual_damage").get<double>(), 2.0 * annual,
              1e-12 * annual);
  // The tables.
  const std::string csv = DesignExtremesCsv(checks);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "block,point,condition,parted_line,line,type,runs,method,mpm,mpm_lower,mpm_upper,"
            "quantile,mean_tension,minimum_breaking_load,design_tension,safety_factor,"
            "required_factor,utilisation,result");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  const std::string fatigue_csv = DesignFatigueCsv(checks);
  EXPECT_EQ(std::count(fatigue_csv.begin(), fatigue_csv.end(), '\n'), 5);
  EXPECT_NE(fatigue_csv.find("1,touchdown,wire,,,\n"), std::string::npos) << fatigue_csv;
}

// A weibull block's one long run: its record's fit of the peaks, scaled from the record's
// length to the campaign's storm.
TEST(DesignChecks, AWeibullBlockScalesItsRunsPeaksToTheStorm) {
  const scenarios::Campaign campaign = scenarios::ParseCampaign(
      "scenario: seed_tapm.yaml\nseed: 1\n"
      "design: {storm_duration: 10800, quantile: 0.9}\n"
      "blocks: [{name: long, design: {method: weibull}, seeds: 1}]\n",
      "design.yaml", false);
  std::mt19937_64 random(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> peaks;
  const double sigma = 1.0e5, mean = 2.0e6;
  for (int i = 0; i < 20000; ++i) {
    const double p = mean + sigma * std::sqrt(-2.0 * std::log(1.0 - u(random)));
    if (p > mean + sigma) peaks.push_back(p);
  }
  const analysis::WeibullFit fit = analysis::FitWeibull(peaks, mean + sigma, mean);
  const nlohmann::json record = {
      {"threshold", fit.threshold},
      {"location", fit.location},
      {"scale", fit.scale},
      {"shape", fit.shape},
      {"covariance", {fit.covariance(0, 0), fit.covariance(0, 1), fit.covariance(1, 1)}},
      {"peaks", peaks.size()}};
  nlohmann::json row = Row(0, "long", {2.1e6, 2.1e6}, 0, 0.0, 10.0);
  // A 36 000 s record: the storm holds 0.3 of its peaks.
  row["design"]["duration"] = 36000.0;
  row["design"]["lines"][0]["top_peaks"] = record;
  row["design"]["lines"][1]["top_peaks"] = nullptr;
  row["design"]["offset_peaks"] = record;
  const nlohmann::json checks = DesignChecks(campaign, {row});
  const nlohmann::json& line1 = checks.at("extremes").at(0);
  EXPECT_EQ(line1.at("method"), "weibull");
  const double storm_peaks = 0.3 * static_cast<double>(peaks.size());
  EXPECT_DOUBLE_EQ(line1.at("weibull").at("storm_peaks").get<double>(), storm_peaks);
  EXPECT_DOUBLE_EQ(line1.at("mpm").at("value").get<double>(), fit.Mpm(storm_peaks).value);
  EXPECT_DOUBLE_EQ(line1.at("mpm").at("upper").get<double>(), fit.Mpm(storm_peaks).upper);
  EXPECT_DOUBLE_EQ(line1.at("quantile").at("value").get<double>(),
                   fit.Quantile(storm_peaks, 0.9).value);
  // 6000 peaks in the storm: near mean + sigma sqrt(2 ln 6000) (Rayleigh).
  EXPECT_NEAR(line1.at("mpm").at("value").get<double>(),
              mean + sigma * std::sqrt(2.0 * std::log(6000.0)), 0.02 * sigma * 4.2);
  const nlohmann::json& line2 = checks.at("extremes").at(1);
  EXPECT_TRUE(line2.at("mpm").is_null());
  EXPECT_EQ(line2.at("note"),
            "fewer than 10 peaks above the mean plus one standard deviation: no fit");
  EXPECT_DOUBLE_EQ(checks.at("offsets").at(0).at("mpm").at("value").get<double>(),
                   fit.Mpm(storm_peaks).value);
}

TEST(DesignChecks, NoneWithoutTheCampaignsDesignAndTooFewRunsAreNotFitted) {
  scenarios::Campaign campaign = scenarios::ParseCampaign(kCampaign, "design.yaml", false);
  EXPECT_TRUE(campaign.design.has_value());
  std::vector<nlohmann::json> rows = {Row(0, "storm", {1e6, 1e6}, 0, 0.0, 1.0),
                                      Row(1, "storm", {1.1e6, 1e6}, 0, 0.0, 1.0)};
  const nlohmann::json checks = DesignChecks(campaign, rows);
  EXPECT_TRUE(checks.at("extremes").at(0).at("mpm").is_null());
  EXPECT_EQ(checks.at("extremes").at(0).at("note"), "fewer than 3 runs: no fit");
  campaign.design.reset();
  EXPECT_TRUE(DesignChecks(campaign, rows).is_null());
}

// A small design campaign through `moorsim batch`'s library call: the thesis plant for 40 s
// at 5 Hz, its chain given a breaking load and DNV's studless curve; three intact storms,
// three with line 2 removed at 0 s (statistics from 10 s), two fatigue states. The tables
// are the fits of the rows' records.
constexpr const char* kDesignPlant =
    "base: " MOORSIM_SOURCE_DIR
    "/scenarios/library/thesis_no_failure.yaml\n"
    "mooring:\n"
    "  line_types:\n"
    "    - {name: chain_seed, diameter: 0.08, mass_per_length: 275, axial_stiffness: "
    "2.28785e8, axial_damping_ratio: 0.5, drag_normal: 0.3, drag_tangential: 1.0, "
    "added_mass_normal: 1.5, friction_axial: 0.5, friction_lateral: 1.0, "
    "minimum_breaking_load: 1.5e7, fatigue: {curve: studless_chain}}\n"
    "detectors: []\n";

TEST(DesignCampaignSlow, WritesItsTablesFromTheRunsRecords) {
  const std::filesystem::path dir = moorsim::testing::FreshDirectory("design_campaign");
  std::ofstream(dir / "plant.yaml") << kDesignPlant;
  std::ofstream(dir / "design.yaml")
      << "scenario: plant.yaml\n"
         "seed: 5\n"
         "set: {simulation.duration: 40, simulation.output_rate_hz: 5}\n"
         "design: {standard: dnv_os_e301, consequence_class: 2, offset_limit: 100}\n"
         "blocks:\n"
         "  - name: storm\n"
         "    design: {condition: intact}\n"
         "    seeds: 3\n"
         "  - name: damaged\n"
         "    design: {condition: damaged}\n"
         "    set: {failure.time: 0, failure.mode: fairlead, simulation.statistics_from: 10}\n"
         "    factors: [{key: failure.line, values: [2]}]\n"
         "    seeds: 3\n"
         "  - name: calm\n"
         "    design: {probability: 0.6}\n"
         "    seeds: 1\n"
         "  - name: rough\n"
         "    design: {probability: 0.4}\n"
         "    set: {environment.waves.hs: 4}\n"
         "    seeds: 1\n";
  BatchOptions o;
  o.campaign_path = (dir / "design.yaml").string();
  o.out = dir / "out";
  o.threads = 2;
  o.progress = false;
  const BatchResult result = RunBatch(o);
  ASSERT_EQ(result.status, BatchStatus::kOk) << result.message;
  std::vector<nlohmann::json> rows = ReadRows(dir / "out");
  ASSERT_EQ(rows.size(), 8u);
  std::sort(rows.begin(), rows.end(), [](const nlohmann::json& a, const nlohmann::json& b) {
    return a.at("run").get<int>() < b.at("run").get<int>();
  });
  std::ifstream in(dir / "out" / "design.json");
  const nlohmann::json checks = nlohmann::json::parse(in);
  EXPECT_EQ(checks.at("standard"), "dnv_os_e301");
  // storm: 8 lines; damaged: 7 (line 2 removed).
  const nlohmann::json& extremes = checks.at("extremes");
  ASSERT_EQ(extremes.size(), 15u);
  for (std::size_t k = 0; k < 8; ++k) {
    std::vector<double> maxima;
    for (std::size_t r = 0; r < 3; ++r) {
      maxima.push_back(rows[r].at("design").at("lines").at(k).at("max_top_tension").get<double>());
    }
    const nlohmann::json& e = extremes.at(k);
    EXPECT_EQ(e.at("line"), k + 1);
    EXPECT_DOUBLE_EQ(e.at("mpm").at("value").get<double>(),
                     analysis::FitGumbel(maxima).Mpm().value);
    EXPECT_EQ(e.at("minimum_breaking_load"), 1.5e7);
    EXPECT_TRUE(e.at("check").at("pass").get<bool>());  // the thesis sea is mild
  }
  for (std::size_t k = 8; k < 15; ++k) EXPECT_NE(extremes.at(k).at("line"), 2);
  EXPECT_EQ(extremes.at(8).at("condition"), "damaged");
  // The damaged runs' records start at 10 s.
  EXPECT_EQ(rows[3].at("design").at("from"), 10.0);
  // Fatigue: both states, every line's top and touchdown on the chain's curve.
  const nlohmann::json& fatigue = checks.at("fatigue");
  EXPECT_DOUBLE_EQ(fatigue.at("probability").get<double>(), 1.0);
  ASSERT_EQ(fatigue.at("lines").size(), 8u);
  for (const nlohmann::json& line : fatigue.at("lines")) {
    EXPECT_GT(line.at("top").at("annual_damage").get<double>(), 0.0);
    EXPECT_GT(line.at("touchdown").at("annual_damage").get<double>(), 0.0);
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "design.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "fatigue.csv"));
  std::filesystem::remove_all(dir);
}

// The library's design campaign on the seed mooring: every run loads, and each transient
// run takes its instant from the intact storm of its seed.
TEST(DesignCampaign, TheSeedMooringsCampaignPreparesAndMatchesItsTransients) {
  const PreparedCampaign p =
      PrepareCampaign(MOORSIM_SOURCE_DIR "/scenarios/campaigns/seed_design.yaml");
  const scenarios::Campaign& c = p.campaign;
  ASSERT_EQ(c.blocks.at(0).name, "storm");
  ASSERT_EQ(p.transients.size(), 80u);
  for (const auto& [index, source] : p.transients) {
    const scenarios::CampaignRun run = scenarios::MakeCampaignRun(c, index);
    const scenarios::CampaignRun intact = scenarios::MakeCampaignRun(c, source.intact_run);
    EXPECT_EQ(c.blocks.at(static_cast<std::size_t>(intact.block)).name, "storm");
    EXPECT_EQ(intact.seed, run.seed);
    EXPECT_EQ(run.factors.at(0).second, std::to_string(source.line));
  }
  std::ostringstream listing;
  DescribeCampaign(p, 2, listing);
  EXPECT_NE(listing.str().find("line 8 at its largest tension in run 9"), std::string::npos);
}

std::map<std::int64_t, nlohmann::json> RowsByRun(const std::filesystem::path& dir) {
  std::map<std::int64_t, nlohmann::json> rows;
  for (nlohmann::json& row : ReadRows(dir)) rows.emplace(row.at("run").get<std::int64_t>(), row);
  return rows;
}

// Transient runs part their line at the instant of its largest top tension in the intact
// run of their seed, run after it; the row's command carries that instant. A shard runs
// the intact runs its transient runs need, and the shards merge to the unsharded table.
TEST(DesignCampaignSlow, ATransientRunPartsItsLineAtItsIntactRunsLargestTension) {
  const std::filesystem::path dir = moorsim::testing::FreshDirectory("design_transient");
  std::ofstream(dir / "plant.yaml") << kDesignPlant;
  std::ofstream(dir / "transient.yaml")
      << "scenario: plant.yaml\n"
         "seed: 5\n"
         "set: {simulation.duration: 40, simulation.output_rate_hz: 5}\n"
         "design: {}\n"
         "blocks:\n"
         "  - name: storm\n"
         "    design: {condition: intact}\n"
         "    seeds: {from: 1, to: 3}\n"
         "  - name: parted\n"
         "    design: {condition: transient, intact: storm}\n"
         "    set: {failure.mode: fairlead}\n"
         "    factors: [{key: failure.line, values: [1, 6]}]\n"
         "    seeds: {from: 1, to: 3}\n";
  const auto batch = [&](const std::string& out, int shard, int shards) {
    BatchOptions o;
    o.campaign_path = (dir / "transient.yaml").string();
    o.out = dir / out;
    o.threads = 2;
    o.progress = false;
    o.shard_index = shard;
    o.shard_count = shards;
    return RunBatch(o);
  };
  const BatchResult whole = batch("whole", 0, 1);
  ASSERT_EQ(whole.status, BatchStatus::kOk) << whole.message;
  const std::map<std::int64_t, nlohmann::json> rows = RowsByRun(dir / "whole");
  ASSERT_EQ(rows.size(), 9u);
  for (std::int64_t run = 3; run < 9; ++run) {
    const nlohmann::json& row = rows.at(run);
    const int line = run < 6 ? 1 : 6;
    const nlohmann::json& intact = rows.at((run - 3) % 3);
    EXPECT_EQ(intact.at("seed"), row.at("seed"));
    const double instant =
        intact.at("design").at("lines").at(line - 1).at("time_of_max_top_tension").get<double>();
    EXPECT_GT(instant, 0.0);
    EXPECT_EQ(row.at("failure").at("line"), line);
    EXPECT_EQ(row.at("failure").at("time").get<double>(), instant);
    EXPECT_NE(row.at("command").get<std::string>().find(
                  "--set failure.time=" + FormatNumber(instant) + " --seed"),
              std::string::npos)
        << row.at("command");
    // Until the instant the transient run is its intact run, bit for bit: another line's
    // largest tension there, if it came earlier, is reached here too (and may be passed
    // after the instant); if both came earlier they are one. The parted line holds none
    // from the instant on.
    for (int k = 1; k <= 8; ++k) {
      const nlohmann::json& mine = row.at("design").at("lines").at(k - 1);
      const nlohmann::json& theirs = intact.at("design").at("lines").at(k - 1);
      if (k == line) {
        EXPECT_EQ(mine.at("max_top_tension_after_failure").get<double>(), 0.0);
        continue;
      }
      if (theirs.at("time_of_max_top_tension").get<double>() < instant) {
        EXPECT_GE(mine.at("max_top_tension").get<double>(),
                  theirs.at("max_top_tension").get<double>())
            << "line " << k;
      }
      if (mine.at("time_of_max_top_tension").get<double>() < instant &&
          theirs.at("time_of_max_top_tension").get<double>() < instant) {
        EXPECT_EQ(mine.at("max_top_tension"), theirs.at("max_top_tension")) << "line " << k;
      }
    }
  }
  // A transient row's run repeats alone from its command's overrides: the same record.
  {
    const PreparedCampaign p = PrepareCampaign((dir / "transient.yaml").string());
    scenarios::CampaignRun run = scenarios::MakeCampaignRun(p.campaign, 7);
    scenarios::SetFailureTime(run, rows.at(7).at("failure").at("time").get<double>());
    runner::RunRequest request;
    request.scenario_path = p.campaign.scenario_path;
    request.overrides = run.overrides;
    request.write_files = false;
    const runner::RunResult alone = runner::RunScenario(request);
    ASSERT_EQ(alone.status, runner::RunStatus::kOk) << alone.message;
    EXPECT_EQ(alone.summary.at("design"), rows.at(7).at("design"));
  }
  const nlohmann::json checks = nlohmann::json::parse(std::ifstream(dir / "whole" / "design.json"));
  std::set<int> parted;
  for (const nlohmann::json& e : checks.at("extremes")) {
    if (e.at("condition") == "transient") parted.insert(e.at("parted_line").get<int>());
  }
  EXPECT_EQ(parted, (std::set<int>{1, 6}));
  // Shard 2 of 2 (runs 1, 3, 5, 7) also runs intact runs 0 and 2, which runs 3, 5 and 7
  // need; with shard 1 the merge is the unsharded table.
  const BatchResult second = batch("second", 1, 2);
  ASSERT_EQ(second.status, BatchStatus::kOk) << second.message;
  EXPECT_EQ(RowsByRun(dir / "second").size(), 6u);
  ASSERT_EQ(batch("first", 0, 2).status, BatchStatus::kOk);
  const MergeResult merged = MergeCampaigns({dir / "first", dir / "second"}, dir / "merged", "");
  EXPECT_TRUE(merged.missing.empty());
  const std::map<std::int64_t, nlohmann::json> merged_rows = RowsByRun(dir / "merged");
  for (const auto& [run, row] : rows) {
    EXPECT_EQ(merged_rows.at(run).at("command"), row.at("command"));
    EXPECT_EQ(merged_rows.at(run).at("design"), row.at("design"));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace moorsim::simulation
