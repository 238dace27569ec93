// Number parsing for command-line flags: every failure is an InputError that names the
// flag and the text it was given.
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "tools/commands.h"

namespace moorsim::cli {

std::vector<double> ParseNumberList(const std::string& flag, const std::string& text) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || !std::isfinite(value)) {
      throw InputError(flag + ": '" + item + "' in '" + text + "' is not a finite number");
    }
    values.push_back(value);
  }
  if (values.empty()) throw InputError(flag + ": no numbers in '" + text + "'");
  return values;
}

double ParseNumber(const std::string& flag, const std::string& text) {
  const std::vector<double> values = ParseNumberList(flag, text);
  if (values.size() != 1) throw InputError(flag + ": '" + text + "' must be a single number");
  return values.front();
}

int ParseInteger(const std::string& flag, const std::string& text, int min, int max) {
  const double value = ParseNumber(flag, text);
  if (value != std::floor(value) || value < min || value > max) {
    throw InputError(flag + ": '" + text + "' must be a whole number in " + std::to_string(min) +
                     ".." + std::to_string(max));
  }
  return static_cast<int>(value);
}

std::string FormatNumber(double value) {
  std::ostringstream out;
  out.precision(17);
  for (int digits = 1; digits <= 17; ++digits) {
    std::ostringstream trial;
    trial.precision(digits);
    trial << value;
    if (std::stod(trial.str()) == value) return trial.str();
  }
  out << value;
  return out.str();
}

}  // namespace moorsim::cli
