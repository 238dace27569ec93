#include "tools/exit_codes.h"

#include <algorithm>

#include <csignal>

namespace moorsim::cli {

int ExitCodeOf(const runner::RunResult& result) {
  switch (result.status) {
    case runner::RunStatus::kOk:
      return 0;
    case runner::RunStatus::kFailed:
    case runner::RunStatus::kTimedOut:
      return 1;
    case runner::RunStatus::kRejected:
      return 2;
    case runner::RunStatus::kInterrupted:
      return 128 + (result.signal > 0 ? result.signal : SIGINT);
  }
  return 1;
}

int ExitCodeOf(const simulation::BatchResult& result) {
  switch (result.status) {
    case simulation::BatchStatus::kOk:
      return 0;
    case simulation::BatchStatus::kRunsFailed:
    case simulation::BatchStatus::kFailed:
      return 1;
    case simulation::BatchStatus::kRejected:
      return 2;
    case simulation::BatchStatus::kInterrupted:
      return 128 + (result.signal > 0 ? result.signal : SIGINT);
  }
  return 1;
}

std::string FlagMessage(const OptionError& error) {
  return error.Renamed([](std::string option) {
    std::replace(option.begin(), option.end(), '_', '-');
    return "--" + option;
  });
}

std::string FlagMessage(const std::string& message,
                        const std::shared_ptr<const OptionError>& error) {
  return error ? FlagMessage(*error) : message;
}

}  // namespace moorsim::cli
