// moorsim's Python module (the compiled part, `moorsim._moorsim`; python/moorsim/ wraps it):
// the lines for a coupling (Lines), the coupled plant stepped by the caller (Plant), a
// scenario's run and a campaign as library calls, and a scenario's detection replayed on
// arrays. Arrays come and go as NumPy arrays, SI units, NED, lines numbered from 1 as in
// the scenario. Long calls release the GIL and stop on Ctrl-C (KeyboardInterrupt).
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "campaign/batch.h"
#include "core/error.h"
#include "core/version.h"
#include "mooring_fem/coupled_lines.h"
#include "runner/lines_coupling.h"
#include "runner/run.h"
#include "runner/scenario_plant.h"
#include "runner/stepped_plant.h"
#include "scenarios/load.h"
#include "simulation/detection.h"
#include "simulation/output_layout.h"
#include "simulation/simulation.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace moorsim::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A 2-D array of `rows` x `columns` from row-major values.
Array Matrix(const std::vector<double>& values, std::size_t rows, std::size_t columns) {
  Array a({rows, columns});
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

Array Vector(const std::vector<double>& values) {
  Array a(values.size());
  std::copy(values.begin(), values.end(), a.mutable_data());
  return a;
}

template <int N>
Array Vector(const Eigen::Matrix<double, N, 1>& v) {
  Array a(N);
  for (int i = 0; i < N; ++i) a.mutable_data()[i] = v(i);
  return a;
}

// `values` as exactly n numbers, or a ValueError naming `name`.
std::vector<double> Numbers(const Array& values, std::size_t n, const char* name) {
  if (values.ndim() != 1 || static_cast<std::size_t>(values.size()) != n) {
    throw py::value_error(std::string(name) + " must hold " + std::to_string(n) + " numbers, not " +
                          std::to_string(values.size()));
  }
  return std::vector<double>(values.data(), values.data() + n);
}

mooring_fem::BodyDofs Dofs(const Array& values, const char* name) {
  const std::vector<double> v = Numbers(values, 6, name);
  mooring_fem::BodyDofs d;
  std::copy(v.begin(), v.end(), d.begin());
  return d;
}

// A saved state as Python bytes, and back (the view lives as long as `state`).
py::bytes ToBytes(const std::vector<std::uint8_t>& bytes) {
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}
std::span<const std::uint8_t> StateOf(const py::bytes& state) {
  const std::string_view view = state;
  return {reinterpret_cast<const std::uint8_t*>(view.data()), view.size()};
}

// Ctrl-C for long calls that run without the GIL. Asked from any thread, as often as a
// call likes (it looks at a clock, and at Python's signals at most every 20 ms); only the
// main thread sees signals. The first stop is kept for every later ask.
class PythonStop {
 public:
  bool operator()() {
    if (signal_.load() != 0) return true;
    const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
    auto last = asked_.load();
    if (now - last < kEvery && now >= last) return false;
    if (!asked_.compare_exchange_strong(last, now)) return signal_.load() != 0;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) signal_ = SIGINT;
    return signal_.load() != 0;
  }
  // As the run and campaign requests ask: the signal, 0 for none.
  std::function<int()> Function() {
    return [this] { return (*this)() ? signal_.load() : 0; };
  }
  bool stopped() const { return signal_.load() != 0; }

 private:
  static constexpr std::chrono::steady_clock::rep kEvery =
      std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::milliseconds(20))
          .count();
  std::atomic<int> signal_{0};
  // The first ask of Python comes 20 ms into the call: a shorter call (a coupling step)
  // never takes the GIL, and Python itself sees Ctrl-C as soon as it returns.
  std::atomic<std::chrono::steady_clock::rep> asked_{
      std::chrono::steady_clock::now().time_since_epoch().count()};
};

// Runs `call(stop)` without the GIL, `stop` answering Ctrl-C; an interrupted call raises
// the KeyboardInterrupt (whatever the call threw on its way out).
template <typename Call>
auto Interruptibly(Call call) {
  PythonStop stop;
  std::optional<decltype(call(stop))> result;
  try {
    py::gil_scoped_release release;
    result.emplace(call(stop));
  } catch (const Error&) {
    if (!stop.stopped()) throw;
  }
  if (stop.stopped()) throw py::error_already_set();
  return std::move(*result);
}

// The same for calls that take a stop hook as a request's `stop_requested`.
template <typename Call>
auto Interruptible(std::function<int()>& stop_requested, Call call) {
  return Interruptibly([&](PythonStop& stop) {
    stop_requested = stop.Function();
    return call();
  });
}

// An integer argument in [low, high], or a TypeError (not an integer) or ValueError (out of
// range; IndexError for an index) naming it: pybind's own refusal of a Python int too large
// for a C++ one would name no argument.
template <typename Int>
Int IntegerArgument(const py::handle& value, const char* name, Int low, Int high,
                    bool index = false) {
  if (!PyLong_Check(value.ptr()) || PyBool_Check(value.ptr())) {
    throw py::type_error(std::string(name) + " must be an integer, not " +
                         std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  }
  const py::int_ number = py::reinterpret_borrow<py::int_>(value);
  const bool in_range = number >= py::int_(low) && number <= py::int_(high);
  if (!in_range) {
    const std::string range = std::to_string(low) + ".." + std::to_string(high);
    const std::string given = std::string(name) + " " + std::string(py::repr(value));
    if (index) throw py::index_error(given + " is not one of the " + name + "s " + range);
    throw py::value_error(given + " is not in " + range);
  }
  return number.cast<Int>();
}

// moorsim.MoorsimWarning (a RuntimeWarning): what a call did although it looks wrong.
PyObject* warning_category = nullptr;

// Issues each of `warnings` as a MoorsimWarning (an error where the caller's warning filters
// make it one).
void Warn(const std::vector<std::string>& warnings) {
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(warning_category, w.c_str(), 2) < 0) throw py::error_already_set();
  }
}

// The lines of a scenario for a coupling (mooring_fem/coupled_lines.h).
class Lines {
 public:
  explicit Lines(scenarios::Scenario scenario)
      : scenario_(std::move(scenario)), lines_(runner::MakeCoupledLines(scenario_)) {}

  int num_lines() const { return lines_->num_lines(); }
  double time() const { return lines_->time(); }
  int node_count(const py::handle& line) const { return lines_->num_nodes(Index(line)); }

  Array Init(const Array& x, const Array& xd) {
    const auto pose = Dofs(x, "x"), velocity = Dofs(xd, "xd");
    const Vec6 load = runner::InitCoupledLines(*lines_, scenario_, pose, velocity);
    Warn(lines_->TakeWarnings());
    return Vector<6>(load);
  }
  Array Step(const Array& x, const Array& xd, double dt) {
    Ready();
    const auto pose = Dofs(x, "x"), velocity = Dofs(xd, "xd");
    const Vec6 load = Interruptibly([&](PythonStop& stop) {
      return lines_->Step(pose, velocity, dt, [&stop] { return stop(); });
    });
    Warn(lines_->TakeWarnings());
    return Vector<6>(load);
  }
  Array BodyLoad() {
    Ready();
    return Vector<6>(lines_->LoadOnBody());
  }
  Array FairleadTensions() {
    std::vector<double> t;
    Ready();

    for (const Vec3& f : lines_->FairleadForces()) t.push_back(f.norm());
    return Vector(t);
  }
  Array FairleadForces() {
    Ready();
    std::vector<double> v;
    for (const Vec3& f : lines_->FairleadForces()) v.insert(v.end(), f.data(), f.data() + 3);
    return Matrix(v, num_lines(), 3);
  }
  Array AnchorTensions() {
    Ready();
    return Vector(lines_->AnchorTensions());
  }
  Array SegmentTensions(const py::handle& line) {
    Ready();
    return Vector(lines_->SegmentTensions(Index(line)));
  }
  Array NodePositions(const py::handle& line) {
    Ready();
    std::vector<double> v;
    for (const Vec3& p : lines_->NodePositions(Index(line)))
      v.insert(v.end(), p.data(), p.data() + 3);
    return Matrix(v, v.size() / 3, 3);
  }
  void Part(const py::handle& line, const std::string& where, const py::object& node) {
    Ready();
    mooring_fem::LineFailure f;
    f.line = Index(line);
    const std::optional<mooring_fem::FailureMode> mode =
        ParseChoice<mooring_fem::FailureMode>(where);
    if (!mode) {
      throw py::value_error("where must be 'fairlead', 'node' or 'anchor', not '" + where + "'");
    }
    f.mode = *mode;
    if (f.mode == mooring_fem::FailureMode::kNode) {
      if (node.is_none()) throw py::value_error("part(where='node') needs node=K");
      const int last = lines_->num_nodes(f.line) - 2;
      f.node = IntegerArgument<int>(node, "node", 1, std::max(last, 1), true);
    }
    lines_->Part(f);
  }
  py::bytes Save() {
    Ready();
    const std::vector<std::uint8_t> bytes = lines_->Save();
    return ToBytes(bytes);
  }
  void Restore(const py::bytes& state) { lines_->Restore(StateOf(state)); }

 private:
  void Ready() const {
    if (!lines_->initialized()) {
      throw std::runtime_error("the lines are not initialised (call init first)");
    }
  }
  int Index(const py::handle& line) const {
    return IntegerArgument<int>(line, "line", 1, num_lines(), true) - 1;
  }
  scenarios::Scenario scenario_;
  std::unique_ptr<mooring_fem::CoupledLines> lines_;
};

// One output row as a dict of arrays and numbers.
py::dict RowDict(const simulation::Sample& s) {
  py::dict d;
  d["time"] = s.time;
  d["pose"] = Vector<6>(s.pose_true);
  d["pose_low_frequency"] = Vector<6>(s.pose_low_frequency);
  d["velocity"] = Vector<6>(s.velocity);
  d["pose_measured"] = Vector<3>(s.pose_measured);
  d["fairlead_tension"] = Vector(s.fairlead_tension);
  d["tension_measured"] = Vector(s.tension_measured);
  d["thrust_commanded"] = Vector<3>(s.thrust_commanded);
  d["thrust_delivered"] = Vector<3>(s.thrust_delivered);
  d["load_mooring"] = Vector<6>(s.load_mooring);
  d["load_wave_drift"] = Vector<6>(s.load_wave_drift);
  d["load_current"] = Vector<6>(s.load_current);
  d["load_wind"] = Vector<6>(s.load_wind);
  d["load_thrust"] = Vector<6>(s.load_thrust);
  return d;
}

// The coupled plant of a scenario, stepped by the caller (runner/stepped_plant.h).
class Plant {
 public:
  Plant(const std::string& scenario, std::uint64_t seed, const std::vector<std::string>& overrides)
      : plant_(scenarios::LoadScenario(scenario, overrides), seed) {}
  double time() const { return plant_.time(); }
  int num_lines() const { return plant_.num_lines(); }
  void AdvanceTo(double t) {
    Interruptibly([&](PythonStop& stop) {
      plant_.AdvanceTo(t, [&stop] { return stop(); });
      return 0;
    });
  }
  py::dict Record() {
    const simulation::Sample& s = plant_.Now();
    py::dict d = RowDict(s);
    py::list verdicts;
    for (const detectors::Verdict& v : s.detectors) {
      verdicts.append(py::dict("alarm"_a = v.alarm, "hypothesis"_a = v.hypothesis,
                               "score"_a = Vector(v.score)));
    }
    d["detectors"] = verdicts;
    return d;
  }
  void SetThrust(const std::optional<Array>& command) {
    if (!command) {
      plant_.SetThrustCommand(std::nullopt);
      return;
    }
    const std::vector<double> v = Numbers(*command, 3, "thrust");
    plant_.SetThrustCommand(Vec3(v[0], v[1], v[2]));
  }
  void SetExternalLoad(const Array& load) {
    const std::vector<double> v = Numbers(load, 3, "load");
    plant_.SetExternalLoad(Vec3(v[0], v[1], v[2]));
  }
  Array FairleadTensions() { return Vector(plant_.Now().fairlead_tension); }
  std::vector<std::string> HypothesisLabels() const {
    return plant_.simulation().HypothesisLabels();
  }
  py::bytes Save() const {
    const std::vector<std::uint8_t> bytes = plant_.Save();
    return ToBytes(bytes);
  }
  void Restore(const py::bytes& state) {
    const std::span<const std::uint8_t> bytes = StateOf(state);
    Interruptibly([&](PythonStop& stop) {
      plant_.Restore(bytes, [&stop] { return stop(); });
      return 0;
    });
  }

 private:
  runner::SteppedPlant plant_;
};

py::dict Run(const std::string& scenario, const std::vector<std::string>& overrides,
             const std::optional<std::string>& out) {
  runner::RunRequest request;
  request.scenario_path = scenario;
  request.overrides = overrides;
  request.write_files = out.has_value();
  if (out) request.out = *out;
  const runner::RunResult result =
      Interruptible(request.stop_requested, [&request] { return runner::RunScenario(request); });
  py::dict d;
  d["status"] = runner::StatusName(result.status);
  d["message"] = result.message;
  d["directory"] = result.directory.string();
  d["summary"] = result.summary.dump();
  return d;
}

py::dict RunCampaign(const std::string& campaign, const std::optional<std::string>& out,
                     int threads, bool keep_runs, bool progress) {
  simulation::BatchOptions options;
  options.campaign_path = campaign;
  if (out) options.out = *out;
  options.threads = threads;
  options.keep_runs = keep_runs;
  options.progress = progress;
  options.command_line = "python: moorsim.run_campaign('" + campaign + "')";
  const simulation::BatchResult result =
      Interruptible(options.stop_requested, [&options] { return simulation::RunBatch(options); });
  static const char* const kNames[] = {"ok", "runs_failed", "rejected", "interrupted", "failed"};
  return py::dict("status"_a = kNames[static_cast<int>(result.status)],
                  "message"_a = result.message, "runs"_a = result.runs, "done"_a = result.done,
                  "failed"_a = result.failed, "skipped"_a = result.skipped,
                  "directory"_a = result.directory.string());
}

// The scenario's detection on recorded samples: per sample its time, measured x, y, psi
// (NaN: not delivered), the thrust issued and, with load cells, their readings.
py::dict Detect(const std::string& scenario_path, const std::vector<std::string>& overrides,
                const Array& time, const Array& pose, const std::optional<Array>& thrust,
                const std::optional<Array>& tensions) {
  const scenarios::Scenario scenario = scenarios::LoadScenario(scenario_path, overrides);
  const std::size_t n = static_cast<std::size_t>(time.size());
  if (time.ndim() != 1) throw py::value_error("time must be one-dimensional");
  const auto check_rows = [n](const Array& a, std::size_t width, const char* name) {
    if (a.ndim() != 2 || static_cast<std::size_t>(a.shape(0)) != n ||
        (width > 0 && static_cast<std::size_t>(a.shape(1)) != width)) {
      throw py::value_error(std::string(name) + " must have one row per time" +
                            (width > 0 ? " and " + std::to_string(width) + " columns" : ""));
    }
  };
  check_rows(pose, 3, "pose");
  if (thrust) check_rows(*thrust, 3, "thrust");
  // One reading per line, as `moorsim detect` takes them: a cell for every line or none.
  if (tensions) check_rows(*tensions, scenario.mooring.lines.size(), "tensions");
  const std::unique_ptr<simulation::Detection> detection = runner::MakeDetection(scenario);
  const std::size_t detectors = detection->records().size();
  const std::size_t hypotheses = static_cast<std::size_t>(detection->num_hypotheses());
  std::vector<std::vector<double>> alarm(detectors), decision(detectors), score(detectors);
  Interruptibly([&](PythonStop& stop) {
    for (std::size_t k = 0; k < n; ++k) {
      if (k % 256 == 0 && stop()) throw Interrupted("interrupted");
      detectors::Observation o;
      o.t = time.data()[k];
      for (int i = 0; i < 3; ++i) {
        const double v = pose.data()[3 * k + i];
        o.valid[i] = std::isfinite(v);
        o.pose(i) = o.valid[i] ? v : 0.0;
      }
      if (thrust) o.tau_command = Vec3(thrust->data() + 3 * k);
      if (tensions) {
        const std::size_t m = static_cast<std::size_t>(tensions->shape(1));
        o.tensions = Eigen::Map<const VecX>(tensions->data() + m * k, static_cast<int>(m));
      }
      detection->Update(o);
      for (std::size_t j = 0; j < detectors; ++j) {
        const detectors::Verdict& v = detection->verdicts()[j];
        alarm[j].push_back(v.alarm ? 1.0 : 0.0);
        decision[j].push_back(v.hypothesis);
        score[j].insert(score[j].end(), v.score.begin(), v.score.end());
      }
    }
    return 0;
  });
  py::dict by_label;
  for (std::size_t j = 0; j < detectors; ++j) {
    const std::size_t width = n > 0 ? score[j].size() / n : hypotheses;
    by_label[py::str(detection->records()[j].label)] =
        py::dict("type"_a = detection->records()[j].type, "alarm"_a = Vector(alarm[j]),
                 "decision"_a = Vector(decision[j]), "score"_a = Matrix(score[j], n, width));
  }
  return py::dict(
      "detectors"_a = by_label, "hypotheses"_a = detection->HypothesisLabels(),
      "summary"_a =
          runner::DetectorsSummary(scenario, *detection, n > 0 ? time.data()[n - 1] : 0.0).dump());
}

}  // namespace
}  // namespace moorsim::python

PYBIND11_MODULE(_moorsim, m) {
  using namespace moorsim::python;
  m.doc() = "moorsim's compiled core; use the moorsim package";
  m.attr("__version__") = moorsim::kVersion;
  warning_category =
      PyErr_NewException("moorsim._moorsim.MoorsimWarning", PyExc_RuntimeWarning, nullptr);
  m.attr("MoorsimWarning") = py::handle(warning_category);
  static py::exception<moorsim::Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<moorsim::InputError> input_error(m, "InputError", error.ptr());
  static py::exception<moorsim::SolverError> solver_error(m, "SolverError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const moorsim::InputError& e) {
      PyErr_SetString(input_error.ptr(), e.what());
    } catch (const moorsim::SolverError& e) {
      PyErr_SetString(solver_error.ptr(), e.what());
    } catch (const moorsim::Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  py::class_<Lines>(m, "Lines")
      .def(py::init([](const std::string& path, const std::vector<std::string>& overrides) {
             return std::make_unique<Lines>(moorsim::scenarios::LoadScenario(path, overrides));
           }),
           "scenario"_a, "overrides"_a = std::vector<std::string>{})
      .def_static(
          "from_yaml",
          [](const std::string& text) {
            return std::make_unique<Lines>(moorsim::scenarios::ParseScenario(text, "<yaml text>"));
          },
          "text"_a)
      .def_property_readonly("num_lines", &Lines::num_lines)
      .def_property_readonly("time", &Lines::time)
      .def_property_readonly("coupled_dofs", [](const Lines&) { return 6; })
      .def("node_count", &Lines::node_count, "line"_a)
      .def("init", &Lines::Init, "x"_a, "xd"_a)
      .def("step", &Lines::Step, "x"_a, "xd"_a, "dt"_a)
      .def("body_load", &Lines::BodyLoad)
      .def("fairlead_tensions", &Lines::FairleadTensions)
      .def("fairlead_forces", &Lines::FairleadForces)
      .def("anchor_tensions", &Lines::AnchorTensions)
      .def("segment_tensions", &Lines::SegmentTensions, "line"_a)
      .def("node_positions", &Lines::NodePositions, "line"_a)
      .def("part", &Lines::Part, "line"_a, "where"_a = "fairlead", "node"_a = py::none())
      .def("save", &Lines::Save)
      .def("restore", &Lines::Restore, "state"_a);

  py::class_<Plant>(m, "Plant")
      .def(py::init([](const std::string& scenario, const py::handle& seed,
                       const std::vector<std::string>& overrides) {
             return std::make_unique<Plant>(
                 scenario,
                 IntegerArgument<std::uint64_t>(seed, "seed", 0,
                                                std::numeric_limits<std::uint64_t>::max()),
                 overrides);
           }),
           "scenario"_a, "seed"_a, "overrides"_a = std::vector<std::string>{})
      .def_property_readonly("time", &Plant::time)
      .def_property_readonly("num_lines", &Plant::num_lines)
      .def_property_readonly("hypotheses", &Plant::HypothesisLabels)
      .def("advance_to", &Plant::AdvanceTo, "t"_a)
      .def("record", &Plant::Record)
      .def("set_thrust", &Plant::SetThrust, "command"_a)
      .def("set_external_load", &Plant::SetExternalLoad, "load"_a)
      .def("fairlead_tensions", &Plant::FairleadTensions)
      .def("save", &Plant::Save)
      .def("restore", &Plant::Restore, "state"_a);

  // The tables of run.h5 and detect.h5 as the writers declare them: (path, width, units,
  // columns), width -1 per line and -2 per hypothesis.
  m.def("_layout", [] {
    py::list tables;
    for (const moorsim::simulation::layout::Table& t : moorsim::simulation::layout::Tables()) {
      tables.append(py::make_tuple(std::string(t.path), t.width, std::string(t.units),
                                   std::string(t.columns)));
    }
    return tables;
  });
  m.def("_run", &Run, "scenario"_a, "overrides"_a, "out"_a);
  m.def("_run_campaign", &RunCampaign, "campaign"_a, "out"_a, "threads"_a, "keep_runs"_a,
        "progress"_a);
  m.def("_detect", &Detect, "scenario"_a, "overrides"_a, "time"_a, "pose"_a, "thrust"_a,
        "tensions"_a);
}
