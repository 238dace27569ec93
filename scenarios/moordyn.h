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
//     relative to the vessel's reference point; where they lie beyond moorsim's reach of a
//     vessel point, 1000 m, the whole model moves horizontally so that their centre is the
//     reference point, and the scenario says by how much); Free points where exactly two
//     lines meet become the joints of a composite line, with their mass, volume, CdA and
//     Ca as a clump weight or buoy; other free points (where one line ends, or three or
//     more meet) are moorsim's free points.
//   * LINES (LINE LIST, LINE PROPERTIES): each chain of lines from a fixed point through
//     joints to a vessel point or a free point is one moorsim line, its sections from the
//     anchor up.
//   * Visco-elastic ropes (EA_s|EA_D with BA_s or BA_s|BA_D; Hall et al. 2023): MoorDyn's
//     segment, the dynamic spring EA_D (damped by BA_D) in series with the static spring
//     EA_D EA_s / (EA_D - EA_s) (damped by BA_s), is moorsim's dynamic spring in series
//     with its creep spring and dashpot: dynamic_axial_stiffness EA_D, creep_time BA_s
//     over the static spring; BA_D becomes the segment's axial damping (with a warning:
//     moorsim's damps the whole segment). The load-dependent form EA_s|EA_Dc|EA_D_Lm
//     (EA_D = EA_Dc + EA_D_Lm x the mean load, the static spring's tension) is moorsim's
//     dynamic_axial_stiffness EA_Dc with dynamic_axial_stiffness_slope EA_D_Lm, the creep
//     time BA_s over the static spring at no mean load.
//   * EA given as a file (MoorDyn's nonlinear stiffness: three header lines, then rows
//     "strain tension", looked for as the SeafloorFile is): the line type's tension_strain
//     (MoorDyn joins the points by straight lines, moorsim by a monotone cubic).
//   * OPTIONS: WtrDpth, WtrDnsty, g (gravity), kBot and cBot (the same per-area seabed
//     stiffness and damping as moorsim's; MoorDyn's contact is linear from the first touch,
//     so moorsim's contact ramp is narrowed to a tenth of the shallowest resting
//     penetration w / (kBot d) of the sinking line types, within [1 cm, 0.5 m]),
//     FrictionCoefficient (both of moorsim's
//     friction coefficients of every line type), SeafloorFile (the bathymetry, looked for
//     beside the input file and in the folders above it, written as moorsim's depth grid
//     beside the scenario: MoorDynImport::files), dtWave.
//   * MoorDyn's waves, from the files it reads beside the input file: WaveKin 7
//     (wave_frequencies.txt's rows "omega re im [beta]", summed as
//     |A| sin(omega t - k (x cos(beta) + y sin(beta)) + arg A)), WaveKin 2 (the same rows on
//     an even grid of the smallest spacing, inverse-transformed: |A| cos(...), the top bin
//     half its real part) and WaveKin 3 (wave_elevation.txt sampled every dtWave from 0, an
//     even count, Fourier-transformed, frequencies above 0.5 Hz cut, travelling along x):
//     moorsim's environment.waves.trains, felt by the lines, phases moved with the model.
//   * MoorDyn's currents: Currents 1 (current_profile.txt, rows "z ux uy uz") as moorsim's
//     depth profile where the velocity keeps one direction, else as a current table beside
//     the scenario, as are Currents 2 (current_profile_dynamic.txt: z values, then rows
//     "t ux(z) [uy(z) [uz(z)]]") and 5 (current_profile_4d.txt: counts, four axes, rows
//     "x y z t ux uy uz"), repeating every (floor(t_last / dt) + 1) dt as MoorDyn does.
// Frames: MoorDyn's z points up from the still water level; moorsim's Earth and body
// frames point z down and y to starboard: (x, y, z) -> (x, -y, -z).
//
// What does not map is one located line each ("<file>:<line>: <what>"): rods, bodies,
// lines between two fixed or two vessel points, a line ending nowhere, SYROPE ropes and
// visco-elastic ropes on a table, and MoorDyn's node approaches to waves and currents
// (WaveKin 4-6, Currents 3 and 4, which MoorDyn v2.7.1 does not implement either). These are errors
// (InputError, every line at once). Properties moorsim does not model are imported without them and
// reported as warnings: bending stiffness EI, vortex-induced vibration. Integration options (time
// step, scheme, initial-condition settings, outputs) are not part of the model and are
// listed in a comment.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace moorsim::scenarios {

struct MoorDynImport {
  std::string yaml;  ///< the scenario, with comments
  /// Files the scenario names, to be written beside it: (file name, contents). The depth
  /// grid of a SeafloorFile, then the current table of a current that is not a profile.
  std::vector<std::pair<std::string, std::string>> files;
  std::vector<std::string> warnings;  ///< "<file>:<line>: <what>", one per approximation
  int lines = 0;                      ///< moorsim lines written
};

/// Reads the MoorDyn input file at `path` (InputError naming it if it cannot be read) and
/// converts it as described above. `command` is recorded in the scenario's first comment.
/// `files_stem` names the files written beside the scenario (`<stem>_seabed.csv`,
/// `<stem>_current.txt`); empty:
/// the input file's stem.
MoorDynImport ImportMoorDyn(const std::string& path, const std::string& command,
                            const std::string& files_stem = "");

}  // namespace moorsim::scenarios
