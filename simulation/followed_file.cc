#include "simulation/followed_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>
#include <utility>

#include "core/error.h"

namespace moorsim::simulation {
namespace {

// How many of the last bytes read are kept to notice a rewrite: a few rows of a pose log,
// whose times increase, so that a rewritten file cannot match them by chance.
constexpr std::size_t kTailBytes = 256;
constexpr std::size_t kReadBytes = 1 << 16;

}  // namespace

const char* RotationName(Rotation rotation) {
  switch (rotation) {
    case Rotation::kTruncated:
      return "truncated";
    case Rotation::kRewritten:
      return "rewritten";
    case Rotation::kReplaced:
      return "replaced";
    case Rotation::kMissing:
      return "missing";
  }
  return "?";
}

FollowedFile::FollowedFile(std::string path, int poll_ms)
    : path_(std::move(path)), poll_ms_(poll_ms) {
  const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path_ + ": cannot be read: " + std::strerror(errno));
  Reopen(fd);
}

FollowedFile::~FollowedFile() {
  if (fd_ >= 0) ::close(fd_);
}

void FollowedFile::Reopen(int fd) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = fd;
  struct stat status {};
  if (::fstat(fd_, &status) == 0) {
    device_ = status.st_dev;
    inode_ = status.st_ino;
  }
  Rewind();
}

void FollowedFile::Rewind() {
  offset_ = 0;
  ::lseek(fd_, 0, SEEK_SET);
  buffer_.clear();
  tail_.clear();
}

std::size_t FollowedFile::ReadMore() {
  char chunk[kReadBytes];
  // read(), not pread(): the descriptor's offset is then what has been read (what
  // /proc/PID/fdinfo shows a monitoring tool or a test).
  const ssize_t n = ::read(fd_, chunk, sizeof chunk);
  if (n < 0) {
    if (errno == EINTR) return 0;
    throw Error(path_ + ": cannot be read: " + std::strerror(errno));
  }
  const auto count = static_cast<std::size_t>(n);
  buffer_.append(chunk, count);
  offset_ += n;
  tail_.append(chunk, count);
  if (tail_.size() > kTailBytes) tail_.erase(0, tail_.size() - kTailBytes);
  return count;
}

bool FollowedFile::HasBytesAt(const std::string& bytes, off_t end) const {
  if (bytes.empty()) return true;
  std::string now(bytes.size(), '\0');
  const off_t from = end - static_cast<off_t>(bytes.size());
  const ssize_t n = ::pread(fd_, now.data(), now.size(), from);
  return n == static_cast<ssize_t>(now.size()) && now == bytes;
}

bool FollowedFile::CheckRotation(Rotation* rotation) {
  struct stat at_path {};
  if (::stat(path_.c_str(), &at_path) != 0) {
    if (missing_) return false;
    missing_ = true;
    *rotation = Rotation::kMissing;
    return true;
  }
  if (at_path.st_dev != device_ || at_path.st_ino != inode_) {
    // What the writer added to the old file before it moved on is read first.
    if (ReadMore() > 0) return false;
    const int fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;  // gone again between stat and open: look next time
    Reopen(fd);
    missing_ = false;
    *rotation = Rotation::kReplaced;
    return true;
  }
  missing_ = false;
  struct stat open_file {};
  if (::fstat(fd_, &open_file) != 0) return false;
  if (open_file.st_size < offset_) {
    Rewind();
    *rotation = Rotation::kTruncated;
    return true;
  }
  if (!HasBytesAt(tail_, offset_)) {
    Rewind();
    *rotation = Rotation::kRewritten;
    return true;
  }
  return false;
}

bool FollowedFile::Next(
    std::string* line, const std::function<bool()>& stop,
    const std::function<void(Rotation rotation, std::size_t dropped_bytes)>& on_rotation) {
  for (;;) {
    const std::size_t newline = buffer_.find('\n');
    if (newline != std::string::npos) {
      line->assign(buffer_, 0, newline);
      buffer_.erase(0, newline + 1);
      return true;
    }
    // The file is looked at before anything new is read from it, and the bytes already
    // read are checked again after, so that a file rewritten longer is never read from the
    // old offset (a rewrite while a read is under way included).
    const std::size_t partial = buffer_.size();
    Rotation rotation{};
    if (CheckRotation(&rotation)) {
      on_rotation(rotation, rotation == Rotation::kMissing ? 0 : partial);
      continue;
    }
    const std::string before = tail_;
    const off_t before_end = offset_;
    if (ReadMore() > 0) {
      if (!HasBytesAt(before, before_end)) {
        Rewind();
        on_rotation(Rotation::kRewritten, partial);
      }
      continue;
    }
    if (stop()) {
      if (buffer_.empty()) return false;
      line->swap(buffer_);
      buffer_.clear();
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(poll_ms_));
  }
}

}  // namespace moorsim::simulation
