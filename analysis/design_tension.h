// A line's design tension and its check against the line's strength, by the standards a
// mooring analyst signs against:
// * API RP 2SK (dynamic analysis): the design tension is the MPM; the safety factor
//   MBL / MPM must be at least 1.67 intact, 1.25 damaged (one line removed), 1.05 in the
//   transient after a line breaks.
// * DNV-OS-E301 (DNV 2010, Ch.2 Sec.2): the design tension is
//   gamma_mean T_mean + gamma_dyn T_dyn, T_dyn = MPM - T_mean, against the capacity
//   0.95 MBL; ULS (intact) gamma_mean 1.10 / gamma_dyn 1.50 in consequence class 1,
//   1.40 / 2.10 in class 2; ALS (damaged, and the transient) 1.00 / 1.10 in class 1,
//   1.00 / 1.25 in class 2.
// Both give a utilisation, design tension over what is allowed (at most 1 to pass).
#pragma once

#include <string_view>

#include "core/choice.h"

namespace moorsim::analysis {

enum class DesignStandard { kApiRp2sk, kDnvOsE301 };
inline constexpr std::string_view kDesignStandardNames[] = {"api_rp_2sk", "dnv_os_e301"};
constexpr ChoiceInfo ChoicesOf(DesignStandard) { return {"design standard", kDesignStandardNames}; }

enum class DesignCondition { kIntact, kDamaged, kTransient };
inline constexpr std::string_view kDesignConditionNames[] = {"intact", "damaged", "transient"};
constexpr ChoiceInfo ChoicesOf(DesignCondition) {
  return {"design condition", kDesignConditionNames};
}

/// What the check needs of one line in one condition [N].
struct LineExtreme {
  double mpm = 0.0;   ///< most probable maximum tension in the storm
  double mean = 0.0;  ///< mean tension (DNV's T_mean)
  double mbl = 0.0;   ///< minimum breaking load
};

struct DesignCheck {
  double design_tension = 0.0;   ///< [N]
  double allowed = 0.0;          ///< the largest design tension that passes [N]
  double safety_factor = 0.0;    ///< MBL / design tension
  double required_factor = 0.0;  ///< the safety factor that passes: MBL / allowed
  double utilisation = 0.0;      ///< design_tension / allowed
  bool pass = false;
};

/// Checks `line` in `condition` by `standard` (DNV: `consequence_class` 1 or 2). Throws
/// std::invalid_argument for a line without a breaking load or a class that is not 1 or 2.
DesignCheck CheckLine(const LineExtreme& line, DesignStandard standard, DesignCondition condition,
                      int consequence_class = 1);

}  // namespace moorsim::analysis
