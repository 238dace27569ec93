// One exception family for the whole program. The CLI maps InputError to exit code 2
// (bad scenario, bad flag) and every other Error to exit code 1 (a run that failed).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

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

/// Bad input given through one or more of a call's named options (fields of its request,
/// overrides), named as the library names them ("out", "run_timeout", "set"): the message
/// is the options' names joined by ", " and then `rest`. A caller that offers the options
/// under its own names (the command line's flags, "--run-timeout") shows Renamed().
class OptionError : public InputError {
 public:
  OptionError(std::vector<std::string> options, const std::string& rest)
      : InputError(Join(options) + rest), options_(std::move(options)), rest_(rest) {}
  OptionError(const std::string& option, const std::string& rest)
      : OptionError(std::vector<std::string>{option}, rest) {}
  const std::vector<std::string>& options() const { return options_; }
  /// The message with each option's name passed through `rename`.
  template <typename Rename>
  std::string Renamed(Rename rename) const {
    std::vector<std::string> names;
    for (const std::string& o : options_) names.push_back(rename(o));
    return Join(names) + rest_;
  }

 private:
  static std::string Join(const std::vector<std::string>& names) {
    std::string joined;
    for (const std::string& n : names) joined += (joined.empty() ? "" : ", ") + n;
    return joined;
  }
  std::vector<std::string> options_;
  std::string rest_;
};

/// A numerical failure during a run; the message names the time and the solver flag.
class SolverError : public Error {
 public:
  using Error::Error;
};

/// A long call stopped on request (Ctrl-C, an API's interrupt) before it was done; the
/// message names the time reached. What the call leaves behind its own documentation says.
class Interrupted : public Error {
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
