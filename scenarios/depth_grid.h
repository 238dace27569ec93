// Reading the gridded files a scenario names: a seabed depth grid (mooring.seabed.grid)
// and a current table (environment.current.file).
//
// A depth grid's format: '#' lines are comments and blank lines are skipped; fields are separated
// by commas or white space. The first row is a label (any text, e.g. "x\y") followed by the east
// coordinates y [m]; every following row is a north coordinate x [m] followed by the depths [m,
// positive down] at each y. Both axes increase, at least two points each:
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

// A current table's format: '#' lines are comments and blank lines are skipped; fields are
// separated by commas or white space. First the four axes, each a label and its values,
// strictly increasing: "x:" north [m], "y:" east [m], "depth:" [m, down], "time:" [s]. Then
// one row per grid point, in any order: x, y, depth, time (values of the axes) and the
// water's velocity north, east and down [m/s]. Every point once:
//
//   x: 0
//   y: 0
//   depth: 0 50
//   time: 0 600
//   0, 0,  0,   0,  0.5, 0.0, 0.0
//   0, 0, 50,   0,  0.2, 0.0, 0.0
//   0, 0,  0, 600,  0.8, 0.1, 0.0
//   0, 0, 50, 600,  0.3, 0.0, 0.0

/// Reads the table in `path`. Throws InputError "<path>: ..." if it cannot be read, misses
/// an axis or grid points (naming the first missing), and "<path>:<line>: ..." naming what
/// is wrong on that line: an axis out of order or not increasing, a row of other than seven
/// fields, a coordinate off its axis, a point given twice, a field that is not a number, a
/// current faster than mooring_fem::kMaxCurrentSpeed.
mooring_fem::CurrentTable ReadCurrentTable(const std::string& path);

}  // namespace moorsim::scenarios
