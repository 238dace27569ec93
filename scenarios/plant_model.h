// From a scenario to the typed plant model the coupled simulation is built from
// (simulation/plant_model.h): the one place where the scenario's vessel, environment,
// controller, sensors, failure and detection sections become the physics modules' own
// parameter types, as convert.h is for the mooring.
#pragma once

#include <cstdint>

#include "scenarios/scenario.h"
#include "simulation/plant_model.h"

namespace moorsim::scenarios {

/// The plant of a scenario with a vessel section. Throws InputError (naming the file) for
/// a scenario without one.
simulation::PlantModel ToPlantModel(const Scenario& scenario);

/// The scenario's `detectors:` and `detection:` as the detection takes them (the reference
/// pose and turret from the vessel section where there is one).
simulation::DetectionSetup ToDetectionSetup(const Scenario& scenario);

/// The hull for the viscous current load, from `vessel.hull` (form factor by Watanabe's
/// regression when not given) and the water's density. The defaults give
/// vessel::SeedFpsoHull() with that density.
vessel::HullGeometry ToHullGeometry(const VesselSpec& spec, double water_density);

/// The above-water hull for the wind load, from `vessel.windage` (length defaulting to
/// vessel.hull.length) with Blendermann's loaded-tanker coefficients. The defaults give
/// vessel::SeedFpsoWind().
vessel::WindParameters ToWindParameters(const VesselSpec& spec);

/// The sea of `environment.waves` in water of gravity `gravity` [m/s^2].
simulation::SeaModel ToSeaModel(const WavesSpec& spec, double gravity);

}  // namespace moorsim::scenarios
