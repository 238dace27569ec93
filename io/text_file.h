// A text file written with write(2): every write checked, so that a full disk is an error
// naming the file and never a silently short file; Sync makes what was written durable.
// Used for the files that must survive a kill or say why they could not be written
// (summary.json, a live monitor's alarms.csv).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace moorsim::output {

class TextFile {
 public:
  /// Creates or empties `path`. Failures throw moorsim::Error "<name>: <what>: <reason>",
  /// where `name` is the file's name for its reader (the final name of a file written under
  /// a temporary one); empty: `path`.
  explicit TextFile(const std::filesystem::path& path, const std::filesystem::path& name = {});
  ~TextFile();
  TextFile(const TextFile&) = delete;
  TextFile& operator=(const TextFile&) = delete;

  void Write(std::string_view text);
  /// fsync (a file system that cannot, such as a pipe's, is not an error).
  void Sync();
  void Close();

 private:
  [[noreturn]] void Fail(const char* what) const;

  std::filesystem::path name_;
  int fd_;
};

/// Where a file that must appear only when complete is written first: PATH.partial.
std::filesystem::path PartialPath(const std::filesystem::path& path);

/// Gives PATH.partial its name PATH. Throws moorsim::Error "<PATH>: rename failed: ..."
/// (the partial file then stays, for its writer to remove).
void PublishPartial(const std::filesystem::path& path);

}  // namespace moorsim::output
