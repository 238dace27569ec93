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

/// The seed chain (Ren & Skjetne 2016) as a line type named "chain", with seabed friction.
inline LineType ChainType() {
  LineType t = SeedChain();
  t.name = "chain";
  return t;
}

/// A polyester rope of 160 mm named "polyester": 26 kg/m dry, 53 N/m in sea water.
inline LineType PolyesterType() {
  LineType t = ChainType();
  t.name = "polyester";
  t.diameter = 0.16;
  t.mass_per_length = 26.0;
  t.axial_stiffness = 1.2e8;
  t.drag_normal = 1.2;
  t.drag_tangential = 0.008;
  t.added_mass_normal = 1.0;
  t.friction_axial = 0.2;
  t.friction_lateral = 0.3;
  return t;
}

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
inline PrescribedMotion IssueSurge() {
  PrescribedMotion motion;
  motion.components[PrescribedMotion::kSurge] = {{5.0, 100.0}, {2.0, 10.0}};
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
