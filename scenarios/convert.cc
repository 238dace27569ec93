#include "scenarios/convert.h"

namespace moorsim::scenarios {

mooring_fem::MooringParameters ToMooringParameters(const MooringSpec& spec) {
  mooring_fem::MooringParameters p;
  p.water = spec.water;
  p.seabed = spec.seabed;
  p.current = spec.current;
  p.line_types.assign(spec.line_types.begin(), spec.line_types.end());
  p.lines.assign(spec.lines.begin(), spec.lines.end());
  return p;
}

}  // namespace moorsim::scenarios
