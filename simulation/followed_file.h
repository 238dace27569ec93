// A log file followed as it grows, line by line, the way `tail -F` follows it: through
// rotation by copy-and-truncate (the file shrinks), by rename-and-create (a new file appears
// at the path) and through a rewrite in place (the file is written again from its start,
// possibly longer than before). Each rotation is reported once, so that the reader can say
// so and start the new file's lines afresh; rows are never read from the middle of a line.
#pragma once

#include <sys/types.h>

#include <functional>
#include <string>

namespace moorsim::simulation {

/// What happened to a followed file between two reads.
enum class Rotation {
  kTruncated,  // shorter than what was read: read again from its start
  kRewritten,  // the bytes already read changed: read again from its start
  kReplaced,   // another file now sits at the path: the old one was read to its end first
  kMissing,    // nothing at the path any more: the old file is still read, the path watched
};

/// "truncated", "rewritten", ...: for messages.
const char* RotationName(Rotation rotation);

class FollowedFile {
 public:
  /// Opens `path` (throws InputError naming it if it cannot be read). `poll_ms` is the wait
  /// between two looks at a file that has not grown.
  explicit FollowedFile(std::string path, int poll_ms = 50);
  ~FollowedFile();
  FollowedFile(const FollowedFile&) = delete;
  FollowedFile& operator=(const FollowedFile&) = delete;

  /// The next complete line (without its newline). At the end of the file, waits for more
  /// until `stop()` returns true; then returns a last line that has no newline yet, if any,
  /// and false after it. `on_rotation` is called once per rotation before the first line
  /// of the new content; a partial line the rotation cut off is dropped, and
  /// `dropped_bytes` says how long it was.
  bool Next(std::string* line, const std::function<bool()>& stop,
            const std::function<void(Rotation rotation, std::size_t dropped_bytes)>& on_rotation);

  const std::string& path() const { return path_; }

 private:
  // Reads what the file has after offset_ into buffer_; returns the bytes read.
  std::size_t ReadMore();
  // Looks at the path and the open file for a rotation; reopens or rewinds as needed.
  bool CheckRotation(Rotation* rotation);
  void Rewind();
  void Reopen(int fd);
  // Whether the file still holds `bytes` just before offset `end`.
  bool HasBytesAt(const std::string& bytes, off_t end) const;

  std::string path_;
  int poll_ms_;
  int fd_ = -1;
  dev_t device_ = 0;
  ino_t inode_ = 0;
  off_t offset_ = 0;      // bytes of the open file consumed into buffer_
  std::string buffer_;    // bytes read and not yet returned as lines
  std::string tail_;      // the last bytes read before offset_, to notice a rewrite
  bool missing_ = false;  // kMissing reported, the path not yet back
};

}  // namespace moorsim::simulation
