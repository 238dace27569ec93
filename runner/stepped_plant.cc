#include "runner/stepped_plant.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/format.h"
#include "core/sha256.h"
#include "core/state_bytes.h"
#include "runner/scenario_plant.h"

namespace moorsim::runner {

using simulation::Sample;
using simulation::Simulation;
namespace {

constexpr char kTag[9] = "moorsimP";
constexpr std::int64_t kFormat = 1;

// The scenario's whole text (bases merged and overrides applied, as outputs record it)
// and the seed, folded to 64 bits.
std::uint64_t PlantFingerprint(const scenarios::Scenario& scenario, std::uint64_t seed) {
  std::string identity = scenario.text;
  for (const std::string& o : scenario.overrides) identity += "\n" + o;
  identity += "\nseed " + std::to_string(seed);
  return Sha256Prefix64(identity);
}

// The plant at its moored static start, with what happens at t = 0 done (the first sensor
// sample and controller instant), as a run starts.
std::unique_ptr<Simulation> Start(const scenarios::Scenario& scenario, std::uint64_t seed) {
  std::unique_ptr<Simulation> simulation = MakeSimulation(scenario, seed);
  simulation->AdvanceTo(0.0);
  return simulation;
}

}  // namespace

SteppedPlant::SteppedPlant(const scenarios::Scenario& scenario, std::uint64_t seed)
    : scenario_(scenario),
      seed_(seed),
      fingerprint_(PlantFingerprint(scenario, seed)),
      simulation_(Start(scenario_, seed_)) {}

void SteppedPlant::Apply(const Input& input, const std::function<bool()>& interrupt) {
  now_.reset();
  switch (input.kind) {
    case Input::kAdvance: {
      const double from = time();
      try {
        simulation_->AdvanceTo(input.values[0], interrupt);
      } catch (const Interrupted&) {
        if (time() > from) inputs_.push_back({Input::kAdvance, {time(), 0.0, 0.0}});
        throw;
      }
      break;
    }
    case Input::kThrust:
      simulation_->SetThrustCommand(Vec3(input.values[0], input.values[1], input.values[2]));
      break;
    case Input::kController:
      simulation_->SetThrustCommand(std::nullopt);
      break;
    case Input::kLoad:
      simulation_->SetExternalLoad(Vec3(input.values[0], input.values[1], input.values[2]));
      break;
  }
  inputs_.push_back(input);
}

void SteppedPlant::AdvanceTo(double t, const std::function<bool()>& interrupt) {
  if (!std::isfinite(t)) throw InputError("time " + FormatNumber(t) + " s is not a number");
  if (t < time()) {
    throw InputError("time " + FormatNumber(t) + " s is behind the plant's " +
                     FormatNumber(time()) + " s");
  }
  if (t - time() > kMaxAdvance) {
    throw InputError("time " + FormatNumber(t) + " s lies " + FormatNumber(t - time()) +
                     " s ahead of the plant's " + FormatNumber(time()) +
                     " s: one advance spans "
                     "at most " +
                     FormatNumber(kMaxAdvance) + " s (advance again to go further)");
  }
  if (t == time()) return;
  Apply({Input::kAdvance, {t, 0.0, 0.0}}, interrupt);
}

void SteppedPlant::SetThrustCommand(const std::optional<Vec3>& command) {
  Input input{Input::kController, {0.0, 0.0, 0.0}};
  if (command) {
    if (!command->allFinite()) throw InputError("the thrust command is not finite");
    input = {Input::kThrust, {(*command)(0), (*command)(1), (*command)(2)}};
  }
  Apply(input);
}

void SteppedPlant::SetExternalLoad(const Vec3& load) {
  if (!load.allFinite()) throw InputError("the external load is not finite");
  const Input input{Input::kLoad, {load(0), load(1), load(2)}};
  Apply(input);
}

const Sample& SteppedPlant::Now() {
  if (!now_) now_ = simulation_->Record();
  return *now_;
}

std::vector<std::uint8_t> SteppedPlant::Save() const {
  StateWriter w;
  w.PutHeader(kTag, kFormat, fingerprint_);
  w.Put(static_cast<std::int64_t>(inputs_.size()));
  for (const Input& input : inputs_) {
    w.Put(static_cast<std::int64_t>(input.kind));
    for (double v : input.values) w.Put(v);
  }
  return w.Take();
}

void SteppedPlant::Restore(std::span<const std::uint8_t> bytes,
                           const std::function<bool()>& interrupt) {
  StateReader r(bytes, "plant state");
  r.SetFingerprintMeaning("its scenario, overrides or seed differ");
  r.CheckHeader(kTag, kFormat, fingerprint_);
  std::vector<Input> inputs(r.GetCount(32, "inputs"));
  // Each input as AdvanceTo() and the setters would have taken it: a damaged one must not
  // send the replay anywhere the plant could not have gone.
  double reached = 0.0;
  for (Input& input : inputs) {
    const auto kind = r.Get<std::int64_t>("input");
    if (kind < Input::kAdvance || kind > Input::kLoad) r.Damaged("input kind");
    input.kind = static_cast<Input::Kind>(kind);
    for (double& v : input.values) v = r.Get<double>("input");
    if (!std::all_of(input.values, input.values + 3, [](double v) { return std::isfinite(v); })) {
      r.Damaged("input");
    }
    if (input.kind == Input::kAdvance) {
      const double t = input.values[0];
      if (!(t > reached && t - reached <= kMaxAdvance)) r.Damaged("input time");
      reached = t;
    }
  }
  if (r.remaining() != 0) r.Damaged("length");
  const auto same = [](const Input& a, const Input& b) {
    return a.kind == b.kind && std::equal(a.values, a.values + 3, b.values);
  };
  // What this plant has done is where the saved one began: only the rest to repeat.
  const bool continues = inputs.size() >= inputs_.size() &&
                         std::equal(inputs_.begin(), inputs_.end(), inputs.begin(), same);
  if (continues) {  // each input logged as it is applied: a failure leaves the plant there
    for (std::size_t i = inputs_.size(); i < inputs.size(); ++i) Apply(inputs[i], interrupt);
    return;
  }
  auto rebuilt = Start(scenario_, seed_);
  std::swap(rebuilt, simulation_);  // the old plant kept until the replay succeeds
  std::vector<Input> kept;
  std::swap(kept, inputs_);
  try {
    for (const Input& input : inputs) Apply(input, interrupt);
  } catch (...) {
    std::swap(rebuilt, simulation_);
    std::swap(kept, inputs_);
    now_.reset();
    throw;
  }
}

}  // namespace moorsim::runner
