// Reading a seabed depth grid (mooring.seabed.grid) from a text file.
//
// Format: '#' lines are comments and blank lines are skipped; fields are separated by
// commas or white space. The first row is a label (any text, e.g. "x\y") followed by the
// east coordinates y [m]; every following row is a north coordinate x [m] followed by the
// depths [m, positive down] at each y. Both axes increase, at least two points each:
//
//   x\y,   -2000,    0, 2000
//   -2000,  1060, 1030, 1000
//    2000,  1040, 1010,  980
#pragma once

#include <string>

#include "mooring_fem/parameters.h"

namespace moorsim::scenarios {

/// Reads the grid in `path`. Throws InputError "<path>: ..." if it cannot be read or holds
/// no grid, and "<path>:<line>: ..." naming what is wrong on that line: a field that is
/// not a number, a row with the wrong number of depths, a hole (an empty field), an axis
/// that does not increase, a depth at or above the surface.
mooring_fem::DepthGrid ReadDepthGrid(const std::string& path);

}  // namespace moorsim::scenarios
