// Monte-Carlo campaigns (`moorsim batch`): every run of a campaign (scenarios/campaign.h)
// through RunScenario, the very call `moorsim run` makes, on OpenMP threads, with one result
// row per run and the campaign's tables.
//
// Output directory DIR:
//   campaign.yaml     the campaign text (a rerun with another text into DIR is refused)
//   campaign.json     its name, path, seed and factor keys (for --merge)
//   campaign.lock     held (flock) while a batch writes DIR: two campaigns never share it
//   rows/NNNNNNNN.json  one row per finished run, written atomically (temporary name, then
//                     rename): a row is whole or absent, so a rerun of the same command
//                     resumes, skipping runs that have a row
//   runs.csv, campaign.h5  the table of every row (docs/design.md section 7), rewritten at
//                     the end of every batch, also an interrupted one
//   runs/NNNNNNNN/    run.h5 and summary.json of each run, only with keep_runs
//
// A run that fails (integrator, static start) or passes its wall-clock limit is a row
// with that status and the campaign goes on. A stop request (SIGINT/SIGTERM) ends every
// run at its next output row; those runs get no row and are done again on resume.
#pragma once

#include <cstdint>
#include <exception>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scenarios/campaign.h"
#include "tools/simulation/batch_mpi.h"
#include "tools/simulation/run.h"

namespace moorsim::simulation {

/// The scalar statistic each detector type compares with its alarm threshold, and a grid of
/// thresholds for ROC curves (false alarms per hour vs detection within T).
struct DetectorStatistic {
  std::string description;         ///< what the number is
  std::vector<double> thresholds;  ///< increasing
};
/// For "dht", "mle", "glr"; an empty grid for other types (no ROC recorded).
DetectorStatistic StatisticOf(const std::string& detector_type);
/// The statistic of one verdict: DHT max_k>=1 posterior; MLE max_k>=1 (J_0 - J_k); GLR g.
/// NaN when the verdict has no score yet.
double StatisticValue(const std::string& detector_type, const std::vector<double>& score);

/// The ROC record of one detector over one run: upcrossings of each threshold before the
/// failure (in the whole run without one) and the first time at or after the failure
/// that the statistic reaches each threshold. Holds are not applied (a crossing counts
/// at once), so the grid shows the statistic's separation, not the configured rule.
class StatisticTrace {
 public:
  StatisticTrace(std::string type, double failure_time);  // failure_time NaN = intact
  void Add(double t, const std::vector<double>& score);
  nlohmann::json ToJson() const;

 private:
  std::string type_;
  double failure_time_;
  std::vector<double> thresholds_;
  std::vector<std::int64_t> false_crossings_;
  std::vector<double> first_crossing_;
  double max_before_ = std::numeric_limits<double>::quiet_NaN();
  double previous_ = std::numeric_limits<double>::quiet_NaN();
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

/// The campaign's runs and everything checked before the first run starts.
struct PreparedCampaign {
  scenarios::Campaign campaign;
  std::vector<scenarios::CampaignRun> runs;
  /// Per run: the scenario's truth and detectors, as loaded.
  struct Truth {
    int failure_line = 0;
    double failure_time = std::numeric_limits<double>::quiet_NaN();
    std::string failure_mode;
    double duration = 0.0;
    int num_lines = 0;
    std::vector<std::pair<std::string, std::string>> detectors;  ///< (label, type)
  };
  /// The truth of each distinct configuration, and which one each run has: runs that
  /// differ only in their seed share one (a campaign of millions of seeds holds a few).
  std::vector<Truth> truths;
  std::vector<std::uint32_t> truth_of;
  const Truth& TruthOf(std::int64_t run) const {
    return truths[truth_of[static_cast<std::size_t>(run)]];
  }
  /// Simulated seconds in all runs (for the estimate).
  double simulated_seconds = 0.0;
  /// The plugin libraries the runs' scenarios name (`plugin:`), in order without repeats.
  std::vector<std::string> plugin_paths;
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

/// Loads the campaign and the scenario of every distinct configuration (the runs' overrides
/// but the seed: runs that differ only in their seed share one load), checks the detectors
/// of each. Throws InputError naming the campaign file, the run and the scenario's message.
/// `stop_requested` is asked as it goes (PreparationStopped); `progress` shows a line on
/// stderr while it takes more than a second.
PreparedCampaign PrepareCampaign(const std::string& campaign_path,
                                 const std::function<int()>& stop_requested = {},
                                 bool progress = false);

/// The row of one finished run (DIR/rows/*.json).
nlohmann::json MakeRow(const PreparedCampaign& prepared, const scenarios::CampaignRun& run,
                       const RunResult& result, const std::vector<StatisticTrace>& traces,
                       const std::string& out_dir);

struct BatchResult {
  int exit_code = 0;  ///< 0 all ok, 1 some run failed or timed out, 2 rejected, 128+signal
  std::string message;
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

/// `moorsim batch --dry-run`: the runs (index, block, seed, factors) and the estimated wall
/// time on `threads` threads, as text.
std::string DescribeCampaign(const PreparedCampaign& prepared, int threads);

/// Reads every row under each of `directories` (the same campaign, e.g. shards) and
/// writes the campaign's tables into `out` (rows copied there too). Throws Error/InputError.
void MergeCampaigns(const std::vector<std::filesystem::path>& directories,
                    const std::filesystem::path& out, const std::string& command_line);

/// Writes DIR/runs.csv and DIR/campaign.h5 from the rows (any order; sorted by run).
void WriteCampaignTables(const std::filesystem::path& directory, const std::string& campaign_text,
                         const std::string& campaign_name, const std::string& campaign_path,
                         std::uint64_t campaign_seed, const std::vector<std::string>& factor_keys,
                         std::vector<nlohmann::json> rows, const std::string& command_line);

/// Reads DIR/rows/*.json (a row that does not parse is skipped: its run is done again).
std::vector<nlohmann::json> ReadRows(const std::filesystem::path& directory);

}  // namespace moorsim::simulation
