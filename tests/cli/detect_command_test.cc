// `moorsim detect` end to end: replaying a run's recorded detection input gives exactly the
// alarms the run reported (from run.h5, and from the same samples as a CSV log on standard
// input with the sensors' dropouts as empty cells); every kind of bad input is one line
// naming the file, row and column, with exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "io/hdf5_file.h"
#include "io/hdf5_reader.h"
#include "scenarios/load.h"
#include "simulation/pose_stream.h"
#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kDetectScenario = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6.yaml";

// A short thesis line-6 run with the line parting at 100 s, the sensors dropping out now
// and then (the GNSS for 5 s on average), so the replay meets dropouts, and load cells
// (one of them drifting) read by the cells test beside the library's four detectors.
const std::vector<std::string> kDetectSets = {
    "--set",
    "failure.time=100",
    "--set",
    "sensors.gnss.dropout_probability=0.03",
    "--set",
    "sensors.gnss.dropout_mean_duration=5",
    "--set",
    "sensors.gyro.dropout_probability=0.03",
    "--set",
    "sensors.tension_cells={rate_hz: 1, noise: {std_dev: 1.0e4}, faults: [{line: 2, mode: drift, "
    "time: 20, rate: -5000}]}",
    "--set",
    "detectors=[{type: dht}, {type: mle}, {type: glr}, {type: deficit}, {type: cells}]"};

std::vector<std::string> With(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

nlohmann::json ReadJsonFile(const std::filesystem::path& path) {
  return nlohmann::json::parse(ReadWholeFile(path));
}

// The run's /detection/input as a CSV log: columns in another order than the documented
// one, a comment line, NaN (nothing delivered) as an empty cell, every value to 17 digits.
std::string DetectionInputCsv(const std::string& run_h5) {
  const output::Hdf5Reader file(run_h5);
  const output::TableData time = file.ReadTable("/detection/input/time");
  const output::TableData pose = file.ReadTable("/detection/input/pose_measured");
  const output::TableData thrust = file.ReadTable("/detection/input/thrust");
  const output::TableData tension = file.ReadTable("/detection/input/tension_measured");
  std::ostringstream csv;
  csv << "# replayed from " << run_h5 << "\n";
  csv << "heading,time,thrust_surge,north,thrust_sway,east,thrust_yaw";
  for (std::size_t k = 1; k <= tension.columns; ++k) csv << ",tension_" << k;
  csv << "\n";
  const auto cell = [](double v) {
    if (std::isnan(v)) return std::string();
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", v);
    return std::string(text);
  };
  for (std::size_t r = 0; r < time.rows; ++r) {
    csv << cell(pose.at(r, 2)) << ',' << cell(time.values[r]) << ',' << cell(thrust.at(r, 0)) << ','
        << cell(pose.at(r, 0)) << ',' << cell(thrust.at(r, 1)) << ',' << cell(pose.at(r, 1)) << ','
        << cell(thrust.at(r, 2));
    for (std::size_t k = 0; k < tension.columns; ++k) csv << ',' << cell(tension.at(r, k));
    csv << "\n";
  }
  return csv.str();
}

// The JSON lines of stdout, by detector: (time, event, hypothesis) in order.
std::map<std::string, nlohmann::json> EventsByDetector(const std::string& out) {
  std::map<std::string, nlohmann::json> events;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json e = nlohmann::json::parse(line);
    events[e["detector"]].push_back(
        {{"time", e["time"]}, {"event", e["event"]}, {"hypothesis", e["hypothesis"]}});
  }
  return events;
}

class DetectCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDirectory(::testing::TempDir());
    const CliResult r = RunCli(With({"run", kDetectScenario, "--duration", "250", "--quiet",
                                     "--out", (dir_->path() / "run").string()},
                                    kDetectSets),
                               dir_->path());
    ASSERT_EQ(r.exit_code, 0) << r.Describe();
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::filesystem::path RunDir() { return dir_->path() / "run"; }
  static TempDirectory* dir_;
};
TempDirectory* DetectCommand::dir_ = nullptr;

TEST_F(DetectCommand, ReplayingARunGivesExactlyItsAlarms) {
  TempDirectory dir(::testing::TempDir());
  const CliResult r = RunCli(
      {"detect", (RunDir() / "run.h5").string(), "--out", (dir.path() / "d").string()}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json run = ReadJsonFile(RunDir() / "summary.json");
  const nlohmann::json replay = ReadJsonFile(dir.path() / "d" / "summary.json");
  EXPECT_EQ(replay["detectors"], run["detectors"]);
  // The run has alarms to replay: the DHT, MLE, GLR and cells tests name line 6 after the
  // break (the deficit test is still learning its drift model 100 s into a run).
  for (const char* label : {"dht", "mle", "glr", "cells"}) {
    ASSERT_EQ(run["detectors"][label]["isolated_line"], 6) << label;
  }
  // Each event was printed as it happened, in the history's order.
  const std::map<std::string, nlohmann::json> printed = EventsByDetector(r.out);
  std::size_t events = 0;
  for (const auto& [label, d] : run["detectors"].items()) {
    EXPECT_EQ(printed.count(label) ? printed.at(label) : nlohmann::json::array(), d["history"])
        << label;
    events += d["history"].size();
  }
  // alarms.csv: a header and one row per event.
  std::istringstream csv(ReadWholeFile(dir.path() / "d" / "alarms.csv"));
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "time,detector,type,event,hypothesis,line,score");
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, events);
  EXPECT_EQ(replay["samples"], 251);  // the 1 Hz sensors, 0 to 250 s
  // tools/plot_run.py draws what detection alone has: no tensions, no true pose.
  const CliResult plot = RunProgram(
      "/usr/bin/python3", {MOORSIM_SOURCE_DIR "/tools/plot_run.py", (dir.path() / "d").string()},
      dir.path());
  ASSERT_EQ(plot.exit_code, 0) << plot.Describe();
  for (const char* figure : {"trajectory", "pose", "thrust", "detectors", "detector_scores"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.path() / "d" / (std::string(figure) + ".png")))
        << figure;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "d" / "tensions.png"));
}

TEST_F(DetectCommand, ACsvLogOnStandardInputGivesTheSameAlarms) {
  TempDirectory dir(::testing::TempDir());
  const std::string csv = DetectionInputCsv((RunDir() / "run.h5").string());
  ASSERT_NE(csv.find(",,"), std::string::npos) << "the run should have had dropouts";
  WriteWholeFile(dir.path() / "log.csv", csv);
  std::string command = std::string("exec '") + MOORSIM_CLI + "' detect - --scenario '" +
                        kDetectScenario + "' --out '" + (dir.path() / "d").string() + "'";
  for (const std::string& a : kDetectSets) command += " '" + a + "'";
  command += " < '" + (dir.path() / "log.csv").string() + "'";
  const CliResult r = RunProgram("/bin/sh", {"-c", command}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json run = ReadJsonFile(RunDir() / "summary.json");
  EXPECT_EQ(ReadJsonFile(dir.path() / "d" / "summary.json")["detectors"], run["detectors"]);
}

// The lines of `path` so far.
std::vector<std::string> LinesOf(const std::filesystem::path& path) {
  std::vector<std::string> lines;
  std::istringstream in(ReadWholeFile(path));
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Waits up to 30 s for `path` to have at least `n` lines; returns how many it has.
std::size_t AwaitLines(const std::filesystem::path& path, std::size_t n) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  std::size_t have = 0;
  while ((have = LinesOf(path).size()) < n && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return have;
}

void Append(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::app | std::ios::binary);
  out << text << std::flush;
}

// Starts `moorsim detect args...` with standard output on `stdout_fd` and standard input
// on `stdin_fd` (-1: the test's).
pid_t StartDetect(std::vector<std::string> args, int stdout_fd, int stdin_fd = -1) {
  args.insert(args.begin(), "detect");
  return StartCli(args, {.file = {}, .fd = stdout_fd}, {}, stdin_fd);
}

TEST_F(DetectCommand, FollowingALogPrintsEachAlarmWhenItsRowArrives) {
  TempDirectory dir(::testing::TempDir());
  const nlohmann::json run = ReadJsonFile(RunDir() / "summary.json");
  // The first event of the run and how many there are in all.
  double first = 1e300;
  std::size_t events = 0;
  for (const auto& [label, d] : run["detectors"].items()) {
    for (const nlohmann::json& e : d["history"]) first = std::min(first, e["time"].get<double>());
    events += d["history"].size();
  }
  ASSERT_LT(first, 250.0);
  // The log up to the first event's row; the rest comes later, a line split in two.
  const std::string csv = DetectionInputCsv((RunDir() / "run.h5").string());
  std::size_t cut = 0;  // after the first event's row (time is the second column)
  for (std::size_t begin = 0; begin < csv.size() && cut == 0;) {
    const std::size_t end = csv.find('\n', begin);
    const std::string line = csv.substr(begin, end - begin);
    const std::size_t comma = line.find(',');
    if (line[0] != '#' && comma != std::string::npos &&
        std::atof(line.c_str() + comma + 1) == first) {
      cut = end + 1;
    }
    begin = end + 1;
  }
  ASSERT_GT(cut, 0u);
  const std::filesystem::path log = dir.path() / "log.csv";
  WriteWholeFile(log, csv.substr(0, cut));

  const std::filesystem::path events_path = dir.path() / "events.jsonl";
  const int events_fd = ::open(events_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(events_fd, 0);
  const pid_t pid = StartDetect(With({log.string(), "--follow", "--quiet", "--scenario",
                                      kDetectScenario, "--out", (dir.path() / "d").string()},
                                     kDetectSets),
                                events_fd);
  ::close(events_fd);

  // The first alarm is printed while the log still ends at its row.
  EXPECT_GE(AwaitLines(events_path, 1), 1u);
  const nlohmann::json printed = nlohmann::json::parse(LinesOf(events_path).at(0));
  EXPECT_EQ(printed["time"].get<double>(), first);
  const std::string rest = csv.substr(cut);
  Append(log, rest.substr(0, rest.size() / 2));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  Append(log, rest.substr(rest.size() / 2));
  EXPECT_EQ(AwaitLines(events_path, events), events);
  // SIGINT ends it with the summary of everything so far: the run's own verdicts.
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130);
  EXPECT_EQ(ReadJsonFile(dir.path() / "d" / "summary.json")["detectors"], run["detectors"]);
}

// Rows of /time in the detect.h5 at `path` as HDF5 reads it now, -1 if it cannot.
long TimeRows(const std::filesystem::path& path) {
  try {
    return static_cast<long>(output::Hdf5Reader(path.string()).ReadTable("/time").rows);
  } catch (const std::exception&) {
    return -1;
  }
}

// Waits up to 60 s for TimeRows(path) to be `rows`; returns the last value seen.
long AwaitTimeRows(const std::filesystem::path& path, long rows) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  long have = -1;
  while ((have = TimeRows(path)) != rows && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return have;
}

std::vector<std::string> FilesIn(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A live monitor killed outright (SIGKILL, as a power loss would stop it) leaves a detect.h5
// that opens and holds every row up to its last flush: here every row of the log, made
// durable within a flush interval of the monitor going idle, and every alarm printed.
TEST_F(DetectCommand, ALiveMonitorKilledOutrightKeepsEveryRowUpToItsLastFlush) {
  // The test reads detect.h5 while the monitor holds it open for writing.
  setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);
  TempDirectory dir(::testing::TempDir());
  const std::string csv = DetectionInputCsv((RunDir() / "run.h5").string());
  const std::vector<std::string> lines = [&] {
    std::vector<std::string> all;
    std::istringstream in(csv);
    for (std::string line; std::getline(in, line);) all.push_back(line + "\n");
    return all;
  }();
  const long rows = static_cast<long>(lines.size()) - 2;  // a comment and the header
  const long first_rows = rows / 2;
  const std::filesystem::path log = dir.path() / "log.csv";
  std::string head;
  for (long k = 0; k < 2 + first_rows; ++k) head += lines[static_cast<std::size_t>(k)];
  WriteWholeFile(log, head);
  const std::filesystem::path d = dir.path() / "d";
  const std::filesystem::path events_path = dir.path() / "events.jsonl";
  const int events_fd = ::open(events_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(events_fd, 0);
  const pid_t pid =
      StartDetect(With({log.string(), "--follow", "--quiet", "--scenario", kDetectScenario, "--out",
                        d.string(), "--flush-interval", "0.2"},
                       kDetectSets),
                  events_fd);
  ::close(events_fd);
  EXPECT_EQ(AwaitTimeRows(d / "detect.h5", first_rows), first_rows);
  Append(log, csv.substr(head.size()));
  EXPECT_EQ(AwaitTimeRows(d / "detect.h5", rows), rows);
  kill(pid, SIGKILL);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const output::Hdf5Reader file((d / "detect.h5").string());
  const output::TableData time = file.ReadTable("/time");
  ASSERT_EQ(static_cast<long>(time.rows), rows);
  EXPECT_EQ(file.ReadTable("/vessel/pose_measured").rows, time.rows);
  const output::Hdf5Reader run((RunDir() / "run.h5").string());
  EXPECT_EQ(time.values, run.ReadTable("/detection/input/time").values);
  // Every alarm printed is in alarms.csv (made durable before it was printed).
  const std::size_t printed = LinesOf(events_path).size();
  EXPECT_GT(printed, 0u);
  EXPECT_EQ(LinesOf(d / "alarms.csv").size(), 1 + printed);
  EXPECT_FALSE(std::filesystem::exists(d / "summary.json"));
}

// Standard input is a live input too: rows that came before the writer went quiet are
// durable within a flush interval, though no further row arrives to trigger a flush.
TEST_F(DetectCommand, ALiveMonitorOnStandardInputFlushesWhileItsInputIsQuiet) {
  setenv("HDF5_USE_FILE_LOCKING", "FALSE", 1);  // read while the monitor writes
  TempDirectory dir(::testing::TempDir());
  const std::string csv = DetectionInputCsv((RunDir() / "run.h5").string());
  const std::string head = csv.substr(0, csv.find('\n', csv.size() / 2) + 1);
  const long rows = static_cast<long>(std::count(head.begin(), head.end(), '\n')) - 2;
  int input[2];
  ASSERT_EQ(::pipe(input), 0);
  const int null_fd = ::open("/dev/null", O_WRONLY);
  const std::filesystem::path d = dir.path() / "d";
  const pid_t pid = StartDetect(With({"-", "--quiet", "--scenario", kDetectScenario, "--out",
                                      d.string(), "--flush-interval", "0.2"},
                                     kDetectSets),
                                null_fd, input[0]);
  ::close(null_fd);
  ::close(input[0]);
  ASSERT_EQ(::write(input[1], head.data(), head.size()), static_cast<ssize_t>(head.size()));
  EXPECT_EQ(AwaitTimeRows(d / "detect.h5", rows), rows);
  kill(pid, SIGKILL);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ::close(input[1]);
  EXPECT_EQ(TimeRows(d / "detect.h5"), rows);
}

// `moorsim detect run.h5 --out d | head -1`: the first write to the closed pipe stops the
// replay there, with the files finished and consistent, exit 128 + SIGPIPE.
TEST_F(DetectCommand, AClosedStandardOutputStopsTheReplayWithItsFilesFinished) {
  TempDirectory dir(::testing::TempDir());
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  ::close(fds[0]);  // nobody will read
  const std::filesystem::path d = dir.path() / "d";
  const pid_t pid =
      StartDetect({(RunDir() / "run.h5").string(), "--quiet", "--out", d.string()}, fds[1]);
  ::close(fds[1]);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGPIPE);
  const nlohmann::json summary = ReadJsonFile(d / "summary.json");
  EXPECT_EQ(summary["stopped"], "standard output closed");
  const nlohmann::json run = ReadJsonFile(RunDir() / "summary.json");
  EXPECT_LT(summary["last_time"].get<double>(), run["simulated_time"].get<double>());
  EXPECT_EQ(TimeRows(d / "detect.h5"), summary["samples"].get<long>());
  EXPECT_GE(LinesOf(d / "alarms.csv").size(), 2u);
  EXPECT_EQ(FilesIn(d),
            (std::vector<std::string>{"alarms.csv", "detect.h5", "moorsim.lock", "summary.json"}));
}

// A rerun starts by removing the previous run's files, so a failed rerun leaves none of
// them beside its own; a finite input's files are written under temporary names, removed
// when the run fails (here a bad row, then a disk that fills up).
TEST_F(DetectCommand, AFailedRerunLeavesNeitherTheOldFilesNorPartialOnes) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path d = dir.path() / "d";
  std::filesystem::create_directories(d);
  for (const char* name : {"summary.json", "detect.h5", "alarms.csv"}) {
    WriteWholeFile(d / name, "the previous run's\n");
  }
  std::string csv = DetectionInputCsv((RunDir() / "run.h5").string());
  csv += "not a row\n";
  WriteWholeFile(dir.path() / "log.csv", csv);
  CliResult r = RunCli(With({"detect", (dir.path() / "log.csv").string(), "--quiet", "--scenario",
                             kDetectScenario, "--out", d.string()},
                            kDetectSets),
                       dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(FilesIn(d), std::vector<std::string>{"moorsim.lock"});

  // The file size limit makes writes fail as a full disk does (EFBIG instead of ENOSPC).
  std::string command = "trap '' XFSZ; ulimit -f 8; exec '" + std::string(MOORSIM_CLI) +
                        "' detect '" + (RunDir() / "run.h5").string() + "' --quiet --out '" +
                        d.string() + "' > /dev/null";
  r = RunProgram("/bin/sh", {"-c", command}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(FilesIn(d), std::vector<std::string>{"moorsim.lock"});
}

// One bad CSV: exit 2 and one line on stderr that starts "moorsim: <file>:<row>: ..." and
// contains `expected`.
void ExpectOneLocatedLine(const std::string& csv, const std::string& row,
                          const std::string& expected, const std::vector<std::string>& more = {}) {
  SCOPED_TRACE(expected);
  TempDirectory dir(::testing::TempDir());
  const std::string path = (dir.path() / "log.csv").string();
  WriteWholeFile(path, csv);
  const CliResult r =
      RunCli(With({"detect", path, "--scenario", kDetectScenario, "--quiet"}, more), dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err.rfind("moorsim: " + path + ":" + row + ": ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

// Rows every second from t = 0 for `n` rows, position and heading given unless `blank`
// says which column to leave empty from `from` on.
std::string Rows(int n, int blank = -1, int from = 0) {
  std::string csv = "time,north,east,heading,thrust_surge,thrust_sway,thrust_yaw\n";
  for (int t = 0; t < n; ++t) {
    std::string cells[3] = {"1.5", "-2.25", "-2.356"};
    if (blank >= 0 && t >= from) cells[blank] = "";
    // Appended piece by piece: GCC 12 at -O3 warns falsely about the chain of `+`.
    csv.append(std::to_string(t)).append(",").append(cells[0]).append(",").append(cells[1]);
    csv.append(",").append(cells[2]).append(",1e5,0,0\n");
  }
  return csv;
}

// A run made with a relative scenario path (its WAMIT stem relative to the scenario's
// folder) replays from any other folder: the run records where its scenario was.
TEST(DetectCommandInput, ARunMadeFromARelativePathReplaysFromAnywhere) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "run").string();
  // moorsim started in the source tree, then in the scratch folder.
  const CliResult run = RunProgram(
      "/bin/sh",
      {"-c", "cd '" MOORSIM_SOURCE_DIR "' && '" MOORSIM_CLI
             "' run scenarios/library/thesis_no_failure.yaml --duration 30 --quiet --out '" +
                 out + "'"},
      dir.path());
  ASSERT_EQ(run.exit_code, 0) << run.Describe();
  const CliResult replay = RunProgram(
      "/bin/sh",
      {"-c", "cd '" + dir.path().string() + "' && '" MOORSIM_CLI "' detect run/run.h5 --out d"},
      dir.path());
  EXPECT_EQ(replay.exit_code, 0) << replay.Describe();
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "d" / "summary.json"));
}

TEST(DetectCommandInput, EveryBadInputIsOneLineNamingFileRowAndColumn) {
  const std::string header = "time,north,east,heading,thrust_surge,thrust_sway,thrust_yaw\n";
  ExpectOneLocatedLine("time,north,east,heading,thrust_surge,thrust_sway\n0,0,0,0,0,0\n", "1",
                       "header: column 'thrust_yaw' is missing");
  ExpectOneLocatedLine("0,0,0,0,0,0,0\n", "1", "header: unknown column '0'");
  ExpectOneLocatedLine(header + "0,0,0,0,0,0,0\n1,0,0,0,0,0,0\n1,0,0,0,0,0,0\n", "4",
                       "column 'time': 1 s is not after the previous row's 1 s");
  ExpectOneLocatedLine(header + "0,0,0,0,0,0,0\n1,0,nan,0,0,0,0\n", "3",
                       "column 'east': 'nan' is not a finite number");
  ExpectOneLocatedLine(header + "0,0,0,0,0,0,0\n1,0,0,0,0,0,0\n100,0,0,0,0,0,0\n", "4",
                       "column 'time': a gap of 99 s after 1 s, longer than the maximum gap of "
                       "60 s");
  ExpectOneLocatedLine(header + "0,0,0,0,0,0,0\n1,0,0,0,,0,0\n", "3",
                       "column 'thrust_surge': empty (required in every row)");
  ExpectOneLocatedLine(header + "0,0,0,0,0,0\n", "2", "6 cells, the header has 7");
  // The GNSS out for longer than the maximum gap: named at the row where it becomes too long.
  ExpectOneLocatedLine(Rows(80, 0, 10), "72", "column 'north': no value for 61 s (since 9 s)");
  ExpectOneLocatedLine(Rows(30, 2, 10), "22", "column 'heading': no value for 11 s (since 9 s)",
                       {"--max-gap", "10"});
  // A NUL byte ends the number for strtod, but the cell is not that number.
  ExpectOneLocatedLine(header + "0,0,0,0,0,0,0\n1,1.5" + std::string(1, '\0') + "7,0,0,0,0,0\n",
                       "3", "column 'north': a NUL byte (binary data, not text)");
  ExpectOneLocatedLine(std::string("time,nor\0th\n", 12), "1",
                       "header: column 2: a NUL byte (binary data, not text)");
}

TEST(DetectCommandInput, AnEmptyTensionCellWithholdsThatCellAloneAndAllEmptyNone) {
  simulation::CsvPoseStream stream("log.csv", 3, 60.0);
  detectors::Observation o;
  const std::string head = "time,north,east,heading,thrust_surge,thrust_sway,thrust_yaw,";
  EXPECT_FALSE(stream.Take(head + "tension_1,tension_2,tension_3", &o));
  ASSERT_TRUE(stream.Take("0,1,2,0.1,0,0,0,1e6,,3e6", &o));
  ASSERT_TRUE(o.tensions.has_value());
  EXPECT_EQ((*o.tensions)(0), 1e6);
  EXPECT_TRUE(std::isnan((*o.tensions)(1)));
  EXPECT_EQ((*o.tensions)(2), 3e6);
  ASSERT_TRUE(stream.Take("1,1,2,0.1,0,0,0,,,", &o));
  EXPECT_FALSE(o.tensions.has_value());
  try {
    stream.Take("2,1,2,0.1,0,0,0,1e6,inf,3e6", &o);
    ADD_FAILURE() << "an infinite tension was taken";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("log.csv:4: column 'tension_2': ", 0), 0u) << e.what();
  }
}

TEST(DetectCommandInput, AByteOrderMarkBeforeTheHeaderIsSkipped) {
  // Excel's "CSV UTF-8" starts the file with one; the header's first column keeps its name.
  TempDirectory dir(::testing::TempDir());
  const std::string path = (dir.path() / "log.csv").string();
  WriteWholeFile(path, "\xEF\xBB\xBF" + Rows(5));
  const CliResult r = RunCli({"detect", path, "--scenario", kDetectScenario}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NE(r.err.find("moorsim detect: 5 samples (0 s to 4 s)"), std::string::npos) << r.err;
}

// A run.h5 as `moorsim run` records the detection input: the scenario's text, path and
// overrides, and 5 rows at 1 Hz of /detection/input with `tension_columns` load cells.
void WriteRunH5(const std::string& path, const std::string& scenario_text,
                const std::string& scenario_path, int tension_columns) {
  output::Hdf5File file(path);
  file.SetAttribute("/", "scenario", scenario_text);
  file.SetAttribute("/", "scenario_path", scenario_path);
  file.SetAttribute("/", "overrides", std::string());
  const output::TableId time = file.CreateTable("/detection/input/time", 0, "s");
  const output::TableId pose = file.CreateTable("/detection/input/pose_measured", 3, "m,m,rad");
  const output::TableId thrust = file.CreateTable("/detection/input/thrust", 3, "N,N,N m");
  const output::TableId cells =
      file.CreateTable("/detection/input/tension_measured", tension_columns, "N");
  for (int t = 0; t < 5; ++t) {
    file.Append(time, static_cast<double>(t));
    file.Append(pose, std::vector<double>{1.5, -2.25, -2.356});
    file.Append(thrust, std::vector<double>{1e5, 0.0, 0.0});
    file.Append(cells, std::vector<double>(tension_columns, 5e6));
  }
  file.Close();
}

TEST(DetectCommandInput, ARunH5WhoseTensionTableIsNotOneColumnPerLineIsRefused) {
  TempDirectory dir(::testing::TempDir());
  const std::string path = (dir.path() / "run.h5").string();
  const scenarios::Scenario scenario = scenarios::LoadScenario(kDetectScenario);
  ASSERT_EQ(scenario.mooring.lines.size(), 8u);
  WriteRunH5(path, scenario.text, kDetectScenario, 8);
  CliResult r = RunCli({"detect", path, "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  // Seven columns for eight lines: the cells detector would see no reading at all.
  WriteRunH5(path, scenario.text, kDetectScenario, 7);
  r = RunCli({"detect", path, "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: " + path +
                       ": /detection/input/tension_measured: 7 columns, the scenario has 8 "
                       "mooring lines (one tension per line)\n");
}

TEST(DetectCommandInput, ADamagedScenarioInARunH5IsReportedInTheRunH5) {
  TempDirectory dir(::testing::TempDir());
  const std::string path = (dir.path() / "run.h5").string();
  // Recorded from a library file that has far fewer lines than the recorded text: the
  // message must not send the user to line 3 of that file.
  std::string text = scenarios::LoadScenario(kDetectScenario).text;
  const std::size_t depth = text.find("depth:");
  ASSERT_NE(depth, std::string::npos);
  text.replace(depth, 6, "dpeth:");
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + depth, '\n'));
  WriteRunH5(path, text, kDetectScenario, 8);
  const CliResult r = RunCli({"detect", path, "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  const std::string expected = "moorsim: " + path + ": the scenario it records (from " +
                               kDetectScenario + "), line " + std::to_string(line) + ":";
  EXPECT_EQ(r.err.rfind(expected, 0), 0u) << r.err;
  EXPECT_NE(r.err.find("dpeth"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(kDetectScenario + ":"), std::string::npos) << r.err;
}

TEST(DetectCommandInput, AnEmptyOrDamagedRunH5IsNotTakenForACsvLog) {
  TempDirectory dir(::testing::TempDir());
  const std::string empty = (dir.path() / "run.h5").string();
  WriteWholeFile(empty, "");
  CliResult r = RunCli({"detect", empty}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: " + empty + ": empty (0 bytes), not an HDF5 file\n");
  // The first kilobytes overwritten (the signature with them).
  const std::string zeroed = (dir.path() / "zeroed.h5").string();
  WriteWholeFile(zeroed, std::string(4096, '\0'));
  r = RunCli({"detect", zeroed}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: " + zeroed + ": damaged or not an HDF5 file (no HDF5 signature)\n");
  // Any name: the signature says HDF5, what follows it is damaged.
  const std::string named = (dir.path() / "recording").string();
  WriteWholeFile(named, "\x89HDF\r\n\x1a\n" + std::string(100, '\x7f'));
  r = RunCli({"detect", named}, dir.path());
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: " + named + ": damaged HDF5 file (HDF5 cannot open it)\n");
}

TEST(DetectCommandInput, DropoutsWithinTheMaximumGapAreTakenAndBadFlagsRefused) {
  TempDirectory dir(::testing::TempDir());
  const std::string path = (dir.path() / "log.csv").string();
  WriteWholeFile(path, Rows(90, 1, 20));
  // The east channel gone from 20 s to the end at 89 s: 69 s, fine with --max-gap 70.
  CliResult r =
      RunCli({"detect", path, "--scenario", kDetectScenario, "--max-gap", "70"}, dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.Describe();
  EXPECT_NE(r.err.find("moorsim detect: 90 samples (0 s to 89 s)"), std::string::npos) << r.err;
  r = RunCli({"detect", path, "--scenario", kDetectScenario, "--max-gap", "0"}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "moorsim: --max-gap: '0' must be positive [s]\n");
  r = RunCli({"detect", path}, dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--scenario: required for a CSV stream"), std::string::npos) << r.err;
  r = RunCli({"detect", (dir.path() / "missing.csv").string(), "--scenario", kDetectScenario},
             dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "moorsim: " + (dir.path() / "missing.csv").string() + ": no such file\n");
  r = RunCli({"detect", path, "--scenario", kDetectScenario, "--follow", "--out",
              (dir.path() / "d").string(), "--flush-interval", "0"},
             dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "moorsim: --flush-interval: '0' must be positive [s]\n");
  r = RunCli({"detect", path, "--scenario", kDetectScenario, "--out", (dir.path() / "d").string(),
              "--flush-interval", "5"},
             dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--flush-interval: paces the writes of --out DIR for a live input"),
            std::string::npos)
      << r.err;
}

// --out that cannot be a directory to write in: one line naming it and why, exit 2.
TEST(DetectCommandInput, AnOutputDirectoryThatCannotBeWrittenIsOneLine) {
  TempDirectory dir(::testing::TempDir());
  const std::string path = (dir.path() / "log.csv").string();
  WriteWholeFile(path, Rows(5));
  const auto refused = [&](const std::filesystem::path& out) {
    return RunCli({"detect", path, "--scenario", kDetectScenario, "--quiet", "--out", out.string()},
                  dir.path());
  };
  CliResult r = refused(path);
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: --out " + path + ": is a file, not a directory\n");
  r = refused(path + "/d");
  EXPECT_EQ(r.exit_code, 2) << r.Describe();
  EXPECT_EQ(r.err, "moorsim: --out " + path + "/d: cannot create the directory: Not a directory\n");
  if (::geteuid() != 0) {  // permissions do not stop root
    const std::filesystem::path read_only = dir.path() / "read_only";
    std::filesystem::create_directories(read_only);
    std::filesystem::permissions(
        read_only, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    r = refused(read_only);
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.err, "moorsim: --out " + read_only.string() +
                         ": cannot write in the directory: Permission denied\n");
  }
}

// Where process `pid` has read `path` to: the offset of its descriptor of that file, -1
// while it has none.
long ReadOffset(pid_t pid, const std::filesystem::path& path) {
  const std::filesystem::path fds = "/proc/" + std::to_string(pid) + "/fd";
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(fds, error)) {
    std::error_code link_error;
    if (std::filesystem::read_symlink(entry.path(), link_error) != path) continue;
    std::istringstream info(ReadWholeFile("/proc/" + std::to_string(pid) + "/fdinfo/" +
                                          entry.path().filename().string()));
    for (std::string key; info >> key;) {
      long value = 0;
      if (key == "pos:" && info >> value) return value;
    }
  }
  return -1;
}

// Waits until `pid` has read `path` to `offset`; false if it ended or took two minutes.
bool AwaitOffset(pid_t pid, const std::filesystem::path& path, long offset) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (ReadOffset(pid, path) != offset) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      ADD_FAILURE() << "the process ended (status " << status << ") before reading to " << offset;
      return false;
    }
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

// A followed log rotated while it is followed, as logrotate does it: by copy-and-truncate
// (the logger goes on writing rows into the emptied file), then by a rewrite in place longer
// than what was read (a new header and rows). Every row is read, none from the middle of a
// line, and each rotation is said on stderr.
TEST(DetectCommandInput, AFollowedLogIsFollowedThroughItsRotations) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path log = std::filesystem::canonical(dir.path()) / "log.csv";
  const std::string all = Rows(90);
  std::vector<std::size_t> row_end;  // where each line of `all` ends
  for (std::size_t at = all.find('\n'); at != std::string::npos; at = all.find('\n', at + 1)) {
    row_end.push_back(at + 1);
  }
  const std::string header = all.substr(0, row_end[0]);
  // The header and rows 0..49; after the truncation rows 50..59 without a header; then the
  // file rewritten with the header and rows 60..89, longer than anything read before.
  const std::string first = all.substr(0, row_end[50]);
  const std::string after_truncation = all.substr(row_end[50], row_end[60] - row_end[50]);
  const std::string rewritten = header + all.substr(row_end[60]);
  ASSERT_LT(after_truncation.size(), first.size());
  ASSERT_GT(rewritten.size(), after_truncation.size());
  WriteWholeFile(log, first);

  const std::filesystem::path err_path = dir.path() / "stderr.txt";
  const pid_t pid = StartCli({"detect", log.string(), "--follow", "--scenario", kDetectScenario},
                             {"/dev/null"}, {err_path});

  ASSERT_TRUE(AwaitOffset(pid, log, static_cast<long>(first.size())));
  WriteWholeFile(log, "");
  Append(log, after_truncation);
  EXPECT_TRUE(AwaitOffset(pid, log, static_cast<long>(after_truncation.size())));
  {  // over the old bytes without truncating first: the file never looks shorter
    std::ofstream over(log, std::ios::in | std::ios::out | std::ios::binary);
    over << rewritten;
  }
  EXPECT_TRUE(AwaitOffset(pid, log, static_cast<long>(rewritten.size())));
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string err = ReadWholeFile(err_path);
  ASSERT_TRUE(WIFEXITED(status)) << err;
  EXPECT_EQ(WEXITSTATUS(status), 130) << err;
  EXPECT_NE(
      err.find("moorsim detect: " + log.string() + ": truncated; following it from its start\n"),
      std::string::npos)
      << err;
  EXPECT_NE(
      err.find("moorsim detect: " + log.string() + ": rewritten; following it from its start\n"),
      std::string::npos)
      << err;
  EXPECT_NE(err.find("moorsim detect: 90 samples (0 s to 89 s)"), std::string::npos) << err;
}

}  // namespace
}  // namespace moorsim::testing
