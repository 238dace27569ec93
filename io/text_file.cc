#include "io/text_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

#include "core/error.h"

namespace moorsim::output {

TextFile::TextFile(const std::filesystem::path& path, const std::filesystem::path& name)
    : name_(name.empty() ? path : name),
      fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)) {
  if (fd_ < 0) Fail("cannot create");
}

TextFile::~TextFile() {
  if (fd_ >= 0) ::close(fd_);
}

void TextFile::Write(std::string_view text) {
  for (std::size_t written = 0; written < text.size();) {
    const ssize_t n = ::write(fd_, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      Fail("write failed");
    }
    written += static_cast<std::size_t>(n);
  }
}

void TextFile::Sync() {
  if (::fsync(fd_) != 0 && errno != EINVAL) Fail("fsync failed");
}

void TextFile::Close() {
  if (::close(std::exchange(fd_, -1)) != 0) Fail("close failed");
}

void TextFile::Fail(const char* what) const {
  throw Error(name_.string() + ": " + what + ": " + std::strerror(errno));
}

std::filesystem::path PartialPath(const std::filesystem::path& path) {
  return path.string() + ".partial";
}

void PublishPartial(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::rename(PartialPath(path), path, error);
  if (error) throw Error(path.string() + ": rename failed: " + error.message());
}

}  // namespace moorsim::output
