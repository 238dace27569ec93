#include "simulation/lines_coupling.h"

#include "scenarios/convert.h"
#include "scenarios/load.h"
#include "simulation/simulation.h"

namespace moorsim::simulation {

std::unique_ptr<mooring_fem::CoupledLines> MakeCoupledLines(const scenarios::Scenario& scenario) {
  std::shared_ptr<const mooring_fem::WaveKinematics> waves;
  if (scenario.environment.waves.enabled && scenario.environment.waves.on_lines) {
    waves =
        LineWaves(scenario, RealiseSea(scenario.environment.waves, scenario.mooring.water.gravity,
                                       scenario.simulation.seed));
  }
  return std::make_unique<mooring_fem::CoupledLines>(
      scenarios::ToMooringParameters(scenario.mooring), scenario.solver, waves);
}

Vec6 InitCoupledLines(mooring_fem::CoupledLines& lines, const scenarios::Scenario& scenario,
                      const mooring_fem::BodyDofs& pose, const mooring_fem::BodyDofs& velocity) {
  try {
    return lines.Init(pose, velocity);
  } catch (const InputError& e) {  // a free point that cannot rest where it is
    scenarios::PlaceAtKey(scenario, e, "mooring.points[");
  }
}

}  // namespace moorsim::simulation
