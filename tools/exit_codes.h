// The program's exit codes, from the library's results (docs/design.md section 2): 0 ok,
// 1 failed (a run that failed or timed out, a batch with such runs or that failed itself),
// 2 bad input, 128 + signal when interrupted; and the library's messages about its options
// in the command line's words.
#pragma once

#include <memory>
#include <string>

#include "campaign/batch.h"
#include "core/error.h"
#include "runner/run.h"

namespace moorsim::cli {

int ExitCodeOf(const runner::RunResult& result);
int ExitCodeOf(const simulation::BatchResult& result);

/// A library error about its options as the command line names them: the library's "out",
/// "run_timeout", "set" are the flags --out, --run-timeout, --set.
std::string FlagMessage(const OptionError& error);
/// A result's message, its options (if it was about them) named as flags.
std::string FlagMessage(const std::string& message,
                        const std::shared_ptr<const OptionError>& error);

}  // namespace moorsim::cli
