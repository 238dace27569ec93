// From a scenario to the typed plant model the coupled simulation is built from
// (simulation/plant_model.h): the one place where the scenario's vessel, environment,
// controller, sensors, failure and detection sections become the physics modules' own
// parameter types, as convert.h is for the mooring.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "scenarios/scenario.h"
#include "simulation/plant_model.h"

namespace moorsim::scenarios {

/// What a sensor fault's mode takes from a scenario: the field of SensorsSpec::Fault that
/// holds its size (null for stuck and dead; its key is vessel::SensorFaultSizeKey), the
/// size that would leave the sensor as it is, and what the loader says when that size is
/// missing ("{unit}": the sensor's unit).
struct FaultModeSize {
  vessel::SensorFault::Mode mode;
  double SensorsSpec::Fault::*size;
  double neutral;
  std::string_view need;
};
/// Every mode's row, in the order of the modes.
std::span<const FaultModeSize> FaultModeSizes();
/// The row of `mode`.
const FaultModeSize& FaultModeSizeOf(vessel::SensorFault::Mode mode);

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
