#include "analysis/design_tension.h"

#include <stdexcept>

namespace moorsim::analysis {

DesignCheck CheckLine(const LineExtreme& line, DesignStandard standard, DesignCondition condition,
                      int consequence_class) {
  if (!(line.mbl > 0.0)) throw std::invalid_argument("design check: no minimum breaking load");
  DesignCheck check;
  if (standard == DesignStandard::kApiRp2sk) {
    constexpr double kFactor[] = {1.67, 1.25, 1.05};  // intact, damaged, transient
    check.design_tension = line.mpm;
    check.required_factor = kFactor[static_cast<int>(condition)];
    check.allowed = line.mbl / check.required_factor;
  } else {
    if (consequence_class != 1 && consequence_class != 2) {
      throw std::invalid_argument("design check: DNV consequence class must be 1 or 2");
    }
    const bool uls = condition == DesignCondition::kIntact;
    const bool second = consequence_class == 2;
    const double gamma_mean = uls ? (second ? 1.40 : 1.10) : 1.00;
    const double gamma_dyn = uls ? (second ? 2.10 : 1.50) : (second ? 1.25 : 1.10);
    check.design_tension = gamma_mean * line.mean + gamma_dyn * (line.mpm - line.mean);
    check.allowed = 0.95 * line.mbl;
    check.required_factor = line.mbl / check.allowed;
  }
  check.safety_factor = line.mbl / check.design_tension;
  check.utilisation = check.design_tension / check.allowed;
  check.pass = check.utilisation <= 1.0;
  return check;
}

}  // namespace moorsim::analysis
