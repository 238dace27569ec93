// `moorsim batch`: a Monte-Carlo campaign (scenarios/campaign.h) run by the library's
// RunBatch (campaign/batch.h) on OpenMP threads; `--merge` joins shard directories.
#include <cstdio>
#include <iostream>
#include <iterator>
#include <memory>
#include <string>

#include "campaign/batch.h"
#include "core/error.h"
#include "detectors/registry.h"
#include "tools/commands.h"
#include "tools/exit_codes.h"

namespace moorsim::cli {
namespace {

struct BatchCommandOptions {
  std::string campaign;
  std::optional<std::string> out;
  std::optional<std::string> threads;
  std::optional<std::string> shard;
  std::optional<std::string> run_timeout;
  std::vector<std::string> merge;
  bool keep_runs = false;
  bool dry_run = false;
  bool quiet = false;
  std::string command_line;
};

// "K/N" with 1 <= K <= N.
std::pair<int, int> ParseShard(const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) {
    throw InputError("--shard " + text + ": expected K/N (e.g. 3/10: the third of ten shards)");
  }
  const int n = ParseInteger("--shard", text.substr(slash + 1), 1, 1'000'000);
  const int k = ParseInteger("--shard", text.substr(0, slash), 1, n);
  return {k - 1, n};
}

int Batch(const BatchCommandOptions& o) {
  if (!o.merge.empty()) {
    if (!o.campaign.empty()) throw InputError("--merge: give directories only, no campaign file");
    if (!o.out) throw InputError("--merge needs --out DIR for the joined results");
    std::vector<std::filesystem::path> dirs(o.merge.begin(), o.merge.end());
    const simulation::MergeResult merged =
        simulation::MergeCampaigns(dirs, RequireText("--out", *o.out), o.command_line);
    std::fprintf(stderr, "moorsim batch: merged %zu %s -> %s: %lld of %lld runs\n", dirs.size(),
                 dirs.size() == 1 ? "directory" : "directories", o.out->c_str(),
                 static_cast<long long>(merged.runs - std::ssize(merged.missing)),
                 static_cast<long long>(merged.runs));
    if (!merged.missing.empty()) {
      // The tables hold what was merged; a report of them speaks of those runs only.
      std::string runs;
      for (std::size_t k = 0; k < merged.missing.size() && k < 10; ++k) {
        runs += (k ? ", " : "") + std::to_string(merged.missing[k]);
      }
      if (merged.missing.size() > 10) runs += ", ...";
      std::fprintf(stderr,
                   "moorsim batch: warning: the campaign is incomplete: %zu runs have no row "
                   "(runs %s); merge the other shards, or run the campaign with --out %s to "
                   "finish it\n",
                   merged.missing.size(), runs.c_str(), o.out->c_str());
    }
    return 0;
  }
  if (o.campaign.empty()) throw InputError("batch: give a campaign file (or --merge DIR...)");
  simulation::BatchOptions options;
  options.campaign_path = o.campaign;
  if (o.out) options.out = RequireText("--out", *o.out);
  if (o.threads) options.threads = ParseInteger("--threads", *o.threads, 1, 4096);
  if (o.shard) std::tie(options.shard_index, options.shard_count) = ParseShard(*o.shard);
  if (o.run_timeout) {
    options.run_timeout = ParseNumber("--run-timeout", *o.run_timeout);
    if (!(options.run_timeout > 0.0) || options.run_timeout > 1e7) {
      throw InputError("--run-timeout " + *o.run_timeout + ": must be in (0, 1e7] seconds");
    }
  }
  options.keep_runs = o.keep_runs;
  options.progress = !o.quiet;
  options.command_line = o.command_line;
  if (o.dry_run) {
    const simulation::PreparedCampaign prepared =
        simulation::PrepareCampaign(o.campaign, {}, !o.quiet);
    const int threads = options.threads > 0 ? options.threads : simulation::DefaultThreads();
    simulation::DescribeCampaign(prepared, threads, std::cout);
    return 0;
  }
  // Under mpirun: MPI from here to the end of the batch; rank 0 alone speaks.
  struct MpiGuard {
    simulation::MpiSession session;
    ~MpiGuard() { simulation::FinishMpi(session); }
  } mpi{simulation::StartMpi(nullptr, nullptr)};
  options.mpi = mpi.session;
  const bool speaks = mpi.session.rank == 0;
  options.progress = options.progress && speaks;
  runner::InstallStopSignalHandlers();
  options.stop_requested = runner::StopSignal;
  const simulation::BatchResult result = simulation::RunBatch(options);
  if (!speaks) return ExitCodeOf(result);
  if (!result.message.empty()) {
    std::cerr << "moorsim: " << FlagMessage(result.message, result.option_error) << "\n";
  }
  if (result.heading_lost > 0) {
    // Not an error (a campaign may mean to test it), but never silent: such runs met the
    // waves from another side than their factors say.
    std::fprintf(stderr,
                 "moorsim batch: warning: %lld runs left their setpoint heading by more than "
                 "%g deg (the thrust could not hold it: heading_error_max_deg and "
                 "thrust_saturated_share in runs.csv)\n",
                 static_cast<long long>(result.heading_lost), simulation::kHeadingLostDeg);
  }
  if (result.status != simulation::BatchStatus::kRejected && !o.quiet) {
    std::fprintf(stderr,
                 "moorsim batch: %lld runs in this shard: %lld done now, %lld already done, "
                 "%lld not ok%s -> %s\n",
                 static_cast<long long>(result.runs), static_cast<long long>(result.done),
                 static_cast<long long>(result.skipped), static_cast<long long>(result.failed),
                 mpi.session.size > 1
                     ? (" (" + std::to_string(mpi.session.size) + " MPI ranks)").c_str()
                     : "",
                 result.directory.string().c_str());
  }
  return ExitCodeOf(result);
}

}  // namespace

Command AddBatchCommand(CLI::App& app, int argc, char** argv) {
  auto o = std::make_shared<BatchCommandOptions>();
  for (int i = 0; i < argc; ++i) {
    o->command_line += (i ? " " : "") + scenarios::ShellQuote(argv[i]);
  }
  CLI::App* sub =
      app.add_subcommand("batch", "run a Monte-Carlo campaign of many runs on all cores");
  sub->add_option("campaign", o->campaign, "campaign YAML file");
  sub->footer(
      "\nWrites DIR/runs.csv and DIR/campaign.h5 (one row per run), DIR/rows/ (a file per\n"
      "finished run: rerunning the same command resumes) and, with --keep-runs, every run's\n"
      "run.h5 under DIR/runs/. DIR/campaign.json identifies the campaign by the SHA-256 of\n"
      "its files (campaign, scenarios, WAMIT data, plugins): a directory of another campaign,\n"
      "or of one whose files changed, is refused (exit 2), by a batch and by --merge.\n"
      "tools/report.py DIR writes the report. Exit codes: 0 every run\n"
      "ok, 1 some run failed or timed out (recorded in the table), 2 bad input, 130/143\n"
      "interrupted by SIGINT/SIGTERM (finished runs are kept; the same command resumes).\n\n" +
      detectors::DetectorHelp());
  sub->add_option("--out", o->out, "results directory (default out/<campaign name>)");
  sub->add_option("--threads", o->threads, "runs at once (default: every core)");
  sub->add_option("--shard", o->shard, "K/N: only every N-th run from the K-th (job arrays)");
  sub->add_option("--run-timeout", o->run_timeout,
                  "wall-clock limit per run [s] (default none); a run past it is recorded as "
                  "timeout");
  sub->add_option("--merge", o->merge, "join these shard directories into --out")->expected(1, -1);
  sub->add_flag("--keep-runs", o->keep_runs, "keep every run's run.h5 and summary.json");
  sub->add_flag(
      "--dry-run", o->dry_run,
      "list every run (each loaded and checked) and the estimated wall time; run nothing");
  sub->add_flag("--quiet", o->quiet, "no progress line on stderr");
  AddPluginOption(sub);
  return [o] { return Batch(*o); };
}

}  // namespace moorsim::cli
