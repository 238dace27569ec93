// `moorsim simulate-lines`: the mooring lines alone with the turret on a prescribed
// harmonic path; fairlead tensions vs time to CSV, wall time and integrator statistics.
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <numbers>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "core/format.h"
#include "core/version.h"
#include "io/text_file.h"
#include "mooring_fem/line_simulation.h"
#include "runner/lines_coupling.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"
#include "tools/commands.h"

namespace moorsim::cli {
namespace {

struct SimulateLinesOptions {
  std::string scenario;
  std::vector<std::string> motions;
  std::optional<std::string> motion_file;
  std::string duration;
  std::optional<std::string> out;
  std::string output_interval = "0.5";
  std::string segments;
  std::string tolerance_scale = "1";
  std::vector<std::string> parts;
  std::vector<std::string> sets;
  bool segments_given = false;
  bool quiet = false;
};

constexpr double kMinPeriod = 0.1;     // [s]
constexpr double kMaxPeriod = 1e6;     // [s]
constexpr double kMaxAmplitude = 1e4;  // [m]
// The tolerances a --tolerance-scale may give: CVODE's error test needs a relative tolerance
// well above round-off, and the scenario's own limits hold for the scaled values too.
constexpr double kMinRtol = 1e-12;

constexpr double kMaxAngleDeg = 90.0;  // [deg]: a roll, pitch or yaw amplitude

constexpr const char* kDofNames[] = {"surge", "sway", "heave", "roll", "pitch", "yaw"};

// --motion DOF:A1,T1[,A2,T2...], repeatable: each adds harmonics to its degree of freedom.
void AddMotion(const std::string& text, mooring_fem::PrescribedMotion& motion) {
  const std::string usage = "--motion: '" + text +
                            "' must be DOF:A1,T1[,A2,T2...] with DOF one of surge, sway, heave "
                            "(A in m), roll, pitch, yaw (A in deg)";
  const auto colon = text.find(':');
  if (colon == std::string::npos) throw InputError(usage);
  const std::string kind = text.substr(0, colon);
  const auto named = std::find(std::begin(kDofNames), std::end(kDofNames), kind);
  if (named == std::end(kDofNames)) {
    throw InputError("--motion: unknown motion '" + kind +
                     "' (known: surge, sway, heave, roll, pitch, yaw)");
  }
  const int dof = static_cast<int>(named - std::begin(kDofNames));
  const bool angle = dof >= mooring_fem::PrescribedMotion::kRoll;
  const std::vector<double> numbers = ParseNumberList("--motion", text.substr(colon + 1));
  if (numbers.empty() || numbers.size() % 2 != 0) {
    throw InputError(usage + " (amplitude/period pairs)");
  }
  for (std::size_t i = 0; i < numbers.size(); i += 2) {
    // Periods from faster than any sea wave to slower than any drift; amplitudes within a
    // mooring's reach. Outside these the integrator would fail on a nonsense path.
    if (!(numbers[i + 1] >= kMinPeriod && numbers[i + 1] <= kMaxPeriod)) {
      throw InputError("--motion: period " + FormatNumber(numbers[i + 1]) + " s must be in " +
                       FormatNumber(kMinPeriod) + ".." + FormatNumber(kMaxPeriod) + " s");
    }
    const double limit = angle ? kMaxAngleDeg : kMaxAmplitude;
    if (!(std::abs(numbers[i]) <= limit)) {
      throw InputError("--motion: amplitude " + FormatNumber(numbers[i]) + (angle ? " deg" : " m") +
                       " must be within " + FormatNumber(limit) + (angle ? " deg" : " m"));
    }
    motion.components[dof].push_back(
        {angle ? numbers[i] * std::numbers::pi / 180.0 : numbers[i], numbers[i + 1]});
  }
}

// --motion-file: CSV with the header time,x,y,z,roll_deg,pitch_deg,yaw_deg ('#' lines
// before it are comments), then one row per sample.
mooring_fem::MotionSeries ReadMotionFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("--motion-file: cannot read '" + path + "'");
  const std::string header = "time,x,y,z,roll_deg,pitch_deg,yaw_deg";
  mooring_fem::MotionSeries series;
  std::string line;
  int number = 0;
  bool seen_header = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (!seen_header) {
      if (line.empty() || line[0] == '#') continue;
      if (line != header) {
        throw InputError(where + "the header must be '" + header + "' (angles in degrees)");
      }
      seen_header = true;
      continue;
    }
    if (line.empty()) continue;
    std::vector<double> row;
    try {
      row = ParseNumberList("", line);
    } catch (const InputError&) {
      throw InputError(where + "'" + line + "' is not 7 numbers");
    }
    if (row.size() != 7) throw InputError(where + "'" + line + "' is not 7 numbers");
    if (!series.time.empty() && !(row[0] > series.time.back())) {
      throw InputError(where + "time " + FormatNumber(row[0]) + " s does not follow " +
                       FormatNumber(series.time.back()) + " s");
    }
    if (series.time.size() >= 10'000'000) throw InputError(where + "more than 1e7 samples");
    series.time.push_back(row[0]);
    for (int d = 0; d < 6; ++d) {
      series.values[d].push_back(d >= 3 ? row[1 + d] * std::numbers::pi / 180.0 : row[1 + d]);
    }
  }
  if (!seen_header) throw InputError("--motion-file " + path + ": no header '" + header + "'");
  if (series.time.size() < 2) {
    throw InputError("--motion-file " + path + ": at least two samples are needed");
  }
  return series;
}

mooring_fem::PrescribedMotion ParseMotion(const SimulateLinesOptions& o) {
  mooring_fem::PrescribedMotion motion;
  if (o.motions.empty() == !o.motion_file) {
    throw InputError("--motion, --motion-file: give one or more --motion or one --motion-file");
  }
  for (const std::string& text : o.motions) AddMotion(text, motion);
  if (o.motion_file) {
    motion.path = std::make_shared<const mooring_fem::MotionSpline>(
        ReadMotionFile(RequireText("--motion-file", *o.motion_file)));
  }
  return motion;
}

struct ScheduledPart {
  double time;
  mooring_fem::LineFailure failure;
};

// LINE:TIME[:fairlead|anchor|node=K], checked against the scenario's lines.
ScheduledPart ParsePart(const std::string& text, const scenarios::Scenario& scenario) {
  const std::string usage = "--part: '" + text + "' must be LINE:TIME[:fairlead|anchor|node=K]";
  std::vector<std::string> fields;
  std::stringstream in(text);
  for (std::string f; std::getline(in, f, ':');) fields.push_back(f);
  if (fields.size() < 2 || fields.size() > 3) throw InputError(usage);
  const int num_lines = static_cast<int>(scenario.mooring.lines.size());
  const int line = ParseInteger("--part " + text + ": line", fields[0], 1, num_lines);
  const double time = ParseNumber("--part " + text + ": time", fields[1]);
  if (time < 0) throw InputError("--part " + text + ": time " + fields[1] + " s must be >= 0");
  ScheduledPart p{time, {line - 1, mooring_fem::FailureMode::kFairlead, 0}};
  if (fields.size() == 3) {
    const std::string& mode = fields[2];
    if (mode == "anchor") {
      p.failure.mode = mooring_fem::FailureMode::kAnchor;
    } else if (mode.rfind("node=", 0) == 0) {
      // Internal nodes only: node 0 is the anchor, node n the fairlead.
      const int segments = scenario.mooring.lines[line - 1].Segments();
      p.failure.mode = mooring_fem::FailureMode::kNode;
      p.failure.node = ParseInteger("--part " + text + ": node", mode.substr(5), 1, segments - 1);
    } else if (mode != "fairlead") {
      throw InputError("--part: unknown mode '" + mode + "' (known: anchor, fairlead, node=K)");
    }
  }
  return p;
}

/// The CSV of --out: a regular file is written as FILE.partial and renamed to FILE once
/// complete, so that a run that fails (a full disk, the solver, a signal) never leaves a
/// truncated table under the name asked for; a device or a pipe (/dev/stdout) is written
/// directly. A failed write ends the run at once (exit 1), naming the file.
class CsvOutput {
 public:
  explicit CsvOutput(std::string path) : path_(std::move(path)) {
    std::error_code ignored;
    if (std::filesystem::is_directory(path_, ignored)) {
      throw InputError("--out: '" + path_ + "' is a folder (give the CSV file's name)");
    }
    const bool direct = std::filesystem::exists(path_, ignored) &&
                        !std::filesystem::is_regular_file(path_, ignored);
    writing_ = direct ? path_ : output::PartialPath(path_).string();
    stream_.open(writing_, std::ios::binary | std::ios::trunc);
    if (!stream_) {
      throw InputError("--out: cannot write '" + writing_ + "': " + std::strerror(errno));
    }
    created_ = !direct;
  }
  ~CsvOutput() {
    if (created_) {
      std::error_code ignored;
      std::filesystem::remove(writing_, ignored);
    }
  }
  CsvOutput(const CsvOutput&) = delete;
  CsvOutput& operator=(const CsvOutput&) = delete;

  std::ostream& stream() { return stream_; }
  /// Throws if a write failed so far.
  void Check() {
    if (!stream_) Fail();
  }
  /// Flushes, closes and gives the file its name.
  void Commit() {
    stream_.flush();
    Check();
    stream_.close();
    if (!stream_) Fail();
    if (created_) {
      output::PublishPartial(path_);
      created_ = false;
    }
  }

 private:
  [[noreturn]] void Fail() {
    const int error = errno;
    throw Error("--out '" + path_ + "': write failed" +
                (error != 0 ? std::string(": ") + std::strerror(error) : std::string()) +
                " (no CSV written)");
  }
  std::string path_;
  std::string writing_;
  std::ofstream stream_;
  bool created_ = false;
};

int RunSimulateLines(const SimulateLinesOptions& o) {
  scenarios::Scenario scenario = scenarios::LoadScenario(o.scenario, o.sets);
  const double duration = ParseNumber("--duration", o.duration);
  if (!(duration > 0.0)) throw InputError("--duration: " + o.duration + " s must be > 0");
  const double output_interval = ParseNumber("--output-interval", o.output_interval);
  if (!(output_interval > 0.0)) {
    throw InputError("--output-interval: " + o.output_interval + " s must be > 0");
  }
  const double tolerance_scale = ParseNumber("--tolerance-scale", o.tolerance_scale);
  if (!(tolerance_scale > 0.0)) {
    throw InputError("--tolerance-scale: " + o.tolerance_scale + " must be > 0");
  }
  // At most this many CSV rows: a smaller interval is a typo, not a request for terabytes.
  constexpr double kMaxRows = 1e7;
  if (duration / output_interval > kMaxRows) {
    throw InputError("--output-interval: " + o.output_interval + " s gives " +
                     FormatNumber(std::floor(duration / output_interval)) +
                     " rows over --duration " + o.duration + " s (at most 1e7)");
  }
  if (o.segments_given) {
    const int segments = ParseInteger("--segments", o.segments, 2, 10000);
    for (auto& line : scenario.mooring.lines) {
      if (line.sections.size() != 1) {
        throw InputError("--segments " + o.segments + ": line " + std::to_string(line.id) +
                         " has " + std::to_string(line.sections.size()) +
                         " sections; give each its segments in the scenario");
      }
      line.sections.front().segments = segments;
    }
  }
  mooring_fem::ScaleTolerances(scenario.solver, tolerance_scale);
  const auto within = [&](const char* name, double value, double low, double high) {
    if (!(value >= low && value < high)) {
      throw InputError("--tolerance-scale: " + o.tolerance_scale + " makes solver." + name + " " +
                       FormatNumber(value) + " (it must stay in " + FormatNumber(low) + ".." +
                       FormatNumber(high) + ")");
    }
  };
  within("rtol", scenario.solver.rtol, kMinRtol, 1.0);
  within("atol_position", scenario.solver.atol_position, 0.0, 1.0);
  within("atol_velocity", scenario.solver.atol_velocity, 0.0, 1.0);
  const mooring_fem::PrescribedMotion motion = ParseMotion(o);
  std::vector<ScheduledPart> parts;
  for (const std::string& p : o.parts) parts.push_back(ParsePart(p, scenario));

  std::optional<CsvOutput> output;
  std::ostream* csv = nullptr;
  if (o.out) csv = &output.emplace(RequireText("--out", *o.out)).stream();

  using Clock = std::chrono::steady_clock;
  const auto t_start = Clock::now();
  std::optional<mooring_fem::LineSimulation> started;
  try {
    started.emplace(scenarios::ToMooringParameters(scenario.mooring), scenario.solver, motion);
  } catch (const InputError& e) {  // a free point that cannot be at rest where it is
    scenarios::PlaceAtKey(scenario, e, "mooring.points[");
  }
  mooring_fem::LineSimulation& sim = *started;
  for (const ScheduledPart& p : parts) sim.ScheduleFailure(p.time, p.failure);
  // The scenario's waves on the lines (environment.waves.on_lines), realised from its seed
  // as a run of it would realise them; the motion stays the one prescribed.
  if (auto waves = runner::ScenarioLineWaves(scenario)) sim.mooring().SetWaves(waves);
  const auto t_ready = Clock::now();

  auto write_row = [&] {
    if (!csv) return;
    const std::vector<Vec3> forces = sim.FairleadForces();
    *csv << sim.time();
    for (const Vec3& f : forces) *csv << ',' << f.norm();
    *csv << '\n';
    output->Check();
  };
  if (csv) {
    csv->precision(10);
    *csv << "# moorsim " << moorsim::kVersion << " simulate-lines scenario=" << o.scenario
         << " duration=" << duration << " segments=" << scenario.mooring.lines.front().Segments()
         << " rtol=" << scenario.solver.rtol << " tolerance_scale=" << tolerance_scale;
    for (const std::string& m : o.motions) *csv << " motion=" << m;
    if (o.motion_file) *csv << " motion_file=" << *o.motion_file;
    for (const std::string& p : o.parts) *csv << " part=" << p;
    *csv << "\n# fairlead tension = magnitude of the force each line exerts on the turret [N]\n";
    *csv << "time";
    for (const auto& line : scenario.mooring.lines) *csv << ",line" << line.id;
    *csv << '\n';
  }
  write_row();
  const long steps = std::lround(duration / output_interval);
  double last_report = 0.0;
  for (long i = 1; i <= steps; ++i) {
    sim.AdvanceTo(std::min(duration, static_cast<double>(i) * output_interval));
    write_row();
    const double wall = std::chrono::duration<double>(Clock::now() - t_ready).count();
    if (!o.quiet && wall - last_report > 5.0) {
      std::fprintf(stderr, "simulate-lines: t = %.1f / %.1f s (%.0fx real time)\n", sim.time(),
                   duration, sim.time() / wall);
      last_report = wall;
    }
  }
  if (output) output->Commit();
  const auto t_end = Clock::now();
  const double init_s = std::chrono::duration<double>(t_ready - t_start).count();
  const double wall_s = std::chrono::duration<double>(t_end - t_ready).count();
  const IntegratorStats s = sim.stats();
  std::printf(
      "simulated %.1f s in %.3f s wall (+%.3f s static start): %.1fx real time\n"
      "segments %d, state size %zu, rtol %.2e; steps %ld, rhs %ld, jacobians %ld, "
      "linear setups %ld, newton iterations %ld, newton failures %ld, error-test failures %ld, "
      "stability order reductions %ld, last step %.4f s, last order %d\n",
      duration, wall_s, init_s, duration / wall_s, scenario.mooring.lines.front().Segments(),
      sim.state().size(), scenario.solver.rtol, s.steps, s.rhs_evals, s.jacobian_evals,
      s.linear_setups, s.newton_iterations, s.newton_failures, s.error_test_failures,
      s.stability_order_reductions, s.last_step, s.last_order);
  return 0;
}

}  // namespace

Command AddSimulateLinesCommand(CLI::App& app) {
  auto o = std::make_shared<SimulateLinesOptions>();
  CLI::App* sub = app.add_subcommand(
      "simulate-lines", "the mooring lines alone with the turret on a prescribed path (CSV)");
  sub->footer(
      "\nThe lines start from the FEM's static equilibrium; the command writes fairlead\n"
      "tensions vs time (CSV) and prints wall time, real-time factor and CVODE statistics.");
  sub->add_option("--set", o->sets, "override a scenario value: key.path=value (repeatable)");
  sub->add_option("scenario", o->scenario, "scenario YAML file")->required();
  sub->add_option("--motion", o->motions,
                  "DOF:A1,T1[,A2,T2...]: add A_i sin(2 pi t / T_i) to DOF (surge, sway, heave "
                  "[m]; roll, pitch, yaw [deg]), repeatable");
  sub->add_option("--motion-file", o->motion_file,
                  "CSV time,x,y,z,roll_deg,pitch_deg,yaw_deg: the motion's samples "
                  "(natural cubic spline between them)");
  sub->add_option("--duration", o->duration, "simulated time [s]")->required();
  sub->add_option("--out", o->out, "CSV file: time and each line's fairlead tension [N]");
  sub->add_option("--output-interval", o->output_interval, "CSV row interval [s] (default 0.5)");
  CLI::Option* segments =
      sub->add_option("--segments", o->segments, "override every line's number of segments");
  sub->add_option("--tolerance-scale", o->tolerance_scale,
                  "multiply rtol and every atol by this (e.g. 0.01 for a reference run)");
  sub->add_option("--part", o->parts,
                  "part a line: LINE:TIME[:fairlead|anchor|node=K] (repeatable)");
  sub->add_flag("--quiet", o->quiet, "no progress lines on stderr");
  return [o, segments] {
    o->segments_given = segments->count() > 0;
    return RunSimulateLines(*o);
  };
}

}  // namespace moorsim::cli
