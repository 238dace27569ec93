// Loading a scenario from YAML: strict parsing into the structs of scenario.h, then a
// semantic Validate(). Every problem is a moorsim::InputError with a one-line message
//
//   <file>:<line>:<col>: <key.path>: <value> <what is wrong>
//
// e.g. "seed.yaml:14:13: mooring.lines[3].length: 1800 m is shorter than the
// anchor-fairlead distance 2168.2 m". Line and column are 1-based. List indices in key
// paths are 1-based too (mooring.lines[3] is the third entry), the way the project numbers
// mooring lines everywhere a user sees them. A missing key is reported at its parent's
// position; a message has no line:col when the value has no place in the text (a default,
// or a Scenario built in code).
//
// Schema (every number SI; angles only under keys ending in `_deg`, converted to radians):
//
//   name: seed_tapm                  # optional; default: the file name without extension
//   mooring:                         # required
//     water: {density: 1025, gravity: 9.81, depth: 1000}   # depth required; density
//                                    # [kg/m^3] and gravity [m/s^2] default to these values
//     seabed: {stiffness: 3.0e6, damping: 3.0e5, contact_smoothing: 0.5,
//              friction_velocity: 0.1}
//                                    # optional block and keys; these are the defaults
//                                    # [N/m^3, N s/m^3, m, m/s]
//     current:                       # optional; omitted = no current
//       direction_deg: 315           # required: direction the water flows TOWARD, from
//                                    # north, clockwise (east = 90)
//       profile:                     # required, >= 1 point; speed [m/s] piecewise linear
//         - {depth: 0, speed: 0.1}   # in depth [m], constant beyond the end points
//         - {depth: 1000, speed: 0.1}
//     line_types:                    # required
//       - name: chain_seed           # required, unique
//         diameter: 0.08             # required [m]
//         mass_per_length: 275       # required, dry [kg/m]
//         axial_stiffness: 2.28785e8 # required, EA [N]
//         axial_damping_ratio: 0.5   # optional, fraction of a segment's critical damping,
//                                    # or axial_damping: <c [N s]>; not both. Neither
//                                    # given = axial_damping_ratio 0.5
//         drag_normal: 0.3           # required, C_DN
//         drag_tangential: 1.0       # required, C_DT
//         added_mass_normal: 1.5     # required, C_MN
//         friction_axial: 0.5        # optional, default 0: seabed Coulomb coefficients
//         friction_lateral: 1.0      # optional, default 0
//     defaults: {segments: 50}       # optional; segments default 50
//     lines:                         # required, >= 1 entry
//       - id: 1                      # optional; default = position in the list (1-based);
//                                    # the ids must be 1..N in any order
//         type: chain_seed           # required, a line_types name
//         anchor: [1950, 0, 1000]    # required, Earth frame NED [m] (z down: on a 1000 m
//                                    # seabed z = +1000)
//         fairlead: [20, 0, 12]      # required, body frame [m]
//         length: 2250               # required, unstretched [m]
//         segments: 50               # optional; default mooring.defaults.segments
//   solver:                          # optional block, every key optional (SolverSpec)
//     rtol: 1.0e-4
//     atol_position: 1.0e-3          # [m]
//     atol_velocity: 1.0e-3          # [m/s]
//     max_order: 2                   # BDF order, 1..5
//     stability_limit_detection: false
//     max_step: 0                    # [s], 0 = no limit
//     max_steps: 200000              # steps between two stops before CV_TOO_MUCH_WORK
//     linear_solver: block           # block (structured) or klu (general sparse LU)
//   vessel:                          # optional (`run` needs it); besides the keys listed
//                                    # in scenarios/README.md, the hull and the windage:
//     hull: {length: 200, beam: 44, draught: 12, displaced_volume: 97961,
//            wetted_surface: 0, cross_flow_drag_coefficient: 0, kinematic_viscosity: 1.19e-6}
//                                    # optional block and keys; these defaults are the seed
//                                    # FPSO's [m, m, m, m^3, m^2, -, m^2/s]; wetted_surface 0
//                                    # = Denny-Mumford, cross_flow_drag_coefficient 0 =
//                                    # Hoerner's curve; form_factor: <k> optional, omitted =
//                                    # Watanabe's regression (0.505 for the seed)
//     windage: {frontal_area: 1200, lateral_area: 4500, lateral_centroid: 0, air_density: 1.226}
//                                    # optional block and keys, the seed FPSO's [m^2, m^2, m
//                                    # forward of midship, kg/m^3]; length: <m> optional,
//                                    # omitted = hull.length
//
// Strictness: unknown keys, duplicate keys, a value of the wrong kind (a quoted "0.08"
// where a number belongs, 2.5 where an integer belongs, .inf or .nan), an explicit YAML tag
// (`!!str 5`, `!foo`, `! 5`), text that is not UTF-8 and missing required keys are all
// errors. Every number has a physical range (water.gravity in [9.7, 9.9], depth <= 12000 m,
// line length <= 20000 m, ..., listed in scenarios/README.md), angles under *_deg keys are
// in [-360, 360], an anchor lies on the seabed below its fairlead, and a line must reach
// its fairlead without lying slack: distance <= length < horizontal distance + height.
// The coupled-simulation sections (vessel, environment, controller, sensors, failure,
// simulation) are documented in scenarios/README.md; each is a row of the top-level
// section table in load.cc. The mooring and solver blocks are the FEM's parameter types
// (mooring_fem/parameters.h; scenarios/convert.h converts); the coupled sections become the
// typed plant model (simulation/plant_model.h) through scenarios/plant_builder.h.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scenarios/scenario.h"

namespace moorsim::scenarios {

/// Reads the scenario file at `path` (as given, which is also how messages name it), keeps
/// its full text in Scenario::text and the path in Scenario::source_path, parses and
/// validates it. Throws moorsim::InputError.
Scenario LoadScenario(const std::string& path);
/// The same with command-line overrides "key.path=value" applied to the YAML before it is
/// read (`moorsim run --set`): maps by key (created if missing), list entries by [i] from 1,
/// the value parsed as YAML. Messages about an overridden value name its key path without a
/// line:col. A malformed override is an InputError starting "--set <text>:".
Scenario LoadScenario(const std::string& path, const std::vector<std::string>& overrides);

/// Parses and validates scenario YAML text. `source_name` names the text in messages, is
/// stored as Scenario::source_path, and gives the default name (its stem). After loading,
/// mooring.lines is ordered by id. Throws moorsim::InputError.
Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name);
Scenario ParseScenario(const std::string& yaml_text, const std::string& source_name,
                       const std::vector<std::string>& overrides);

/// The semantic checks: physically impossible or inconsistent values (non-positive
/// diameter, a line lighter than the water it displaces, a line shorter than its
/// anchor-fairlead distance or so long it lies slack, a value outside its physical range,
/// ids that are not 1..N, ...). Positions come from Scenario::marks. Throws
/// moorsim::InputError at the first violation.
void Validate(const Scenario& scenario);

/// Throws InputError "<file>:<line>:<col>: <path>: <what>", placed at `path` (key path with
/// 1-based list indices) or, if that was not written, its nearest written parent. For checks
/// that live outside this module (the detector registry).
[[noreturn]] void FailAt(const Scenario& scenario, const std::string& path,
                         const std::string& what);

/// Rethrows `error`, an InputError a module raised about a key ("<path>: <what>", the path
/// starting with `prefix`: "detectors[2].floor: ...", "mooring.points[1]: ..."), placed at
/// that key as FailAt places it; any other error as it is.
[[noreturn]] void PlaceAtKey(const Scenario& scenario, const InputError& error,
                             std::string_view prefix);

}  // namespace moorsim::scenarios
