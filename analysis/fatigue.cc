#include "analysis/fatigue.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace moorsim::analysis {
namespace {

// In the order of TnPreset.
constexpr std::array<TnCurve, 5> kPresets = {{
    {TnRange::kStress, 6.0e10, 3.0, 0.0},
    {TnRange::kStress, 1.2e11, 3.0, 0.0},
    {TnRange::kStress, 3.4e14, 4.0, 0.0},
    {TnRange::kStress, 1.7e17, 4.8, 0.0},
    {TnRange::kNormalised, 25000.0, 5.2, 0.0},
}};

}  // namespace

double TnCurve::CyclesToFailure(double tension_range, double mean, double area,
                                double breaking) const {
  if (!(tension_range > 0.0)) return std::numeric_limits<double>::infinity();
  const double s = range == Range::kStress ? tension_range / area / 1.0e6  // MPa
                                           : tension_range / breaking;
  double a_corrected = a;
  if (mean_load_slope != 0.0) a_corrected *= std::pow(10.0, -mean_load_slope * mean / breaking);
  return a_corrected * std::pow(s, -m);
}

TnCurve TnCurveOf(TnPreset preset) { return kPresets[static_cast<std::size_t>(preset)]; }

double NominalArea(TnPreset preset, double diameter) {
  const double section = std::numbers::pi * diameter * diameter / 4.0;
  const bool chain = preset == TnPreset::kStudlessChain || preset == TnPreset::kStudlinkChain;
  return chain ? 2.0 * section : section;
}

double MinerDamage(std::span<const RainflowCycle> cycles, const FatigueComponent& component) {
  double damage = 0.0;
  for (const RainflowCycle& c : cycles) {
    damage += c.count /
              component.curve.CyclesToFailure(c.range, c.mean, component.area, component.breaking);
  }
  return damage;
}

double MinerDamage(std::span<const double> tension, const FatigueComponent& component) {
  const std::vector<RainflowCycle> cycles = Rainflow(tension);
  return MinerDamage(cycles, component);
}

}  // namespace moorsim::analysis
