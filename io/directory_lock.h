// One moorsim process at a time in an output directory: `run`, `detect` and `batch` hold an
// exclusive flock on DIR/moorsim.lock while they write DIR, so two processes never write,
// rename or remove each other's files there.
#pragma once

#include <filesystem>
#include <string>

namespace moorsim::output {

/// Creates `directory` (and its parents) if missing and takes an exclusive, non-blocking
/// flock on directory/moorsim.lock for the object's lifetime. The kernel releases the lock
/// when the process ends, however it ends. The lock file itself stays: removing it would let
/// a process that has just opened it lock an orphan while a third locks a new one.
///
/// Throws OptionError, about the option `option` that gave the directory (one line: the
/// option, the directory, what is wrong): a file is in the way,
/// the directory cannot be created or written (the system's reason, e.g. a read-only file
/// system), or another moorsim holds it (its pid when known).
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::filesystem::path& directory, const std::string& option = "out");
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

  /// The name of the lock file in every directory moorsim writes.
  static constexpr const char* kFileName = "moorsim.lock";

 private:
  int fd_ = -1;
};

}  // namespace moorsim::output
