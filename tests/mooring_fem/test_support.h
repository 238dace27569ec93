// Shared set-up for the mooring physics tests: the seed scenario from the library (so the
// tests check exactly what users run) at a chosen number of segments, converted to the
// FEM's parameter types as the CLI converts it (scenarios/convert.h).
#pragma once

#include <string>
#include <vector>

#include "mooring_fem/catenary.h"
#include "mooring_fem/line_simulation.h"
#include "mooring_fem/mooring_system.h"
#include "mooring_fem/parameters.h"
#include "scenarios/convert.h"
#include "scenarios/load.h"

namespace moorsim::mooring_fem::testing {

/// What the FEM takes of a scenario.
struct SeedCase {
  MooringParameters mooring;
  SolverSettings solver;
};

inline SeedCase SeedScenario(int segments) {
  const scenarios::Scenario s = scenarios::LoadScenario(std::string(MOORSIM_SOURCE_DIR) +
                                                        "/scenarios/library/seed_tapm.yaml");
  SeedCase seed{scenarios::ToMooringParameters(s.mooring), s.solver};
  for (auto& line : seed.mooring.lines) line.sections.front().segments = segments;
  return seed;
}

/// The issue's turret motion: surge 5 m / 100 s plus 2 m / 10 s.
inline HarmonicMotion IssueSurge() {
  HarmonicMotion motion;
  motion.components = {{5.0, 100.0}, {2.0, 10.0}};
  return motion;
}

/// Fairlead kinematics of every line for the vessel at rest at `pose`.
inline std::vector<PointKinematics> FairleadsAt(const MooringSystem& mooring,
                                                const PlanarPose& pose) {
  std::vector<PointKinematics> fairleads(mooring.num_lines());
  for (int i = 0; i < mooring.num_lines(); ++i) {
    fairleads[i].position = FairleadPosition(pose, mooring.line(i).fairlead_body);
  }
  return fairleads;
}

inline std::vector<Vec3> Positions(const std::vector<PointKinematics>& fairleads) {
  std::vector<Vec3> p;
  for (const auto& f : fairleads) p.push_back(f.position);
  return p;
}

/// The FEM settled to rest at `pose`: catenary placement, then Newton.
inline std::vector<double> StaticState(MooringSystem& mooring, const PlanarPose& pose) {
  const std::vector<Vec3> p = Positions(FairleadsAt(mooring, pose));
  std::vector<double> x(mooring.StateSize());
  mooring.CatenaryState(p, x.data());
  mooring.SettleStatic(p, x.data());
  return x;
}

inline CatenaryLineProperties CatenaryProperties(const LineProperties& lp) {
  const SectionProperties& sp = lp.sections.front();
  return {sp.length, sp.weight_per_length, sp.axial_stiffness};
}

}  // namespace moorsim::mooring_fem::testing
