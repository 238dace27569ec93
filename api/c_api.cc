// The C API (include/moorsim/moorsim.h) over the C++ library: each call checks its
// arguments, runs inside one exception barrier that turns moorsim's errors into return
// codes and the calling thread's message, and never lets an exception cross into C.
#include "moorsim/moorsim.h"

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/version.h"
#include "mooring_fem/coupled_lines.h"
#include "runner/lines_coupling.h"
#include "runner/stepped_plant.h"
#include "scenarios/load.h"

// An interrupt request (moorsim_*_interrupt): set from any thread or a signal handler,
// taken by the call that honours it.
static_assert(std::atomic<bool>::is_always_lock_free,
              "an interrupt request is set from signal handlers");

struct moorsim_lines {
  moorsim::scenarios::Scenario scenario;
  std::unique_ptr<moorsim::mooring_fem::CoupledLines> lines;
  std::atomic<bool> interrupt{false};
};

struct moorsim_plant {
  std::unique_ptr<moorsim::runner::SteppedPlant> plant;
  std::atomic<bool> interrupt{false};
};

namespace {

using moorsim::mooring_fem::BodyDofs;
using moorsim::mooring_fem::CoupledLines;

thread_local std::string last_error;

// Misuse of the API by the caller: MOORSIM_ERROR_USAGE with its message.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Runs `body`, mapping what it throws to a return code and the thread's message.
template <typename Body>
int Guard(const char* function, Body&& body) {
  try {
    body();
    last_error.clear();
    return MOORSIM_OK;
  } catch (const UsageError& e) {
    last_error = std::string(function) + ": " + e.what();
    return MOORSIM_ERROR_USAGE;
  } catch (const moorsim::InputError& e) {
    last_error = std::string(function) + ": " + e.what();
    return MOORSIM_ERROR_INPUT;
  } catch (const moorsim::SolverError& e) {
    last_error = std::string(function) + ": " + e.what();
    return MOORSIM_ERROR_SOLVER;
  } catch (const moorsim::Interrupted& e) {
    last_error = std::string(function) + ": " + e.what() + " (on request)";
    return MOORSIM_ERROR_INTERRUPTED;
  } catch (const moorsim::ContractError& e) {
    last_error = std::string(function) + ": " + e.what();
    return MOORSIM_ERROR_INTERNAL;
  } catch (const moorsim::Error& e) {  // a static solve that does not converge
    last_error = std::string(function) + ": " + e.what();
    return MOORSIM_ERROR_SOLVER;
  } catch (const std::bad_alloc&) {
    last_error = std::string(function) + ": out of memory";
    return MOORSIM_ERROR_INTERNAL;
  } catch (const std::exception& e) {
    last_error = std::string(function) + ": " + e.what();
    return MOORSIM_ERROR_INTERNAL;
  } catch (...) {
    last_error = std::string(function) + ": unknown exception";
    return MOORSIM_ERROR_INTERNAL;
  }
}

// The process's warning handler (moorsim_set_warning_handler) and its user pointer, read as
// a pair.
struct WarningHandler {
  moorsim_warning_handler handler = nullptr;
  void* user = nullptr;
};
std::mutex warning_mutex;
WarningHandler warning_handler;

// Hands each of `warnings` (from a call of `function`) to the handler, or to stderr.
void Warn(const char* function, const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  WarningHandler h;
  {
    const std::lock_guard<std::mutex> lock(warning_mutex);
    h = warning_handler;
  }
  for (const std::string& w : warnings) {
    const std::string message = std::string(function) + ": " + w;
    if (h.handler != nullptr) {
      h.handler(message.c_str(), h.user);
    } else {
      std::fprintf(stderr, "moorsim: warning: %s\n", message.c_str());
    }
  }
}

void Require(bool condition, const std::string& what) {
  if (!condition) throw UsageError(what);
}

CoupledLines& Lines(moorsim_lines* handle) {
  Require(handle != nullptr, "the lines handle is NULL");
  return *handle->lines;
}

const CoupledLines& Lines(const moorsim_lines* handle) {
  Require(handle != nullptr, "the lines handle is NULL");
  return *handle->lines;
}

CoupledLines& Initialised(moorsim_lines* handle) {
  CoupledLines& lines = Lines(handle);
  Require(lines.initialized(), "the lines are not initialised (call moorsim_lines_init first)");
  return lines;
}

BodyDofs Dofs(const double* values, const char* name) {
  Require(values != nullptr, std::string(name) + " is NULL");
  BodyDofs dofs;
  for (int d = 0; d < 6; ++d) dofs[d] = values[d];
  return dofs;
}

void WriteLoad(const moorsim::Vec6& load, double* f) {
  for (int d = 0; d < 6; ++d) f[d] = load(d);
}

// Line `line` (1-based) as a 0-based index.
int LineIndex(const CoupledLines& lines, int line) {
  Require(line >= 1 && line <= lines.num_lines(), "line " + std::to_string(line) +
                                                      " is not one of the lines 1.." +
                                                      std::to_string(lines.num_lines()));
  return line - 1;
}

void RequireLength(int n, int expected, const char* what) {
  Require(n == expected, std::string(what) + " has length " + std::to_string(n) + ", expected " +
                             std::to_string(expected));
}

// A new handle from `make` (which fills it), or null with the thread's message.
template <typename Handle>
Handle* Create(const char* function, const std::function<void(Handle&)>& make) {
  Handle* made = nullptr;
  Guard(function, [&] {
    auto handle = std::make_unique<Handle>();
    make(*handle);
    made = handle.release();
  });
  return made;
}

moorsim::runner::SteppedPlant& Plant(moorsim_plant* handle) {
  Require(handle != nullptr, "the plant handle is NULL");
  return *handle->plant;
}

const moorsim::runner::SteppedPlant& Plant(const moorsim_plant* handle) {
  Require(handle != nullptr, "the plant handle is NULL");
  return *handle->plant;
}

void Copy(const double* from, int n, double* to) { std::copy(from, from + n, to); }

// The plant's interrupt request, taken when it is honoured.
std::function<bool()> InterruptOf(moorsim_plant* plant) {
  return [plant] { return plant->interrupt.exchange(false); };
}

}  // namespace

extern "C" {

int moorsim_api_version(void) { return MOORSIM_API_VERSION; }

const char* moorsim_version(void) { return moorsim::kVersion; }

const char* moorsim_last_error(void) { return last_error.c_str(); }

void moorsim_set_warning_handler(moorsim_warning_handler handler, void* user) {
  const std::lock_guard<std::mutex> lock(warning_mutex);
  warning_handler = {handler, user};
}

moorsim_lines* moorsim_lines_create(const char* scenario_path) {
  return Create<moorsim_lines>("moorsim_lines_create", [&](moorsim_lines& h) {
    Require(scenario_path != nullptr, "the scenario path is NULL");
    h.scenario = moorsim::scenarios::LoadScenario(scenario_path);
    h.lines = moorsim::runner::MakeCoupledLines(h.scenario);
  });
}

moorsim_lines* moorsim_lines_create_from_yaml(const char* yaml_text) {
  return Create<moorsim_lines>("moorsim_lines_create_from_yaml", [&](moorsim_lines& h) {
    Require(yaml_text != nullptr, "the YAML text is NULL");
    h.scenario = moorsim::scenarios::ParseScenario(yaml_text, "<yaml text>");
    h.lines = moorsim::runner::MakeCoupledLines(h.scenario);
  });
}

void moorsim_lines_destroy(moorsim_lines* lines) { delete lines; }

int moorsim_lines_coupled_dofs(const moorsim_lines* lines, int* count) {
  return Guard("moorsim_lines_coupled_dofs", [&] {
    Lines(lines);
    Require(count != nullptr, "count is NULL");
    *count = 6;
  });
}

int moorsim_lines_count(const moorsim_lines* lines, int* count) {
  return Guard("moorsim_lines_count", [&] {
    const CoupledLines& l = Lines(lines);
    Require(count != nullptr, "count is NULL");
    *count = l.num_lines();
  });
}

int moorsim_lines_node_count(const moorsim_lines* lines, int line, int* count) {
  return Guard("moorsim_lines_node_count", [&] {
    const CoupledLines& l = Lines(lines);
    Require(count != nullptr, "count is NULL");
    *count = l.num_nodes(LineIndex(l, line));
  });
}

int moorsim_lines_time(const moorsim_lines* lines, double* t) {
  return Guard("moorsim_lines_time", [&] {
    const CoupledLines& l = Lines(lines);
    Require(t != nullptr, "t is NULL");
    *t = l.time();
  });
}

int moorsim_lines_init(moorsim_lines* lines, const double* x, const double* xd) {
  return Guard("moorsim_lines_init", [&] {
    CoupledLines& l = Lines(lines);
    const BodyDofs pose = Dofs(x, "x"), velocity = Dofs(xd, "xd");
    moorsim::runner::InitCoupledLines(l, lines->scenario, pose, velocity);
    Warn("moorsim_lines_init", l.TakeWarnings());
  });
}

int moorsim_lines_step(moorsim_lines* lines, const double* x, const double* xd, double* f,
                       double* t, double* dt) {
  return Guard("moorsim_lines_step", [&] {
    CoupledLines& l = Initialised(lines);
    const BodyDofs pose = Dofs(x, "x"), velocity = Dofs(xd, "xd");
    Require(f != nullptr, "f is NULL");
    Require(t != nullptr, "t is NULL");
    Require(dt != nullptr, "dt is NULL");
    // The caller's clock may have summed its steps in another order: a relative 1e-9.
    Require(std::abs(*t - l.time()) <= 1e-9 * std::max(1.0, std::abs(l.time())),
            "t = " + moorsim::FormatNumber(*t) + " s but the lines are at " +
                moorsim::FormatNumber(l.time()) + " s");
    try {
      WriteLoad(l.Step(pose, velocity, *dt, [lines] { return lines->interrupt.exchange(false); }),
                f);
    } catch (...) {  // what was doubtful may be why it failed
      Warn("moorsim_lines_step", l.TakeWarnings());
      throw;
    }
    *t = l.time();
    Warn("moorsim_lines_step", l.TakeWarnings());
  });
}

int moorsim_lines_interrupt(moorsim_lines* lines) {
  if (lines == nullptr) return MOORSIM_ERROR_USAGE;
  lines->interrupt.store(true);
  return MOORSIM_OK;
}

int moorsim_lines_body_load(moorsim_lines* lines, double* f) {
  return Guard("moorsim_lines_body_load", [&] {
    CoupledLines& l = Initialised(lines);
    Require(f != nullptr, "f is NULL");
    WriteLoad(l.LoadOnBody(), f);
  });
}

int moorsim_lines_fairlead_tensions(moorsim_lines* lines, double* tensions, int n) {
  return Guard("moorsim_lines_fairlead_tensions", [&] {
    CoupledLines& l = Initialised(lines);
    Require(tensions != nullptr, "tensions is NULL");
    RequireLength(n, l.num_lines(), "tensions");
    const std::vector<moorsim::Vec3> forces = l.FairleadForces();
    for (int i = 0; i < n; ++i) tensions[i] = forces[i].norm();
  });
}

int moorsim_lines_fairlead_forces(moorsim_lines* lines, double* forces, int n) {
  return Guard("moorsim_lines_fairlead_forces", [&] {
    CoupledLines& l = Initialised(lines);
    Require(forces != nullptr, "forces is NULL");
    RequireLength(n, 3 * l.num_lines(), "forces");
    const std::vector<moorsim::Vec3> f = l.FairleadForces();
    for (int i = 0; i < l.num_lines(); ++i) {
      for (int m = 0; m < 3; ++m) forces[3 * i + m] = f[i](m);
    }
  });
}

int moorsim_lines_anchor_tensions(moorsim_lines* lines, double* tensions, int n) {
  return Guard("moorsim_lines_anchor_tensions", [&] {
    CoupledLines& l = Initialised(lines);
    Require(tensions != nullptr, "tensions is NULL");
    RequireLength(n, l.num_lines(), "tensions");
    const std::vector<double> anchor = l.AnchorTensions();
    std::copy(anchor.begin(), anchor.end(), tensions);
  });
}

int moorsim_lines_segment_tensions(moorsim_lines* lines, int line, double* tensions, int n) {
  return Guard("moorsim_lines_segment_tensions", [&] {
    CoupledLines& l = Initialised(lines);
    const int index = LineIndex(l, line);
    Require(tensions != nullptr, "tensions is NULL");
    RequireLength(n, l.num_nodes(index) - 1, "tensions");
    const std::vector<double> segments = l.SegmentTensions(index);
    std::copy(segments.begin(), segments.end(), tensions);
  });
}

int moorsim_lines_node_positions(moorsim_lines* lines, int line, double* xyz, int n) {
  return Guard("moorsim_lines_node_positions", [&] {
    CoupledLines& l = Initialised(lines);
    const int index = LineIndex(l, line);
    Require(xyz != nullptr, "xyz is NULL");
    RequireLength(n, 3 * l.num_nodes(index), "xyz");
    const std::vector<moorsim::Vec3> nodes = l.NodePositions(index);
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      for (int m = 0; m < 3; ++m) xyz[3 * k + m] = nodes[k](m);
    }
  });
}

int moorsim_lines_part(moorsim_lines* lines, int line, int where, int node) {
  return Guard("moorsim_lines_part", [&] {
    CoupledLines& l = Initialised(lines);
    moorsim::mooring_fem::LineFailure failure;
    failure.line = LineIndex(l, line);
    switch (where) {
      case MOORSIM_PART_FAIRLEAD:
        failure.mode = moorsim::mooring_fem::FailureMode::kFairlead;
        break;
      case MOORSIM_PART_ANCHOR:
        failure.mode = moorsim::mooring_fem::FailureMode::kAnchor;
        break;
      case MOORSIM_PART_NODE: {
        const int last = l.num_nodes(failure.line) - 2;
        Require(node >= 1 && node <= last,
                "node " + std::to_string(node) + " is not an internal node of line " +
                    std::to_string(line) + " (1.." + std::to_string(last) + ")");
        failure.mode = moorsim::mooring_fem::FailureMode::kNode;
        failure.node = node;
        break;
      }
      default:
        throw UsageError("where = " + std::to_string(where) +
                         " is not MOORSIM_PART_FAIRLEAD, MOORSIM_PART_NODE or MOORSIM_PART_ANCHOR");
    }
    l.Part(failure);
  });
}

int moorsim_lines_save(moorsim_lines* lines, void* buffer, size_t capacity, size_t* size) {
  return Guard("moorsim_lines_save", [&] {
    CoupledLines& l = Initialised(lines);
    Require(size != nullptr, "size is NULL");
    *size = l.SavedSize();
    if (buffer == nullptr) return;
    Require(capacity >= *size, "the buffer holds " + std::to_string(capacity) +
                                   " bytes, the state needs " + std::to_string(*size));
    const std::vector<std::uint8_t> bytes = l.Save();
    std::memcpy(buffer, bytes.data(), bytes.size());
    *size = bytes.size();
  });
}

int moorsim_lines_restore(moorsim_lines* lines, const void* buffer, size_t size) {
  return Guard("moorsim_lines_restore", [&] {
    CoupledLines& l = Lines(lines);
    Require(buffer != nullptr, "the buffer is NULL");
    l.Restore({static_cast<const std::uint8_t*>(buffer), size});
  });
}

moorsim_plant* moorsim_plant_create(const char* scenario_path, unsigned long long seed) {
  return Create<moorsim_plant>("moorsim_plant_create", [&](moorsim_plant& h) {
    Require(scenario_path != nullptr, "the scenario path is NULL");
    h.plant = std::make_unique<moorsim::runner::SteppedPlant>(
        moorsim::scenarios::LoadScenario(scenario_path), seed);
  });
}

moorsim_plant* moorsim_plant_create_from_yaml(const char* yaml_text, unsigned long long seed) {
  return Create<moorsim_plant>("moorsim_plant_create_from_yaml", [&](moorsim_plant& h) {
    Require(yaml_text != nullptr, "the YAML text is NULL");
    h.plant = std::make_unique<moorsim::runner::SteppedPlant>(
        moorsim::scenarios::ParseScenario(yaml_text, "<yaml text>"), seed);
  });
}

void moorsim_plant_destroy(moorsim_plant* plant) { delete plant; }

int moorsim_plant_line_count(const moorsim_plant* plant, int* count) {
  return Guard("moorsim_plant_line_count", [&] {
    const auto& p = Plant(plant);
    Require(count != nullptr, "count is NULL");
    *count = p.num_lines();
  });
}

int moorsim_plant_time(const moorsim_plant* plant, double* t) {
  return Guard("moorsim_plant_time", [&] {
    const auto& p = Plant(plant);
    Require(t != nullptr, "t is NULL");
    *t = p.time();
  });
}

int moorsim_plant_advance_to(moorsim_plant* plant, double t) {
  return Guard("moorsim_plant_advance_to", [&] { Plant(plant).AdvanceTo(t, InterruptOf(plant)); });
}

int moorsim_plant_interrupt(moorsim_plant* plant) {
  if (plant == nullptr) return MOORSIM_ERROR_USAGE;
  plant->interrupt.store(true);
  return MOORSIM_OK;
}

int moorsim_plant_set_thrust(moorsim_plant* plant, const double* command) {
  return Guard("moorsim_plant_set_thrust", [&] {
    auto& p = Plant(plant);
    if (command == nullptr) {
      p.SetThrustCommand(std::nullopt);
    } else {
      p.SetThrustCommand(moorsim::Vec3(command[0], command[1], command[2]));
    }
  });
}

int moorsim_plant_set_external_load(moorsim_plant* plant, const double* load) {
  return Guard("moorsim_plant_set_external_load", [&] {
    auto& p = Plant(plant);
    Require(load != nullptr, "load is NULL");
    p.SetExternalLoad(moorsim::Vec3(load[0], load[1], load[2]));
  });
}

int moorsim_plant_pose(moorsim_plant* plant, double* pose) {
  return Guard("moorsim_plant_pose", [&] {
    auto& p = Plant(plant);
    Require(pose != nullptr, "pose is NULL");
    Copy(p.Now().pose_true.data(), 6, pose);
  });
}

int moorsim_plant_measured_pose(moorsim_plant* plant, double* pose) {
  return Guard("moorsim_plant_measured_pose", [&] {
    auto& p = Plant(plant);
    Require(pose != nullptr, "pose is NULL");
    Copy(p.Now().pose_measured.data(), 3, pose);
  });
}

int moorsim_plant_fairlead_tensions(moorsim_plant* plant, double* tensions, int n) {
  return Guard("moorsim_plant_fairlead_tensions", [&] {
    auto& p = Plant(plant);
    Require(tensions != nullptr, "tensions is NULL");
    RequireLength(n, p.num_lines(), "tensions");
    Copy(p.Now().fairlead_tension.data(), n, tensions);
  });
}

int moorsim_plant_measured_tensions(moorsim_plant* plant, double* tensions, int n) {
  return Guard("moorsim_plant_measured_tensions", [&] {
    auto& p = Plant(plant);
    Require(tensions != nullptr, "tensions is NULL");
    RequireLength(n, p.num_lines(), "tensions");
    const std::vector<double>& cells = p.Now().tension_measured;
    if (cells.empty()) {
      throw moorsim::InputError("the scenario has no load cells (sensors.tension_cells)");
    }
    Copy(cells.data(), n, tensions);
  });
}

int moorsim_plant_thrust(moorsim_plant* plant, double* commanded, double* delivered) {
  return Guard("moorsim_plant_thrust", [&] {
    auto& p = Plant(plant);
    if (commanded != nullptr) Copy(p.Now().thrust_commanded.data(), 3, commanded);
    if (delivered != nullptr) Copy(p.Now().thrust_delivered.data(), 3, delivered);
  });
}

int moorsim_plant_loads(moorsim_plant* plant, double* loads, int n) {
  return Guard("moorsim_plant_loads", [&] {
    auto& p = Plant(plant);
    Require(loads != nullptr, "loads is NULL");
    RequireLength(n, 30, "loads");
    const moorsim::simulation::Sample& s = p.Now();
    Copy(s.load_mooring.data(), 6, loads);
    Copy(s.load_wave_drift.data(), 6, loads + 6);
    Copy(s.load_current.data(), 6, loads + 12);
    Copy(s.load_wind.data(), 6, loads + 18);
    Copy(s.load_thrust.data(), 6, loads + 24);
  });
}

int moorsim_plant_save(const moorsim_plant* plant, void* buffer, size_t capacity, size_t* size) {
  return Guard("moorsim_plant_save", [&] {
    const auto& p = Plant(plant);
    Require(size != nullptr, "size is NULL");
    const std::vector<std::uint8_t> bytes = p.Save();
    *size = bytes.size();
    if (buffer == nullptr) return;
    Require(capacity >= bytes.size(), "the buffer holds " + std::to_string(capacity) +
                                          " bytes, the state needs " +
                                          std::to_string(bytes.size()));
    std::memcpy(buffer, bytes.data(), bytes.size());
  });
}

int moorsim_plant_restore(moorsim_plant* plant, const void* buffer, size_t size) {
  return Guard("moorsim_plant_restore", [&] {
    auto& p = Plant(plant);
    Require(buffer != nullptr, "the buffer is NULL");
    p.Restore({static_cast<const std::uint8_t*>(buffer), size}, InterruptOf(plant));
  });
}

}  // extern "C"
