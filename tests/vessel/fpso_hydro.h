// The seed FPSO's WAMIT data (data/fpso_wamit), read once per test executable.
#pragma once

#include <string>

#include "vessel/hydro_data.h"

namespace moorsim::vessel::test_data {

inline const HydroData& Fpso() {
  static const HydroData data =
      ReadWamit(std::string(MOORSIM_SOURCE_DIR) + "/data/fpso_wamit/fpso");
  return data;
}

}  // namespace moorsim::vessel::test_data
