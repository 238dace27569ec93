#include "analysis/fatigue.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace moorsim::analysis {
namespace {

// Sorted by name.
const std::array<TnCurve, 5> kPresets = {{
    {"polyester", TnCurve::Range::kNormalised, 25000.0, 5.2, 0.0},
    {"six_strand_rope", TnCurve::Range::kStress, 3.4e14, 4.0, 0.0},
    {"spiral_rope", TnCurve::Range::kStress, 1.7e17, 4.8, 0.0},
    {"studless_chain", TnCurve::Range::kStress, 6.0e10, 3.0, 0.0},
    {"studlink_chain", TnCurve::Range::kStress, 1.2e11, 3.0, 0.0},
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

const TnCurve* TnCurvePreset(std::string_view name) {
  for (const TnCurve& c : kPresets) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

std::vector<std::string_view> TnCurvePresetNames() {
  std::vector<std::string_view> names;
  for (const TnCurve& c : kPresets) names.push_back(c.name);
  return names;
}

double NominalArea(std::string_view curve_name, double diameter) {
  const double section = std::numbers::pi * diameter * diameter / 4.0;
  return curve_name.ends_with("_chain") ? 2.0 * section : section;
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
