// The program's exit codes, from the library's results (docs/design.md section 2): 0 ok,
// 1 failed (a run that failed or timed out, a batch with such runs or that failed itself),
// 2 bad input, 128 + signal when interrupted.
#pragma once

#include "campaign/batch.h"
#include "simulation/run.h"

namespace moorsim::cli {

int ExitCodeOf(const simulation::RunResult& result);
int ExitCodeOf(const simulation::BatchResult& result);

}  // namespace moorsim::cli
