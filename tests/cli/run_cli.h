// Runs the built `moorsim` binary (MOORSIM_CLI) as a child process and captures its exit
// status, stdout and stderr separately, for the CLI tests. stdout and stderr go to two temp
// files (no pipes, so a chatty child cannot deadlock the test); a child that outlives the
// time limit is killed and reported as such, so a hang fails one test instead of the suite.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace moorsim::testing {

struct CliResult {
  int exit_code = -1;      // WEXITSTATUS, or -1 if the child did not exit normally
  int signal = 0;          // WTERMSIG if the child was killed by a signal (a crash)
  bool timed_out = false;  // killed by RunCli after the time limit
  std::string out;         // everything the child wrote to stdout
  std::string err;         // everything the child wrote to stderr

  /// For assertion messages: the whole result in a few lines.
  std::string Describe() const {
    std::ostringstream s;
    s << "exit code " << exit_code;
    if (signal != 0) s << ", killed by signal " << signal << " (" << strsignal(signal) << ")";
    if (timed_out) s << ", timed out";
    s << "\n--- stderr ---\n" << err << "--- stdout ---\n" << out << "---";
    return s.str();
  }
};

/// A fresh directory of its own under `root` (e.g. ::testing::TempDir()); removed by the
/// destructor. Tests may run in parallel processes, so every test makes its own.
class TempDirectory {
 public:
  explicit TempDirectory(const std::string& root) {
    std::string pattern = (std::filesystem::path(root) / "moorsim_cli_XXXXXX").string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (mkdtemp(buffer.data()) == nullptr) {
      throw std::runtime_error("mkdtemp(" + pattern + "): " + std::strerror(errno));
    }
    path_ = buffer.data();
  }
  ~TempDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDirectory(const TempDirectory&) = delete;
  TempDirectory& operator=(const TempDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The library's seed case: the turret-moored FPSO on eight chain lines in 1000 m of water.
inline const std::string kSeed = MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml";

inline std::string ReadWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void WriteWholeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

/// Where a started program's standard stream goes: a file (created or emptied), a
/// descriptor of the test's own (a pipe's end), or, with neither, the test's own stream.
struct Redirect {
  std::filesystem::path file;
  int fd = -1;
};

/// Starts `program args...` in the background with its stdout and stderr redirected, stdin
/// from `stdin_fd` (-1: /dev/null); returns its pid. For tests that signal or feed a running
/// command. Throws std::runtime_error if it cannot start.
inline pid_t StartProgram(const std::string& program, const std::vector<std::string>& args,
                          const Redirect& out, const Redirect& err = {}, int stdin_fd = -1) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (stdin_fd >= 0) {
    posix_spawn_file_actions_adddup2(&actions, stdin_fd, STDIN_FILENO);
  } else {
    posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  }
  const auto to = [&](int fd, const Redirect& where) {
    if (where.fd >= 0) {
      posix_spawn_file_actions_adddup2(&actions, where.fd, fd);
    } else if (!where.file.empty()) {
      posix_spawn_file_actions_addopen(&actions, fd, where.file.c_str(),
                                       O_WRONLY | O_CREAT | O_TRUNC, 0644);
    }
  };
  to(STDOUT_FILENO, out);
  to(STDERR_FILENO, err);

  std::vector<std::string> argv_text;
  argv_text.push_back(program);
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);

  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    throw std::runtime_error("posix_spawn(" + program + "): " + std::strerror(spawned));
  }
  return pid;
}

/// Starts the built moorsim (MOORSIM_CLI) with `args`, as StartProgram does.
inline pid_t StartCli(const std::vector<std::string>& args, const Redirect& out,
                      const Redirect& err = {}, int stdin_fd = -1) {
  return StartProgram(MOORSIM_CLI, args, out, err, stdin_fd);
}

/// Runs `program args...` with stdout and stderr captured through files in `scratch`.
/// Throws std::runtime_error if the process cannot be started at all.
inline CliResult RunProgram(const std::string& program, const std::vector<std::string>& args,
                            const std::filesystem::path& scratch,
                            std::chrono::seconds time_limit = std::chrono::seconds(60)) {
  const std::filesystem::path out_path = scratch / "cli_stdout.txt";
  const std::filesystem::path err_path = scratch / "cli_stderr.txt";
  const pid_t pid = StartProgram(program, args, {out_path}, {err_path});

  CliResult result;
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + time_limit;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    }
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);  // our own child, by its id
      waitpid(pid, &status, 0);
      result.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  result.out = ReadWholeFile(out_path);
  result.err = ReadWholeFile(err_path);
  return result;
}

/// Runs the built moorsim (MOORSIM_CLI) with `args`.
inline CliResult RunCli(const std::vector<std::string>& args, const std::filesystem::path& scratch,
                        std::chrono::seconds time_limit = std::chrono::seconds(60)) {
  return RunProgram(MOORSIM_CLI, args, scratch, time_limit);
}

}  // namespace moorsim::testing
