#include "vessel/checks.h"

#include <sstream>

#include "core/error.h"

namespace moorsim::vessel::internal {

std::string FormatValue(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

void ThrowBadValue(std::string_view field, double value, std::string_view unit,
                   std::string_view constraint) {
  std::string message = std::string(field) + ": " + FormatValue(value);
  if (!unit.empty()) message += " " + std::string(unit);
  message += " " + std::string(constraint);
  throw InputError(message);
}

}  // namespace moorsim::vessel::internal
