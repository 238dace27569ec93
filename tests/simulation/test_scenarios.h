// Scenarios for the coupled-simulation tests: the seed mooring of
// scenarios/library/seed_tapm.yaml with sections appended.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "scenarios/load.h"

namespace moorsim::simulation::testing {

inline std::string SeedMooringText() {
  std::ifstream file(MOORSIM_SOURCE_DIR "/scenarios/library/seed_tapm.yaml");
  std::ostringstream text;
  text << file.rdbuf();
  // The mooring and solver only: cut the coupled-simulation sections.
  const std::string all = text.str();
  return all.substr(0, all.find("# --- coupled simulation"));
}

/// The seed mooring plus the seed FPSO (no controller, calm water unless `extra` says
/// otherwise). `extra` is YAML appended at the top level.
inline scenarios::Scenario SeedVesselScenario(const std::string& extra = "",
                                              const std::string& vessel_extra = "") {
  std::string text = SeedMooringText();
  text += "\nvessel:\n  hydrodynamics: ../../data/fpso_wamit/fpso\n" + vessel_extra + "\n" + extra;
  return scenarios::ParseScenario(text, MOORSIM_SOURCE_DIR "/scenarios/library/test.yaml");
}

}  // namespace moorsim::simulation::testing
