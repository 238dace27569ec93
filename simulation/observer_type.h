// Which observer each hypothesis of the detectors' bank runs (a scenario's
// detection.observer).
#pragma once

#include <string_view>

#include "core/choice.h"

namespace moorsim::simulation {

/// Which observer each hypothesis of the bank runs.
enum class ObserverType {
  kEkf,      ///< an EKF each, mixed by ObserverBankOptions::switch_rate
  kPassive,  ///< the TAPM thesis's passive observer, covariance from training runs
};

inline constexpr std::string_view kObserverTypeNames[] = {"ekf", "passive"};
constexpr ChoiceInfo ChoicesOf(ObserverType) { return {"observer", kObserverTypeNames}; }

}  // namespace moorsim::simulation
