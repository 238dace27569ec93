#include "scenarios/convert.h"

#include <algorithm>
#include <cmath>

namespace moorsim::scenarios {

mooring_fem::MooringParameters ToMooringParameters(const MooringSpec& spec) {
  mooring_fem::MooringParameters p;
  p.water = spec.water;
  p.seabed = spec.seabed;
  p.current = spec.current;
  p.line_types.assign(spec.line_types.begin(), spec.line_types.end());
  p.lines.assign(spec.lines.begin(), spec.lines.end());
  p.points.assign(spec.points.begin(), spec.points.end());
  return p;
}

double TurretRadius(const Scenario& scenario) {
  if (!scenario.vessel) return 0.0;
  const TurretSpec& t = scenario.vessel->turret;
  if (t.radius) return *t.radius;
  double radius = 0.0;
  for (const LineSpec& line : scenario.mooring.lines) {
    if (line.upper_point >= 0) continue;  // not at the vessel
    radius =
        std::max(radius, std::hypot(line.fairlead_body.x() - t.x, line.fairlead_body.y() - t.y));
  }
  return radius;
}

}  // namespace moorsim::scenarios
