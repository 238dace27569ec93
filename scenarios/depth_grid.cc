#include "scenarios/depth_grid.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <vector>

#include "core/error.h"
#include "core/format.h"
#include "core/types.h"
#include "mooring_fem/environment.h"
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

// Calls body(line, first, number, where) for each line of `in` that is not blank or a
// '#' comment: the line without its '\r', the column of its first character, its 1-based
// number and "<path>:<number>: " for messages.
template <class Body>
void ForEachDataLine(std::istream& in, const std::string& path, Body&& body) {
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    body(line, first, number, path + ":" + std::to_string(number) + ": ");
  }
}

}  // namespace

mooring_fem::DepthGrid ReadDepthGrid(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the depth grid");
  mooring_fem::DepthGrid grid;
  grid.source = path;
  std::vector<int> row_lines;  // the line of each x row
  int header_line = 0;
  ForEachDataLine(
      in, path, [&](const std::string& line, std::size_t, int number, const std::string& where) {
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
            throw InputError(where +
                             "the first row must be a label and at least two y coordinates");
          }
          return;
        }
        if (fields.size() != grid.y.size() + 1) {
          throw InputError(where + std::to_string(fields.size() == 0 ? 0 : fields.size() - 1) +
                           " depths for " + std::to_string(grid.y.size()) +
                           " y coordinates (a row is x and one depth per y)");
        }
        const double x = Value(fields[0], where);
        if (!std::isfinite(x)) throw InputError(where + "the row has no x coordinate");
        grid.x.push_back(x);
        for (std::size_t k = 1; k < fields.size(); ++k)
          grid.depth.push_back(Value(fields[k], where));
        row_lines.push_back(number);
        if (grid.depth.size() > kMaxPoints) throw InputError(where + "more than 1e7 grid points");
      });
  if (header_line == 0) throw InputError(path + ": no grid (the file has no rows)");
  int row = -1;
  if (const std::string problem = mooring_fem::DepthGridProblem(grid, &row); !problem.empty()) {
    const int at = row >= 0 ? row_lines[static_cast<std::size_t>(row)] : header_line;
    throw InputError(path + ":" + std::to_string(at) + ": " + problem);
  }
  return grid;
}

mooring_fem::CurrentTable ReadCurrentTable(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the current table");
  mooring_fem::CurrentTable table;
  table.source = path;
  std::vector<double>* axes[] = {&table.x, &table.y, &table.z, &table.t};
  const char* labels[] = {"x:", "y:", "depth:", "time:"};
  int axis_count = 0;
  std::vector<int> row_at;  // the file line that gave each grid point (0: none yet)
  std::size_t rows = 0;
  ForEachDataLine(
      in, path,
      [&](const std::string& line, std::size_t first, int number, const std::string& where) {
        if (axis_count < 4) {
          // The axes first, in order, each labelled: "x: -50 0 50".
          const std::string label = labels[axis_count];
          if (line.compare(first, label.size(), label) != 0) {
            throw InputError(
                where + "expected the " + label +
                " axis (the four axes x:, y:, depth:, time: come first, in this order)");
          }
          const std::vector<std::string> fields = Fields(line.substr(first + label.size()));
          std::vector<double>& axis = *axes[axis_count];
          for (std::size_t k = 0; k < fields.size(); ++k) {
            const double value = Value(fields[k], where);
            if (!std::isfinite(value) || (!axis.empty() && !(value > axis.back()))) {
              throw InputError(where + "the " + std::string(labels[axis_count]) +
                               " axis must be numbers, strictly increasing");
            }
            axis.push_back(value);
          }
          if (axis.empty()) throw InputError(where + "the axis has no values");
          if (++axis_count == 4) {
            std::size_t points = 1;
            for (const std::vector<double>* a : axes) points *= a->size();
            if (points > kMaxPoints) throw InputError(where + "more than 1e7 grid points");
            table.velocity.assign(points, Vec3::Zero());
            row_at.assign(points, 0);
          }
          return;
        }
        // A grid point: x y depth time u_north u_east u_down.
        const std::vector<std::string> fields = Fields(line);
        if (fields.size() != 7) {
          throw InputError(where + std::to_string(fields.size()) +
                           " fields; a row is x, y, depth, time and the velocity north, east, down "
                           "[m/s]");
        }
        std::size_t index = 0;
        for (int a = 0; a < 4; ++a) {
          const double value = Value(fields[a], where);
          const std::vector<double>& axis = *axes[a];
          const auto it =
              std::lower_bound(axis.begin(), axis.end(), value - 1e-9 * (1.0 + std::abs(value)));
          if (it == axis.end() || std::abs(*it - value) > 1e-9 * (1.0 + std::abs(value))) {
            throw InputError(where + std::string(labels[a]) + " " + fields[a] +
                             " is not on the table's " + labels[a] + " axis");
          }
          index = index * axis.size() + static_cast<std::size_t>(it - axis.begin());
        }
        if (row_at[index] != 0) {
          throw InputError(where + "the point is given twice (also on line " +
                           std::to_string(row_at[index]) + ")");
        }
        row_at[index] = number;
        Vec3& v = table.velocity[index];
        for (int m = 0; m < 3; ++m) {
          v(m) = Value(fields[4 + m], where);
          if (!std::isfinite(v(m))) throw InputError(where + "a velocity component is empty");
        }
        if (const std::string problem = mooring_fem::CurrentSpeedProblem(v); !problem.empty()) {
          throw InputError(where + problem);
        }
        ++rows;
      });
  if (axis_count < 4) {
    throw InputError(path + ": the " + std::string(labels[axis_count]) + " axis is missing");
  }
  if (rows != table.velocity.size()) {
    const std::size_t missing =
        static_cast<std::size_t>(std::find(row_at.begin(), row_at.end(), 0) - row_at.begin());
    std::size_t rest = missing;
    double at[4];
    for (int a = 3; a >= 0; --a) {
      at[a] = (*axes[a])[rest % axes[a]->size()];
      rest /= axes[a]->size();
    }
    throw InputError(path + ": " + std::to_string(rows) + " rows for a grid of " +
                     std::to_string(table.velocity.size()) + " points; none for x " +
                     FormatNumber(at[0]) + ", y " + FormatNumber(at[1]) + ", depth " +
                     FormatNumber(at[2]) + ", time " + FormatNumber(at[3]));
  }
  mooring_fem::CheckCurrentTable(table);
  return table;
}

}  // namespace moorsim::scenarios
