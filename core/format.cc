#include "core/format.h"

#include <charconv>
#include <cmath>

namespace moorsim {

std::string FormatNumber(double value) {
  // to_chars writes a NaN's sign bit ("-nan"); a message has no use for it.
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0.0 ? "inf" : "-inf";
  char buffer[32];  // the longest shortest form, "-2.2250738585072014e-308", is 24
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

}  // namespace moorsim
