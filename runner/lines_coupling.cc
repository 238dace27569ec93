#include "runner/lines_coupling.h"

#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "scenarios/plant_builder.h"
#include "simulation/simulation.h"

namespace moorsim::runner {

using simulation::LineWaves;
using simulation::RealiseSea;
using simulation::SeaModel;

std::shared_ptr<const mooring_fem::WaveKinematics> ScenarioLineWaves(
    const scenarios::Scenario& scenario) {
  const scenarios::WavesSpec& spec = scenario.environment.waves;
  if (!spec.enabled || !spec.on_lines) return nullptr;
  const SeaModel sea = scenarios::ToSeaModel(spec, scenario.mooring.water.gravity);
  return LineWaves(RealiseSea(sea, scenario.simulation.seed), scenario.mooring.water,
                   *sea.on_lines);
}

std::unique_ptr<mooring_fem::CoupledLines> MakeCoupledLines(const scenarios::Scenario& scenario) {
  return std::make_unique<mooring_fem::CoupledLines>(
      scenarios::ToMooringParameters(scenario.mooring), scenario.solver,
      ScenarioLineWaves(scenario));
}

Vec6 InitCoupledLines(mooring_fem::CoupledLines& lines, const scenarios::Scenario& scenario,
                      const mooring_fem::BodyDofs& pose, const mooring_fem::BodyDofs& velocity) {
  try {
    return lines.Init(pose, velocity);
  } catch (const InputError& e) {  // a free point that cannot rest where it is
    scenarios::PlaceAtKey(scenario, e, "mooring.points[");
  }
}

}  // namespace moorsim::runner
