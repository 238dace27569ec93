#include "campaign/batch_mpi.h"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <thread>
#include <vector>

#include "core/error.h"

#ifdef MOORSIM_WITH_MPI
// The C API only: Open MPI's and MPICH's deprecated C++ bindings would need their own library.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace moorsim::simulation {
namespace {

// Whether a launcher started this process, and with how many ranks (Open MPI, PMI/PMIx as
// set by MPICH, Slurm and others).
int LaunchedRanks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* value = std::getenv(name)) return std::max(1, std::atoi(value));
  }
  return 0;
}

}  // namespace

#ifdef MOORSIM_WITH_MPI
namespace {

static_assert(std::is_trivially_copyable_v<NextRun>, "NextRun is sent as its bytes");

enum Tag : int { kRequest = 1, kIndex = 2, kRow = 3, kFinished = 4 };

void CheckMpi(int code, const char* call) {
  if (code != MPI_SUCCESS) {
    char text[MPI_MAX_ERROR_STRING];
    int length = 0;
    MPI_Error_string(code, text, &length);
    throw Error(std::string(call) +
                " failed: " + std::string(text, static_cast<std::size_t>(length)));
  }
}

class Remote final : public RunSource {
 public:
  NextRun Next() override {
    const std::lock_guard<std::mutex> guard(mutex_);
    CheckMpi(MPI_Send(nullptr, 0, MPI_CHAR, 0, kRequest, MPI_COMM_WORLD), "MPI_Send");
    NextRun next;
    CheckMpi(MPI_Recv(&next, sizeof next, MPI_BYTE, 0, kIndex, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
             "MPI_Recv");
    return next;
  }
  void Deliver(std::int64_t run, const std::string& row, bool ok) override {
    std::vector<char> message(sizeof run + 1 + row.size());
    std::memcpy(message.data(), &run, sizeof run);
    message[sizeof run] = ok ? 1 : 0;
    std::memcpy(message.data() + sizeof run + 1, row.data(), row.size());
    const std::lock_guard<std::mutex> guard(mutex_);
    CheckMpi(MPI_Send(message.data(), static_cast<int>(message.size()), MPI_CHAR, 0, kRow,
                      MPI_COMM_WORLD),
             "MPI_Send");
  }

 private:
  std::mutex mutex_;
};

}  // namespace

MpiSession StartMpi(int* argc, char*** argv) {
  MpiSession s;
  if (LaunchedRanks() == 0) return s;
  int provided = 0;
  CheckMpi(MPI_Init_thread(argc, argv, MPI_THREAD_MULTIPLE, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_SERIALIZED) {
    MPI_Finalize();
    throw Error("this MPI library offers no thread support (MPI_THREAD_SERIALIZED needed)");
  }
  s.active = true;
  CheckMpi(MPI_Comm_rank(MPI_COMM_WORLD, &s.rank), "MPI_Comm_rank");
  CheckMpi(MPI_Comm_size(MPI_COMM_WORLD, &s.size), "MPI_Comm_size");
  return s;
}

void FinishMpi(const MpiSession& session) {
  if (session.active) MPI_Finalize();
}

int BroadcastDecision(const MpiSession& session, int decision) {
  if (!session.active || session.size == 1) return decision;
  CheckMpi(MPI_Bcast(&decision, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
  return decision;
}

void ServeRemoteWorkers(const MpiSession& session, RunSource& local,
                        const std::function<int()>& stop) {
  int finished = 0;
  std::vector<char> buffer;
  while (finished < session.size - 1) {
    int waiting = 0;
    MPI_Status status;
    CheckMpi(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status),
             "MPI_Iprobe");
    if (!waiting) {
      // Polling with a short sleep: a blocking probe spins a core that a run needs.
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    int count = 0;
    CheckMpi(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
    buffer.resize(static_cast<std::size_t>(count));
    CheckMpi(MPI_Recv(buffer.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG,
                      MPI_COMM_WORLD, MPI_STATUS_IGNORE),
             "MPI_Recv");
    switch (status.MPI_TAG) {
      case kRequest: {
        NextRun next;  // the same binary on every rank: sent as its bytes
        if (stop() == 0) next = local.Next();
        CheckMpi(MPI_Send(&next, sizeof next, MPI_BYTE, status.MPI_SOURCE, kIndex, MPI_COMM_WORLD),
                 "MPI_Send");
        break;
      }
      case kRow: {
        std::int64_t run = 0;
        if (buffer.size() < sizeof run + 1) throw Error("MPI: a row message too short");
        std::memcpy(&run, buffer.data(), sizeof run);
        const bool ok = buffer[sizeof run] != 0;
        local.Deliver(run, std::string(buffer.begin() + sizeof run + 1, buffer.end()), ok);
        break;
      }
      case kFinished:
        ++finished;
        break;
      default:
        throw Error("MPI: unexpected message tag " + std::to_string(status.MPI_TAG));
    }
  }
}

std::unique_ptr<RunSource> RemoteRunSource(const MpiSession&) { return std::make_unique<Remote>(); }

void NotifyFinished(const MpiSession&) {
  CheckMpi(MPI_Send(nullptr, 0, MPI_CHAR, 0, kFinished, MPI_COMM_WORLD), "MPI_Send");
}

#else  // built without MPI

MpiSession StartMpi(int*, char***) {
  if (LaunchedRanks() > 1) {
    throw Error(
        "this moorsim was built without MPI (install libopenmpi-dev and rebuild); under "
        "mpirun every rank would run the whole campaign");
  }
  return {};
}

void FinishMpi(const MpiSession&) {}

int BroadcastDecision(const MpiSession&, int decision) { return decision; }

void ServeRemoteWorkers(const MpiSession&, RunSource&, const std::function<int()>&) {}

std::unique_ptr<RunSource> RemoteRunSource(const MpiSession&) {
  throw Error("RemoteRunSource: built without MPI");
}

void NotifyFinished(const MpiSession&) {}

#endif

}  // namespace moorsim::simulation
