// One coupled run of a scenario as a library call: what `moorsim run` does, what the batch
// runner and the tests call. It loads and checks the scenario, simulates, writes run.h5 and
// summary.json, and returns a status; no exception escapes.
//
// Outputs are never a lie (docs/design.md section 7):
// * the output directory is held (output::DirectoryLock, DIR/moorsim.lock) for the whole
//   run: a second moorsim writing the same directory is refused with kRejected, and a run
//   removes only files it created or the previous run's outputs in the directory it holds;
// * run.h5 and summary.json are written under temporary names (".partial") and renamed into
//   place at the end, the old summary.json removed first, so an old complete result is
//   never paired with a new partial one: a run.h5 without a summary.json is incomplete;
// * run.h5 is flushed every `flush_rows` rows, so a run killed outright leaves a
//   run.h5.partial that opens and holds the rows up to the last flush;
// * a stop request (SIGINT/SIGTERM through InstallStopSignalHandlers) ends the run at the
//   next output row: the file is closed with every row so far and summary.json says
//   "interrupted" with the simulated time reached;
// * every write is checked; when run.h5 cannot be written (disk full) the run stops, the
//   broken file is removed, and summary.json says "failed" with the reason if it fits;
//   summary.json names run.h5 only once run.h5 is in place.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "scenarios/scenario.h"
#include "simulation/simulation.h"

namespace moorsim::runner {

enum class RunStatus {
  kOk,           ///< simulated to the end, outputs written
  kFailed,       ///< the integrator, the static start or an output write failed
  kInterrupted,  ///< stopped on request (a signal) before the end
  kRejected,     ///< bad input: nothing was simulated or written
  kTimedOut,     ///< stopped at its wall-clock deadline (RunRequest::deadline)
};

/// "ok", "failed", "interrupted", "rejected", "timeout": the summary's "status".
const char* StatusName(RunStatus status);

struct RunRequest {
  std::string scenario_path;
  /// key.path=value overrides, in order (the `--set` flags, then --seed/--duration).
  std::vector<std::string> overrides;
  /// The scenario, already loaded from `scenario_path` with `overrides` (a campaign's
  /// thread loads it first for the run's truth); null: RunScenario loads it.
  std::shared_ptr<const scenarios::Scenario> scenario;
  /// Output directory; empty = out/<scenario name>.
  std::filesystem::path out;
  /// Progress lines on stderr (every ~2 s of wall time).
  bool progress = false;
  /// run.h5 is flushed to disk every this many rows.
  long flush_rows = 256;
  /// Asked after every output row: a nonzero value (a signal number) stops the run there.
  std::function<int()> stop_requested;
  /// Wall-clock limit: checked after every output row; reaching it stops the run there
  /// with status timeout.
  std::optional<std::chrono::steady_clock::time_point> deadline;
  /// False: write no files at all (no directory, run.h5 or summary.json); the summary is
  /// still built and returned. A campaign's runs are kept this way unless asked.
  bool write_files = true;
  /// Called with every output row, in order, after it is recorded.
  std::function<void(const simulation::Sample&)> on_row;
};

struct RunResult {
  RunStatus status = RunStatus::kRejected;
  /// Why the run did not complete (empty when ok): one line.
  std::string message;
  /// A rejection about one of the request's options (an override): the error, whose
  /// options a caller may name its own way (OptionError::Renamed).
  std::shared_ptr<const OptionError> option_error;
  /// The signal that interrupted the run (0 if none).
  int signal = 0;
  std::filesystem::path directory;
  double simulated_time = 0.0;
  /// summary.json as written (empty for a rejected run).
  nlohmann::json summary;
  /// False if summary.json could not be written (the reason is in message).
  bool summary_written = false;
};

/// Runs the scenario as described above. Never throws (std::bad_alloc aside).
RunResult RunScenario(const RunRequest& request) noexcept;

/// Writes `text` to `path` through `path`.partial, checking every write, the flush and
/// the close, then renames it into place. Throws moorsim::Error naming the file and the
/// system's reason; the partial file is removed on failure.
void WriteFileAtomically(const std::filesystem::path& path, const std::string& text);
/// The same for files that belong together (a scenario and the files it names): each is
/// written whole to its partial file before any is renamed, so that a failure (a full disk)
/// leaves none of them new and no partial file behind.
void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

/// Makes SIGINT and SIGTERM set a flag that StopSignal() returns, instead of killing the
/// process; a second signal of the same kind kills as usual.
void InstallStopSignalHandlers();
/// The signal number caught since InstallStopSignalHandlers, 0 if none.
int StopSignal();

}  // namespace moorsim::runner
