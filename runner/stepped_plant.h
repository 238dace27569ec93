// The coupled plant of a scenario stepped by a caller (the C API, the Python module): its
// own controller or the caller's thrust, a steady external load, the state at any time;
// and its whole state saved and restored.
//
// Saving records the plant's inputs (the scenario, the seed, and every call that moved it
// or changed its inputs, in order); restoring rebuilds the plant and repeats those calls.
// The plant is deterministic (a scenario and a seed give the run bit for bit), so the
// restored plant is the saved one bit for bit, and stepping on repeats its trajectory. The
// cost is the simulated time up to the saved instant, run again (a restore to a state
// that continues the current one runs only the difference); the lines alone
// (mooring_fem::CoupledLines) save their numbers and restore in microseconds.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "scenarios/scenario.h"
#include "simulation/simulation.h"

namespace moorsim::runner {

class SteppedPlant {
 public:
  /// The plant of `scenario` (loaded with `overrides`, which are part of its identity) for
  /// run seed `seed`, at its moored static start. Throws as simulation::Simulation does.
  SteppedPlant(const scenarios::Scenario& scenario, std::uint64_t seed);

  double time() const { return simulation_->time(); }
  int num_lines() const { return simulation_->num_lines(); }
  /// The longest span one AdvanceTo() may cover [s]: a day (longer is a loop of calls).
  static constexpr double kMaxAdvance = 86400.0;

  /// Integrates to t (nothing for t = time()). Throws InputError for a t that is not
  /// finite, is behind or lies more than kMaxAdvance ahead, SolverError as
  /// Simulation::AdvanceTo. Once `interrupt` (asked after every event, empty: never)
  /// returns true, stops there and throws Interrupted: the plant is then at that instant,
  /// and saving it or going on from it is as if it had been asked to go there.
  void AdvanceTo(double t, const std::function<bool()>& interrupt = {});
  /// The caller's thrust command X, Y, N (body frame) from now on; nullopt: the controller.
  void SetThrustCommand(const std::optional<Vec3>& command);
  /// A steady load on the hull, Earth axes (X north, Y east [N], moment about z [N m]).
  void SetExternalLoad(const Vec3& load);
  /// Everything recorded at the current time (Simulation::Record), computed once per time.
  const simulation::Sample& Now();
  const simulation::Simulation& simulation() const { return *simulation_; }

  std::vector<std::uint8_t> Save() const;
  /// Returns to a saved state. Throws InputError for bytes that are not a moorsim plant
  /// state or are from another scenario, seed or version; the plant is then as it was.
  /// `interrupt` as for AdvanceTo(): a restore that replays the saved plant's inputs from
  /// its start leaves the plant as it was; one that continues the current plant leaves it
  /// where the replay stopped.
  void Restore(std::span<const std::uint8_t> bytes, const std::function<bool()>& interrupt = {});

 private:
  struct Input {
    enum Kind : std::int64_t { kAdvance, kThrust, kController, kLoad } kind;
    double values[3];
  };
  // Applies `input` and logs it (an advance that was interrupted: as the advance to where it
  // stopped, which is what the plant did).
  void Apply(const Input& input, const std::function<bool()>& interrupt = {});

  scenarios::Scenario scenario_;
  std::uint64_t seed_;
  std::uint64_t fingerprint_;
  std::unique_ptr<simulation::Simulation> simulation_;
  std::vector<Input> inputs_;
  std::optional<simulation::Sample> now_;
};

}  // namespace moorsim::runner
