// Bad-input cases shared by the loader's tests (message text) and the CLI's tests (the
// same files through `moorsim validate` and `moorsim static`: exit code 2, one line).
// One case per rule; each edits kBase once, and the expected message is
// "<file>:<position of `at`>: <message>".
#pragma once

#include <gtest/gtest.h>

#include <ostream>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "scenarios/load.h"

namespace moorsim::scenarios::test_cases {

// A valid scenario that uses every key; each error case edits one spot of it.
inline const std::string kBase = R"(name: base
mooring:
  water: {density: 1025, gravity: 9.81, depth: 1000}
  seabed: {stiffness: 3.0e6, damping: 3.0e5, friction_velocity: 0.01}
  current:
    direction_deg: 90
    profile:
      - {depth: 0, speed: 0.2}
      - {depth: 500, speed: 0.1}
  line_types:
    - name: chain
      diameter: 0.08
      mass_per_length: 275
      axial_stiffness: 2.28785e8
      axial_damping_ratio: 0.5
      drag_normal: 0.3
      drag_tangential: 1.0
      added_mass_normal: 1.5
      friction_axial: 0.5
      friction_lateral: 1.0
      minimum_breaking_load: 5.4e6
      fatigue: {curve: studless_chain, nominal_area: 0.0101}
    - name: wire
      diameter: 0.1
      mass_per_length: 40
      axial_stiffness: 8.0e8
      axial_damping: 1.0e5
      drag_normal: 1.2
      drag_tangential: 0.008
      added_mass_normal: 1.0
      minimum_breaking_load: 7.0e6
      fatigue: {a: 231, m: 4.09, range: normalised, mean_load_slope: 2.79}
  defaults: {segments: 40}
  lines:
    - id: 1
      type: chain
      anchor: [1950, 0, 1000]
      fairlead: [20, 0, 12]
      length: 2250
      segments: 30
    - id: 2
      type: wire
      anchor: [0, 1950, 1000]
      fairlead: [0, 20, 12]
      length: 2250
    - id: 3
      type: chain
      anchor: [-1950, 0, 1000]
      fairlead: [-20, 0, 12]
      length: 2250
solver:
  rtol: 1.0e-4
  atol_position: 1.0e-3
  atol_velocity: 2.0e-3
  max_order: 4
  stability_limit_detection: false
  max_step: 0.5
  linear_solver: klu
vessel:
  hydrodynamics: )" MOORSIM_SOURCE_DIR R"(/data/fpso_wamit/fpso
  length_scale: 1
  mass: 1.0041e8
  centre_of_gravity: [0, 0, 1]
  radii_of_gyration: [16.3, 54, 54]
  damping: {surge_time: 50, sway_time: 100, yaw_time: 20, heave_ratio: 0.1, roll_ratio: 0.07, pitch_ratio: 0.1}
  initial_pose: {x: 2, y: 2, heading_deg: 10}
  hull: {length: 200, beam: 44, draught: 12, displaced_volume: 97961, wetted_surface: 0, cross_flow_drag_coefficient: 0, form_factor: 0.505, kinematic_viscosity: 1.19e-6}
  windage: {frontal_area: 1200, lateral_area: 4500, length: 200, lateral_centroid: 0, air_density: 1.226}
  turret: {bearing: friction, x: 0, y: 0, radius: 20, inertia: 6.0e8, damping: 1.0e7, friction_coefficient: 0.01, bearing_radius: 18, slip_rate: 1.0e-5}
  thrusters:
    - {name: aft_port, x: -90, y: -8, angle_deg: 0, azimuth: false, max_thrust: 1.0e6, min_thrust: -6.0e5, weight: 1, time_constant: 5, rate_limit: 2.0e5}
    - {name: aft_starboard, x: -90, y: 8, max_thrust: 1.0e6, min_thrust: -6.0e5}
    - {name: bow_tunnel, x: 90, y: 0, angle_deg: 90, max_thrust: 6.0e5, min_thrust: -6.0e5}
environment:
  waves: {hs: 2.5, tp: 7, gamma: 3.3, direction_toward_deg: 315, spreading: 10, components: 200}
  wind: {speed: 12, direction_from_deg: 135, gust: true, components: 100}
  hull_viscous_drag: true
controller:
  type: pi
  rate_hz: 1
  setpoint: {x: 0, y: 0, heading_deg: 0}
  kp: [1.0e5, 1.0e6, 1.0e3]
  ki: [1.0e3, 1.0e3, 1.0e2]
  kd: [0, 0, 0]
  natural_period: 120
  damping_ratio: 0.8
  heading: {natural_period: 200, damping_ratio: 0.8}
sensors:
  gnss:
    rate_hz: 1
    north: {std_dev: 0.07, bias_walk: 0.001, bias_time_constant: 600, initial_bias: 0.1, outlier_probability: 0.01, outlier_std_dev: 2}
    east: {std_dev: 0.07}
    dropout_probability: 0.01
    dropout_mean_duration: 5
  gyro:
    rate_hz: 1
    heading: {std_dev: 0.07}
    dropout_probability: 0.01
  tension_cells:
    rate_hz: 1
    noise: {std_dev: 1.0e4}
    faults: [{line: 3, mode: drift, time: 500, rate: -1000}]
failure: {line: 2, time: 300, mode: node, node: 10}
simulation: {duration: 1000, output_rate_hz: 2, seed: 7}
detection:
  observer: ekf
  sensor_checks: false
  pairs: false
  measurement_variance: 0.005
  switch_rate: 0.01
  training_seed: 3
  model: {wave_motion_std: [0.15, 0.15, 0.0087], bias_std: [1.0e6, 1.0e6, 5.0e7], bias_time_constant: [1000, 1000, 1000], force_noise: [5.0e4, 5.0e4, 1.0e7], mooring_damping_ratio: [0, 0, 0]}
detectors:
  - {type: dht, floor: 1.0e-9}
  - {type: mle, forgetting_factor: 0.99}
  - {type: glr, threshold: 120}
)";

// The loader's message for `text` as file test.yaml, or "(no error)".
inline std::string ErrorOf(const std::string& text) {
  try {
    ParseScenario(text, "test.yaml");
  } catch (const InputError& error) {
    return error.what();
  } catch (const std::exception& error) {
    return std::string("not an InputError: ") + error.what();
  }
  return "(no error)";
}

// Replaces the first `old_text` at or after the first `after` ("" = the start).
inline std::string Edit(const std::string& text, const std::string& after,
                        const std::string& old_text, const std::string& new_text) {
  const std::size_t from = text.find(after);
  const std::size_t at = from == std::string::npos ? from : text.find(old_text, from);
  if (at == std::string::npos) {
    ADD_FAILURE() << "'" << old_text << "' not found after '" << after << "'";
    return text;
  }
  std::string edited = text;
  edited.replace(at, old_text.size(), new_text);
  return edited;
}

// "line:column" (1-based) of the first `at` found at or after the first `after`; a '^' in
// `at` marks the spot inside it (default: its first character).
inline std::string PositionOf(const std::string& text, const std::string& after, std::string at) {
  std::size_t spot = at.find('^');
  if (spot == std::string::npos) {
    spot = 0;
  } else {
    at.erase(spot, 1);
  }
  const std::size_t from = text.find(after);
  const std::size_t found = from == std::string::npos ? from : text.find(at, from);
  if (found == std::string::npos) {
    ADD_FAILURE() << "'" << at << "' not found after '" << after << "'";
    return "?:?";
  }
  const std::size_t position = found + spot;
  const std::size_t line_start = position == 0 ? std::string::npos : text.rfind('\n', position - 1);
  const std::size_t column = line_start == std::string::npos ? position + 1 : position - line_start;
  const auto line = 1 + std::count(text.begin(), text.begin() + position, '\n');
  return std::to_string(line) + ":" + std::to_string(column);
}

// Input errors: one case per rule. Each edits kBase once; the expected message is
// "test.yaml:<position of `at`>: <message>".

struct BadInput {
  std::string name;
  std::string after;     // where to start looking for old_text and at ("" = the start)
  std::string old_text;  // replaced by new_text
  std::string new_text;
  std::string at;  // text the message points at; '^' marks the spot (default: its start)
  std::string message;
};

inline void PrintTo(const BadInput& input, std::ostream* out) { *out << input.name; }
inline const BadInput kParseErrors[] = {
    {"SectionsBesideType", "- id: 2", "length: 2250",
     "sections: [{type: wire, length: 2250, segments: 40}]", "wire",
     "mooring.lines[2].type: give a line either type, length and segments or its sections, not "
     "both"},
    {"BodyOnALineOfOneType", "- id: 2", "length: 2250",
     "length: 2250\n      bodies: [{joint: 1, mass: 1000}]", "[{joint",
     "mooring.lines[2].bodies: bodies sit on the joints between sections: give the line's "
     "sections"},
    {"BodyOnAJointTheLineDoesNotHave", "- id: 2",
     "type: wire\n      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      length: 2250",
     "anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      sections: [{type: wire, length: "
     "1000, segments: 20}, {type: chain, length: 1250, segments: 20}]\n      bodies: [{joint: 2, "
     "mass: 1000}]",
     "2, mass",
     "mooring.lines[2].bodies[1].joint: 2 is not a joint of the line: its 2 sections meet at "
     "joints 1..1"},
    {"TwoBodiesOnOneJoint", "- id: 2",
     "type: wire\n      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      length: 2250",
     "anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      sections: [{type: wire, length: "
     "1000, segments: 20}, {type: chain, length: 1250, segments: 20}]\n      bodies: [{joint: 1, "
     "mass: 1000}, {joint: 1, volume: 3}]",
     "1, volume", "mooring.lines[2].bodies[2].joint: 1 has a body already"},
    {"NoSectionsWithABody", "- id: 2",
     "type: wire\n      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      length: 2250",
     "anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      sections: []\n      bodies: "
     "[{joint: 1, mass: 1000}]",
     "[]",
     "mooring.lines[2].sections: lists no section: a line needs one or more (or type, length "
     "and segments)"},
    {"SectionWithoutSegments", "- id: 2",
     "type: wire\n      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      length: 2250",
     "anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      sections: [{type: wire, length: "
     "2250}]",
     "{type: wire", "mooring.lines[2].sections[1]: required key 'segments' is missing"},
    {"UnknownKeyInLine", "- id: 2", "length: 2250", "lenght: 2250", "lenght",
     "mooring.lines[2]: unknown key 'lenght' (did you mean 'length'?)"},
    {"UnknownFatigueCurve", "- name: chain", "curve: studless_chain", "curve: studless", "studless",
     "mooring.line_types[1].fatigue.curve: unknown T-N curve 'studless' (known: polyester, "
     "six_strand_rope, spiral_rope, studless_chain, studlink_chain)"},
    {"FatigueWithoutCurveOrExponent", "- name: wire", "a: 231, m: 4.09, ", "a: 231, ", "{a: 231",
     "mooring.line_types[2].fatigue: give a curve, or a and m (m missing)"},
    {"NormalisedCurveWithoutBreakingLoad", "- name: wire", "      minimum_breaking_load: 7.0e6\n",
     "", "{a: 231",
     "mooring.line_types[2].fatigue: a curve on the breaking load (normalised, or with "
     "a mean-load term) needs the type's minimum_breaking_load"},
    {"UnknownTopLevelSection", "", "solver:\n", "vessels: {}\nsolver:\n", "vessels",
     "unknown key 'vessels' (did you mean 'vessel'?)"},
    {"UnknownKeyInFlowMap", "", "gravity: 9.81", "gravity: 9.81, salinity: 35", "salinity",
     "mooring.water: unknown key 'salinity' (known: density, depth, gravity)"},
    {"DuplicateKey", "- name: chain", "diameter: 0.08\n", "diameter: 0.08\n      diameter: 0.09\n",
     "diameter: 0.09", "mooring.line_types[1]: duplicate key 'diameter'"},
    {"MissingKeyInFlowMap", "", ", depth: 1000}", "}", "{density",
     "mooring.water: required key 'depth' is missing"},
    {"MissingKeyInListEntry", "- name: wire", "      axial_stiffness: 8.0e8\n", "", "name: wire",
     "mooring.line_types[2]: required key 'axial_stiffness' is missing"},
    {"NumberIsText", "- name: chain", "diameter: 0.08", "diameter: thick", "thick",
     "mooring.line_types[1].diameter: thick must be a number"},
    {"NumberIsQuoted", "- name: chain", "diameter: 0.08", "diameter: \"0.08\"", "\"0.08\"",
     "mooring.line_types[1].diameter: \"0.08\" must be a number"},
    {"NumberIsEmpty", "- name: chain", "diameter: 0.08", "diameter:", "diameter",
     "mooring.line_types[1].diameter: an empty value must be a number"},
    {"NumberIsNotFinite", "", "depth: 1000}", "depth: .inf}", ".inf",
     "mooring.water.depth: .inf must be a finite number"},
    {"IntegerHasFraction", "- id: 1", "segments: 30", "segments: 30.5", "30.5",
     "mooring.lines[1].segments: 30.5 must be an integer"},
    {"BooleanIsText", "", "stability_limit_detection: false", "stability_limit_detection: maybe",
     "maybe", "solver.stability_limit_detection: maybe must be true or false"},
    {"VectorHasTwoNumbers", "- id: 2", "[0, 20, 12]", "[0, 20]", "[0, 20]",
     "mooring.lines[2].fairlead: [0, 20] must be a list of 3 numbers [x, y, z]"},
    {"VectorElementIsText", "- id: 2", "[0, 20, 12]", "[0, 20, deep]", "deep",
     "mooring.lines[2].fairlead[3]: deep must be a number"},
    {"MapIsNumber", "", "water: {density: 1025, gravity: 9.81, depth: 1000}", "water: 1000",
     "water: ^1000", "mooring.water: 1000 must be a map"},
    {"ListIsMap", "profile:", "\n      - {depth: 0, speed: 0.2}\n      - {depth: 500, speed: 0.1}",
     " {depth: 0, speed: 0.2}", "{depth", "mooring.current.profile: a map must be a list"},
    {"StringIsList", "- id: 2", "type: wire", "type: [wire]", "[wire]",
     "mooring.lines[2].type: [wire] must be a string"},
    {"CurrentProfileIsEmpty",
     "profile:", "\n      - {depth: 0, speed: 0.2}\n      - {depth: 500, speed: 0.1}", " []", "[]",
     "mooring.current.profile: [] must hold at least one {depth, speed} point"},
    {"CurrentDirectionInRadians", "", "direction_deg: 90", "direction: 1.57",
     "direction:", "mooring.current: unknown key 'direction' (did you mean 'direction_deg'?)"},
    {"SecondDocument", "", "linear_solver: klu\n", "linear_solver: klu\n---\nname: other\n",
     "name: other", "a scenario file holds one YAML document; this is a second one"},
    // The coupled-simulation sections.
    {"VesselUnknownKey", "vessel:", "mass: 1.0041e8", "mas: 1.0041e8", "mas",
     "vessel: unknown key 'mas' (did you mean 'mass'?)"},
    {"HullUnknownKey", "hull:", "beam: 44", "breadth: 44", "breadth",
     "vessel.hull: unknown key 'breadth' (known: beam, cross_flow_drag_coefficient, "
     "displaced_volume, draught, form_factor, kinematic_viscosity, length, wetted_surface)"},
    {"WavesMissingHs", "environment:", "{hs: 2.5, tp: 7", "{tp: 7", "{tp",
     "environment.waves: required key 'hs' is missing"},
    {"WaveTrainsAndHs", "environment:", "{hs: 2.5, tp: 7",
     "{hs: 2.5, trains: [{period: 10, amplitude: 1, phase_deg: 0, direction_toward_deg: 0}], tp: 7",
     "hs: ^2.5", "environment.waves.hs: give the JONSWAP sea (hs, tp, ...) or trains, not both"},
    {"WaveTrainWithoutPeriod", "environment:",
     "{hs: 2.5, tp: 7, gamma: 3.3, direction_toward_deg: 315, spreading: 10, components: 200}",
     "{trains: [{amplitude: 1, phase_deg: 0, direction_toward_deg: 0}]}", "{amplitude",
     "environment.waves.trains[1]: required key 'period' is missing"},
    {"CurrentFileAndProfile", "", "direction_deg: 90", "file: flow.txt\n    direction_deg: 90",
     "direction_deg: ^90", "mooring.current.direction_deg: give a profile or a file, not both"},
    {"CurrentPeriodWithoutFile", "", "direction_deg: 90", "period: 60\n    direction_deg: 90",
     "period: ^60", "mooring.current.period: repeats a current table: give it with file"},
    {"ControllerGainNotAList", "controller:", "kp: [1.0e5, 1.0e6, 1.0e3]", "kp: 1.0e5",
     "kp: ^1.0e5", "controller.kp: 1.0e5 must be a list of 3 numbers [x, y, z]"},
    {"SeedNegative", "simulation:", "seed: 7", "seed: -7", "seed: ^-7",
     "simulation.seed: -7 must be a non-negative integer"},
    {"SensorNoiseQuoted", "north:", "std_dev: 0.07, bias", "std_dev: \"0.07\", bias",
     "std_dev: ^\"0.07\"", "sensors.gnss.north.std_dev: \"0.07\" must be a number"},
    {"FailureMissingLine", "failure:", "{line: 2, time", "{time", "{time",
     "failure: required key 'line' is missing"},
    {"CurrentGivenTwice", "", "hull_viscous_drag: true",
     "hull_viscous_drag: true\n  current: {direction_deg: 0, profile: [{depth: 0, speed: 0.1}]}",
     "direction_deg: 90",
     "mooring.current: the current is given twice; keep it under environment.current only"},
    // YAML tags: none is accepted, on values or keys. `!!str 1.0041e8` is text
    // that yaml-cpp would still convert to a number.
    {"TaggedStringOnNumber", "vessel:", "mass: 1.0041e8", "mass: !!str 1.0041e8", "!!str",
     "vessel.mass: tagged value '!!str' (tags are not accepted; write the plain number)"},
    {"CustomTag", "vessel:", "mass: 1.0041e8", "mass: !foo 1.0041e8", "!foo",
     "vessel.mass: tagged value '!foo' (tags are not accepted; write the plain number)"},
    {"BinaryTag", "vessel:", "mass: 1.0041e8", "mass: !!binary aGVsbG8=", "!!binary",
     "vessel.mass: tagged value '!!binary' (tags are not accepted; write the plain number)"},
    {"NonSpecificTag", "vessel:", "mass: 1.0041e8", "mass: ! 1.0041e8", "mass: ^!",
     "vessel.mass: tagged value '!' (tags are not accepted; write the plain number)"},
    {"TagAfterAnchor", "vessel:", "mass: 1.0041e8", "mass: &m ! 1.0041e8", "&m",
     "vessel.mass: tagged value '!' (tags are not accepted; write the plain number)"},
    {"FloatTagOnInteger", "- id: 1", "segments: 30", "segments: !!float 30", "!!float",
     "mooring.lines[1].segments: tagged value '!!float' (tags are not accepted; write the "
     "plain integer)"},
    {"TaggedSeed", "simulation:", "seed: 7", "seed: !!int 7", "!!int",
     "simulation.seed: tagged value '!!int' (tags are not accepted; write the plain integer)"},
    {"TaggedBoolean", "wind:", "gust: true", "gust: !!bool true", "!!bool",
     "environment.wind.gust: tagged value '!!bool' (tags are not accepted; write true or "
     "false)"},
    {"TaggedText", "", "name: base", "name: !!str base", "!!str",
     "name: tagged value '!!str' (tags are not accepted; write the plain text)"},
    {"TaggedMap", "", "water: {density", "water: !!map {density", "!!map",
     "mooring.water: tagged value '!!map' (tags are not accepted; write the plain map)"},
    {"TaggedList", "- id: 1", "anchor: [1950", "anchor: !!seq [1950", "!!seq",
     "mooring.lines[1].anchor: tagged value '!!seq' (tags are not accepted; write the plain "
     "list)"},
    {"TaggedListItem", "- id: 1", "anchor: [1950", "anchor: [!!float 1950", "!!float",
     "mooring.lines[1].anchor[1]: tagged value '!!float' (tags are not accepted; write the "
     "plain number)"},
    {"TaggedKey", "vessel:", "mass: 1.0041e8", "!!str mass: 1.0041e8", "!!str",
     "vessel: tagged key '!!str' (tags are not accepted; write the plain name)"},
    {"TaggedDetectorParameter", "detectors:", "floor: 1.0e-9", "floor: !!float 1.0e-9", "!!float",
     "detectors[1].floor: tagged value '!!float' (tags are not accepted; write the plain "
     "number)"},
    // Bytes that are not UTF-8: placed at the first bad byte, wherever it is.
    {"Latin1ByteInName", "", "name: base", "name: b\xE9se", "\xE9",
     "not valid UTF-8 (byte 0xE9); save the file as UTF-8"},
    {"LoneContinuationByteInComment", "vessel:", "  mass: 1.0041e8", "  mass: 1.0041e8  # 10\x80 t",
     "\x80", "not valid UTF-8 (byte 0x80); save the file as UTF-8"},
    {"OverlongEncoding", "", "name: base", "name: b\xC0\xAFse", "\xC0",
     "not valid UTF-8 (byte 0xC0); save the file as UTF-8"},
    {"EncodedSurrogate", "", "name: base", "name: b\xED\xA0\x80se", "\xED",
     "not valid UTF-8 (byte 0xED); save the file as UTF-8"},
    {"TruncatedSequence", "- id: 2", "type: wire", "type: wir\xC3", "\xC3",
     "not valid UTF-8 (byte 0xC3); save the file as UTF-8"},
    // Angles: a full turn either way at most.
    {"DirectionBeyondAFullTurn", "", "direction_deg: 90", "direction_deg: 400", "400",
     "mooring.current.direction_deg: 400 deg must be in [-360, 360]"},
    {"HeadingBeyondAFullTurn", "initial_pose:", "heading_deg: 10", "heading_deg: -720", "-720",
     "vessel.initial_pose.heading_deg: -720 deg must be in [-360, 360]"},
    {"WaveDirectionHuge", "waves:", "direction_toward_deg: 315", "direction_toward_deg: 1e308",
     "1e308", "environment.waves.direction_toward_deg: 1e+308 deg must be in [-360, 360]"},
    {"WindDirectionBeyondAFullTurn", "wind:", "direction_from_deg: 135", "direction_from_deg: 495",
     "495", "environment.wind.direction_from_deg: 495 deg must be in [-360, 360]"},
    {"SetpointHeadingBeyondAFullTurn", "setpoint:", "heading_deg: 0", "heading_deg: 361", "361",
     "controller.setpoint.heading_deg: 361 deg must be in [-360, 360]"},
    {"ThrusterAngleBeyondAFullTurn", "bow_tunnel", "angle_deg: 90", "angle_deg: -450", "-450",
     "vessel.thrusters[3].angle_deg: -450 deg must be in [-360, 360]"},
};
inline const BadInput kValidationErrors[] = {
    {"DiameterNotPositive", "- name: chain", "diameter: 0.08", "diameter: -0.08", "-0.08",
     "mooring.line_types[1].diameter: -0.08 m must be > 0"},
    // Displaced water: 1025 kg/m^3 x pi x 0.08^2 / 4 = 5.152 kg/m.
    {"LineWouldFloat", "- name: chain", "mass_per_length: 275", "mass_per_length: 5",
     "mass_per_length: ^5",
     "mooring.line_types[1].mass_per_length: 5 kg/m must exceed the displaced water mass "
     "5.152 kg/m (the line would float)"},
    {"AxialStiffnessNotPositive", "- name: chain", "axial_stiffness: 2.28785e8",
     "axial_stiffness: 0", "axial_stiffness: ^0",
     "mooring.line_types[1].axial_stiffness: 0 N must be > 0"},
    {"DragNormalNegative", "- name: chain", "drag_normal: 0.3", "drag_normal: -0.3", "-0.3",
     "mooring.line_types[1].drag_normal: -0.3 must be >= 0"},
    {"DragTangentialNegative", "- name: wire", "drag_tangential: 0.008", "drag_tangential: -0.008",
     "-0.008", "mooring.line_types[2].drag_tangential: -0.008 must be >= 0"},
    {"AddedMassNegative", "- name: chain", "added_mass_normal: 1.5", "added_mass_normal: -1.5",
     "-1.5", "mooring.line_types[1].added_mass_normal: -1.5 must be >= 0"},
    {"FrictionAxialNegative", "- name: chain", "friction_axial: 0.5", "friction_axial: -0.5",
     "-0.5", "mooring.line_types[1].friction_axial: -0.5 must be >= 0"},
    {"FrictionLateralNegative", "- name: chain", "friction_lateral: 1.0", "friction_lateral: -1",
     "-1", "mooring.line_types[1].friction_lateral: -1 must be >= 0"},
    {"AxialDampingNegative", "- name: wire", "axial_damping: 1.0e5", "axial_damping: -1", "-1",
     "mooring.line_types[2].axial_damping: -1 N s must be >= 0"},
    {"AxialDampingHuge", "- name: wire", "axial_damping: 1.0e5", "axial_damping: 1e11", "1e11",
     "mooring.line_types[2].axial_damping: 1e+11 N s must be <= 1e+10"},
    {"DiameterAboveOneMetre", "- name: chain", "diameter: 0.08", "diameter: 1.5", "1.5",
     "mooring.line_types[1].diameter: 1.5 m must be <= 1 (the thickest mooring lines are about "
     "0.3 m)"},
    {"MassPerLengthHuge", "- name: chain", "mass_per_length: 275", "mass_per_length: 20000",
     "20000",
     "mooring.line_types[1].mass_per_length: 20000 kg/m must be <= 10000 (the heaviest chains "
     "weigh about 1000 kg/m)"},
    {"AxialStiffnessHuge", "- name: chain", "axial_stiffness: 2.28785e8", "axial_stiffness: 1e12",
     "1e12",
     "mooring.line_types[1].axial_stiffness: 1e+12 N must be <= 1e+11 (a solid steel bar 0.8 m "
     "thick)"},
    {"DragNormalAboveTen", "- name: chain", "drag_normal: 0.3", "drag_normal: 12", "12",
     "mooring.line_types[1].drag_normal: 12 must be <= 10 (a dimensionless coefficient, of "
     "order 1)"},
    {"DragTangentialAboveTen", "- name: wire", "drag_tangential: 0.008", "drag_tangential: 80",
     "80",
     "mooring.line_types[2].drag_tangential: 80 must be <= 10 (a dimensionless coefficient, of "
     "order 1)"},
    {"AddedMassAboveTen", "- name: chain", "added_mass_normal: 1.5", "added_mass_normal: 15", "15",
     "mooring.line_types[1].added_mass_normal: 15 must be <= 10 (a dimensionless coefficient, "
     "of order 1)"},
    {"FrictionAxialAboveTen", "- name: chain", "friction_axial: 0.5", "friction_axial: 50", "50",
     "mooring.line_types[1].friction_axial: 50 must be <= 10 (a dimensionless coefficient, of "
     "order 1)"},
    {"FrictionLateralAboveTen", "- name: chain", "friction_lateral: 1.0", "friction_lateral: 1e308",
     "1e308",
     "mooring.line_types[1].friction_lateral: 1e+308 must be <= 10 (a dimensionless "
     "coefficient, of order 1)"},
    {"AxialDampingRatioNegative", "- name: chain", "axial_damping_ratio: 0.5",
     "axial_damping_ratio: -0.1", "-0.1",
     "mooring.line_types[1].axial_damping_ratio: -0.1 must be in [0, 10]"},
    {"AxialDampingRatioAboveTen", "- name: chain", "axial_damping_ratio: 0.5",
     "axial_damping_ratio: 12", "12",
     "mooring.line_types[1].axial_damping_ratio: 12 must be in [0, 10]"},
    {"BothAxialDampingsGiven", "- name: chain", "axial_damping_ratio: 0.5\n",
     "axial_damping_ratio: 0.5\n      axial_damping: 2.0e4\n", "axial_damping_ratio: ^0.5",
     "mooring.line_types[1].axial_damping_ratio: 0.5 cannot be combined with axial_damping "
     "20000 N s; give one of them"},
    {"SegmentsBelowTwo", "- id: 1", "segments: 30", "segments: 1", "segments: ^1",
     "mooring.lines[1].segments: 1 must be in 2..10000"},
    {"SegmentsAboveTenThousand", "- id: 1", "segments: 30", "segments: 10001", "10001",
     "mooring.lines[1].segments: 10001 must be in 2..10000"},
    {"DefaultSegmentsBelowTwo", "", "defaults: {segments: 40}", "defaults: {segments: 0}",
     "segments: ^0", "mooring.defaults.segments: 0 must be in 2..10000"},
    {"LengthNotPositive", "- id: 2", "length: 2250", "length: 0", "length: ^0",
     "mooring.lines[2].length: 0 m must be > 0"},
    {"LengthAboveTwentyKilometres", "- id: 2", "length: 2250", "length: 20001", "20001",
     "mooring.lines[2].length: 20001 m must be <= 20000"},
    // Geometry the static solution cannot hold. Line 2 runs from (0, 20,
    // 12) to (0, 1950, 1000): 1930 m across, 988 m down.
    {"LineWouldLieSlack", "- id: 2", "length: 2250", "length: 3000", "3000",
     "mooring.lines[2].length: 3000 m must be shorter than the horizontal anchor-fairlead "
     "distance plus the fairlead's height above the anchor, 1930.0 + 988.0 = 2918.0 m (a longer "
     "line lies slack on the seabed, with no horizontal tension)"},
    {"AnchorDirectlyBelowFairlead", "- id: 3", "[-1950, 0, 1000]", "[-20, 0, 1000]",
     "length: ^2250",
     "mooring.lines[3].length: 2250 m must be shorter than the horizontal anchor-fairlead "
     "distance plus the fairlead's height above the anchor, 0.0 + 988.0 = 988.0 m (a longer "
     "line lies slack on the seabed, with no horizontal tension)"},
    {"AnchorInsideTheTurret", "- id: 3", "[-1950, 0, 1000]", "[-5, 0, 1000]", "length: ^2250",
     "mooring.lines[3].length: 2250 m must be shorter than the horizontal anchor-fairlead "
     "distance plus the fairlead's height above the anchor, 15.0 + 988.0 = 1003.0 m (a longer "
     "line lies slack on the seabed, with no horizontal tension)"},
    {"AnchorAtTheFairlead", "- id: 3", "[-1950, 0, 1000]", "[-20, 0, 12]", "[-20",
     "mooring.lines[3].anchor: z = 12 m is level with the fairlead; it must be below it (z "
     "points down)"},
    {"AnchorAboveTheSeabed", "- id: 3", "[-1950, 0, 1000]", "[-1950, 0, 990]", "[-1950",
     "mooring.lines[3].anchor: z = 990 m is above the seabed at depth 1000 m (an anchor lies on "
     "the seabed, within 1 m; one held in the water says anchor_in_water: true)"},
    {"FairleadFarFromTheVessel", "- id: 2", "[0, 20, 12]", "[0, 2000, 12]", "2000",
     "mooring.lines[2].fairlead[2]: 2000 m must be in [-1000, 1000] (a point on the vessel)"},
    // |(0, 1950, 1000) - (0, 20, 12)| = sqrt(1930^2 + 988^2) = 2168.189 m.
    {"LengthShorterThanAnchorFairleadDistance", "- id: 2", "length: 2250", "length: 1800", "1800",
     "mooring.lines[2].length: 1800 m is shorter than the anchor-fairlead distance 2168.2 m"},
    {"AnchorBelowSeabed", "- id: 3", "[-1950, 0, 1000]", "[-1950, 0, 1000.5]", "[-1950",
     "mooring.lines[3].anchor: z = 1000.5 m is below the seabed at depth 1000 m"},
    {"AnchorAboveFairlead", "- id: 3", "[-1950, 0, 1000]", "[-1950, 0, 5]", "[-1950",
     "mooring.lines[3].anchor: z = 5 m is above the fairlead at z = 12 m (z points down)"},
    {"WaterDepthNotPositive", "", "depth: 1000}", "depth: 0}", "depth: ^0}",
     "mooring.water.depth: 0 m must be > 0"},
    {"WaterDensityNotWater", "", "density: 1025", "density: 0", "density: ^0",
     "mooring.water.density: 0 kg/m^3 must be in [900, 1100] (water: fresh 1000, sea about "
     "1025)"},
    {"WaterDensityInTonnes", "", "density: 1025", "density: 1.025", "1.025",
     "mooring.water.density: 1.025 kg/m^3 must be in [900, 1100] (water: fresh 1000, sea about "
     "1025)"},
    {"GravityNotPositive", "", "gravity: 9.81", "gravity: -9.81", "-9.81",
     "mooring.water.gravity: -9.81 m/s^2 must be in [9.7, 9.9] (Earth's gravity)"},
    {"GravityHuge", "", "gravity: 9.81", "gravity: 1e308", "1e308",
     "mooring.water.gravity: 1e+308 m/s^2 must be in [9.7, 9.9] (Earth's gravity)"},
    {"WaterDeeperThanAnyOcean", "", "depth: 1000}", "depth: 13000}", "13000",
     "mooring.water.depth: 13000 m must be <= 12000 (the deepest ocean is 11 km)"},
    {"SeabedStiffnessNotPositive", "", "stiffness: 3.0e6", "stiffness: 0", "stiffness: ^0",
     "mooring.seabed.stiffness: 0 N/m^3 must be > 0"},
    {"SeabedDampingNegative", "", "damping: 3.0e5", "damping: -1", "damping: ^-1",
     "mooring.seabed.damping: -1 N s/m^3 must be >= 0"},
    {"SeabedStiffnessHuge", "", "stiffness: 3.0e6", "stiffness: 1e11", "1e11",
     "mooring.seabed.stiffness: 1e+11 N/m^3 must be <= 1e+10 (stiffer than rock)"},
    {"SeabedDampingHuge", "", "damping: 3.0e5", "damping: 1e11", "1e11",
     "mooring.seabed.damping: 1e+11 N s/m^3 must be <= 1e+10"},
    {"ContactSmoothingHuge", "", "friction_velocity: 0.01",
     "contact_smoothing: 20, friction_velocity: 0.01", "contact_smoothing: ^20",
     "mooring.seabed.contact_smoothing: 20 m must be <= 10"},
    {"FrictionVelocityHuge", "", "friction_velocity: 0.01", "friction_velocity: 20",
     "friction_velocity: ^20", "mooring.seabed.friction_velocity: 20 m/s must be <= 10"},
    {"ContactSmoothingNotPositive", "", "friction_velocity: 0.01",
     "contact_smoothing: -0.5, friction_velocity: 0.01", "contact_smoothing: ^-0.5",
     "mooring.seabed.contact_smoothing: -0.5 m must be > 0"},
    {"FrictionVelocityNotPositive", "", "friction_velocity: 0.01", "friction_velocity: 0",
     "friction_velocity: ^0", "mooring.seabed.friction_velocity: 0 m/s must be > 0"},
    {"CurrentDepthsNotIncreasing", "", "{depth: 500, speed: 0.1}", "{depth: 0, speed: 0.1}",
     "speed: 0.2}\n      - {depth: ^0",
     "mooring.current.profile[2].depth: 0 m must be greater than the previous point's depth "
     "0 m"},
    {"CurrentDepthNegative", "", "{depth: 0, speed: 0.2}", "{depth: -10, speed: 0.2}", "-10",
     "mooring.current.profile[1].depth: -10 m must be >= 0"},
    {"CurrentSpeedNegative", "", "speed: 0.1}", "speed: -0.1}", "-0.1",
     "mooring.current.profile[2].speed: -0.1 m/s must be >= 0"},
    {"CurrentSpeedTooFast", "", "speed: 0.1}", "speed: 6}", "speed: ^6",
     "mooring.current.profile[2].speed: 6 m/s must be <= 5 (the strongest ocean currents run at "
     "about 2.5 m/s)"},
    {"CurrentDepthTooDeep", "", "{depth: 500", "{depth: 13000", "13000",
     "mooring.current.profile[2].depth: 13000 m must be <= 12000 (the deepest ocean is 11 km)"},
    {"DuplicateLineTypeName", "friction_lateral", "name: wire", "name: chain", "name: ^chain",
     "mooring.line_types[2].name: 'chain' is already the name of mooring.line_types[1]"},
    {"DynamicStiffnessWithoutCreepTime", "name: wire", "axial_stiffness: 8.0e8",
     "axial_stiffness: 8.0e8\n      dynamic_axial_stiffness: 1.2e9", "1.2e9",
     "mooring.line_types[2].dynamic_axial_stiffness: a visco-elastic rope needs both "
     "dynamic_axial_stiffness and creep_time"},
    {"DynamicStiffnessBelowTheQuasiStatic", "name: wire", "axial_stiffness: 8.0e8",
     "axial_stiffness: 8.0e8\n      dynamic_axial_stiffness: 5.0e8\n      creep_time: 20", "5.0e8",
     "mooring.line_types[2].dynamic_axial_stiffness: 5e+08 N must exceed the "
     "quasi-static axial_stiffness 8e+08 N"},
    {"CreepTimeZero", "name: wire", "axial_stiffness: 8.0e8",
     "axial_stiffness: 8.0e8\n      dynamic_axial_stiffness: 1.2e9\n      creep_time: 0",
     "creep_time: ^0", "mooring.line_types[2].creep_time: 0 s must be > 0"},
    {"DynamicStiffnessSlopeWithoutARope", "name: wire", "axial_stiffness: 8.0e8",
     "axial_stiffness: 8.0e8\n      dynamic_axial_stiffness_slope: 30", "30",
     "mooring.line_types[2].dynamic_axial_stiffness_slope: a dynamic stiffness slope needs a "
     "visco-elastic rope (dynamic_axial_stiffness and creep_time)"},
    {"DynamicStiffnessSlopeNegative", "name: wire", "axial_stiffness: 8.0e8",
     "axial_stiffness: 8.0e8\n      dynamic_axial_stiffness: 1.2e9\n      creep_time: 20\n"
     "      dynamic_axial_stiffness_slope: -1",
     "-1", "mooring.line_types[2].dynamic_axial_stiffness_slope: -1 must be >= 0"},
    {"UnknownLineType", "- id: 2", "type: wire", "type: wier", "wier",
     "mooring.lines[2].type: unknown line type 'wier' (known: chain, wire)"},
    {"UnknownSectionType", "- id: 2",
     "type: wire\n      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      length: 2250",
     "anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      sections: [{type: wire, "
     "length: 1000, segments: 20}, {type: rope, length: 1250, segments: 20}]",
     "rope", "mooring.lines[2].sections[2].type: unknown line type 'rope' (known: chain, wire)"},
    {"CompositeLineShorterThanTheDistance", "- id: 2",
     "type: wire\n      anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      length: 2250",
     "anchor: [0, 1950, 1000]\n      fairlead: [0, 20, 12]\n      sections: [{type: wire, "
     "length: 1000, segments: 20}, {type: chain, length: 900, segments: 20}]",
     "[{type: wire",
     "mooring.lines[2].sections: 1900 m is shorter than the anchor-fairlead distance 2168.2 m"},
    {"DuplicateLineId", "type: chain", "- id: 2", "- id: 1", "- id: ^1",
     "mooring.lines[2].id: 1 is already the id of mooring.lines[1]"},
    {"LineIdsNotOneToN", "type: wire", "- id: 3", "- id: 4", "- id: ^4",
     "mooring.lines[3].id: 4 must be in 1..3 (ids number the 3 lines from 1)"},
    {"RelativeToleranceNotPositive", "", "rtol: 1.0e-4", "rtol: 0", "rtol: ^0",
     "solver.rtol: 0 must be in (0, 1)"},
    {"RelativeToleranceNotBelowOne", "", "rtol: 1.0e-4", "rtol: 1", "rtol: ^1",
     "solver.rtol: 1 must be in (0, 1)"},
    {"PositionToleranceNotPositive", "", "atol_position: 1.0e-3", "atol_position: 0",
     "atol_position: ^0", "solver.atol_position: 0 m must be > 0"},
    {"VelocityToleranceNotPositive", "", "atol_velocity: 2.0e-3", "atol_velocity: -0.5", "-0.5",
     "solver.atol_velocity: -0.5 m/s must be > 0"},
    {"UnknownLinearSolver", "", "linear_solver: klu", "linear_solver: lu", "linear_solver: ^lu",
     "solver.linear_solver: unknown linear solver 'lu' (known: block, klu)"},
    {"MaxOrderZero", "", "max_order: 4", "max_order: 0", "max_order: ^0",
     "solver.max_order: 0 must be in 1..5"},
    {"MaxOrderAboveFive", "", "max_order: 4", "max_order: 6", "max_order: ^6",
     "solver.max_order: 6 must be in 1..5"},
    {"MaxStepNegative", "", "max_step: 0.5", "max_step: -1", "max_step: ^-1",
     "solver.max_step: -1 s must be >= 0 (0 = no limit)"},
    {"PositionToleranceAboveOneMetre", "", "atol_position: 1.0e-3", "atol_position: 2",
     "atol_position: ^2", "solver.atol_position: 2 m must be <= 1"},
    {"VelocityToleranceAboveOne", "", "atol_velocity: 2.0e-3", "atol_velocity: 5",
     "atol_velocity: ^5", "solver.atol_velocity: 5 m/s must be <= 1"},
    {"MaxStepHuge", "", "max_step: 0.5", "max_step: 1e8", "1e8",
     "solver.max_step: 1e+08 s must be <= 1e+07"},
    // The coupled-simulation sections.
    {"HydrodynamicsMissing", "vessel:", "fpso_wamit/fpso", "fpso_wamit/nothing", "hydrodynamics: ^",
     "vessel.hydrodynamics: '" MOORSIM_SOURCE_DIR
     "/data/fpso_wamit/nothing': no WAMIT file '" MOORSIM_SOURCE_DIR "/data/fpso_wamit/nothing.1'"},
    {"VesselMassZero", "vessel:", "mass: 1.0041e8", "mass: 0", "mass: ^0",
     "vessel.mass: 0 kg must be > 0"},
    {"VesselMassHuge", "vessel:", "mass: 1.0041e8", "mass: 1.0041e11", "1.0041e11",
     "vessel.mass: 1.0041e+11 kg must be <= 1e+09 (the largest floating structures displace "
     "about 6e8 kg)"},
    {"LengthScaleHuge", "vessel:", "length_scale: 1", "length_scale: 2000", "2000",
     "vessel.length_scale: 2000 m must be <= 1000"},
    {"CentreOfGravityOffTheVessel", "vessel:", "centre_of_gravity: [0, 0, 1]",
     "centre_of_gravity: [0, 0, 1500]", "1500",
     "vessel.centre_of_gravity[3]: 1500 m must be in [-1000, 1000] (a point on the vessel)"},
    {"RadiusOfGyrationZero", "vessel:", "[16.3, 54, 54]", "[16.3, 0, 54]", "[16.3, ^0",
     "vessel.radii_of_gyration[2]: 0 m must be > 0"},
    {"RadiusOfGyrationHuge", "vessel:", "[16.3, 54, 54]", "[16.3, 54, 5400]", "5400",
     "vessel.radii_of_gyration[3]: 5400 m must be <= 1000"},
    {"SurgeTimeHuge", "vessel:", "surge_time: 50", "surge_time: 1e8", "surge_time: ^1e8",
     "vessel.damping.surge_time: 1e+08 s must be <= 1e+07"},
    {"HullDraughtZero", "hull:", "draught: 12", "draught: 0", "draught: ^0",
     "vessel.hull.draught: 0 m must be > 0"},
    {"HullFullerThanItsBox", "hull:", "displaced_volume: 97961", "displaced_volume: 2e5", "2e5",
     "vessel.hull.displaced_volume: 2e+05 m^3 must be <= length x beam x draught = 105600 m^3 "
     "(a block coefficient <= 1)"},
    {"HullFormFactorMinusOne", "hull:", "form_factor: 0.505", "form_factor: -1", "form_factor: ^-1",
     "vessel.hull.form_factor: -1 must be in (-1, 10] (k of (1 + k) C_F; ships 0.1 to 0.5)"},
    {"HullViscosityOfAir", "hull:", "kinematic_viscosity: 1.19e-6", "kinematic_viscosity: 1.5e-5",
     "1.5e-5",
     "vessel.hull.kinematic_viscosity: 1.5e-05 m^2/s must be in [1e-07, 1e-05] (water: 1.8e-6 "
     "at 0 deg C, 0.7e-6 at 40 deg C)"},
    {"WindageAreaZero", "windage:", "frontal_area: 1200", "frontal_area: 0", "frontal_area: ^0",
     "vessel.windage.frontal_area: 0 m^2 must be > 0"},
    {"WindageCentroidOffTheVessel", "windage:", "lateral_centroid: 0", "lateral_centroid: 150",
     "150",
     "vessel.windage.lateral_centroid: 150 m must be in [-100, 100] (on the vessel: within half "
     "of windage.length from midship)"},
    {"WindageAirDensityOfWater", "windage:", "air_density: 1.226", "air_density: 1025", "1025",
     "vessel.windage.air_density: 1025 kg/m^3 must be in [1, 1.5] (air: 1.226 at sea level and "
     "15 deg C)"},
    {"InitialPoseFarAway", "initial_pose:", "x: 2,", "x: 2e5,", "2e5",
     "vessel.initial_pose.x: 2e+05 m must be in [-1e+05, 1e+05]"},
    // The reach and slack rules with the vessel at its initial pose (2, 2) m, 10 deg; with
    // it at x 1500 m line 1's fairlead is 430.3 m across from its anchor.
    {"LineSlackAtTheInitialPose", "initial_pose:", "x: 2,", "x: 1500,", "initial_pose: ^{",
     "vessel.initial_pose: at x 1500 m, y 2 m, heading 10 deg, mooring.lines[1].length 2250 m "
     "must be shorter than the horizontal anchor-fairlead distance plus the fairlead's height "
     "above the anchor, 430.3 + 988.0 = 1418.3 m (a longer line lies slack on the seabed, with "
     "no horizontal tension)"},
    {"LineCannotReachAtTheInitialPose", "initial_pose:", "x: 2,", "x: -1500,", "initial_pose: ^{",
     "vessel.initial_pose: at x -1500 m, y 2 m, heading 10 deg, mooring.lines[1].length 2250 m "
     "is shorter than the anchor-fairlead distance 3569.8 m"},
    {"ThrusterOffTheVessel", "name: aft_port", "x: -90", "x: -9000", "-9000",
     "vessel.thrusters[1].x: -9000 m must be in [-1000, 1000] (a point on the vessel)"},
    {"ThrusterMaxThrustHuge", "name: aft_port", "max_thrust: 1.0e6", "max_thrust: 1.0e9", "1.0e9",
     "vessel.thrusters[1].max_thrust: 1e+09 N must be <= 1e+08 (the largest thrusters give "
     "about 2e6 N)"},
    {"ThrusterMinThrustHuge", "name: aft_port", "min_thrust: -6.0e5", "min_thrust: -6.0e9",
     "-6.0e9",
     "vessel.thrusters[1].min_thrust: -6e+09 N must be >= -1e+08 (the largest thrusters "
     "give about 2e6 N)"},
    {"ThrusterWeightHuge", "name: aft_port", "weight: 1", "weight: 1e7", "1e7",
     "vessel.thrusters[1].weight: 1e+07 must be <= 1e+06"},
    {"ThrusterTimeConstantHuge", "name: aft_port", "time_constant: 5", "time_constant: 5000",
     "5000", "vessel.thrusters[1].time_constant: 5000 s must be <= 1000"},
    {"ThrusterRateLimitHuge", "name: aft_port", "rate_limit: 2.0e5", "rate_limit: 2.0e10", "2.0e10",
     "vessel.thrusters[1].rate_limit: 2e+10 N/s must be <= 1e+09"},
    {"ThrusterMinThrustPositive", "name: aft_port", "min_thrust: -6.0e5", "min_thrust: 5",
     "min_thrust: ^5", "vessel.thrusters[1].min_thrust: 5 N must be <= 0"},
    {"ThrusterNameTwice", "y: -8", "name: aft_starboard", "name: aft_port", "aft_port",
     "vessel.thrusters[2].name: 'aft_port' is used by thruster 1 too"},
    {"WavesGammaBelowOne", "environment:", "gamma: 3.3", "gamma: 0.5", "gamma: ^0.5",
     "environment.waves.gamma: 0.5 must be in [1, 10]"},
    {"WavesHigherThanAnySea", "environment:", "hs: 2.5", "hs: 35", "35",
     "environment.waves.hs: 35 m must be <= 30 (the highest sea states measured)"},
    {"WavesPeriodBelowOneSecond", "environment:", "tp: 7", "tp: 0.5", "0.5",
     "environment.waves.tp: 0.5 s must be in [1, 40] (wind sea and swell)"},
    {"WavesPeriodInMinutes", "environment:", "tp: 7", "tp: 420", "420",
     "environment.waves.tp: 420 s must be in [1, 40] (wind sea and swell)"},
    // Hs / (g Tp^2 / (2 pi)) = 12 x 2 pi / (9.81 x 49) = 0.157.
    {"WavesTooSteep", "environment:", "hs: 2.5", "hs: 12", "12",
     "environment.waves.hs: 12 m is too steep for tp 7 s: Hs / (g Tp^2 / (2 pi)) = 0.157 must "
     "be <= 1/7 (such waves break)"},
    {"AnchorInWaterWithDetectors", "- id: 1", "anchor: [1950, 0, 1000]",
     "anchor: [1950, 0, 900]\n      anchor_in_water: true", "anchor_in_water: ^true",
     "mooring.lines[1].anchor_in_water: the detectors' line models have no line held in the "
     "water; run this mooring without detectors"},
    // 2 a / L with L = g T^2 / (2 pi) = 9.81 x 9 / (2 pi) = 14.05 m: 4 / 14.05 = 0.285.
    {"WaveTrainTooSteep", "environment:",
     "{hs: 2.5, tp: 7, gamma: 3.3, direction_toward_deg: 315, spreading: 10, components: 200}",
     "{trains: [{period: 3, amplitude: 2, phase_deg: 0, direction_toward_deg: 0}]}",
     "amplitude: ^2",
     "environment.waves.trains[1].amplitude: 2 m is too steep for period 3 s: "
     "2 a / L = 0.285 must be <= 1/7 (such waves break)"},
    {"WavesSpreadingHuge", "environment:", "spreading: 10", "spreading: 200", "200",
     "environment.waves.spreading: 200 must be <= 100 (s = 75 is narrow swell; omit it for "
     "long-crested waves)"},
    {"WindSpeedNegative", "wind:", "speed: 12", "speed: -12", "speed: ^-12",
     "environment.wind.speed: -12 m/s must be >= 0"},
    {"WindSpeedAboveAnyHurricane", "wind:", "speed: 12", "speed: 90", "speed: ^90",
     "environment.wind.speed: 90 m/s must be <= 80 (above any hurricane's 1-hour mean)"},
    {"ControllerUnknownType", "controller:", "type: pi", "type: pid", "type: ^pid",
     "controller.type: unknown controller 'pid' (known: none, observer_pid, pi)"},
    {"ControllerRateZero", "controller:", "rate_hz: 1", "rate_hz: 0", "rate_hz: ^0",
     "controller.rate_hz: 0 Hz must be > 0"},
    {"ControllerRateAboveOneKilohertz", "controller:", "rate_hz: 1", "rate_hz: 2000",
     "rate_hz: ^2000", "controller.rate_hz: 2000 Hz must be <= 1000"},
    {"ControllerGainNegative", "controller:", "kp: [1.0e5", "kp: [-1.0e5", "-1.0e5",
     "controller.kp[1]: -1e+05 must be >= 0"},
    {"ControllerGainHuge", "controller:", "ki: [1.0e3, 1.0e3", "ki: [1.0e3, 1.0e13", "1.0e13",
     "controller.ki[2]: 1e+13 must be <= 1e+12"},
    {"SetpointFarAway", "setpoint:", "x: 0", "x: 1e6", "1e6",
     "controller.setpoint.x: 1e+06 m must be in [-1e+05, 1e+05]"},
    {"NaturalPeriodHuge", "controller:", "natural_period: 120", "natural_period: 1e5", "1e5",
     "controller.natural_period: 1e+05 s must be <= 10000"},
    {"ControllerDampingRatioHuge", "controller:", "damping_ratio: 0.8", "damping_ratio: 20",
     "damping_ratio: ^20", "controller.damping_ratio: 20 must be <= 10"},
    {"GnssRateZero", "gnss:", "rate_hz: 1", "rate_hz: 0", "rate_hz: ^0",
     "sensors.gnss.rate_hz: 0 Hz must be > 0"},
    {"GnssRateAboveOneKilohertz", "gnss:", "rate_hz: 1", "rate_hz: 5000", "rate_hz: ^5000",
     "sensors.gnss.rate_hz: 5000 Hz must be <= 1000"},
    {"GyroRateAboveOneKilohertz", "gyro:", "rate_hz: 1", "rate_hz: 1e6", "rate_hz: ^1e6",
     "sensors.gyro.rate_hz: 1e+06 Hz must be <= 1000"},
    {"CellFaultModeUnknown", "faults:", "mode: drift", "mode: broken", "mode: ^broken",
     "sensors.tension_cells.faults[1].mode: unknown sensor fault 'broken' (known: dead, "
     "degraded, drift, gain, step, stuck)"},
    {"CellFaultLineBeyondTheMooring", "faults:", "line: 3", "line: 9", "line: ^9",
     "sensors.tension_cells.faults[1].line: 9 must be in 1..3"},
    {"CellDriftWithoutRate", "faults:", "rate: -1000", "rate: 0", "rate: ^0",
     "sensors.tension_cells.faults[1].rate: a drift needs a nonzero rate [N/s]"},
    {"FaultEndBeforeItsTime", "faults:", "time: 500,", "time: 500, end: 400,", "end: ^400",
     "sensors.tension_cells.faults[1].end: 400 s must be after the fault's time (500 s)"},
    {"FaultAfterTheEnd", "faults:", "time: 500,", "time: 1500,", "time: ^1500",
     "sensors.tension_cells.faults[1].time: 1500 s is not before the end of the run "
     "(simulation.duration 1000 s)"},
    {"DeadCellWhileItIsStuck", "faults:", "rate: -1000}]",
     "rate: -1000}, {line: 3, mode: stuck, time: 550, end: 700}, {line: 3, mode: dead, time: "
     "600}]",
     "time: ^600",
     "sensors.tension_cells.faults[3].time: the dead fault at 600 s overlaps "
     "sensors.tension_cells.faults[2] (stuck at 550 s) on the same channel: each replaces the "
     "sensor's reading, so the two cannot act at once (other faults add to them in the order "
     "listed)"},
    {"FaultSizeOfAnotherMode", "faults:", "rate: -1000", "offset: -1000", "offset: ^-1000",
     "sensors.tension_cells.faults[1].offset: only applies to mode 'step' (the mode is "
     "'drift')"},
    {"GnssFaultChannelUnknown", "gnss:", "dropout_mean_duration: 5",
     "dropout_mean_duration: 5\n    faults: [{mode: step, time: 10, offset: 1, channel: up}]",
     "channel: ^up",
     "sensors.gnss.faults[1].channel: unknown GNSS channel 'up' (known: both, east, north)"},
    {"GnssFaultLine", "gnss:", "dropout_mean_duration: 5",
     "dropout_mean_duration: 5\n    faults: [{mode: dead, time: 10, line: 2}]", "line: 2",
     "sensors.gnss.faults[1]: unknown key 'line' (known: channel, end, factor, gain, mode, "
     "offset, rate, time)"},
    {"GyroDegradedBelowOne", "gyro:", "dropout_probability: 0.01",
     "dropout_probability: 0.01\n    faults: [{mode: degraded, time: 10, factor: 0.5}]",
     "factor: ^0.5", "sensors.gyro.faults[1].factor: 0.5 must be > 1"},
    {"TensionCellRateAboveOneKilohertz", "tension_cells:", "rate_hz: 1", "rate_hz: 2000",
     "rate_hz: ^2000", "sensors.tension_cells.rate_hz: 2000 Hz must be <= 1000"},
    {"GnssStdDevHuge", "north:", "std_dev: 0.07", "std_dev: 5000", "5000",
     "sensors.gnss.north.std_dev: 5000 m must be <= 1000"},
    {"GnssBiasWalkHuge", "north:", "bias_walk: 0.001", "bias_walk: 2000", "2000",
     "sensors.gnss.north.bias_walk: 2000 m/sqrt(s) must be <= 1000"},
    {"GnssBiasTimeConstantHuge", "north:", "bias_time_constant: 600", "bias_time_constant: 1e9",
     "1e9", "sensors.gnss.north.bias_time_constant: 1e+09 s must be <= 1e+07"},
    {"GnssInitialBiasHuge", "north:", "initial_bias: 0.1", "initial_bias: -1e4", "-1e4",
     "sensors.gnss.north.initial_bias: -10000 m must be in [-1000, 1000]"},
    {"GnssOutlierStdDevHuge", "north:", "outlier_std_dev: 2", "outlier_std_dev: 2e3", "2e3",
     "sensors.gnss.north.outlier_std_dev: 2000 m must be <= 1000"},
    {"GnssDropoutDurationHuge", "gnss:", "dropout_mean_duration: 5", "dropout_mean_duration: 1e8",
     "1e8", "sensors.gnss.dropout_mean_duration: 1e+08 s must be <= 1e+07"},
    {"GyroStdDevAboveHalfATurn", "heading: {std_dev", "std_dev: 0.07", "std_dev: 4", "4",
     "sensors.gyro.heading.std_dev: 4 rad must be <= 3.141592653589793"},
    {"TensionNoiseHuge", "tension_cells:", "std_dev: 1.0e4", "std_dev: 1.0e9", "1.0e9",
     "sensors.tension_cells.noise.std_dev: 1e+09 N must be <= 1e+08"},
    {"DropoutProbabilityAboveOne", "gnss:", "dropout_probability: 0.01", "dropout_probability: 1.5",
     "dropout_probability: ^1.5", "sensors.gnss.dropout_probability: 1.5 must be in [0, 1)"},
    {"FailureLineOutOfRange", "failure:", "line: 2", "line: 9", "line: ^9",
     "failure.line: 9 must be in 1..3"},
    {"FailureAfterTheEnd", "failure:", "time: 300", "time: 1300", "time: ^1300",
     "failure.time: 1300 s is not before the end of the run (simulation.duration 1000 s)"},
    {"FailureUnknownMode", "failure:", "mode: node", "mode: middle", "mode: ^middle",
     "failure.mode: unknown failure mode 'middle' (known: anchor, fairlead, node)"},
    {"FailureNodeOutOfRange", "failure:", "node: 10", "node: 60", "node: ^60",
     "failure.node: 60 must be in 1..39"},
    {"SensorChecksWithPassiveObservers", "detection:", "observer: ekf\n  sensor_checks: false",
     "observer: passive\n  sensor_checks: true", "sensor_checks: ^true",
     "detection.sensor_checks: the passive observers make no sensor checks (they need "
     "observer: ekf)"},
    {"DetectionSwitchRateNegative", "detection:", "switch_rate: 0.01", "switch_rate: -1",
     "switch_rate: ^-1", "detection.switch_rate: -1 1/s must be >= 0"},
    {"TurretUnknownBearing", "turret:", "bearing: friction", "bearing: sliding",
     "bearing: ^sliding",
     "vessel.turret.bearing: unknown turret bearing 'sliding' (known: free, friction, locked)"},
    {"TurretOutsideTheHull", "turret:", "x: 0, y: 0", "x: 85, y: 0", "x: ^85",
     "vessel.turret.x: 85 m puts the turret (radius 20 m) outside the hull: |x| + radius must "
     "be <= hull.length / 2 = 100 m"},
    {"TurretBeyondTheBeam", "turret:", "x: 0, y: 0", "x: 0, y: -5", "y: ^-5",
     "vessel.turret.y: -5 m puts the turret (radius 20 m) outside the hull: |y| + radius must "
     "be <= hull.beam / 2 = 22 m"},
    {"TurretRadiusShortOfTheFairleads", "turret:", "radius: 20", "radius: 15", "radius: ^15",
     "vessel.turret.radius: 15 m does not reach the fairlead of mooring.lines[1], 20 m from "
     "the turret centre (the fairleads are on the turret)"},
    {"TurretInitialHeadingLocked", "turret:", "bearing: friction",
     "bearing: locked, initial_heading_deg: 30", "initial_heading_deg: ^30",
     "vessel.turret.initial_heading_deg: a locked turret turns with the hull: give bearing free "
     "or friction, or leave initial_heading_deg out"},
    {"TurretInitialHeadingRange", "turret:", "bearing: friction",
     "bearing: friction, initial_heading_deg: 400", "initial_heading_deg: ^400",
     "vessel.turret.initial_heading_deg: 400 deg must be in [-360, 360]"},
    {"TurretRadiusNegative", "turret:", "radius: 20", "radius: -20", "radius: ^-20",
     "vessel.turret.radius: -20 m must be > 0"},
    {"TurretInertiaNegative", "turret:", "inertia: 6.0e8", "inertia: -6.0e8", "inertia: ^-6.0e8",
     "vessel.turret.inertia: -6e+08 kg m^2 must be > 0"},
    {"TurretFrictionNegative", "turret:", "friction_coefficient: 0.01",
     "friction_coefficient: -0.01", "friction_coefficient: ^-0.01",
     "vessel.turret.friction_coefficient: -0.01 must be >= 0"},
    {"TurretSlipRateZero", "turret:", "slip_rate: 1.0e-5", "slip_rate: 0", "slip_rate: ^0",
     "vessel.turret.slip_rate: 0 rad/s must be > 0"},
    {"HeadingLoopPeriodZero", "heading:", "natural_period: 200", "natural_period: 0",
     "natural_period: ^0", "controller.heading.natural_period: 0 s must be > 0"},
    {"HeadingLoopDampingNegative", "heading:", "damping_ratio: 0.8", "damping_ratio: -0.8",
     "damping_ratio: ^-0.8", "controller.heading.damping_ratio: -0.8 must be > 0"},
    {"DetectionTrainingSeedNegative", "detection:", "training_seed: 3", "training_seed: -3",
     "training_seed: ^-3", "detection.training_seed: -3 must be a non-negative integer"},
    {"DetectionSwitchRateHuge", "observer: ekf", "switch_rate: 0.01", "switch_rate: 2000",
     "switch_rate: ^2000", "detection.switch_rate: 2000 1/s must be <= 1000"},
    {"MeasurementVarianceHuge", "observer: ekf", "measurement_variance: 0.005",
     "measurement_variance: 1e5", "1e5", "detection.measurement_variance: 1e+05 must be <= 10000"},
    {"DetectionWaveMotionStdHuge", "observer: ekf", "wave_motion_std: [0.15",
     "wave_motion_std: [1500", "1500", "detection.model.wave_motion_std[1]: 1500 must be <= 1000"},
    {"DetectionBiasStdHuge", "observer: ekf", "bias_std: [1.0e6", "bias_std: [1.0e13", "1.0e13",
     "detection.model.bias_std[1]: 1e+13 must be <= 1e+12"},
    {"DetectionTimeConstantHuge", "observer: ekf", "bias_time_constant: [1000, 1000, 1000]",
     "bias_time_constant: [1000, 1000, 1e8]", "1e8",
     "detection.model.bias_time_constant[3]: 1e+08 s must be <= 1e+07"},
    {"DetectionForceNoiseHuge", "observer: ekf", "force_noise: [5.0e4", "force_noise: [5.0e14",
     "5.0e14", "detection.model.force_noise[1]: 5e+14 must be <= 1e+12"},
    {"DetectionMooringDampingRatioHuge", "observer: ekf", "mooring_damping_ratio: [0, 0, 0]",
     "mooring_damping_ratio: [0, 20, 0]", "20",
     "detection.model.mooring_damping_ratio[2]: 20 must be <= 10"},
    {"DetectionBiasStdNegative", "detection:", "bias_std: [1.0e6", "bias_std: [-1.0e6",
     "bias_std: [^-1.0e6", "detection.model.bias_std[1]: -1e+06 must be >= 0"},
    {"DetectionTimeConstantZero", "detection:", "bias_time_constant: [1000, 1000, 1000]",
     "bias_time_constant: [1000, 0, 1000]", "bias_time_constant: [1000, ^0",
     "detection.model.bias_time_constant[2]: 0 s must be > 0"},
    {"DetectionModelUnknownKey", "detection:", "force_noise:", "force_noises:", "^force_noises:",
     "detection.model: unknown key 'force_noises' (did you mean 'force_noise'?)"},
    {"SimulationDurationZero", "simulation:", "duration: 1000", "duration: 0", "duration: ^0",
     "simulation.duration: 0 s must be > 0"},
    {"SimulationDurationHuge", "simulation:", "duration: 1000", "duration: 2e7", "2e7",
     "simulation.duration: 2e+07 s must be <= 1e+07 (116 days)"},
    {"OutputRateAboveOneKilohertz", "simulation:", "output_rate_hz: 2", "output_rate_hz: 2000",
     "2000", "simulation.output_rate_hz: 2000 Hz must be <= 1000"},
    {"TooManyOutputRows", "simulation:", "duration: 1000, output_rate_hz: 2",
     "duration: 9.0e6, output_rate_hz: 200", "output_rate_hz: ^200",
     "simulation.output_rate_hz: 200 Hz for simulation.duration 9e+06 s would write 1.8e+09 "
     "rows (at most 1e+09)"},
};
}  // namespace moorsim::scenarios::test_cases
