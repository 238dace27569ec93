// A scenario's mooring lines for a coupling to someone else's body model
// (mooring_fem/coupled_lines.h), as the C API and the Python module build them.
#pragma once

#include <memory>

#include "mooring_fem/coupled_lines.h"
#include "scenarios/scenario.h"

namespace moorsim::runner {

/// The waves the scenario's lines see (environment.waves.on_lines, realised from
/// simulation.seed as a run realises them); null where they see none.
std::shared_ptr<const mooring_fem::WaveKinematics> ScenarioLineWaves(
    const scenarios::Scenario& scenario);

/// The scenario's lines (its mooring, current and solver settings) with the waves they see
/// (environment.waves.on_lines, realised from simulation.seed as a run realises them).
/// Throws moorsim::InputError for a mooring that cannot be built.
std::unique_ptr<mooring_fem::CoupledLines> MakeCoupledLines(const scenarios::Scenario& scenario);

/// CoupledLines::Init, with a free point that cannot rest where it is reported at its key
/// in the scenario file.
Vec6 InitCoupledLines(mooring_fem::CoupledLines& lines, const scenarios::Scenario& scenario,
                      const mooring_fem::BodyDofs& pose, const mooring_fem::BodyDofs& velocity);

}  // namespace moorsim::runner
