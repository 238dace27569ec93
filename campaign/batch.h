// Monte-Carlo campaigns (`moorsim batch`): every run of a campaign (scenarios/campaign.h)
// through RunScenario, the very call `moorsim run` makes, on OpenMP threads, with one result
// row per run and the campaign's tables.
//
// Output directory DIR:
//   campaign.json     the campaign's identity (CampaignIdentity), name, path, seed and factor
//                     keys: DIR holds this campaign's results and no other's (a batch or a
//                     --merge of another campaign into DIR is refused, naming what differs)
//   campaign.yaml     the campaign text
//   moorsim.lock      held (output::DirectoryLock) while a batch or a merge writes DIR: no
//                     other moorsim process (batch, run, detect) writes DIR meanwhile
//   rows/NNNNNNNN.json  one row per finished run, with the campaign's identity, written
//                     atomically (temporary name, then rename): a row is whole or absent, so
//                     a rerun of the same command resumes, skipping runs that have a row. A
//                     file there that is not a row of one of the campaign's runs is an error
//                     naming it, never a row of the table.
//   runs.csv, campaign.h5  the table of every row (docs/design.md section 7), rewritten at
//                     the end of every batch, also an interrupted one
//   runs/NNNNNNNN/    run.h5 and summary.json of each run, only with keep_runs
//
// A transient block that names its intact block (design.intact) runs after the intact runs
// it needs: each of its runs parts its line at the instant of that line's largest top
// tension in its intact run (the time added to its overrides as failure.time, so its row's
// command repeats it alone). A shard runs, and keeps the rows of, the intact runs its
// transient runs need that DIR does not hold yet, also those of other shards.
//
// A run that fails (integrator, static start) or passes its wall-clock limit is a row
// with that status and the campaign goes on. A stop request (SIGINT/SIGTERM) ends every
// run at its next output row; those runs get no row and are done again on resume.
#pragma once

#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"

#include "campaign/batch_mpi.h"
#include "core/types.h"
#include "detectors/registry.h"
#include "runner/run.h"
#include "scenarios/campaign.h"

namespace moorsim::simulation {

/// The ROC record of one detector over one run: upcrossings of each threshold of its
/// type's statistic (detectors::StatisticOf; none: an empty record) before the failure
/// (in the whole run without one) and the first time at or after the failure that the
/// statistic reaches each threshold. Holds are not applied (a crossing counts at once), so
/// the grid shows the statistic's separation, not the configured rule.
class StatisticTrace {
 public:
  StatisticTrace(std::string type, double failure_time);  // failure_time NaN = intact
  void Add(double t, const std::vector<double>& score);
  nlohmann::json ToJson() const;

 private:
  const detectors::DetectorStatistic* statistic_;  // null: none
  double failure_time_;
  std::vector<double> thresholds_;
  std::vector<std::int64_t> false_crossings_;
  std::vector<double> first_crossing_;
  double max_before_ = kNaN;
  double previous_ = kNaN;
};

struct BatchOptions {
  std::string campaign_path;
  /// Results directory; empty = out/<campaign name>.
  std::filesystem::path out;
  /// OpenMP threads; 0 = as many as the machine has cores.
  int threads = 0;
  /// Only runs with index % shard_count == shard_index (0-based), for job arrays.
  int shard_index = 0;
  int shard_count = 1;
  /// Keep every run's run.h5 and summary.json under DIR/runs/.
  bool keep_runs = false;
  /// Wall-clock limit per run [s]; 0 = none.
  double run_timeout = 0.0;
  /// The updating progress line on stderr.
  bool progress = true;
  /// Recorded in the results.
  std::string command_line;
  /// Asked between runs and after every output row: nonzero (a signal) stops the batch.
  std::function<int()> stop_requested;
  /// Under mpirun (StartMpi): rank 0 owns the directory and deals runs to the others.
  MpiSession mpi;
};

/// What determines a campaign's rows, so that a results directory is resumed, and shards
/// are merged, only by the campaign that started them: every input by its SHA-256, paths
/// left out of `sha256` (the same files in another folder are the same campaign).
/// moorsim's release (PROJECT_VERSION without the commit: a rebuild of the same release
/// resumes a campaign, another release does not, as its numbers may differ); the campaign
/// file (which gives every run's overrides); the scenario and every base scenario a run's
/// resolved scenario takes values from (together they are that text); each WAMIT file of
/// every hydrodynamics stem the runs name (an optional one that is not there as absent);
/// each plugin library (the scenarios' and --plugin's).
struct CampaignIdentity {
  struct Input {
    std::string what;    ///< "campaign file", "base scenario", "hydrodynamics file", ...
    std::string path;    ///< as the campaign names it (messages only); the release: its number
    std::string sha256;  ///< of its bytes; "absent" for a file that is not there
  };
  std::vector<Input> inputs;  ///< in the order above
  std::string sha256;         ///< of every input's `what` and `sha256`, in order
};

/// What a run's row records of its scenario: the truth the detectors are scored against
/// and the detectors it runs.
struct RunTruth {
  int failure_line = 0;
  double failure_time = kNaN;
  std::string failure_mode;
  double duration = 0.0;
  int num_lines = 0;
  std::vector<std::pair<std::string, std::string>> detectors;  ///< (label, type)
};

/// The truth of a scenario loaded for a campaign run. Throws InputError for a scenario
/// without a vessel (a campaign runs `moorsim run`).
RunTruth TruthOf(const scenarios::Scenario& scenario);

/// The campaign and everything checked before its first run starts. The work does not grow
/// with the number of runs: each run's scenario is loaded by the thread that runs it (a
/// value the scenario refuses there is that run's "rejected" row, naming the run), and
/// before the first run only these are loaded and checked:
///   * the first run of each block;
///   * for every value a factor lists (values, range, choice), the first run that has it
///     (the run of its point for values and ranges; the first run that draws it for a
///     choice);
/// once per configuration (the overrides but the seed). They give the files the runs read
/// (the identity), the plugins, and each block's duration for the time estimate. A
/// listed value the scenario refuses is therefore refused before anything runs; a drawn
/// one (uniform, normal, follows) in the run that draws it, and `--dry-run` loads every
/// run as it lists it.
struct PreparedCampaign {
  scenarios::Campaign campaign;
  /// The runs checked before the first one (above), in the order they were loaded.
  std::vector<std::int64_t> checked_runs;
  /// Each block's first run's simulated duration [s]: the time estimate of its runs.
  std::vector<double> block_durations;
  /// The plugin libraries the checked runs' scenarios name (`plugin:`), without repeats.
  std::vector<std::string> plugin_paths;
  CampaignIdentity identity;
  /// Every transient run that takes its instant from an intact run (design.intact), by index.
  std::map<std::int64_t, scenarios::TransientSource> transients;
  /// The estimated simulated duration of run `index` (its block's).
  double EstimatedDuration(std::int64_t index) const;
};

/// Thrown by PrepareCampaign when asked to stop: nothing has run.
class PreparationStopped : public std::exception {
 public:
  explicit PreparationStopped(int signal) : signal_(signal) {}
  int signal() const { return signal_; }
  const char* what() const noexcept override { return "stopped while preparing the runs"; }

 private:
  int signal_;
};

/// Loads the campaign and the runs checked before the first (PreparedCampaign), checks the
/// detectors of each, and hashes the inputs (CampaignIdentity). Throws InputError naming
/// the campaign file, the run and the scenario's message (RunLocation). `stop_requested` is
/// asked between loads (PreparationStopped); `progress` shows a line on stderr while it
/// takes more than a second.
PreparedCampaign PrepareCampaign(const std::string& campaign_path,
                                 const std::function<int()>& stop_requested = {},
                                 bool progress = false);

/// "<campaign file>:<line>:<col>: blocks.<name>: run <index> (<factors>): <what>".
std::string RunLocation(const scenarios::Campaign& campaign, const scenarios::CampaignRun& run,
                        const std::string& what);

/// The row of one run (DIR/rows/*.json). `truth` is null for a run whose scenario was
/// refused: its row has no failure, lines or detectors.
nlohmann::json MakeRow(const PreparedCampaign& prepared, const scenarios::CampaignRun& run,
                       const RunTruth* truth, const runner::RunResult& result,
                       const std::vector<StatisticTrace>& traces, const std::string& out_dir);

/// How a batch ended: every run ok; some run failed or timed out (their rows say why); the
/// campaign or the options refused before any run; stopped by a signal (the same batch
/// resumes); or the batch itself failed (a file it could not write, a lost MPI rank).
enum class BatchStatus { kOk, kRunsFailed, kRejected, kInterrupted, kFailed };

struct BatchResult {
  BatchStatus status = BatchStatus::kOk;
  int signal = 0;  ///< the signal that stopped it (kInterrupted)
  std::string message;
  /// A rejection about one of the options (BatchOptions): the error, whose options a
  /// caller may name its own way (OptionError::Renamed).
  std::shared_ptr<const OptionError> option_error;
  std::int64_t runs = 0;     ///< in this shard
  std::int64_t skipped = 0;  ///< had a row already (resumed)
  std::int64_t done = 0;     ///< finished in this batch
  std::int64_t failed = 0;   ///< rows with a status other than ok, this batch
  /// Rows (all of the campaign's) whose hull left its setpoint heading by more than
  /// kHeadingLostDeg before the failure (in the whole run without one): it met other seas
  /// than the campaign set.
  std::int64_t heading_lost = 0;
  std::filesystem::path directory;
};

/// [deg] The heading error past which `moorsim batch` warns that runs lost their heading.
inline constexpr double kHeadingLostDeg = 10.0;

/// Threads when none are asked for: the machine's cores (omp_get_num_procs).
int DefaultThreads();

/// Runs the campaign as described at the top of this file. Never throws.
BatchResult RunBatch(const BatchOptions& options) noexcept;

/// `moorsim batch --dry-run`: every run (index, block, seed, failure, duration, factors),
/// each loaded and checked as it is written to `out` (a run that shares the previous one's
/// configuration but the seed shares its load), then the total and the estimated wall time
/// on `threads` threads. Throws InputError (RunLocation) at the first run its scenario
/// refuses, after the runs before it.
void DescribeCampaign(const PreparedCampaign& prepared, int threads, std::ostream& out);

/// Reads every row under each of `directories` (the same campaign, e.g. shards) and
/// writes the campaign's tables into `out` (rows copied there too, with the rows `out`
/// already holds). Throws InputError, before writing anything, for directories of different
/// campaigns, an `out` that holds another campaign, a directory without campaign.json and a
/// file in rows/ that is not a row of the campaign (ReadRows); Error when writing fails.
/// Returns the campaign's runs and those no directory held a row of (shards not merged,
/// runs not yet run): the tables then hold the others only.
struct MergeResult {
  std::int64_t runs = 0;
  std::vector<std::int64_t> missing;  ///< run indices, ascending
};
MergeResult MergeCampaigns(const std::vector<std::filesystem::path>& directories,
                           const std::filesystem::path& out, const std::string& command_line);

/// Writes DIR/runs.csv and DIR/campaign.h5 from the rows (any order; sorted by run).
void WriteCampaignTables(const std::filesystem::path& directory, const std::string& campaign_text,
                         const std::string& campaign_name, const std::string& campaign_path,
                         std::uint64_t campaign_seed, const std::vector<std::string>& factor_keys,
                         std::vector<nlohmann::json> rows, const std::string& command_line);

/// Reads DIR/rows/*.json, the rows of the campaign DIR/campaign.json records. Throws
/// InputError naming the first file there that is not the row of one of its runs (damaged,
/// of a run beyond the campaign's, named for another run, of another campaign).
std::vector<nlohmann::json> ReadRows(const std::filesystem::path& directory);

}  // namespace moorsim::simulation
