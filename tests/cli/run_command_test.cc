// `moorsim run` end to end: the datasets and attributes docs/design.md section 7 names, the
// summary, bit-for-bit reproducibility per seed, --set overrides and their errors.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <hdf5.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <algorithm>

#include <cmath>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "core/version.h"
#include "tests/cli/run_cli.h"

namespace moorsim::testing {
namespace {

const std::string kThesisNoFailure = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_no_failure.yaml";

/// Shape of a dataset (empty if it does not exist).
std::vector<hsize_t> Shape(hid_t file, const char* path) {
  if (H5Lexists(file, path, H5P_DEFAULT) <= 0) return {};
  const hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  const hid_t space = H5Dget_space(d);
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(d);
  return dims;
}

std::vector<double> Read(hid_t file, const char* path) {
  std::vector<hsize_t> dims = Shape(file, path);
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  std::vector<double> values(n);
  const hid_t d = H5Dopen2(file, path, H5P_DEFAULT);
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
  H5Dclose(d);
  return values;
}

bool HasAttribute(hid_t file, const char* object, const char* name) {
  return H5Aexists_by_name(file, object, name, H5P_DEFAULT) > 0;
}

TEST(RunCommand, WritesTheDesignDatasetsAndTheSummary) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "seed").string();
  const CliResult r =
      RunCli({"run", kSeed, "--out", out, "--duration", "20", "--quiet"}, dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();

  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  EXPECT_EQ(summary["scenario"], "seed_tapm");
  EXPECT_EQ(summary["seed"], 1);
  EXPECT_EQ(summary["version"], std::string(moorsim::kVersion));
  EXPECT_TRUE(summary["failure"].is_null());
  EXPECT_TRUE(summary["detectors"].is_object());
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_DOUBLE_EQ(summary["simulated_time"].get<double>(), 20.0);

  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hsize_t n = 21;  // 1 Hz output, t = 0 .. 20 s
  EXPECT_EQ(Shape(file, "/time"), std::vector<hsize_t>({n}));
  EXPECT_EQ(Shape(file, "/vessel/pose_true"), std::vector<hsize_t>({n, 6}));
  EXPECT_EQ(Shape(file, "/vessel/velocity_true"), std::vector<hsize_t>({n, 6}));
  EXPECT_EQ(Shape(file, "/vessel/pose_measured"), std::vector<hsize_t>({n, 3}));
  EXPECT_EQ(Shape(file, "/mooring/fairlead_tension"), std::vector<hsize_t>({n, 8}));
  EXPECT_EQ(Shape(file, "/thrust/commanded"), std::vector<hsize_t>({n, 3}));
  EXPECT_EQ(Shape(file, "/thrust/delivered"), std::vector<hsize_t>({n, 3}));
  for (const char* load : {"/environment/mooring", "/environment/waves_drift",
                           "/environment/current", "/environment/wind", "/environment/thrust"}) {
    EXPECT_EQ(Shape(file, load), std::vector<hsize_t>({n, 6})) << load;
  }
  for (const char* d : {"/time", "/vessel/pose_true", "/mooring/fairlead_tension"}) {
    EXPECT_TRUE(HasAttribute(file, d, "units")) << d;
  }
  for (const char* a : {"scenario", "scenario_name", "seed", "version", "failure_line"}) {
    EXPECT_TRUE(HasAttribute(file, "/", a)) << a;
  }
  // The seed case's start: tensions near the catenary's 6.06 MN, the vessel near (2, 2).
  const std::vector<double> tension = Read(file, "/mooring/fairlead_tension");
  EXPECT_NEAR(tension[0], 6.06e6, 0.02 * 6.06e6);
  const std::vector<double> pose = Read(file, "/vessel/pose_low_frequency");
  EXPECT_DOUBLE_EQ(pose[0], 2.0);
  H5Fclose(file);
}

TEST(RunCommand, SameSeedIsBitIdenticalAndAnotherSeedDiffers) {
  TempDirectory dir(::testing::TempDir());
  const std::string a = (dir.path() / "a").string(), b = (dir.path() / "b").string(),
                    c = (dir.path() / "c").string();
  for (const auto& [out, seed] : {std::pair{a, "5"}, {b, "5"}, {c, "6"}}) {
    const CliResult r = RunCli(
        {"run", kSeed, "--out", out, "--duration", "30", "--seed", seed, "--quiet"}, dir.path());
    ASSERT_EQ(r.exit_code, 0) << r.Describe();
  }
  // The writer stores no timestamps, so the same run gives the same bytes.
  EXPECT_EQ(ReadWholeFile(a + "/run.h5"), ReadWholeFile(b + "/run.h5"));
  const hid_t fa = H5Fopen((a + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t fc = H5Fopen((c + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  // Another seed: other waves (so another true motion) and other sensor noise.
  EXPECT_NE(Read(fa, "/vessel/pose_measured"), Read(fc, "/vessel/pose_measured"));
  EXPECT_NE(Read(fa, "/vessel/pose_true"), Read(fc, "/vessel/pose_true"));
  H5Fclose(fa);
  H5Fclose(fc);
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(c + "/summary.json"));
  EXPECT_EQ(summary["seed"], 6);
}

TEST(RunCommand, SetOverridesAValueAndIsRecorded) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "o").string();
  const CliResult r = RunCli({"run", kSeed, "--out", out, "--duration", "5", "--quiet", "--set",
                              "controller.type=none", "--set",
                              "environment.wind={speed: 8, "
                              "direction_from_deg: 90}"},
                             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  ASSERT_EQ(summary["overrides"].size(), 3u);  // the two --set and --duration
  EXPECT_EQ(summary["overrides"][0], "controller.type=none");
  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const std::vector<double> commanded = Read(file, "/thrust/commanded");
  for (double v : commanded) EXPECT_EQ(v, 0.0);  // no controller
  const std::vector<double> wind = Read(file, "/environment/wind");
  EXPECT_NE(wind[1], 0.0);  // wind from the east pushes the vessel
  H5Fclose(file);
}

TEST(RunCommand, BadOverridesAndFlagsExitWithCode2AndOneLine) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "x").string();
  const struct {
    std::vector<std::string> args;
    std::string message;
  } cases[] = {
      {{"--set", "controller.type=pid"},
       "moorsim: " + kSeed +
           ": controller.type: unknown controller 'pid' (known: none, observer_pid, pi)\n"},
      {{"--set", "nonsense"},
       "moorsim: --set nonsense: expected key.path=value (e.g. "
       "controller.type=pi)\n"},
      {{"--seed", "-3"},
       "moorsim: " + kSeed +
           ": simulation.seed: -3 must be a non-negative "
           "integer\n"},
      {{"--duration", "0"}, "moorsim: " + kSeed + ": simulation.duration: 0 s must be > 0\n"},
      {{"--set", "mooring.lines[9].length=1"},
       "moorsim: --set mooring.lines[9].length=1: there is no list entry [9]\n"},
  };
  for (const auto& c : cases) {
    std::vector<std::string> args = {"run", kSeed, "--out", out, "--quiet"};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const CliResult r = RunCli(args, dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(r.err, c.message);
  }
}

TEST(RunCommandSlow, ThesisCaseLine6PartsAtItsTime) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "l6").string();
  const CliResult r = RunCli({"run", MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6.yaml",
                              "--out", out, "--duration", "410", "--quiet"},
                             dir.path(), std::chrono::seconds(600));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  EXPECT_EQ(summary["failure"]["line"], 6);
  EXPECT_EQ(summary["failure"]["time"], 400.0);
  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const std::vector<double> tension = Read(file, "/mooring/fairlead_tension");
  const std::vector<double> time = Read(file, "/time");
  H5Fclose(file);
  for (std::size_t k = 0; k < time.size(); ++k) {
    const double t6 = tension[8 * k + 5];
    if (time[k] < 400.0) {
      EXPECT_GT(t6, 4e6) << "t = " << time[k];
    } else {
      EXPECT_EQ(t6, 0.0) << "t = " << time[k];
    }
  }
}

// The alarm history in summary.json against the alarm and decision tables of run.h5, read
// here without the library: line 6 parts at 60 s of the thesis case under a GLR with a
// threshold low enough to raise, revise and end alarms before and after the break.
TEST(RunCommandSlow, TheAlarmHistoryIsTheAlarmTableSummarised) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "h").string();
  const CliResult r =
      RunCli({"run", MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6_current.yaml", "--out",
              out, "--duration", "150", "--quiet", "--set", "failure.time=60", "--set",
              "detectors=[{type: glr, threshold: 12, hold: 0}]"},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const std::vector<double> time = Read(file, "/time");
  const std::vector<double> alarm = Read(file, "/detectors/glr/alarm");
  const std::vector<double> decision = Read(file, "/detectors/glr/decision");
  H5Fclose(file);
  ASSERT_EQ(alarm.size(), time.size());
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  const nlohmann::json& glr = summary["detectors"]["glr"];
  const nlohmann::json& history = glr["history"];

  // Events from the tables: the output is at 1 Hz like the sensors, so every verdict is a row.
  std::vector<std::pair<double, std::string>> expected;
  std::optional<double> named;  // first row at or after 60 s naming line 6
  double on_before = 0.0, on_after = 0.0;
  bool was = false;
  int named_before = 0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    const bool on = alarm[k] != 0.0;
    const int h = static_cast<int>(decision[k]);
    if (on && !was) expected.emplace_back(time[k], "onset");
    if (on && was && h != named_before) expected.emplace_back(time[k], "revision");
    if (!on && was) expected.emplace_back(time[k], "end");
    if (!named && on && h == 6 && time[k] >= 60.0) named = time[k];
    if (was && k > 0) (time[k] <= 60.0 ? on_before : on_after) += time[k] - time[k - 1];
    was = on;
    named_before = on ? h : 0;
  }
  ASSERT_GE(expected.size(), 3u) << "the threshold should give several events";
  ASSERT_EQ(history.size(), expected.size()) << history.dump();
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(history[i]["time"].get<double>(), expected[i].first) << i;
    EXPECT_EQ(history[i]["event"], expected[i].second) << i;
  }
  ASSERT_TRUE(named.has_value());
  EXPECT_EQ(glr["isolation_time"].get<double>(), *named);
  EXPECT_EQ(glr["isolation_delay"].get<double>(), *named - 60.0);
  EXPECT_EQ(glr["final_alarm"].get<bool>(), alarm.back() != 0.0);
  EXPECT_NEAR(glr["alarm_seconds_before_failure"].get<double>(), on_before, 1e-9);
  EXPECT_NEAR(glr["alarm_seconds_after_failure"].get<double>(), on_after, 1e-9);
}

TEST(RunCommand, DetectorsWriteScoresDecisionsAlarmsAndASummary) {
  // Wiring only (the detection performance is judged by the detector tests): three detectors
  // on 20 s of the seed case give their datasets with one column per hypothesis (9) and
  // their summary entries; a bad parameter is placed at its entry in the file.
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "d").string();
  const CliResult r =
      RunCli({"run", kSeed, "--out", out, "--duration", "20", "--quiet", "--set",
              "detectors=[{type: dht}, {type: mle, label: mle_slow, forgetting_factor: 0.9999}, "
              "{type: glr}]"},
             dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  for (const char* d : {"dht", "mle_slow", "glr"}) {
    const std::string group = std::string("/detectors/") + d;
    EXPECT_EQ(Shape(file, (group + "/score").c_str()), std::vector<hsize_t>({21, 9})) << d;
    EXPECT_EQ(Shape(file, (group + "/decision").c_str()), std::vector<hsize_t>({21})) << d;
    EXPECT_EQ(Shape(file, (group + "/alarm").c_str()), std::vector<hsize_t>({21})) << d;
  }
  EXPECT_TRUE(HasAttribute(file, "/detectors", "hypotheses"));
  H5Fclose(file);
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  for (const char* d : {"dht", "mle_slow", "glr"}) {
    ASSERT_TRUE(summary["detectors"].contains(d)) << d;
    const nlohmann::json& j = summary["detectors"][d];
    for (const char* key : {"alarm_time", "isolated_line", "delay", "false_alarms"}) {
      EXPECT_TRUE(j.contains(key)) << d << " " << key;
    }
  }

  const CliResult bad =
      RunCli({"run", kSeed, "--out", out, "--quiet", "--set", "detectors=[{type: dht, floor: 2}]"},
             dir.path());
  EXPECT_EQ(bad.exit_code, 2) << bad.Describe();
  EXPECT_EQ(bad.err, "moorsim: " + kSeed + ": detectors[1].floor: 2 must be in (0, 1)\n");
}

}  // namespace
}  // namespace moorsim::testing

namespace moorsim::testing {
namespace {

// Bad detector configuration in a scenario file fails `moorsim validate` with one line that
// places it (file:line:col) and names the entry, the value and the rule; exit code 2.
TEST(ValidateDetectors, BadConfigurationIsOneLineWithExitCode2) {
  TempDirectory dir(::testing::TempDir());
  std::string base = ReadWholeFile(kSeed);
  const std::string relative = "../../data/fpso_wamit/fpso";
  base.replace(base.find(relative), relative.size(), MOORSIM_SOURCE_DIR "/data/fpso_wamit/fpso");
  struct Case {
    std::string entry, message;
  };
  const Case cases[] = {
      {"{type: dhx}",
       "detectors[1].type: unknown detector 'dhx' (known: cells, deficit, dht, fused, glr, mle)"},
      {"{type: dht, floor: 0}", "detectors[1].floor: 0 must be in (0, 1)"},
      {"{type: dht, floor: 1}", "detectors[1].floor: 1 must be in (0, 1)"},
      {"{type: mle, forgetting_factor: 1.5}",
       "detectors[1].forgetting_factor: 1.5 must be in (0, 1]"},
      {"{type: mle, forgetting_factor: 0}", "detectors[1].forgetting_factor: 0 must be in (0, 1]"},
      {"{type: glr, threshold: }", "detectors[1].threshold: an empty value must be a number"},
      {"{type: glr, threshold: 50, false_alarm_probability: 0.001}",
       "detectors[1]: give threshold or false_alarm_probability, not both"},
      {"{type: deficit}",
       "detectors[1].type: deficit reads the EKF observers' load estimate, which "
       "detection.observer: passive does not give (use ekf)"},
  };
  // The force-deficit detector reads the EKF bank's load estimate, which the passive
  // observers do not make.
  const std::string passive = "detection: {observer: passive}\n";
  for (const Case& c : cases) {
    SCOPED_TRACE(c.entry);
    const std::filesystem::path file = dir.path() / "bad.yaml";
    const bool needs_ekf = c.entry == "{type: deficit}";
    WriteWholeFile(file,
                   base + "\n" + (needs_ekf ? passive : "") + "detectors:\n  - " + c.entry + "\n");
    const CliResult r = RunCli({"validate", file.string()}, dir.path());
    EXPECT_EQ(r.exit_code, 2) << r.Describe();
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("moorsim: " + file.string() + ":", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(": " + c.message + "\n"), std::string::npos) << r.err;
  }
}

TEST(RunCommand, TheObserverBanksLoadPictureIsRecorded) {
  // The EKF bank's intact filter: its bias and wave-motion estimate at 1 Hz, Earth frame.
  // The wave motion it estimates is the vessel's: over the last 100 s of a thesis-sea run
  // its horizontal RMS lies within a factor of 2 of the true wave-frequency motion's (the
  // pose less its low-frequency part). The passive bank estimates no load: no tables.
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "ekf").string();
  CliResult r = RunCli({"run", kThesisNoFailure, "--duration", "200", "--out", out, "--quiet"},
                       dir.path(), std::chrono::seconds(120));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hsize_t n = 201;
  EXPECT_EQ(Shape(file, "/observer/bias"), std::vector<hsize_t>({n, 3}));
  EXPECT_EQ(Shape(file, "/observer/wave_motion"), std::vector<hsize_t>({n, 3}));
  EXPECT_TRUE(HasAttribute(file, "/observer/bias", "units"));
  const std::vector<double> bias = Read(file, "/observer/bias");
  const std::vector<double> wave = Read(file, "/observer/wave_motion");
  const std::vector<double> pose = Read(file, "/vessel/pose_true");
  const std::vector<double> low = Read(file, "/vessel/pose_low_frequency");
  H5Fclose(file);
  double estimated = 0.0, actual = 0.0;
  for (hsize_t i = n - 100; i < n; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(bias[3 * i + c])) << i;
    for (int c = 0; c < 2; ++c) {
      estimated += wave[3 * i + c] * wave[3 * i + c];
      const double w = pose[6 * i + c] - low[6 * i + c];
      actual += w * w;
    }
  }
  EXPECT_GT(actual, 0.0);
  EXPECT_GT(estimated, actual / 4.0);
  EXPECT_LT(estimated, actual * 4.0);

  const std::string passive = (dir.path() / "passive").string();
  r = RunCli({"run", kThesisNoFailure, "--duration", "10", "--set", "detection.observer=passive",
              "--set", "detectors=[{type: glr}]", "--out", passive, "--quiet"},
             dir.path(), std::chrono::seconds(120));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  file = H5Fopen((passive + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  EXPECT_LE(H5Lexists(file, "/observer", H5P_DEFAULT), 0);
  H5Fclose(file);
}

TEST(RunCommand, ATenHertzControllerFinishes) {
  // Once a hang: the controller's instant k / 10 and its test t >= k * 0.1 disagreed.
  TempDirectory dir(::testing::TempDir());
  const CliResult r =
      RunCli({"run", kThesisNoFailure, "--duration", "20", "--set", "controller.rate_hz=10",
              "--out", (dir.path() / "r").string(), "--quiet"},
             dir.path(), std::chrono::seconds(120));
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const nlohmann::json summary =
      nlohmann::json::parse(ReadWholeFile(dir.path() / "r" / "summary.json"));
  EXPECT_EQ(summary["simulated_time"], 20.0);
}

// Starts a run that would take hours into `out` and returns its pid once run.h5.partial
// exists (the stop handlers are in place and the run has started) or two minutes passed.
pid_t StartLongRun(const std::filesystem::path& out) {
  const pid_t pid = StartCli(
      {"run", kThesisNoFailure, "--duration", "100000", "--out", out.string(), "--quiet"}, {});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!std::filesystem::exists(out / "run.h5.partial") &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return pid;
}

// Stops the run `pid` started by StartLongRun with SIGTERM and checks that it closed its
// files: exit 143, summary.json "interrupted" naming run.h5, run.h5 with every row reached.
void ExpectSigtermStopsItWithItsFiles(pid_t pid, const std::filesystem::path& out) {
  kill(pid, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 143);
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out / "summary.json"));
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["signal"], SIGTERM);
  EXPECT_EQ(summary["outputs"]["run"], "run.h5");
  const double reached = summary["simulated_time"].get<double>();
  EXPECT_GT(reached, 0.0);
  EXPECT_LT(reached, 100000.0);
  EXPECT_FALSE(std::filesystem::exists(out / "run.h5.partial"));
  const hid_t file = H5Fopen((out / "run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  EXPECT_EQ(Shape(file, "/time"), std::vector<hsize_t>{static_cast<hsize_t>(reached) + 1});
  H5Fclose(file);
}

TEST(RunCommand, SigtermStopsTheRunClosesTheFileAndExits143) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path out = dir.path() / "r";
  const pid_t pid = StartLongRun(out);
  ASSERT_GT(pid, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  ExpectSigtermStopsItWithItsFiles(pid, out);
}

// A second run into the directory of a run in progress is refused with one line, and the
// first run's files are untouched: it finishes (here: stops on SIGTERM) as if alone.
TEST(RunCommand, ASecondRunIntoABusyDirectoryIsRefusedAndTheFirstIsIntact) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path out = dir.path() / "r";
  const pid_t pid = StartLongRun(out);
  ASSERT_GT(pid, 0);
  const CliResult second =
      RunCli({"run", kSeed, "--out", out.string(), "--duration", "1", "--quiet"}, dir.path());
  EXPECT_EQ(second.exit_code, 2) << second.Describe();
  EXPECT_EQ(second.err, "moorsim: --out " + out.string() + ": in use by another moorsim (pid " +
                            std::to_string(pid) +
                            "); wait for it to finish or choose another directory\n");
  EXPECT_TRUE(std::filesystem::exists(out / "run.h5.partial"));
  ExpectSigtermStopsItWithItsFiles(pid, out);
}

// The same lock serves every command that writes a directory: held here by the test itself.
TEST(RunCommand, ADirectoryLockedByAnotherMoorsimIsRefusedForRunAndDetect) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path out = dir.path() / "busy";
  std::filesystem::create_directories(out);
  WriteWholeFile(out / "summary.json", "theirs\n");
  WriteWholeFile(out / "run.h5.partial", "theirs\n");
  const int fd = ::open((out / "moorsim.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  const std::string message = "moorsim: --out " + out.string() +
                              ": in use by another moorsim; wait for it to finish or choose "
                              "another directory\n";
  const CliResult run =
      RunCli({"run", kSeed, "--out", out.string(), "--duration", "1", "--quiet"}, dir.path());
  EXPECT_EQ(run.exit_code, 2) << run.Describe();
  EXPECT_EQ(run.err, message);
  WriteWholeFile(dir.path() / "log.csv",
                 "time,north,east,heading,thrust_surge,thrust_sway,"
                 "thrust_yaw\n0,0,0,0,0,0,0\n");
  const CliResult detect = RunCli({"detect", (dir.path() / "log.csv").string(), "--scenario",
                                   kThesisNoFailure, "--out", out.string(), "--quiet"},
                                  dir.path());
  EXPECT_EQ(detect.exit_code, 2) << detect.Describe();
  EXPECT_EQ(detect.err, message);
  ::close(fd);
  EXPECT_EQ(ReadWholeFile(out / "summary.json"), "theirs\n");
  EXPECT_EQ(ReadWholeFile(out / "run.h5.partial"), "theirs\n");
}

// summary.json names run.h5 only when run.h5 is there: here the rename into place fails (a
// directory is in the way).
TEST(RunCommand, TheSummaryNeverNamesARunFileThatIsNotThere) {
  TempDirectory dir(::testing::TempDir());
  const std::filesystem::path out = dir.path() / "r";
  std::filesystem::create_directories(out / "run.h5" / "in_the_way");
  const CliResult r =
      RunCli({"run", kSeed, "--out", out.string(), "--duration", "1", "--quiet"}, dir.path());
  EXPECT_EQ(r.exit_code, 1) << r.Describe();
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out / "summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_TRUE(summary["outputs"]["run"].is_null()) << summary["outputs"];
}

TEST(RunCommand, TheSeedAttributeIsUnsigned) {
  TempDirectory dir(::testing::TempDir());
  const std::string out = (dir.path() / "seed").string();
  const CliResult r = RunCli(
      {"run", kSeed, "--out", out, "--duration", "1", "--seed", "9223372036854775808", "--quiet"},
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.Describe();
  const hid_t file = H5Fopen((out + "/run.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const hid_t attribute = H5Aopen(file, "seed", H5P_DEFAULT);
  const hid_t type = H5Aget_type(attribute);
  EXPECT_EQ(H5Tget_sign(type), H5T_SGN_NONE);
  std::uint64_t seed = 0;
  H5Aread(attribute, H5T_NATIVE_UINT64, &seed);
  EXPECT_EQ(seed, 9223372036854775808ull);
  H5Tclose(type);
  H5Aclose(attribute);
  H5Fclose(file);
  const nlohmann::json summary = nlohmann::json::parse(ReadWholeFile(out + "/summary.json"));
  EXPECT_EQ(summary["seed"].get<std::uint64_t>(), 9223372036854775808ull);
}

}  // namespace
}  // namespace moorsim::testing
