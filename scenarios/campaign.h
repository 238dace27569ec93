// A Monte-Carlo campaign: one base scenario run many times with factors varied and seeds
// drawn, for statistics of the detectors (detection and isolation rates, delays, false
// alarms per hour). Loading is strict like a scenario's: every problem is one
// moorsim::InputError line "<file>:<line>:<col>: <key.path>: <what>".
//
// Schema (scenarios/README.md, "Campaigns"):
//
//   name: thesis_detection            # optional; default: the file name without extension
//   scenario: ../library/thesis_no_failure_current.yaml   # required; relative to this file
//   seed: 2026                        # required: the campaign seed (unsigned 64-bit)
//   set:                              # optional: overrides for every run, as `--set`
//                                     # (no key may be simulation.seed or base)
//     simulation.duration: 800        #   key path: value (any YAML value)
//   blocks:                           # required, >= 1: groups of runs
//     - name: failures                # required, unique ([A-Za-z0-9_-]+)
//       set: {failure.mode: fairlead} # optional: overrides for this block's runs
//       factors:                      # optional: the varied keys, each one of
//         - {key: failure.line, values: [1, 2, 3]}            # a list of values
//         - {key: solver.rtol, range: {from: 1e-5, to: 1e-4, step: 4.5e-5}}  # inclusive
//         - {key: failure.time, uniform: [200, 600]}          # a draw per run
//         - {key: environment.waves.hs, normal: {mean: 2.5, std_dev: 0.3, min: 0.5, max: 6}}
//         - {key: controller.type, choice: [pi, observer_pid]}  # a draw per run
//         - {key: controller.setpoint.heading_deg, follows: environment.waves.direction_toward_deg,
//            add: [165, 195], modulo: 360}   # an earlier factor's value + a constant or a
//                                            # uniform draw, reduced to [-180, 180)
//         - {key: controller.setpoint.x, follows: controller.setpoint.heading_deg,
//            function: cos, scale: -60, add: 60}  # add + scale * cos(value in deg): a point
//                                                 # that turns with the heading
//       combine: grid                 # grid (every combination of the listed values,
//                                     # first factor slowest) or zip (the i-th value of
//                                     # every list together; the lists equally long)
//       seeds: 50                     # a count (each run's seed derived from the campaign
//                                     # seed and the run index) or {from: 1, to: 50}
//                                     # (these simulator seeds, for each point)
//       design: {condition: transient, intact: storm}  # optional: its part in the design
//                                     # checks (campaign/design.h): intact, damaged or
//                                     # transient (with `intact`, each run parts its line at
//                                     # its largest tension in that block's run of its seed),
//                                     # method gumbel or weibull, or a fatigue sea state
//                                     # {probability: p}
//   design: {standard: api_rp_2sk}    # optional: the design checks' settings
//
// Runs are numbered from 0 in order: block by block, the points of the block (grid or zip
// order), and within a point its seeds. Random factors are drawn per run from a stream
// named by the campaign seed, the run index and the key, so a run's values do not depend
// on which runs are done, in what order or on how many threads. A run's overrides are the
// campaign's `set`, the block's `set`, the factors in order, then simulation.seed: exactly
// what `moorsim run SCENARIO --set ... --seed N` applies (CampaignRun::Command).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "analysis/design_tension.h"
#include "analysis/extremes.h"
#include "scenarios/scenario.h"

namespace moorsim::scenarios {

struct CampaignFactor {
  enum class Kind { kValues, kUniform, kNormal, kChoice, kFollows };
  std::string key;  ///< a `--set` key path
  Kind kind = Kind::kValues;
  /// kValues (also an expanded range) and kChoice: each value as `--set` text.
  std::vector<std::string> values;
  double low = 0.0, high = 0.0;      ///< kUniform: [low, high)
  double mean = 0.0, std_dev = 0.0;  ///< kNormal
  /// kNormal: draws outside are drawn again, or, for a window holding under 1% of the
  /// distribution, the distribution function is inverted within it.
  std::optional<double> min, max;
  /// kFollows: v, the value of `follows` (an earlier factor of the block, numeric), made
  /// scale * function(v) (function: unset, or cos / sin of v in degrees), plus `low`, or a
  /// uniform draw in [low, high) when high > low; reduced to [-modulo / 2, modulo / 2) when
  /// modulo > 0.
  enum class Function { kCos, kSin };
  std::string follows;
  std::optional<Function> function;
  double scale = 1.0;
  double modulo = 0.0;
  SourceMark mark;  ///< the factor's list entry
};

struct CampaignBlock {
  /// grid: every combination of the factors' values, the first factor slowest; zip: the
  /// i-th value of each.
  enum class Combine { kGrid, kZip };
  std::string name;
  std::vector<std::string> set;  ///< "key.path=value", in the order written
  std::vector<CampaignFactor> factors;
  bool zip = false;
  /// Its runs' part in the design checks (`design:`): the condition its storms test, and
  /// for fatigue the share of the time its sea state holds; unset: none.
  struct Design {
    analysis::DesignCondition condition = analysis::DesignCondition::kIntact;
    std::optional<double> probability;  ///< in (0, 1]: a fatigue sea state
    /// The storm maxima of its points' seeds (Gumbel), or one long run's peaks (Weibull:
    /// one seed per point).
    analysis::ExtremesMethod method = analysis::ExtremesMethod::kGumbel;
    /// kTransient: the intact block whose run of the same seed and factor values gives
    /// each run's failure time (the instant of its line's largest top tension there);
    /// empty: the failure.time the runs are given.
    std::string intact;
    SourceMark intact_mark;
  };
  std::optional<Design> design;
  /// Derived seeds: this many per point. Explicit seeds: first_seed..last_seed per point.
  std::int64_t seed_count = 1;
  std::optional<std::uint64_t> first_seed, last_seed;
  SourceMark mark;
  /// Points (combinations of the listed values) and runs of the block.
  std::int64_t Points() const;
  std::int64_t SeedsPerPoint() const;
  std::int64_t Runs() const { return Points() * SeedsPerPoint(); }
  /// A transient block whose runs take their instants from an intact block (Design::intact).
  bool TakesIntactInstants() const { return design && !design->intact.empty(); }
};

inline constexpr std::string_view kFunctionNames[] = {"cos", "sin"};
constexpr ChoiceInfo ChoicesOf(CampaignFactor::Function) { return {"function", kFunctionNames}; }
inline constexpr std::string_view kCombineNames[] = {"grid", "zip"};
constexpr ChoiceInfo ChoicesOf(CampaignBlock::Combine) { return {"combination", kCombineNames}; }

/// The campaign's design checks (`design:`): the standard and its settings.
struct CampaignDesign {
  analysis::DesignStandard standard = analysis::DesignStandard::kApiRp2sk;
  int consequence_class = 1;           ///< DNV-OS-E301: 1 or 2
  double quantile = 0.9;               ///< a storm maximum's quantile reported beside the MPM
  double confidence = 0.95;            ///< of the intervals
  std::optional<double> offset_limit;  ///< [m] the vessel's largest allowed offset
  double fatigue_factor = 1.0;         ///< the life must exceed service_life times this
  double service_life = 20.0;          ///< [years]
  double storm_duration = 10800.0;     ///< [s] the storm a Weibull block's maxima are of
};

struct Campaign {
  std::string name;
  std::string source_path;    ///< as given
  std::string text;           ///< the YAML text, recorded in the results
  std::string scenario_path;  ///< the base scenario, resolved against source_path's directory
  std::uint64_t seed = 0;
  std::vector<std::string> set;  ///< for every run
  std::vector<CampaignBlock> blocks;
  std::optional<CampaignDesign> design;
  std::int64_t NumRuns() const;
  /// The index of block `block`'s first run.
  std::int64_t FirstRunOf(std::size_t block) const;
  /// Every factor key of every block, first appearance first (the results' columns).
  std::vector<std::string> FactorKeys() const;
};

/// One run of a campaign, fully determined by the campaign and its index.
struct CampaignRun {
  std::int64_t index = 0;
  int block = 0;  ///< index into Campaign::blocks
  std::uint64_t seed = 0;
  /// (key, value text) of every factor of the block, in order.
  std::vector<std::pair<std::string, std::string>> factors;
  /// The overrides RunScenario applies: campaign set, block set, factors, then
  /// "simulation.seed=<seed>" (last, as `moorsim run --seed` appends it).
  std::vector<std::string> overrides;
  /// The `moorsim run` command that repeats this run alone (shell-quoted).
  std::string Command(const Campaign& campaign, const std::string& out_dir) const;
};

/// Reads and checks the campaign file (the base scenario is not loaded here; see
/// simulation::PrepareCampaign). Throws InputError.
Campaign LoadCampaign(const std::string& path);
/// `need_scenario` false: the base scenario need not be where the campaign names it (a
/// results directory's copy of the campaign, read where its scenario is not).
Campaign ParseCampaign(const std::string& yaml_text, const std::string& source_name,
                       bool need_scenario = true);

/// The derived simulator seed of run `index`: SplitMix64Mix(SplitMix64Mix(campaign seed) ^
/// Fnv1a64("campaign run <index>")), so neighbouring indices give unrelated seeds.
std::uint64_t DerivedRunSeed(std::uint64_t campaign_seed, std::int64_t index);

/// Run `index` (0 <= index < NumRuns()) with its seed and drawn values.
CampaignRun MakeCampaignRun(const Campaign& campaign, std::int64_t index);

/// A transient run that takes its instant from an intact run (CampaignBlock::Design::intact):
/// that run and the line this one parts.
struct TransientSource {
  std::int64_t intact_run = 0;
  int line = 0;
};
/// The intact run `run` takes its failure time from: the run of the named intact block
/// with the same seed and the same value of each of that block's factors; nothing for a
/// run of any other block. Throws InputError (naming the run) when no intact run matches.
std::optional<TransientSource> TransientSourceOf(const Campaign& campaign, const CampaignRun& run);
/// Gives `run` its failure time: `failure.time=<time>` just before its seed.
void SetFailureTime(CampaignRun& run, double time);

/// `text` quoted for a POSIX shell when it holds anything but [A-Za-z0-9_./:=,+-].
std::string ShellQuote(const std::string& text);

}  // namespace moorsim::scenarios
