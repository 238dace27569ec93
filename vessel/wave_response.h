// The hull's response to a realised irregular sea, from its WAMIT data: the first-order
// wave-frequency motion (RAOs) and the second-order slowly-varying drift load (Newman's
// approximation), cheap enough to evaluate inside the coupled ODE right-hand side.
//
// Frames and phases are those of vessel/hydro_data.h and vessel/waves.h, unchanged:
//   - The sea (WaveRealisation) is a sum of components i with frequency ω_i [rad/s],
//     amplitude a_i [m], phase φ_i [rad] and travel-to compass direction θ_i [rad] (from
//     north toward east). Its elevation (positive up) at the Earth position (x, y) is
//     η = Σ a_i cos(χ_i), with the component's phase at that point
//       χ_i(t, x, y) = ω_i t − k_i (x cos θ_i + y sin θ_i) + φ_i,   k_i = ω_i² / g.
//   - With the hull's body origin at (x, y) and heading ψ (NED, Fossen's η = [x y z φ θ ψ]),
//     component i meets the hull at the relative heading β_i = θ_i − ψ, in hydro_data.h's
//     convention (travel-to, from body +x toward +y = starboard; ±π head seas).
//   - An RAO is a lead over the elevation at the body origin (WAMIT's e^{iωt}): a
//     unit wave Re{e^{iχ}} gives the response Re{RAO e^{iχ}}. Heave is positive down, so
//     in long waves RAO₃ → −1 and heave → −η.
#pragma once

#include <cstddef>
#include <numbers>
#include <vector>

#include "vessel/hydro_data.h"
#include "vessel/waves.h"

namespace moorsim::vessel {

struct WaveResponseOptions {
  /// Spacing of the relative-heading grid the RAOs and drift coefficients are tabulated on
  /// [rad], in [0.1°, 45°]. The grid covers a full turn from β = −π with
  /// n = ceil(2π / step) equal cells, so the step used is 2π / n (2° exactly for the
  /// default). When the step divides the spacing of HydroData's headings (10° for the seed
  /// FPSO), every WAMIT heading is a grid node and the grid's linear interpolation
  /// reproduces HydroData's own (linear in β) to round-off; otherwise the error is at most
  /// step / 4 times the largest change of slope of the data between headings. One more
  /// difference either way: HydroData mirrors the tabulated half, so its sway, roll and yaw
  /// jump from v to −v across β = 0 and ±π when WAMIT's values there are not exactly zero
  /// (they are round-off: ~1e-9 of the beam-sea RAO, ~1e-6 of the beam-sea drift); the grid
  /// blends through that jump within one cell.
  double heading_step = 2.0 * std::numbers::pi / 180.0;
  /// Apply drift in all six modes. Default false: surge, sway and yaw only (heave, roll and
  /// pitch are set to zero), because Newman's approximation replaces the difference-
  /// frequency QTF by its diagonal, which is only sound where the QTF varies slowly over the
  /// difference frequencies that excite the mode (Newman 1974; Faltinsen 1990, ch. 5). That
  /// holds for the horizontal modes, which have no hydrostatic stiffness and whose moored
  /// natural periods (typically 100 s or more) lie far below the wave band. Heave, roll and
  /// pitch of the seed FPSO resonate at 10.4, 13.5 and 10.1 s, where the off-diagonal QTF is
  /// not its diagonal, and their mean drift is small against the hydrostatic stiffness:
  /// in the seed sea state 2 mm of heave and 0.001° of pitch (first-order standard
  /// deviations 2-15 cm and 0.02-0.08°). Roll is the exception worth the option: 0.02° of
  /// mean heel in beam seas against 0.09° first-order, and slow-drift roll is a known FPSO
  /// concern; the option applies Newman's form to it regardless.
  bool drift_all_modes = false;
  /// Acceleration of gravity g [m/s²] in the dispersion relation k = ω² / g. Must be the
  /// realisation's (WaveRealisationOptions::gravity, which WaveRealisation does not expose),
  /// or the phases at the hull drift away from WaveRealisation::Elevation at (x, y) ≠ 0.
  double gravity = 9.81;
};

/// First-order motion and slowly-varying drift load of the hull in a realised sea.
///
/// Motion (Faltinsen 1990, ch. 2-3; Fossen 2011, ch. 8: wave-frequency motion from motion
/// RAOs, superposed on the low-frequency pose):
///
///   ξ(t) = Σ_i Re{ RAO(ω_i, β_i) a_i e^{iχ_i} },   ξ̇ = Σ_i Re{ i ω_i RAO(ω_i, β_i) a_i e^{iχ_i} }
///
/// with χ_i evaluated at the low-frequency position (x, y) of the body origin (file
/// comment), in body axes: surge, sway, heave [m] and roll, pitch, yaw [rad] (project body
/// frame, heave positive down). ξ̇ is ∂ξ/∂t at fixed (x, y, ψ): the encounter-frequency
/// shift k_i · v of a moving hull (a few % at 1 m/s against wave celerities of 3-20 m/s) and
/// the rate of the relative heading are left out.
///
/// Drift (Newman 1974, "Second-order, slowly-varying forces on vessels in irregular
/// waves", Int. Symp. Dynamics of Marine Vehicles and Structures in Waves, London;
/// Faltinsen 1990, ch. 5). With D_j(ω, β) the mean drift coefficient of mode j
/// [N/m², N·m/m²] (HydroData::Drift), per mode j the components are split by the sign of
/// D_ij = D_j(ω_i, β_i):
///
///   z₊ = Σ_{D_ij > 0} a_i √D_ij e^{iχ_i},   z₋ = Σ_{D_ij < 0} a_i √(−D_ij) e^{iχ_i}
///   F_j = |z₊|² − |z₋|²
///
/// This is the difference-frequency part of Newman's 2 (Σ a_i √D_ij cos χ_i)² (which is
/// |z|² + Re{z²}; the Re{z²} part oscillates at sums of wave frequencies, which the
/// approximation does not model), and its time average is exactly the mean drift
/// Σ_i a_i² D_ij = Σ_i 2 S(ω_i) Δω D_j(ω_i, β_i). F is in body axes; by default only
/// surge, sway and yaw (WaveResponseOptions::drift_all_modes).
///
/// Precomputation: per component, RAO and D on a grid of relative headings over a full
/// turn (HydroData's bilinear interpolation is done once, at construction); at run time
/// β_i is located on the grid and the two neighbouring rows are blended linearly, so the
/// heading may change freely between calls. Memory: N (n + 1) 16 doubles (18 with all drift
/// modes), 4.6 MB for 200 components at 2°; construction takes about 5 ms.
///
/// Evaluation allocates nothing and throws nothing: a non-finite t, x, y or ψ gives NaN in
/// every output, for the ODE adapter to reject the step. Cost per component: one sincos
/// (internal::SinCos, core/sincos.h), 6 complex and 4 or 6 real blends, and as many square roots.
/// For 200 components (release build, SSE2, thread CPU time on a shared 2.6 GHz AMD EPYC VM):
/// Evaluate 5.5 µs, Motion alone 3.1 µs, DriftLoad alone 4.3 µs, MeanDrift 1.1 µs; with
/// std::sin and std::cos instead of SinCos, Evaluate takes 7.5 µs.
class WaveResponse {
 public:
  /// Throws moorsim::InputError naming the field and value for a heading_step outside
  /// [0.1°, 45°] or a non-finite or non-positive gravity, and naming the missing file when
  /// `hydro` holds no motion RAOs (.4) or no mean drift (.9). Keeps no reference to
  /// `hydro` or `waves`.
  WaveResponse(const HydroData& hydro, const WaveRealisation& waves,
               const WaveResponseOptions& options = {});

  /// Everything in one pass over the components (one sincos each): ξ and ξ̇ of the body
  /// origin and the drift load, at time t [s], low-frequency position (x north, y east) [m]
  /// and heading ψ [rad] (any real value; only ψ mod 2π matters). Any output pointer may be
  /// null; the work for the outputs not asked for is skipped.
  void Evaluate(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot,
                Vec6* drift) const;

  /// Wave-frequency motion ξ [m, rad] and its time derivative ξ̇ [m/s, rad/s] (class
  /// comment); either pointer may be null.
  void Motion(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot) const;

  /// Slowly-varying drift force and moment [N, N·m] in body axes (class comment).
  Vec6 DriftLoad(double t, double x, double y, double psi) const;

  /// Time average of DriftLoad at heading ψ [rad] (any fixed position): Σ_i a_i² D(ω_i, β_i)
  /// [N, N·m], with the same modes set to zero.
  Vec6 MeanDrift(double psi) const;

  std::size_t components() const { return omega_.size(); }
  /// Cells of the heading grid over a full turn, and their width [rad].
  int heading_cells() const { return heading_cells_; }
  double heading_step() const;
  /// The body modes (0-based: 0 surge … 5 yaw) DriftLoad computes; the others are zero.
  const std::vector<int>& drift_modes() const { return drift_modes_; }

 private:
  // The one pass behind Evaluate: motion if kMotion, drift if kDriftColumns (= drift_columns_)
  // is not 0.
  template <bool kMotion, int kDriftColumns>
  void Accumulate(double t, double x, double y, double psi, Vec6* xi, Vec6* xi_dot,
                  Vec6* drift) const;

  // Components, structure of arrays: ω_i, a_i, φ_i, k_i (cos θ_i, sin θ_i), and θ_i's
  // position on the heading grid in turns, (θ_i + π) / 2π.
  std::vector<double> omega_;
  std::vector<double> amplitude_;
  std::vector<double> phase_;
  std::vector<double> wave_number_north_;
  std::vector<double> wave_number_east_;
  std::vector<double> direction_turns_;

  int heading_cells_ = 0;  // n; the grid has n + 1 nodes, the last a copy of the first
  std::vector<int> drift_modes_;
  int drift_columns_ = 0;  // D per drift mode, padded to an even count (3 modes: 4)
  int row_size_ = 0;       // doubles per grid node: Re RAO (6), Im RAO (6), D columns
  // Row (component i, node g) starts at ((n + 1) i + g) row_size_; node g is at
  // β = −π + 2π g / n.
  std::vector<double> table_;
};

}  // namespace moorsim::vessel
