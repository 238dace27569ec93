// Parameter checks shared by the vessel module's constructors: one InputError line naming
// the field, the value (with its unit) and the rule.
#pragma once

#include <string>
#include <string_view>

namespace moorsim::vessel::internal {

/// Throws InputError "<field>: <value>[ <unit>] <constraint>".
[[noreturn]] void ThrowBadValue(std::string_view field, double value, std::string_view unit,
                                std::string_view constraint);

}  // namespace moorsim::vessel::internal
