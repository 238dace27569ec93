// Frequency-domain hydrodynamic data of the hull from a WAMIT run: added mass, radiation
// damping, wave exciting force, motion RAOs, mean drift and hydrostatic restoring, in SI
// units and in the project's body frame.
//
// Source format: WAMIT User Manual (v6.3 / v7), chapter 4 "Output": numeric files .1, .3,
// .4, .9 and .hst, each a table of rows "PER [BETA [BETA2]] I [J] value(s)" with PER the wave
// period [s] (−1: zero frequency, 0: infinite frequency) and the values non-dimensional.
// The same files are read by OpenFAST HydroDyn and BEMRosetta; the frame change follows
// MSS `wamit2vessel.m` (Fossen), which produced this FPSO's vessel model.
//
// Conventions of everything stored here (read this before using the tables):
//
// Body frame. The project's: origin at midship on the waterline and centreline, x forward,
//   y to starboard, z down (the hull's NED-like frame, vessel/rigid_body.h). WAMIT's has the
//   same origin but y to port and z up. One is the other turned 180° about x — a proper
//   rotation R = diag(1, −1, −1) — so translations and rotations (axial vectors) both
//   transform with R: surge and roll keep their sign; sway, heave, pitch and yaw flip.
//   With T = diag(1, −1, −1, 1, −1, −1) (kWamitToProject) a 6x6 matrix becomes T M T and a
//   6-vector T v. (Roll about +x is the same motion in both frames, starboard side down;
//   pitch is bow down in WAMIT, bow up here.) This is MSS's Tscale.
//
// Wave heading β [rad]: the direction the waves travel TOWARD, measured in the body x-y
//   plane from +x toward +y. WAMIT measures toward its +y (port); here +y is starboard, so
//   the same waves have β = −β_WAMIT (ProjectHeadingFromWamit). Here: 0 following seas
//   (travelling bow-ward), −π/2 travelling to port (coming from starboard), +π/2 to
//   starboard, ±π head seas. With the vessel at heading ψ (NED), the waves travel toward
//   the compass direction ψ + β.
//
// Wave and phase. Unit-amplitude incident wave, elevation positive UP (not along z):
//   η(x, y, t) = Re{exp(i(ωt − k(x cos β + y sin β)))}, k = ω²/g (deep water), with (x, y)
//   in this frame and β in this convention (the product y sin β is the same in both
//   frames, so WAMIT's phases carry over unchanged). A response is r(t) = Re{R exp(iωt)}
//   per metre of amplitude: R's phase is a lead over η at the body origin (WAMIT's e^{iωt}
//   convention; Nemoh and Capytaine use e^{−iωt}, i.e. the complex conjugate). Heave is
//   positive down here, so a hull riding long waves has heave RAO → −1 (WAMIT: +1).
//
// Headings outside the table. WAMIT ran 0..180° because the hull is symmetric about its
//   centre plane y = 0; the table holds β ∈ [−π, 0]. The response to the mirrored wave
//   (β → −β) is the mirror image. The reflection y → −y flips the y part of a force or
//   displacement, and the x and z parts of a moment or rotation (an axial vector also takes
//   the reflection's determinant −1): M = diag(1, −1, 1, −1, 1, −1) (kPortStarboardMirror),
//   F(ω, β) = M F(ω, −β) for β in (0, π); ±π are both the tabulated head seas. When it
//   reads wave data, the reader refuses added mass or damping that couples the symmetric
//   modes (1, 3, 5) with the antisymmetric ones (2, 4, 6): the mirror would be wrong for
//   such a hull.
//
// Interpolation. Linear in ω, linear in β, on real and imaginary parts separately (a
//   bilinear blend with real weights): well defined where a magnitude passes through zero
//   and its phase jumps, unlike magnitude/phase blending, at the cost of underestimating
//   the magnitude between points whose phases differ a lot. Outside the tabulated
//   frequencies the value at the nearest end is returned (clamped, not extrapolated; here
//   1.05 s … 163.88 s, i.e. 0.0383 … 5.98 rad/s): A(0) and A(∞) are kept separately for
//   callers that need the limits.
#pragma once

#include <array>
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace moorsim::vessel {

// The same aliases as vessel/rigid_body.h (a repeated alias declaration of the same type is
// allowed), so this header stands alone.
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using ComplexVec6 = Eigen::Matrix<std::complex<double>, 6, 1>;

/// Signs taking a WAMIT-frame 6-vector to the project's body frame (see the file comment).
inline constexpr std::array<double, 6> kWamitToProject = {1.0, -1.0, -1.0, 1.0, -1.0, -1.0};

/// Signs taking the response at heading −β to the response at +β for a hull symmetric
/// about y = 0 (see the file comment).
inline constexpr std::array<double, 6> kPortStarboardMirror = {1.0, -1.0, 1.0, -1.0, 1.0, -1.0};

/// The same physical wave direction: WAMIT's β (toward port positive) to the project's β
/// (toward starboard positive) and back, both in radians.
constexpr double ProjectHeadingFromWamit(double beta_wamit) { return -beta_wamit; }
constexpr double WamitHeadingFromProject(double beta) { return -beta; }

/// How to turn WAMIT's non-dimensional numbers into SI. g and ULEN must be those of the
/// WAMIT run (its .out file: "Gravity:", "Length scale:"); ρ is not in the WAMIT data.
struct WamitOptions {
  double water_density = 1025.0;  ///< ρ [kg/m³]
  double gravity = 9.81;          ///< g [m/s²]
  double length_scale = 1.0;      ///< ULEN [m]
};

/// Hydrodynamic data in SI and the project's body frame (file comment). Wave tables are
/// flat, index WaveIndex(frequency, heading); a table whose optional file was absent is
/// empty, and asking it for a value throws moorsim::Error.
struct HydroData {
  std::string source;  ///< the stem the data came from, for messages

  std::vector<double> frequencies;  ///< ω [rad/s], ascending, finite periods of the .1 only
  std::vector<double> headings;     ///< β [rad], project convention, ascending in [−π, 0]

  Mat6 added_mass_zero_frequency = Mat6::Zero();      ///< A(0) (PER = −1) [kg, kg·m, kg·m²]
  Mat6 added_mass_infinite_frequency = Mat6::Zero();  ///< A(∞) (PER = 0)
  std::vector<Mat6> added_mass;                       ///< A(ω) per frequency [kg, kg·m, kg·m²]
  std::vector<Mat6> damping;  ///< B(ω) per frequency [N·s/m, N·s, N·m·s/rad]

  /// Hydrostatic and gravitational restoring C [N/m, N/rad, N·m/m, N·m/rad], as WAMIT
  /// gives it (C44, C55 include the weight's moment: C44 = ρ g ∇ GM_T).
  Mat6 restoring = Mat6::Zero();

  /// Diffraction exciting force per metre of wave amplitude [N/m, N·m/m] (.3).
  std::vector<ComplexVec6> exciting_force;
  /// Motion RAOs per metre of wave amplitude [m/m, rad/m] (.4).
  std::vector<ComplexVec6> motion_rao;
  /// Mean drift force per square metre of wave amplitude [N/m², N·m/m²] (.9, pressure
  /// integration, β1 = β2 rows, modes 1…6: WAMIT's Re column, which is the magnitude with
  /// the sign of its 0°/±180° phase; the imaginary part is round-off and is dropped).
  std::vector<Vec6> mean_drift;

  double water_density = 0.0;  ///< ρ used to dimensionalise [kg/m³]
  double gravity = 0.0;        ///< g used to dimensionalise [m/s²]

  std::size_t WaveIndex(std::size_t frequency, std::size_t heading) const {
    return frequency * headings.size() + heading;
  }

  /// A(ω) and B(ω), linear in ω, clamped to the tabulated range.
  Mat6 AddedMass(double omega) const;
  Mat6 Damping(double omega) const;

  /// Exciting force, RAO and mean drift at any (ω [rad/s], β [rad]): bilinear on Re and Im,
  /// ω clamped, β wrapped to (−π, π] and mirrored into the table (file comment). Throw
  /// moorsim::Error for non-finite arguments or a table that was not read.
  ComplexVec6 Exciting(double omega, double beta) const;
  ComplexVec6 Rao(double omega, double beta) const;
  Vec6 Drift(double omega, double beta) const;
};

/// The files ReadWamit reads beside its stem (what a run depends on of the vessel's data).
inline constexpr std::array<const char*, 5> kWamitExtensions = {".1", ".hst", ".3", ".4", ".9"};

/// Reads stem + ".1" and ".hst" (required) and ".3", ".4", ".9" (optional; a missing one
/// leaves its table empty). Wave files must hold the finite periods of the .1 and,
/// between them, the same headings, which must run 0°…180° (WAMIT convention); every
/// (period, heading) needs the same set of modes (a mode absent from a whole file is zero).
/// Throws moorsim::InputError naming file:line and the offending text for a missing
/// required file, a malformed or duplicate row, a truncated table or data of a hull that
/// is not port/starboard symmetric. Takes about 12 ms for the seed FPSO (2.3 MB, release build).
HydroData ReadWamit(const std::string& stem, const WamitOptions& options = {});

}  // namespace moorsim::vessel
