// One exception family for the whole program. The CLI maps InputError to exit code 2
// (bad scenario, bad flag) and every other Error to exit code 1 (a run that failed).
#pragma once

#include <stdexcept>
#include <string>

namespace moorsim {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad user input. The message already names file:line:col, the key path, the value and
/// the constraint it breaks, e.g.
/// "seed.yaml:12:15: mooring.lines[3].segments: 0 must be >= 2".
class InputError : public Error {
 public:
  using Error::Error;
};

/// A numerical failure during a run; the message names the time and the solver flag.
class SolverError : public Error {
 public:
  using Error::Error;
};

/// A broken programming contract (wrong sizes, a call out of order): a bug, reported as a
/// failed run rather than an abort.
class ContractError : public Error {
 public:
  using Error::Error;
};

}  // namespace moorsim
