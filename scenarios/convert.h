// From the scenario model to the physics modules' own parameter types: the one place where
// the scenario's mooring becomes the FEM's (docs/design.md section 1). The mooring_fem and
// detectors libraries take mooring_fem::MooringParameters and never include scenarios/;
// the solver block already is mooring_fem::SolverSettings (scenarios::SolverSpec).
#pragma once

#include "mooring_fem/parameters.h"
#include "scenarios/scenario.h"

namespace moorsim::scenarios {

/// The mooring as the FEM and the hypothesis bank take it: the same water, seabed, current,
/// line types and lines (in the same order), without the source marks.
mooring_fem::MooringParameters ToMooringParameters(const MooringSpec& spec);

/// vessel.turret.radius, or (unset) the fairleads' largest horizontal distance from the
/// turret centre; 0 without a vessel.
double TurretRadius(const Scenario& scenario);

}  // namespace moorsim::scenarios
