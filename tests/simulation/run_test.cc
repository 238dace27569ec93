// One run as a library call (runner/run.h): every clock reached at any rate, the
// status and exit code of each outcome, and outputs that never lie after an interruption,
// a crash or a full disk (fault injection: a stop request at a chosen row, a child process
// that dies without closing its files, a file-size limit that makes writes fail).
#include "runner/run.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <hdf5.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/extremes.h"
#include "analysis/fatigue.h"
#include "core/angles.h"
#include "core/error.h"
#include "core/sample_clock.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::simulation {
namespace {

using runner::RunRequest;
using runner::RunResult;
using runner::RunScenario;
using runner::RunStatus;
using runner::WriteFileAtomically;

namespace fs = std::filesystem;

const std::string kThesis = MOORSIM_SOURCE_DIR "/scenarios/library/thesis_no_failure.yaml";

using moorsim::testing::FreshDirectory;

nlohmann::json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::json::parse(text.str());
}

/// Rows of /time in an HDF5 file, -1 if it does not open.
long TimeRows(const fs::path& path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) return -1;
  long rows = -1;
  const hid_t d = H5Dopen2(file, "/time", H5P_DEFAULT);
  if (d >= 0) {
    const hid_t space = H5Dget_space(d);
    hsize_t n = 0;
    H5Sget_simple_extent_dims(space, &n, nullptr);
    rows = static_cast<long>(n);
    H5Sclose(space);
    H5Dclose(d);
  }
  H5Fclose(file);
  return rows;
}

RunRequest Request(const fs::path& out, std::vector<std::string> overrides) {
  RunRequest request;
  request.scenario_path = kThesis;
  request.overrides = std::move(overrides);
  request.out = out;
  return request;
}

// A hang fails the test instead of the suite's time limit.
class RunTest : public ::testing::Test {
 protected:
  void SetUp() override { alarm(300); }
  void TearDown() override { alarm(0); }
};

using RunSlow = RunTest;

TEST_F(RunSlow, EveryControllerRateReachesEveryInstant) {
  // 10 Hz and 5 Hz once hung: the loop stopped at k / rate but fired at t >= k * (1 / rate).
  for (const char* rate : {"0.5", "1", "2", "3", "5", "10", "20"}) {
    SCOPED_TRACE(rate);
    const scenarios::Scenario scenario = scenarios::LoadScenario(
        kThesis, {std::string("controller.rate_hz=") + rate, "simulation.duration=20"});
    Simulation sim(scenarios::ToPlantModel(scenario), 1);
    sim.AdvanceTo(20.0);
    EXPECT_EQ(sim.time(), 20.0);
    const SampleClock clock(scenario.controller.rate);
    EXPECT_EQ(sim.controller_updates(), clock.LastIndex(20.0) + 1);
    EXPECT_EQ(sim.detection_timing().samples, 21);  // the 1 Hz GNSS/gyro
  }
}

// The low-frequency heading's distance from `target` [rad], recomputed from the record.
double HeadingError(Simulation& sim, double target) {
  return std::abs(std::remainder(sim.Record().pose_low_frequency(5) - target, 2.0 * kPi));
}

TEST_F(RunTest, StationKeepingFollowsTheHeadingAndTheThrustersLimits) {
  // The heading error is the low-frequency heading's distance from the setpoint at each
  // controller update, recomputed here from the recorded pose; the saturated share counts
  // the updates whose command the allocation scaled down: none without control, nearly all
  // with the setpoint 300 m away.
  for (const auto& [setpoint, saturates] : std::vector<std::pair<std::string, bool>>{
           {"controller.type=none", false},
           {"controller.setpoint={x: 300, y: 0, heading_deg: -105}", true}}) {
    SCOPED_TRACE(setpoint);
    const scenarios::Scenario scenario =
        scenarios::LoadScenario(kThesis, {setpoint, "simulation.duration=40"});
    Simulation sim(scenarios::ToPlantModel(scenario), 1);
    const double target = scenario.controller.setpoint ? scenario.controller.setpoint->z()
                                                       : scenario.vessel->initial_pose.z();
    double largest = 0.0, last = 0.0;
    for (int k = 0; k <= 40; ++k) {
      sim.AdvanceTo(k);
      last = HeadingError(sim, target);
      largest = std::max(largest, last);
    }
    const StationKeeping& kept = sim.station_keeping();
    EXPECT_EQ(kept.updates, 41);
    EXPECT_NEAR(kept.heading_error_max, largest, 1e-12);
    EXPECT_NEAR(kept.heading_error_last, last, 1e-12);
    if (saturates) {
      // 300 m off: the PI asks for far more than the seed thrusters' ~1-2 MN.
      EXPECT_GT(kept.SaturatedShare(), 0.9);
      EXPECT_GT(kept.heading_error_max, 29.0 * kDegree);  // the start is 30 deg off
    } else {
      EXPECT_EQ(kept.saturated, 0);
      EXPECT_LT(kept.heading_error_max, 1.0 * kDegree);  // 40 s adrift from the setpoint
    }
  }
  {
    // Without control the beam wind turns the free-turret hull; the largest error counts
    // up to the failure only (what a parted line does to the heading is the failure's).
    const scenarios::Scenario scenario = scenarios::LoadScenario(
        kThesis, {"controller.type=none", "environment.wind={speed: 20, direction_from_deg: -45}",
                  "failure.line=2", "failure.time=30.5", "simulation.duration=60"});
    Simulation sim(scenarios::ToPlantModel(scenario), 1);
    const double target = scenario.controller.setpoint->z();
    double before = 0.0, after = 0.0;
    for (int k = 0; k <= 60; ++k) {
      sim.AdvanceTo(k);
      double& largest = k <= 30 ? before : after;
      largest = std::max(largest, HeadingError(sim, target));
    }
    EXPECT_GT(after, before + 0.1 * kDegree);  // the test tells the two apart
    EXPECT_NEAR(sim.station_keeping().heading_error_max, before, 1e-12);
  }
  // The summary and a campaign's table carry the same numbers, in degrees.
  const fs::path dir = FreshDirectory("run_station_keeping");
  ASSERT_EQ(RunScenario(Request(dir, {"controller.setpoint={x: 300, y: 0, heading_deg: -105}",
                                      "simulation.duration=10"}))
                .status,
            RunStatus::kOk);
  const nlohmann::json kept = ReadJson(dir / "summary.json")["station_keeping"];
  EXPECT_EQ(kept["controller_updates"], 11);
  EXPECT_GT(kept["thrust_saturated_share"].get<double>(), 0.9);
  EXPECT_NEAR(kept["heading_error_max_deg"].get<double>(), 30.0, 1.0);
  EXPECT_LE(kept["heading_error_final_deg"].get<double>(),
            kept["heading_error_max_deg"].get<double>());
  fs::remove_all(dir);
}

TEST_F(RunTest, ClocksWithNoCommonPeriodAllKeepTheirInstants) {
  // Sensors 1 Hz, controller 3 Hz, output 7 Hz.
  const fs::path dir = FreshDirectory("run_clocks");
  const RunResult r = RunScenario(Request(
      dir, {"controller.rate_hz=3", "simulation.output_rate_hz=7", "simulation.duration=20"}));
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  EXPECT_EQ(r.simulated_time, 20.0);
  EXPECT_EQ(TimeRows(dir / "run.h5"), 141);
  const nlohmann::json summary = ReadJson(dir / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["detection"]["samples"], 21);
  EXPECT_FALSE(fs::exists(dir / "run.h5.partial"));
  fs::remove_all(dir);
}

TEST_F(RunTest, AStopRequestEndsTheRunWithEveryRowSoFarAndSaysSo) {
  const fs::path dir = FreshDirectory("run_stop");
  RunRequest request = Request(dir, {"simulation.duration=1000"});
  int rows = 0;
  request.stop_requested = [&rows] { return ++rows == 6 ? SIGTERM : 0; };
  const RunResult r = RunScenario(request);
  ASSERT_EQ(r.status, RunStatus::kInterrupted) << r.message;
  EXPECT_EQ(r.signal, SIGTERM);
  EXPECT_EQ(r.simulated_time, 5.0);
  EXPECT_EQ(TimeRows(dir / "run.h5"), 6);
  const nlohmann::json summary = ReadJson(dir / "summary.json");
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["simulated_time"], 5.0);
  EXPECT_EQ(summary["signal"], SIGTERM);
  EXPECT_EQ(summary["outputs"]["run"], "run.h5");
  fs::remove_all(dir);
}

TEST_F(RunTest, ACrashMidRunLeavesTheOldResultWholeAndTheFlushedRowsReadable) {
  const fs::path dir = FreshDirectory("run_crash");
  // A complete earlier result in the directory.
  ASSERT_EQ(RunScenario(Request(dir, {"simulation.duration=5"})).status, RunStatus::kOk);
  // A longer run into the same directory dies without closing anything at row 300: after
  // the flush at row 256, before the next one.
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    RunRequest request = Request(dir, {"simulation.duration=1000"});
    request.flush_rows = 256;
    int rows = 0;
    request.stop_requested = [&rows] {
      if (++rows == 300) _exit(0);
      return 0;
    };
    RunScenario(request);
    _exit(3);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  // The old pair is untouched: summary (5 s, ok) and run.h5 (6 rows) still belong together.
  const nlohmann::json summary = ReadJson(dir / "summary.json");
  EXPECT_EQ(summary["status"], "ok");
  EXPECT_EQ(summary["duration"], 5.0);
  EXPECT_EQ(TimeRows(dir / "run.h5"), 6);
  // The new run's partial file opens and holds the rows up to its last flush.
  EXPECT_EQ(TimeRows(dir / "run.h5.partial"), 256);
  fs::remove_all(dir);
}

TEST_F(RunTest, AFullDiskFailsTheRunWithoutACrashAndTheSummarySaysWhy) {
  const fs::path dir = FreshDirectory("run_full");
  // Writes beyond 200 kB fail with EFBIG, as they would with ENOSPC on a full disk; the
  // child also exits through HDF5's exit handlers, where a failed close once crashed.
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{200 * 1024, 200 * 1024};
    setrlimit(RLIMIT_FSIZE, &limit);
    const RunResult r = RunScenario(Request(dir, {"simulation.duration=1000"}));
    // 1: failed, as it should; 2: any other status; 10 more without a summary.
    const int code = r.status == RunStatus::kFailed ? 1 : 2;
    std::exit(r.summary_written ? code : 10 + code);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the run crashed: signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const nlohmann::json summary = ReadJson(dir / "summary.json");
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_THAT(summary["error"].get<std::string>(), ::testing::HasSubstr("File too large"));
  EXPECT_TRUE(summary["outputs"]["run"].is_null());
  EXPECT_FALSE(fs::exists(dir / "run.h5"));
  EXPECT_FALSE(fs::exists(dir / "run.h5.partial"));
  fs::remove_all(dir);
}

TEST_F(RunTest, AFileThatDoesNotFitIsAnErrorNotAnEmptyFile) {
  const fs::path dir = FreshDirectory("run_write");
  std::signal(SIGXFSZ, SIG_IGN);
  rlimit saved{};
  getrlimit(RLIMIT_FSIZE, &saved);
  const rlimit limit{1000, saved.rlim_max};
  setrlimit(RLIMIT_FSIZE, &limit);
  std::string message;
  try {
    WriteFileAtomically(dir / "summary.json", std::string(5000, 'x'));
  } catch (const Error& e) {
    message = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &saved);
  EXPECT_THAT(message, ::testing::HasSubstr("summary.json: write failed: File too large"));
  EXPECT_FALSE(fs::exists(dir / "summary.json"));
  EXPECT_FALSE(fs::exists(dir / "summary.json.partial"));
  WriteFileAtomically(dir / "summary.json", "{}\n");
  EXPECT_EQ(fs::file_size(dir / "summary.json"), 3u);
  fs::remove_all(dir);
}

TEST_F(RunTest, AMooredEquilibriumThatDoesNotConvergeFailsLoudly) {
  // A hull scaled to a fifth cannot carry the lines' 40 MN: the heave/roll/pitch iteration
  // diverges, and the run says so instead of starting from an unbalanced pose.
  const fs::path dir = FreshDirectory("run_equilibrium");
  const RunResult r = RunScenario(Request(dir, {"vessel.length_scale=0.2"}));
  EXPECT_EQ(r.status, RunStatus::kFailed);
  EXPECT_THAT(r.message, ::testing::HasSubstr("moored static equilibrium (heave, roll, pitch) "
                                              "did not converge in 30 iterations"));
  const nlohmann::json summary = ReadJson(dir / "summary.json");
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_TRUE(summary["outputs"]["run"].is_null());
  fs::remove_all(dir);
}

TEST_F(RunTest, BadInputIsRejectedBeforeAnythingIsWritten) {
  const fs::path dir = FreshDirectory("run_rejected");
  const RunResult r = RunScenario(Request(dir / "out", {"controller.rate_hz=-1"}));
  EXPECT_EQ(r.status, RunStatus::kRejected);
  EXPECT_THAT(r.message, ::testing::HasSubstr("controller.rate_hz"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace moorsim::simulation

namespace moorsim::simulation {
namespace {

// Runs `request` (line `line` parts at 400 s): the force-deficit test names it within
// 2 min, with no false alarm before.
void ExpectTheDeficitTestNames(const RunRequest& request, int line = 6) {
  const RunResult r = RunScenario(request);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  const nlohmann::json& deficit = r.summary.at("detectors").at("deficit");
  EXPECT_EQ(deficit.at("isolated_line"), line) << deficit.dump();
  EXPECT_EQ(deficit.at("false_alarms"), 0) << deficit.dump();
  const double delay = deficit.at("delay").get<double>();
  EXPECT_GT(delay, 0.0);
  EXPECT_LT(delay, 120.0);
}

// A mooring of composite lines (chain, polyester, chain, a clump weight on each) runs
// through the same coupled plant and detectors unchanged: the force-deficit test, whose
// quasi-static model tabulates each line's composite catenary, names the line that parts.
TEST(CompositeMooringSlow, TheDeficitTestNamesThePartedLine) {
  RunRequest request;
  request.scenario_path = MOORSIM_SOURCE_DIR "/scenarios/library/composite_line6.yaml";
  request.write_files = false;
  ExpectTheDeficitTestNames(request);
}

// The thesis case with line 6 parting, on a seabed sloping 1.5 deg (deeper toward east,
// each anchor moved onto it: 51 m deeper at y = 1950 m, 51 m shallower at y = -1950 m): the
// detectors' line model lays each chain on its slope, and the deficit test still names the
// parted line.
TEST(SlopingSeabedSlow, TheDeficitTestNamesThePartedLine) {
  auto scenario = std::make_shared<scenarios::Scenario>(
      scenarios::LoadScenario(MOORSIM_SOURCE_DIR "/scenarios/library/thesis_line6.yaml"));
  const double slope = 1.5 * std::numbers::pi / 180.0;
  scenario->mooring.seabed.slope = slope;
  scenario->mooring.seabed.slope_direction = 0.5 * std::numbers::pi;
  for (scenarios::LineSpec& line : scenario->mooring.lines) {
    line.anchor.z() = scenario->mooring.water.depth + std::tan(slope) * line.anchor.y();
  }
  ASSERT_NO_THROW(scenarios::Validate(*scenario));
  RunRequest request;
  request.scenario_path = scenario->source_path;
  request.scenario = scenario;
  request.write_files = false;
  ExpectTheDeficitTestNames(request);
}

// The seed mooring with its north line on a bridle (a free point where the anchor line
// meets two legs to the turret): the detectors' quasi-static model solves the apex's
// balance at every pose, and the force-deficit test names the anchor line when it parts
// at the apex, as it names the seed's own line 1.
TEST(BridledMooringSlow, TheDeficitTestNamesThePartedLine) {
  RunRequest request;
  request.scenario_path = MOORSIM_SOURCE_DIR "/scenarios/library/seed_bridled.yaml";
  request.overrides = {"failure={line: 1, time: 400, mode: fairlead}",
                       "detectors=[{type: deficit}]", "simulation.duration=800"};
  request.write_files = false;
  ExpectTheDeficitTestNames(request, 1);
}

// Load cells on the bridle, one at each line's upper end: a leg that parts barely moves the
// vessel (no pose-only detector sees it), but its twin's cell takes the load, which
// corroborates the leg's own cell reading zero: the cells test names the leg within
// seconds, with no false alarm.
TEST(BridledMooringSlow, TheCellsTestNamesAPartedLeg) {
  RunRequest request;
  request.scenario_path = MOORSIM_SOURCE_DIR "/scenarios/library/seed_bridled.yaml";
  request.overrides = {"failure={line: 9, time: 400, mode: fairlead}",
                       "sensors.tension_cells={rate_hz: 1, noise: {std_dev: 1.0e4}}",
                       "detectors=[{type: cells}]", "simulation.duration=800"};
  request.write_files = false;
  const RunResult r = RunScenario(request);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  const nlohmann::json& cells = r.summary.at("detectors").at("cells");
  EXPECT_EQ(cells.at("isolated_line"), 9) << cells.dump();
  EXPECT_EQ(cells.at("false_alarms"), 0) << cells.dump();
  EXPECT_LT(cells.at("delay").get<double>(), 20.0) << cells.dump();
}

// The design record (summary.json's "design") against the rows the run gave its caller:
// each line's largest top tension, when, its mean and spread, its largest after the
// failure, the rainflow damage of the rows' top tensions on the line type's curve; the
// largest tension along a line at least the top's; the vessel's largest offset from its
// initial pose.
TEST_F(RunTest, TheDesignRecordIsTheRowsExtremesAndTheirDamage) {
  scenarios::Scenario scenario =
      scenarios::LoadScenario(kThesis, {"simulation.duration=60", "simulation.output_rate_hz=5",
                                        "failure={line: 3, time: 30, mode: fairlead}"});
  scenarios::LineType& chain = scenario.mooring.line_types[0];
  chain.minimum_breaking_load = 5.4e6;
  chain.fatigue_curve = analysis::TnCurveOf(analysis::TnPreset::kStudlessChain);
  chain.fatigue_area = analysis::NominalArea(analysis::TnPreset::kStudlessChain, chain.diameter);
  RunRequest request;
  request.scenario = std::make_shared<const scenarios::Scenario>(scenario);
  request.write_files = false;
  const std::size_t lines = scenario.mooring.lines.size();
  std::vector<std::vector<double>> top(lines);
  std::vector<double> times;
  double offset = 0.0;
  const Vec3 start = scenarios::ToPlantModel(scenario).initial_pose;
  request.on_row = [&](const Sample& s) {
    times.push_back(s.time);
    for (std::size_t k = 0; k < lines; ++k) top[k].push_back(s.fairlead_tension[k]);
    offset = std::max(offset, std::hypot(s.pose_true(0) - start(0), s.pose_true(1) - start(1)));
  };
  const RunResult r = RunScenario(request);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  const nlohmann::json& design = r.summary.at("design");
  EXPECT_EQ(design.at("output_rate"), 5.0);
  EXPECT_EQ(times.size(), 301u);
  EXPECT_EQ(design.at("max_offset").get<double>(), offset);
  const analysis::FatigueComponent component{*chain.fatigue_curve, chain.fatigue_area,
                                             chain.minimum_breaking_load};
  for (std::size_t k = 0; k < lines; ++k) {
    SCOPED_TRACE("line " + std::to_string(k + 1));
    const nlohmann::json& line = design.at("lines").at(k);
    const std::vector<double>& t = top[k];
    const auto largest = std::max_element(t.begin(), t.end());
    EXPECT_EQ(line.at("max_top_tension").get<double>(), *largest);
    EXPECT_EQ(line.at("time_of_max_top_tension").get<double>(), times[largest - t.begin()]);
    double mean = 0.0;
    for (double x : t) mean += x;
    mean /= static_cast<double>(t.size());
    EXPECT_NEAR(line.at("mean_top_tension").get<double>(), mean, 1e-9 * mean);
    EXPECT_GT(line.at("std_top_tension").get<double>(), 0.0);
    const double after = *std::max_element(t.begin() + 150, t.end());  // from 30 s on
    EXPECT_EQ(line.at("max_top_tension_after_failure").get<double>(), after);
    EXPECT_GE(line.at("max_tension_along").get<double>(), *largest);
    EXPECT_EQ(line.at("minimum_breaking_load").get<double>(), 5.4e6);
    EXPECT_DOUBLE_EQ(line.at("top_damage").get<double>(), analysis::MinerDamage(t, component));
    EXPECT_GT(line.at("touchdown_damage").get<double>(), 0.0);
    // The thesis lines lie on the seabed near their anchors: the touchdown is up the line.
    EXPECT_GT(line.at("touchdown_segment").get<int>(), 1);
  }
  // Line 3 parted at its fairlead: nothing at its top after the failure.
  EXPECT_EQ(design.at("lines").at(2).at("max_top_tension_after_failure").get<double>(), 0.0);
}

// The record's Weibull fits of the peaks (the extremes of one long run) are those of the
// rows: each top tension's peaks above mean plus one standard deviation; none for the
// offset, whose slow drift gives too few peaks in 500 s.
TEST_F(RunTest, TheDesignRecordFitsTheRowsPeaks) {
  RunRequest request;
  request.scenario_path = kThesis;
  request.overrides = {"simulation.duration=600", "simulation.output_rate_hz=5",
                       "simulation.statistics_from=100"};
  request.write_files = false;
  std::vector<std::vector<double>> series(9);  // eight top tensions, then the offset
  const Vec3 start =
      scenarios::ToPlantModel(scenarios::LoadScenario(kThesis, request.overrides)).initial_pose;
  request.on_row = [&](const Sample& s) {
    if (s.time < 100.0) return;
    for (std::size_t k = 0; k < 8; ++k) series[k].push_back(s.fairlead_tension[k]);
    series[8].push_back(std::hypot(s.pose_true(0) - start(0), s.pose_true(1) - start(1)));
  };
  const RunResult r = RunScenario(request);
  ASSERT_EQ(r.status, RunStatus::kOk) << r.message;
  const nlohmann::json& design = r.summary.at("design");
  for (std::size_t k = 0; k < 9; ++k) {
    SCOPED_TRACE("series " + std::to_string(k));
    const std::vector<double>& x = series[k];
    double mean = 0.0, square = 0.0;
    for (double v : x) mean += v;
    mean /= static_cast<double>(x.size());
    for (double v : x) square += (v - mean) * (v - mean);
    const double threshold = mean + std::sqrt(square / static_cast<double>(x.size()));
    const std::vector<double> peaks = analysis::PeaksOverThreshold(x, threshold);
    const nlohmann::json& record =
        k < 8 ? design.at("lines").at(k).at("top_peaks") : design.at("offset_peaks");
    if (k == 8) {  // the offset drifts slowly: too few peaks in 500 s for a fit
      ASSERT_LT(peaks.size(), 10u);
      EXPECT_TRUE(record.is_null());
      continue;
    }
    ASSERT_GE(peaks.size(), 10u);
    const analysis::WeibullFit fit = analysis::FitWeibull(peaks, threshold, mean);
    ASSERT_TRUE(record.is_object()) << record;
    EXPECT_EQ(record.at("peaks").get<std::size_t>(), peaks.size());
    EXPECT_NEAR(record.at("threshold").get<double>(), threshold, 1e-9 * std::abs(threshold));
    EXPECT_NEAR(record.at("scale").get<double>(), fit.scale, 1e-6 * fit.scale);
    EXPECT_NEAR(record.at("shape").get<double>(), fit.shape, 1e-6 * fit.shape);
  }
}

}  // namespace
}  // namespace moorsim::simulation
