// Seeded fuzz of the inputs a user hands moorsim: the library's scenario and a campaign
// file (YAML), a `moorsim detect` CSV log, and a run.h5 written by the current writer
// (truncated at many lengths and with flipped bits). Each mutated input goes through the
// library's loader or reader in a child process of its own, with a time limit, and a few
// through the built program. Whatever the damage: no crash, no hang, and an input that is
// refused is refused with an InputError (exit 2 from the CLI) whose message names the file
// on every line.
//
// Deterministic: a fixed seed, mutations drawn with the generator's raw output (no standard
// distribution, whose results differ between standard libraries) and a fixed number of
// cases per input, chosen so that the whole file takes a few seconds in the release build
// and well under 20 s under the sanitizers. A case that fails is reported with its number
// and what was done to the input, which is enough to repeat it.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "core/error.h"
#include "io/hdf5_file.h"
#include "runner/scenario_plant.h"
#include "scenarios/campaign.h"
#include "scenarios/load.h"
#include "scenarios/moordyn.h"
#include "simulation/pose_stream.h"
#include "tests/cli/run_cli.h"
#include "tests/support/moordyn_spread.h"
#include "tests/support/sanitized.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::simulation {

using runner::ReadRunScenario;
namespace {

constexpr std::uint64_t kFuzzSeed = 20261126;
const std::string kScenario = MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml";
const std::string kRunScenario = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6.yaml";
const std::string kCampaign = MOORSIM_SOURCE_DIR "/scenarios/campaigns/thesis_detection_small.yaml";
constexpr int kLines = 8;  // of both library scenarios
// A loader or reader case takes milliseconds; this is far beyond it even under the
// sanitizers, and short enough that a hang costs one case, not the suite.
constexpr std::chrono::milliseconds kCaseLimit{10'000};
constexpr std::chrono::seconds kCliLimit{60};

// ---------------------------------------------------------------------------------------
// One case in a child process.

struct Outcome {
  enum class Kind { kAccepted, kRejected, kOtherException, kCrashed, kHung };
  Kind kind = Kind::kAccepted;
  std::string message;  ///< the exception's, for kRejected and kOtherException
  int signal = 0;       ///< for kCrashed
};

/// Runs `body` in a forked child: its InputError (rejected) or other exception comes back
/// with its message; a crash (a signal, a sanitizer's abort) or a child that outlives
/// `limit` is reported as such instead of taking the test process down.
Outcome Isolated(const std::function<void()>& body, std::chrono::milliseconds limit) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw std::runtime_error("pipe failed");
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    close(pipe_ends[0]);
    int code = 0;
    std::string message;
    try {
      body();
    } catch (const InputError& error) {
      code = 2;
      message = error.what();
    } catch (const std::exception& error) {
      code = 3;
      message = error.what();
    }
    for (std::size_t written = 0; written < message.size();) {
      const ssize_t n = write(pipe_ends[1], message.data() + written, message.size() - written);
      if (n <= 0) break;
      written += static_cast<std::size_t>(n);
    }
    _exit(code);  // no exit handlers: the parent's state is not the child's to tear down
  }
  close(pipe_ends[1]);
  Outcome outcome;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  bool hung = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      hung = true;
      break;
    }
    pollfd ready{pipe_ends[0], POLLIN, 0};
    const int polled = poll(&ready, 1, static_cast<int>(left.count()));
    if (polled < 0 && errno == EINTR) continue;
    if (polled <= 0) continue;  // the deadline is checked above
    char buffer[4096];
    const ssize_t n = read(pipe_ends[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the child closed its end: it is exiting
    outcome.message.append(buffer, static_cast<std::size_t>(n));
  }
  close(pipe_ends[0]);
  int status = 0;
  if (hung) {
    kill(pid, SIGKILL);  // our own child, by its id
    waitpid(pid, &status, 0);
    outcome.kind = Outcome::Kind::kHung;
    return outcome;
  }
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status)) {
    outcome.kind = Outcome::Kind::kCrashed;
    outcome.signal = WTERMSIG(status);
  } else if (WEXITSTATUS(status) == 0) {
    outcome.kind = Outcome::Kind::kAccepted;
  } else if (WEXITSTATUS(status) == 2) {
    outcome.kind = Outcome::Kind::kRejected;
  } else {
    outcome.kind = Outcome::Kind::kOtherException;
  }
  return outcome;
}

/// The lines of `text` (a last line without its newline counts; an empty text has none).
std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  for (std::size_t begin = 0; begin < text.size();) {
    const std::size_t end = std::min(text.find('\n', begin), text.size());
    lines.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

/// Checks one outcome: accepted, or rejected with an InputError every line of which starts
/// with `prefix` (the file it is about) and says something after it. `label` says which
/// case and what was done to its input.
void ExpectAcceptedOrLocatedRejection(const Outcome& outcome, const std::string& prefix,
                                      const std::string& label) {
  switch (outcome.kind) {
    case Outcome::Kind::kAccepted:
      return;
    case Outcome::Kind::kCrashed:
      ADD_FAILURE() << label << ": crashed with signal " << outcome.signal << " ("
                    << strsignal(outcome.signal) << ")";
      return;
    case Outcome::Kind::kHung:
      ADD_FAILURE() << label << ": still running after " << kCaseLimit.count() << " ms";
      return;
    case Outcome::Kind::kOtherException:
      ADD_FAILURE() << label << ": not an InputError: " << outcome.message;
      return;
    case Outcome::Kind::kRejected:
      break;
  }
  const std::vector<std::string> lines = Lines(outcome.message);
  EXPECT_FALSE(lines.empty()) << label << ": an InputError without a message";
  for (const std::string& line : lines) {
    EXPECT_TRUE(line.rfind(prefix, 0) == 0 && line.size() > prefix.size() + 2)
        << label << ": a line that does not name " << prefix << ": " << line;
  }
}

// ---------------------------------------------------------------------------------------
// Mutations.

/// Draws mutations of a text from one seeded generator: bit flips, deletions, insertions
/// of bytes YAML and CSV give meaning to, repeated or moved lines, known lines spliced in,
/// numbers replaced by extreme ones, truncation.
class Mutator {
 public:
  /// `splices`: lines worth inserting whole (hostile keys and values of the format).
  Mutator(std::uint64_t seed, std::vector<std::string> splices)
      : random_(seed), splices_(std::move(splices)) {}

  /// 1 to 3 mutations of `text`; `what` gets a short account of them.
  std::string Mutate(std::string text, std::string* what) {
    const int count = 1 + static_cast<int>(Below(3));
    for (int i = 0; i < count; ++i) text = MutateOnce(std::move(text), what);
    return text;
  }

  std::uint64_t Below(std::uint64_t n) { return n == 0 ? 0 : random_() % n; }

 private:
  std::string MutateOnce(std::string text, std::string* what) {
    const std::size_t at = static_cast<std::size_t>(Below(text.size() + 1));
    const auto note = [&](const std::string& kind) {
      *what += (what->empty() ? "" : ", ") + kind + " at " + std::to_string(at);
    };
    switch (Below(7)) {
      case 0:
        if (text.empty()) break;
        note("bit flip");
        text[std::min(at, text.size() - 1)] ^= static_cast<char>(1u << Below(8));
        break;
      case 1:
        note("deletion");
        text.erase(at, static_cast<std::size_t>(1 + Below(16)));
        break;
      case 2: {
        static const std::string kBytes = std::string(":-[]{}&*!|>'\"#,%@`?\n\t 0123456789.eE+") +
                                          std::string("\0\xff\xc3\xef\xbb\xbf", 6);
        std::string inserted;
        for (std::uint64_t n = 1 + Below(8); n > 0; --n) inserted += kBytes[Below(kBytes.size())];
        note("insertion");
        text.insert(at, inserted);
        break;
      }
      case 3: {
        const std::vector<std::string> lines = Lines(text);
        if (lines.empty()) break;
        note("repeated line");
        text.insert(LineStart(text, at), lines[Below(lines.size())] + "\n");
        break;
      }
      case 4:
        note("spliced line");
        text.insert(LineStart(text, at), splices_[Below(splices_.size())] + "\n");
        break;
      case 5: {
        static const std::vector<std::string> kNumbers = {
            "0",      "-0",     "1e308",
            "-1e308", "1e-320", ".nan",
            ".inf",   "-.inf",  "99999999999999999999",
            "0x10",   "1_000",  "-1"};
        const std::size_t digit = text.find_first_of("0123456789", at);
        if (digit == std::string::npos) break;
        const std::size_t end = text.find_first_not_of("0123456789.eE+-", digit);
        note("number replaced");
        text.replace(digit, (end == std::string::npos ? text.size() : end) - digit,
                     kNumbers[Below(kNumbers.size())]);
        break;
      }
      default:
        note("truncation");
        text.resize(at);
    }
    return text;
  }

  static std::size_t LineStart(const std::string& text, std::size_t at) {
    const std::size_t newline = at == 0 ? std::string::npos : text.rfind('\n', at - 1);
    return newline == std::string::npos ? 0 : newline + 1;
  }

  std::mt19937_64 random_;
  std::vector<std::string> splices_;
};

/// Lines of YAML a user (or damage) could put into a scenario or campaign file: the file's
/// own lines elsewhere, an include of itself, anchors and aliases, tags, merge keys, values
/// of the wrong kind.
std::vector<std::string> YamlSplices(const std::string& text, const std::string& self) {
  std::vector<std::string> splices = Lines(text);
  for (const char* line :
       {"base: ", "base: missing.yaml", "a: &a [1, 2]", "b: [*a, *a, *a]", "<<: {x: 1}",
        "simulation: !!binary aGVsbG8=", "seed: 18446744073709551616", "...", "---",
        "  - {line: 0}", "mooring: ~", "{", "[[[[[[[[[[", "'", "\"\\u0000\"", "? complex key",
        "scenario: /dev/null", "blocks: []", "factors: [{key: failure.line, values: []}]"}) {
    splices.emplace_back(line);
  }
  splices.push_back("base: " + std::filesystem::path(self).filename().string());
  return splices;
}

// ---------------------------------------------------------------------------------------
// The inputs.

/// A `moorsim detect` log of the library's eight lines: 30 rows at 1 Hz with every column,
/// a comment, an empty position cell (a GNSS dropout).
std::string DetectCsv() {
  std::string csv = "# a moored FPSO\ntime,north,east,heading,thrust_surge,thrust_sway,thrust_yaw";
  for (int k = 1; k <= kLines; ++k) csv += ",tension_" + std::to_string(k);
  csv += "\n";
  for (int t = 0; t < 30; ++t) {
    csv += std::to_string(t) + "," + (t == 7 ? "" : "1.5") + ",-2.25,-2.356,1e5,0,-3.5e6";
    for (int k = 1; k <= kLines; ++k) csv.append(",").append(std::to_string(4.9e6 + 1e4 * k + t));
    csv += "\n";
  }
  return csv;
}

/// A run.h5 as the current writer writes it: the scenario's attributes and the tables of
/// the recorded detection input (30 rows at 1 Hz), with a few of the run's other tables.
void WriteRunH5(const std::string& path) {
  const scenarios::Scenario scenario = scenarios::LoadScenario(kRunScenario);
  output::Hdf5File file(path);
  file.SetAttribute("/", "scenario", scenario.text);
  file.SetAttribute("/", "scenario_name", scenario.name);
  file.SetAttribute("/", "scenario_path", scenario.source_path);
  file.SetAttribute("/", "overrides", std::string("simulation.duration=30"));
  file.SetAttribute("/", "seed", std::uint64_t{7});
  file.SetAttribute("/", "failure_line", std::int64_t{6});
  file.SetAttribute("/", "failure_time", 400.0);
  const std::vector<std::string> line_names = {"line1", "line2", "line3", "line4",
                                               "line5", "line6", "line7", "line8"};
  const output::TableId time = file.CreateTable("/time", 0, "s");
  const output::TableId pose = file.CreateTable("/vessel/pose_true", 6, "m,m,m,rad,rad,rad",
                                                {"x", "y", "z", "phi", "theta", "psi"});
  const output::TableId tension =
      file.CreateTable("/mooring/fairlead_tension", kLines, "N", line_names);
  const output::TableId input_time = file.CreateTable("/detection/input/time", 0, "s");
  const output::TableId measured =
      file.CreateTable("/detection/input/pose_measured", 3, "m,m,rad", {"x", "y", "psi"});
  const output::TableId thrust =
      file.CreateTable("/detection/input/thrust", 3, "N,N,N m", {"X", "Y", "N"});
  const output::TableId cells =
      file.CreateTable("/detection/input/tension_measured", kLines, "N", line_names);
  file.CreateGroup("/detectors/glr");
  file.SetAttribute("/detectors/glr", "type", std::string("glr"));
  const output::TableId decision =
      file.CreateTable("/detectors/glr/decision", 0, "", {}, output::TableType::kInt8);
  for (int t = 0; t < 30; ++t) {
    const double s = t;
    file.Append(time, s);
    file.Append(input_time, s);
    const std::vector<double> eta = {1.5 + 1e-3 * s, -2.25, 0.0, 0.0, 0.0, -2.356};
    file.Append(pose, eta);
    file.Append(measured, std::vector<double>{eta[0], eta[1], eta[5]});
    file.Append(thrust, std::vector<double>{1e5, 0.0, -3.5e6});
    std::vector<double> loads(kLines);
    for (int k = 0; k < kLines; ++k) loads[k] = 4.9e6 + 1e4 * k + s;
    file.Append(tension, loads);
    file.Append(cells, loads);
    file.Append(decision, std::int32_t{0});
  }
  file.Close();
}

class Fuzz : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::filesystem::path(moorsim::testing::FreshDirectory("fuzz_test"));
    WriteRunH5(RunH5());
  }
  static void TearDownTestSuite() {
    std::filesystem::remove_all(*dir_);
    delete dir_;
    dir_ = nullptr;
  }
  static std::string RunH5() { return (*dir_ / "run.h5").string(); }
  static std::filesystem::path Dir() { return *dir_; }

 private:
  static std::filesystem::path* dir_;
};
std::filesystem::path* Fuzz::dir_ = nullptr;

std::string Label(const char* input, int index, const std::string& what) {
  // Appended piece by piece: GCC 12 warns falsely (-Wstringop-overflow) on a chain of +.
  std::string label(input);
  label.append(" case ").append(std::to_string(index)).append(" (").append(what).append(")");
  return label;
}

// ---------------------------------------------------------------------------------------
// Through the library, each case in a child process.

TEST_F(Fuzz, MutatedScenariosLoadOrAreRefusedNamingTheFile) {
  const std::string original = moorsim::testing::ReadWholeFile(kScenario);
  Mutator mutator(kFuzzSeed, YamlSplices(original, kScenario));
  int refused = 0;
  for (int i = 0; i < 150; ++i) {
    std::string what;
    const std::string text = mutator.Mutate(original, &what);
    const Outcome outcome =
        Isolated([&] { scenarios::ParseScenario(text, kScenario); }, kCaseLimit);
    ExpectAcceptedOrLocatedRejection(outcome, kScenario, Label("scenario", i, what));
    refused += outcome.kind == Outcome::Kind::kRejected ? 1 : 0;
  }
  // The mutations reach the checks: most damaged scenarios are refused.
  EXPECT_GT(refused, 50);
}

TEST_F(Fuzz, MutatedCampaignsLoadOrAreRefusedNamingTheFile) {
  const std::string original = moorsim::testing::ReadWholeFile(kCampaign);
  Mutator mutator(kFuzzSeed + 1, YamlSplices(original, kCampaign));
  int refused = 0;
  for (int i = 0; i < 150; ++i) {
    std::string what;
    const std::string text = mutator.Mutate(original, &what);
    const Outcome outcome = Isolated(
        [&] {
          const scenarios::Campaign campaign = scenarios::ParseCampaign(text, kCampaign);
          scenarios::MakeCampaignRun(campaign, 0);
          scenarios::MakeCampaignRun(campaign, campaign.NumRuns() - 1);
        },
        kCaseLimit);
    ExpectAcceptedOrLocatedRejection(outcome, kCampaign, Label("campaign", i, what));
    refused += outcome.kind == Outcome::Kind::kRejected ? 1 : 0;
  }
  EXPECT_GT(refused, 30);
}

TEST_F(Fuzz, MutatedDetectLogsAreReadOrRefusedAtTheirRow) {
  const std::string original = DetectCsv();
  std::vector<std::string> splices = Lines(original);
  for (const char* line : {"time", ",,,,,,,,,,,,,,", "\xef\xbb\xbftime,north", "1e999,0,0,0,0,0,0",
                           "\"1\",2,3", "nan,nan,nan,nan,nan,nan,nan"}) {
    splices.emplace_back(line);
  }
  Mutator mutator(kFuzzSeed + 2, splices);
  const std::string name = (Dir() / "log.csv").string();
  int refused = 0;
  for (int i = 0; i < 200; ++i) {
    std::string what;
    const std::string text = mutator.Mutate(original, &what);
    const Outcome outcome = Isolated(
        [&] {
          CsvPoseStream stream(name, kLines, kDefaultMaxGap);
          detectors::Observation observation;
          for (const std::string& line : Lines(text)) stream.Take(line, &observation);
        },
        kCaseLimit);
    const std::string label = Label("detect log", i, what);
    ExpectAcceptedOrLocatedRejection(outcome, name + ":", label);
    if (outcome.kind == Outcome::Kind::kRejected) {
      ++refused;
      EXPECT_EQ(Lines(outcome.message).size(), 1u) << label << ": " << outcome.message;
    }
  }
  EXPECT_GT(refused, 50);
}

/// The run.h5 at `path` read as `moorsim detect` reads it: its scenario, then its
/// detection input.
void ReadAsDetectDoes(const std::string& path) {
  const scenarios::Scenario scenario = ReadRunScenario(path);
  ReadRunDetectionInput(path, static_cast<int>(scenario.mooring.lines.size()), kDefaultMaxGap);
}

TEST_F(Fuzz, TruncatedRunH5IsRefusedNamingTheFile) {
  const std::string original = moorsim::testing::ReadWholeFile(RunH5());
  ASSERT_FALSE(original.empty());
  const std::string path = (Dir() / "truncated.h5").string();
  // Every length would be 100 000 cases; 200 evenly spread ones cover every region of the
  // file (superblock, object headers, heaps, B-trees, chunks, the end-of-file metadata).
  constexpr int kCases = moorsim::testing::CaseCount(200, 50);
  for (int i = 0; i < kCases; ++i) {
    const std::size_t length = original.size() * static_cast<std::size_t>(i) / kCases;
    moorsim::testing::WriteWholeFile(path, original.substr(0, length));
    const Outcome outcome = Isolated([&] { ReadAsDetectDoes(path); }, kCaseLimit);
    const std::string label = Label("run.h5", i, "truncated to " + std::to_string(length));
    ExpectAcceptedOrLocatedRejection(outcome, path + ": ", label);
    // A truncated file is never taken for a whole one.
    EXPECT_EQ(outcome.kind, Outcome::Kind::kRejected) << label;
  }
}

TEST_F(Fuzz, RunH5WithFlippedBitsIsReadOrRefusedNamingTheFile) {
  const std::string original = moorsim::testing::ReadWholeFile(RunH5());
  ASSERT_FALSE(original.empty());
  const std::string path = (Dir() / "flipped.h5").string();
  Mutator mutator(kFuzzSeed + 3, {});
  int refused = 0;
  const int cases = moorsim::testing::CaseCount(300, 100);
  for (int i = 0; i < cases; ++i) {
    std::string damaged = original;
    const std::size_t bit = static_cast<std::size_t>(mutator.Below(8 * original.size()));
    damaged[bit / 8] ^= static_cast<char>(1u << (bit % 8));
    moorsim::testing::WriteWholeFile(path, damaged);
    const Outcome outcome = Isolated([&] { ReadAsDetectDoes(path); }, kCaseLimit);
    ExpectAcceptedOrLocatedRejection(outcome, path + ": ",
                                     Label("run.h5", i, "bit " + std::to_string(bit) + " flipped"));
    refused += outcome.kind == Outcome::Kind::kRejected ? 1 : 0;
  }
  EXPECT_GT(refused, cases / 10);
}

/// The importer's test spread (three lines, one of them two lines in series through a
/// clump weight) on a surveyed seabed (bottom.txt beside it), its wire's stiffness a table
/// (rope.txt beside it).
std::string FuzzedSpread() {
  std::string text = moorsim::testing::kMoorDynSpread;
  const auto replace = [&](const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
  };
  replace("5.0e8 ", "rope.txt");
  replace("0.4           FrictionCoefficient",
          "bottom.txt    SeafloorFile  bathymetry\n0.4           FrictionCoefficient");
  return text;
}

const char kSeafloor[] =
    "2 3\n-1000 1000\n-800 0 800\n-1000 -800 -200\n-1000 0 -200.2\n-1000 800 -200.4\n"
    "1000 -800 -200.1\n1000 0 -200.3\n1000 800 -200.5\n";
const char kRope[] = "strain tension\n(-) (N)\n---\n0 0\n0.01 1.0e6\n0.02 2.5e6\n0.05 9e6\n";

/// Lines a MoorDyn file (or damage to it) could hold: its own rows elsewhere, rows with
/// columns missing or added, references to what is not there, names given twice, sections
/// moorsim does not model, options of every kind, other line ends and encodings.
std::vector<std::string> MoorDynSplices(const std::string& text) {
  std::vector<std::string> splices = Lines(text);
  for (const char* line :
       {"8     Fixed     0       0       -200    0      0       0      0",
        "5     chain      9        4         680       30      p",
        "5     nylon      1        4",
        "1     Fixed     600     0       -200",
        "4     Body1     0       0       -10",
        "6     chain      4        5         30        10      p",
        "7     chain      7        7         100       10      p",
        "poly       0.2     50         1e8|2e8    1e7|1e6  0  1.2  1.0  0.01  0.0",
        "syn        0.2     50         SYROPE:r.txt|1e8|2  1e7  0  1.2  1.0  0.01  0.0",
        "---------------------- RODS ----",
        "---------------------- BODIES ----",
        "---------------------- SOMETHING ELSE ----",
        "1 WaveKin",
        "2 Currents",
        "missing.txt SeafloorFile",
        "-5 WtrDpth",
        "abc WtrDpth",
        "0 g",
        "1e308 kBot",
        "chain      0.1     150        8.0e8      -0.6        0    2.0    0.9    0.3     0.0 7",
        "\xef\xbb\xbf--------------------- MoorDyn Input File ---",
        "1\t\tFixed\t600\t0\t-200",
        "caf\xe9       0.1     150        8.0e8      -0.6        0    2.0    0.9    0.3     0.0",
        "4     Vessel    1e300   0       -15     0      0       0      0",
        "END"}) {
    splices.emplace_back(line);
  }
  return splices;
}

TEST_F(Fuzz, MutatedMoorDynFilesImportOrAreRefusedAtTheirLine) {
  const std::filesystem::path dir = Dir() / "moordyn";
  std::filesystem::create_directories(dir);
  moorsim::testing::WriteWholeFile(dir / "bottom.txt", kSeafloor);
  moorsim::testing::WriteWholeFile(dir / "rope.txt", kRope);
  const std::string path = (dir / "spread.txt").string();
  const std::string original = FuzzedSpread();
  Mutator mutator(kFuzzSeed + 5, MoorDynSplices(original));
  int refused = 0, located = 0;
  for (int i = 0; i < 150; ++i) {
    std::string what;
    // Now and then a line end of another system.
    std::string text = mutator.Mutate(original, &what);
    if (i % 15 == 0) {
      for (std::size_t at = 0; (at = text.find('\n', at)) != std::string::npos; at += 2) {
        text.insert(at, "\r");
      }
      what += ", CRLF";
    }
    moorsim::testing::WriteWholeFile(path, text);
    const Outcome outcome =
        Isolated([&] { scenarios::ImportMoorDyn(path, "fuzz", "fuzzed"); }, kCaseLimit);
    const std::string label = Label("MoorDyn file", i, what);
    ExpectAcceptedOrLocatedRejection(outcome, path + ":", label);
    if (outcome.kind == Outcome::Kind::kRejected) {
      ++refused;
      // Said of a line of the file (a number after its name), but for what concerns the
      // file as a whole (no tables, no depth, no line moorsim can hold).
      for (const std::string& line : Lines(outcome.message)) {
        const bool at_line = line.size() > path.size() + 1 &&
                             std::isdigit(static_cast<unsigned char>(line[path.size() + 1]));
        located += at_line ? 1 : 0;
        EXPECT_TRUE(at_line || line.find(": no ") != std::string::npos ||
                    line.find("not a MoorDyn") != std::string::npos ||
                    line.find("cannot") != std::string::npos)
            << label << ": a line that names no line of the file: " << line;
      }
    }
  }
  EXPECT_GT(refused, 50);
  EXPECT_GT(located, 50);
}

TEST_F(Fuzz, MutatedSeafloorGridsAndStiffnessTablesAreRefusedAtTheMoorDynLine) {
  const std::filesystem::path dir = Dir() / "moordyn_files";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "spread.txt").string();
  moorsim::testing::WriteWholeFile(path, FuzzedSpread());
  std::vector<std::string> splices = {"9223372036854775808 9223372036854777856",
                                      "1e300 2",
                                      "2 2",
                                      "0 3",
                                      "-1 -1",
                                      "0 0 0",
                                      "nan nan nan",
                                      "1e-320 1e308",
                                      "4294967296 4294967297"};
  Mutator mutator(kFuzzSeed + 6, splices);
  int refused = 0;
  for (int i = 0; i < 80; ++i) {
    std::string what;
    const bool grid = i % 2 == 0;
    moorsim::testing::WriteWholeFile(dir / "bottom.txt",
                                     grid ? mutator.Mutate(kSeafloor, &what) : kSeafloor);
    moorsim::testing::WriteWholeFile(dir / "rope.txt", grid ? kRope : mutator.Mutate(kRope, &what));
    const Outcome outcome =
        Isolated([&] { scenarios::ImportMoorDyn(path, "fuzz", "fuzzed"); }, kCaseLimit);
    const std::string label = Label(grid ? "seafloor grid" : "stiffness table", i, what);
    // The grid's problems are said at the SeafloorFile option's line, the table's at its
    // own row (the table is a file of the user's too) or at the line type's.
    const std::string named = grid ? path + ":" : "";
    ExpectAcceptedOrLocatedRejection(outcome, named, label);
    if (outcome.kind == Outcome::Kind::kRejected) {
      ++refused;
      if (!grid) {
        EXPECT_TRUE(outcome.message.rfind(path + ":", 0) == 0 ||
                    outcome.message.rfind((dir / "rope.txt").string() + ":", 0) == 0)
            << label << ": " << outcome.message;
      }
    }
  }
  EXPECT_GT(refused, 25);
}

// ---------------------------------------------------------------------------------------
// Through the program: a few cases of each input, exit 2 with every line of stderr naming
// the file.

void ExpectCliAcceptedOrRefused(const moorsim::testing::CliResult& r, const std::string& file,
                                const std::string& label) {
  EXPECT_EQ(r.signal, 0) << label << ": " << r.Describe();
  EXPECT_FALSE(r.timed_out) << label << ": " << r.Describe();
  if (r.exit_code == 0) return;
  EXPECT_EQ(r.exit_code, 2) << label << ": " << r.Describe();
  const std::vector<std::string> lines = Lines(r.err);
  EXPECT_FALSE(lines.empty()) << label;
  for (const std::string& line : lines) {
    EXPECT_EQ(line.rfind("moorsim: " + file, 0), 0u) << label << ": " << r.err;
  }
}

TEST_F(Fuzz, TheProgramRefusesDamagedInputsWithExitTwo) {
  const std::string run = moorsim::testing::ReadWholeFile(RunH5());
  Mutator mutator(kFuzzSeed + 4,
                  YamlSplices(moorsim::testing::ReadWholeFile(kScenario), kScenario));
  const std::filesystem::path dir = Dir() / "cli";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "run.h5").string();
  for (int i = 0; i < 6; ++i) {
    std::string damaged = run;
    std::string what;
    if (i % 2 == 0) {
      damaged.resize(run.size() * static_cast<std::size_t>(i + 1) / 7);
      what = "truncated to " + std::to_string(damaged.size());
    } else {
      const std::size_t bit = static_cast<std::size_t>(mutator.Below(8 * run.size()));
      damaged[bit / 8] ^= static_cast<char>(1u << (bit % 8));
      what = "bit " + std::to_string(bit) + " flipped";
    }
    moorsim::testing::WriteWholeFile(path, damaged);
    const moorsim::testing::CliResult r =
        moorsim::testing::RunCli({"detect", path, "--quiet"}, dir, kCliLimit);
    ExpectCliAcceptedOrRefused(r, path, Label("moorsim detect run.h5", i, what));
  }
  const std::string scenario_path = (dir / "scenario.yaml").string();
  std::string scenario = moorsim::testing::ReadWholeFile(kScenario);
  // Its hull's data found from the scratch directory too.
  const std::string hull = "../../data/fpso_wamit/fpso";
  ASSERT_NE(scenario.find(hull), std::string::npos);
  scenario.replace(scenario.find(hull), hull.size(), MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso");
  for (int i = 0; i < 3; ++i) {
    std::string what;
    moorsim::testing::WriteWholeFile(scenario_path, mutator.Mutate(scenario, &what));
    const moorsim::testing::CliResult r =
        moorsim::testing::RunCli({"validate", scenario_path}, dir, kCliLimit);
    ExpectCliAcceptedOrRefused(r, scenario_path, Label("moorsim validate", i, what));
  }
  const std::string log_path = (dir / "log.csv").string();
  const std::string log = DetectCsv();
  for (int i = 0; i < 2; ++i) {
    std::string what;
    moorsim::testing::WriteWholeFile(log_path, mutator.Mutate(log, &what));
    const moorsim::testing::CliResult r = moorsim::testing::RunCli(
        {"detect", log_path, "--scenario", kRunScenario, "--quiet"}, dir, kCliLimit);
    ExpectCliAcceptedOrRefused(r, log_path, Label("moorsim detect log", i, what));
  }
}

}  // namespace
}  // namespace moorsim::simulation
