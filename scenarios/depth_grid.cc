#include "scenarios/depth_grid.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/types.h"
#include "mooring_fem/seabed.h"

namespace moorsim::scenarios {

namespace {

constexpr std::size_t kMaxPoints = 10'000'000;

// The fields of a row: split at commas; white space also separates where there is no
// comma. An empty field between two commas is kept (a hole).
std::vector<std::string> Fields(const std::string& line) {
  std::vector<std::string> out;
  const bool commas = line.find(',') != std::string::npos;
  std::string field;
  bool in_field = false;
  for (char ch : line) {
    const bool space = ch == ' ' || ch == '\t';
    if (commas ? ch == ',' : space) {
      if (commas || in_field) out.push_back(field);
      field.clear();
      in_field = false;
    } else if (!space) {
      field += ch;
      in_field = true;
    }
  }
  if (commas || in_field) out.push_back(field);
  return out;
}

// A field as a number; an empty one is a hole (NaN). Throws for text.
double Value(const std::string& field, const std::string& where) {
  if (field.empty()) return kNaN;
  double value = 0.0;
  const char* end = field.data() + field.size();
  const auto [ptr, ec] = std::from_chars(field.data(), end, value);
  if (ec != std::errc() || ptr != end) throw InputError(where + "'" + field + "' is not a number");
  return value;
}

}  // namespace

mooring_fem::DepthGrid ReadDepthGrid(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the depth grid");
  mooring_fem::DepthGrid grid;
  grid.source = path;
  std::vector<int> row_lines;  // the line of each x row
  int header_line = 0;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    const std::vector<std::string> fields = Fields(line);
    if (header_line == 0) {
      header_line = number;
      for (std::size_t k = 1; k < fields.size(); ++k) {
        const double y = Value(fields[k], where);
        if (!std::isfinite(y))
          throw InputError(where + "y value " + std::to_string(k) + " is empty");
        grid.y.push_back(y);
      }
      if (grid.y.size() < 2) {
        throw InputError(where + "the first row must be a label and at least two y coordinates");
      }
      continue;
    }
    if (fields.size() != grid.y.size() + 1) {
      throw InputError(where + std::to_string(fields.size() == 0 ? 0 : fields.size() - 1) +
                       " depths for " + std::to_string(grid.y.size()) +
                       " y coordinates (a row is x and one depth per y)");
    }
    const double x = Value(fields[0], where);
    if (!std::isfinite(x)) throw InputError(where + "the row has no x coordinate");
    grid.x.push_back(x);
    for (std::size_t k = 1; k < fields.size(); ++k) grid.depth.push_back(Value(fields[k], where));
    row_lines.push_back(number);
    if (grid.depth.size() > kMaxPoints) throw InputError(where + "more than 1e7 grid points");
  }
  if (header_line == 0) throw InputError(path + ": no grid (the file has no rows)");
  int row = -1;
  if (const std::string problem = mooring_fem::DepthGridProblem(grid, &row); !problem.empty()) {
    const int at = row >= 0 ? row_lines[static_cast<std::size_t>(row)] : header_line;
    throw InputError(path + ":" + std::to_string(at) + ": " + problem);
  }
  return grid;
}

}  // namespace moorsim::scenarios
