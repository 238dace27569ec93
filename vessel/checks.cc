#include "vessel/checks.h"

#include "core/error.h"
#include "core/format.h"

namespace moorsim::vessel::internal {

void ThrowBadValue(std::string_view field, double value, std::string_view unit,
                   std::string_view constraint) {
  std::string message = std::string(field) + ": " + FormatNumber(value);
  if (!unit.empty()) message += " " + std::string(unit);
  message += " " + std::string(constraint);
  throw InputError(message);
}

}  // namespace moorsim::vessel::internal
