// Numbers in messages: one way to write a double wherever an error or a report quotes it.
// The shortest text that reads back as the same double names the value exactly, and a value
// the user typed as they typed it (9.81, 120, 0.1), with no digits lost or invented.
#pragma once

#include <string>

namespace moorsim {

/// The shortest text that reads back (std::strtod, std::stod) as exactly `value`:
/// std::to_chars without a precision, fixed or scientific, whichever is shorter ("9.81",
/// "120", "1e+09", "2.5e-05", "-0"); "nan", "inf" or "-inf" for a value that is not finite.
std::string FormatNumber(double value);

}  // namespace moorsim
