// Fatigue of mooring components: T-N (or S-N) curves, N = a_D S^-m cycles to failure at
// range S, and Miner's sum of the damage of a counted load history.
//
// Two ways of measuring the range, as the standards do:
// * a nominal stress range [MPa]: the tension range over the component's nominal area.
//   DNV-OS-E301 (DNV 2010, Ch.2 Sec.2 D): studless chain a_D = 6.0e10, m = 3.0; studlink
//   chain 1.2e11, 3.0 (area two bars, 2 pi d^2 / 4); six-strand rope 3.4e14, 4.0; spiral
//   rope 1.7e17, 4.8 (area pi d^2 / 4 of the nominal diameter).
// * a normalised range R = tension range / reference breaking strength, N R^M = K: the
//   form of API RP 2SK and API RP 2SM, whose polyester curve is M = 5.2, K = 25000. A
//   mean-load term, log10 K = log10 K0 - c L_m with L_m the cycle's mean tension over
//   the breaking strength (API RP 2SK's form for steel wire ropes), corrects K for the
//   mean load where the curve carries one.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/rainflow.h"
#include "core/choice.h"

namespace moorsim::analysis {

/// How a curve measures the range.
enum class TnRange {
  kStress,      ///< S = tension range / nominal area, in MPa
  kNormalised,  ///< R = tension range / breaking strength
};
inline constexpr std::string_view kTnRangeNames[] = {"stress", "normalised"};
constexpr ChoiceInfo ChoicesOf(TnRange) { return {"T-N range", kTnRangeNames}; }

/// The standards' curves (TnCurveOf()).
enum class TnPreset { kStudlessChain, kStudlinkChain, kSixStrandRope, kSpiralRope, kPolyester };
inline constexpr std::string_view kTnPresetNames[] = {
    "studless_chain", "studlink_chain", "six_strand_rope", "spiral_rope", "polyester"};
constexpr ChoiceInfo ChoicesOf(TnPreset) { return {"T-N curve", kTnPresetNames}; }

struct TnCurve {
  using Range = TnRange;
  Range range = Range::kStress;
  /// N = a S^-m: a_D for a stress curve (S in MPa), K for a normalised one.
  double a = 0.0;
  double m = 3.0;
  /// The mean-load term c of log10 a = log10 a0 - c L_m (L_m = mean tension / breaking
  /// strength); 0: none.
  double mean_load_slope = 0.0;

  /// Cycles to failure at a tension range `tension_range` [N] with mean `mean` [N], for a
  /// component of nominal area `area` [m^2] (stress curves) and breaking strength
  /// `breaking` [N] (normalised curves and the mean-load term). Infinite for a zero range.
  double CyclesToFailure(double tension_range, double mean, double area, double breaking) const;
};

/// A standard's curve.
TnCurve TnCurveOf(TnPreset preset);

/// The nominal area [m^2] a stress curve divides by, for a component of nominal diameter
/// `diameter` [m]: two bars for a chain, one section otherwise.
double NominalArea(TnPreset preset, double diameter);

/// What a T-N curve needs of the component.
struct FatigueComponent {
  TnCurve curve;
  double area = 0.0;      ///< [m^2], for stress curves
  double breaking = 0.0;  ///< minimum breaking load [N], for normalised curves and L_m
};

/// Miner's damage of counted cycles (ranges and means in N): sum of count / N(range, mean).
double MinerDamage(std::span<const RainflowCycle> cycles, const FatigueComponent& component);

/// The damage of a tension history [N] (rainflow-counted).
double MinerDamage(std::span<const double> tension, const FatigueComponent& component);

}  // namespace moorsim::analysis
