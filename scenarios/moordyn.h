// `moorsim import moordyn`: a MoorDyn (v1 and v2) input file as a moorsim scenario.
//
// What maps (the written YAML says where each value came from):
//   * LINE TYPES (LINE DICTIONARY): Diam (the volume-equivalent diameter: moorsim's
//     hydrodynamic and displacement diameter alike), Mass/m (dry), EA, BA/-zeta (a damping
//     coefficient in N s, or minus a damping ratio of one segment's axial mode: the same
//     rule as moorsim's axial_damping_ratio), Cd (normal drag on the diameter), Ca (normal
//     added mass), CdAx (tangential drag: MoorDyn applies it to the circumference pi d,
//     moorsim to d, so it is multiplied by pi), CaAx (tangential added mass, on the same
//     displaced volume). Columns are found by their header names,
//     so the v1 order (Can Cat Cdn Cdt) reads as well.
//   * POINTS (POINT LIST, CONNECTION PROPERTIES, NODE PROPERTIES): Fixed points are
//     anchors; Vessel and Coupled points are fairleads on the vessel (their coordinates are
//     relative to the vessel's reference point); Free points where exactly two lines meet
//     become the joints of a composite line, with their mass, volume, CdA and Ca as a
//     clump weight or buoy.
//   * LINES (LINE LIST, LINE PROPERTIES): each chain of lines from a fixed point through
//     free points to a vessel point is one moorsim line, its sections from the anchor up.
//   * OPTIONS: WtrDpth, WtrDnsty, g (gravity), kBot and cBot (the same per-area seabed
//     stiffness and damping as moorsim's), FrictionCoefficient (both of moorsim's
//     friction coefficients of every line type).
// Frames: MoorDyn's z points up from the still water level; moorsim's Earth and body
// frames point z down and y to starboard: (x, y, z) -> (x, -y, -z).
//
// What does not map is one located line each ("<file>:<line>: <what>"): rods, bodies,
// free points where one or more than two lines meet (bridles, shared buoys), lines between
// two fixed or two vessel points, a line ending nowhere, non-linear or visco-elastic EA
// (tables, files, `EA|EAd` pairs), seabed bathymetry files and wave or current
// kinematics options. These are errors (InputError, every line at once). Properties
// moorsim does not model are imported without them and reported as warnings: bending
// stiffness EI, vortex-induced vibration. Integration options (time step, scheme,
// initial-condition settings, outputs) are not part of the model and are listed in a
// comment.
#pragma once

#include <string>
#include <vector>

namespace moorsim::scenarios {

struct MoorDynImport {
  std::string yaml;                   ///< the scenario, with comments
  std::vector<std::string> warnings;  ///< "<file>:<line>: <what>", one per approximation
  int lines = 0;                      ///< moorsim lines written
};

/// Reads the MoorDyn input file at `path` (InputError naming it if it cannot be read) and
/// converts it as described above. `command` is recorded in the scenario's first comment.
MoorDynImport ImportMoorDyn(const std::string& path, const std::string& command);

}  // namespace moorsim::scenarios
