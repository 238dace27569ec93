// moorsim batch across MPI ranks (`mpirun -np R moorsim batch ...`): rank 0 owns the
// campaign directory and deals runs out one at a time on request (dynamic work sharing: a
// slow run never idles the others), receives every finished row and alone writes them and
// the tables; every rank runs its own OpenMP threads. The same binary runs without mpirun
// as a plain threaded batch: MPI is initialised only when a launcher started the process.
//
// Protocol (MPI_COMM_WORLD, rank 0's service thread answers; a worker rank's threads take
// turns under a mutex, so MPI_THREAD_SERIALIZED suffices):
//   worker -> 0  kRequest (empty)               0 -> worker  kIndex: NextRun (int64 run,
//                                                                  -1 none, -2 not yet; double)
//   worker -> 0  kRow: int64 run, ok byte, the row's JSON text
//   worker -> 0  kFinished (empty) once its threads are done
// Built without MPI (no libopenmpi-dev at configure time), a launch by mpirun with more
// than one rank is refused with a message instead of running the campaign R times.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace moorsim::simulation {

/// What a worker does next: a run (index >= 0), with the failure time a transient run takes
/// from its intact run (NaN: its own); kNoRun when none is left (or the batch is stopping);
/// kNotYet when the runs left wait for rows still being made (ask again shortly).
struct NextRun {
  static constexpr std::int64_t kNoRun = -1;
  static constexpr std::int64_t kNotYet = -2;
  std::int64_t index = kNoRun;
  double failure_time = std::numeric_limits<double>::quiet_NaN();
};

/// Where a worker thread gets its next run and where its finished row goes.
class RunSource {
 public:
  virtual ~RunSource() = default;
  virtual NextRun Next() = 0;
  /// A finished run's row; `ok` says whether its status is ok.
  virtual void Deliver(std::int64_t run, const std::string& row, bool ok) = 0;
};

struct MpiSession {
  bool active = false;  ///< MPI initialised (started by a launcher)
  int rank = 0;
  int size = 1;
};

/// Initialises MPI if a launcher (mpirun, srun) started this process; call once, first
/// thing. Throws Error if launched with several ranks but built without MPI.
MpiSession StartMpi(int* argc, char*** argv);
/// MPI_Finalize if StartMpi initialised it.
void FinishMpi(const MpiSession& session);

/// Rank 0 tells the other ranks whether the batch goes ahead (0) or stops (a nonzero code);
/// every rank calls it and gets rank 0's value.
int BroadcastDecision(const MpiSession& session, int decision);

/// Rank 0: answers the other ranks from `local` until each has said it finished. `stop`
/// nonzero makes every later request get "none". Blocks; run it on its own thread.
void ServeRemoteWorkers(const MpiSession& session, RunSource& local,
                        const std::function<int()>& stop);

/// Ranks > 0: a RunSource that asks rank 0.
std::unique_ptr<RunSource> RemoteRunSource(const MpiSession& session);
/// Ranks > 0: tells rank 0 this rank's threads are done.
void NotifyFinished(const MpiSession& session);

}  // namespace moorsim::simulation
