#include "io/directory_lock.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "core/error.h"

namespace moorsim::output {
namespace {

/// The pid the holder wrote into the lock file, or "" if it has not (yet).
std::string HolderPid(int fd) {
  char text[32] = {};
  const ssize_t n = ::pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, n > 0 ? static_cast<std::size_t>(n) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return "";
  return pid;
}

}  // namespace

DirectoryLock::DirectoryLock(const std::filesystem::path& directory, const std::string& option) {
  // Built in steps: GCC 12 warns (-Wrestrict, a false positive) on " " + string + ": ".
  std::string where = " ";
  where += directory.string();
  where += ": ";
  std::error_code error;
  if (std::filesystem::exists(directory, error) &&
      !std::filesystem::is_directory(directory, error)) {
    throw OptionError(option, where + "is a file, not a directory");
  }
  std::filesystem::create_directories(directory, error);
  if (error) throw OptionError(option, where + "cannot create the directory: " + error.message());
  const std::filesystem::path path = directory / kFileName;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw OptionError(option, where + "cannot write in the directory: " + std::strerror(errno));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const std::string pid = HolderPid(fd_);
    ::close(fd_);
    fd_ = -1;
    throw OptionError(option, where + "in use by another moorsim" +
                                  (pid.empty() ? std::string() : " (pid " + pid + ")") +
                                  "; wait for it to finish or choose another directory");
  }
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) < 0) {
    // The pid is only informative; the lock is what matters.
  }
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace moorsim::output
