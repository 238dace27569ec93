#include "simulation/pose_stream.h"

#include "core/types.h"
#include "simulation/output_layout.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "io/csv_table.h"
#include "io/hdf5_reader.h"

namespace moorsim::simulation {

namespace {

constexpr std::array<const char*, 7> kColumns = {
    "time", "north", "east", "heading", "thrust_surge", "thrust_sway", "thrust_yaw"};
constexpr std::array<const char*, 3> kPoseColumns = {"north", "east", "heading"};

std::string Trim(const std::string& text) {
  const std::size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const std::size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

std::string Shortest(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

void StreamChecks::Check(const detectors::Observation& o, const std::string& where) {
  const auto fail = [&](const char* column, const std::string& what) {
    throw InputError(where + ": column '" + column + "': " + what);
  };
  if (!std::isfinite(o.t)) fail("time", "not a finite number");
  if (!std::isnan(last_time_)) {
    if (!(o.t > last_time_)) {
      fail("time", Shortest(o.t) + " s is not after the previous row's " + Shortest(last_time_) +
                       " s (time must increase)");
    }
    if (o.t - last_time_ > max_gap_) {
      fail("time", "a gap of " + Shortest(o.t - last_time_) + " s after " + Shortest(last_time_) +
                       " s, longer than the maximum gap of " + Shortest(max_gap_) + " s");
    }
  } else {
    last_valid_.fill(o.t);  // a channel's gap counts from the stream's start
  }
  last_time_ = o.t;
  for (int i = 0; i < 3; ++i) {
    if (o.valid[i]) {
      if (!std::isfinite(o.pose(i))) fail(kPoseColumns[i], "not a finite number");
      last_valid_[i] = o.t;
    } else if (o.t - last_valid_[i] > max_gap_) {
      fail(kPoseColumns[i], "no value for " + Shortest(o.t - last_valid_[i]) + " s (since " +
                                Shortest(last_valid_[i]) + " s), longer than the maximum gap of " +
                                Shortest(max_gap_) + " s");
    }
  }
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(o.tau_command(i))) fail(kColumns[4 + i], "not a finite number");
  }
  if (o.tensions) {
    // NaN: that cell's reading withheld (the others count).
    for (Eigen::Index i = 0; i < o.tensions->size(); ++i) {
      if (std::isinf((*o.tensions)(i))) {
        const std::string column = "tension_" + std::to_string(i + 1);
        fail(column.c_str(), "not a finite number");
      }
    }
  }
}

CsvPoseStream::CsvPoseStream(std::string name, int lines, double max_gap)
    : name_(std::move(name)), lines_(lines), checks_(max_gap) {}

void CsvPoseStream::Header(const std::vector<std::string>& cells) {
  const std::string where = name_ + ":" + std::to_string(line_number_) + ": header: ";
  header_ = cells;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const std::string& name = cells[c];
    bool known = false;
    for (std::size_t k = 0; k < kColumns.size(); ++k) {
      if (name != kColumns[k]) continue;
      if (columns_[k] >= 0) throw InputError(where + "column '" + name + "' appears twice");
      columns_[k] = static_cast<int>(c);
      known = true;
    }
    if (name.rfind("tension_", 0) == 0) {
      char* end = nullptr;
      const long line = std::strtol(name.c_str() + 8, &end, 10);
      if (*end == '\0' && line >= 1 && line <= lines_) {
        if (tension_columns_.empty()) tension_columns_.assign(lines_, -1);
        if (tension_columns_[line - 1] >= 0) {
          throw InputError(where + "column '" + name + "' appears twice");
        }
        tension_columns_[line - 1] = static_cast<int>(c);
        known = true;
      }
    }
    if (!known) {
      throw InputError(where + "unknown column '" + name +
                       "' (known: time, north, east, heading, thrust_surge, thrust_sway, "
                       "thrust_yaw, tension_1 .. tension_" +
                       std::to_string(lines_) + ")");
    }
  }
  for (std::size_t k = 0; k < kColumns.size(); ++k) {
    if (columns_[k] < 0) {
      throw InputError(where + "column '" + kColumns[k] +
                       "' is missing (a header line naming "
                       "time, north, east, heading, thrust_surge, thrust_sway, thrust_yaw is "
                       "required)");
    }
  }
  for (int i = 0; i < static_cast<int>(tension_columns_.size()); ++i) {
    if (tension_columns_[i] < 0) {
      throw InputError(where + "column 'tension_" + std::to_string(i + 1) +
                       "' is missing (tension columns come for all " + std::to_string(lines_) +
                       " lines or none)");
    }
  }
  have_header_ = true;
}

void CsvPoseStream::Restart() {
  line_number_ = 0;
  header_may_repeat_ = have_header_;
}

bool CsvPoseStream::Take(const std::string& line, detectors::Observation* observation) {
  ++line_number_;
  const std::string trimmed =
      Trim(line_number_ == 1 ? std::string(output::WithoutByteOrderMark(line)) : line);
  if (trimmed.empty() || trimmed[0] == '#') return false;
  std::vector<std::string> cells =
      output::SplitCsvRecord(trimmed, name_ + ":" + std::to_string(line_number_));
  for (std::string& cell : cells) cell = Trim(cell);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (cells[c].find('\0') == std::string::npos) continue;
    throw InputError(name_ + ":" + std::to_string(line_number_) + ": " +
                     (have_header_ && c < header_.size()
                          ? "column '" + header_[c] + "'"
                          : "header: column " + std::to_string(c + 1)) +
                     ": a NUL byte (binary data, not text)");
  }
  if (!have_header_) {
    Header(cells);
    return false;
  }
  if (header_may_repeat_) {
    header_may_repeat_ = false;
    if (cells == header_) return false;
  }
  const std::string where = name_ + ":" + std::to_string(line_number_);
  if (cells.size() != header_.size()) {
    throw InputError(where + ": " + std::to_string(cells.size()) + " cells, the header has " +
                     std::to_string(header_.size()));
  }
  // The cell of column `c` as a number; empty cells are NaN when `may_be_empty`.
  const auto number = [&](int c, bool may_be_empty) {
    const std::string& cell = cells[c];
    if (cell.empty()) {
      if (may_be_empty) return kNaN;
      throw InputError(where + ": column '" + header_[c] + "': empty (required in every row)");
    }
    char* end = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    if (end != cell.c_str() + cell.size() || !std::isfinite(value)) {
      throw InputError(where + ": column '" + header_[c] + "': '" + cell +
                       "' is not a finite number");
    }
    return value;
  };
  detectors::Observation o;
  o.t = number(columns_[0], false);
  for (int i = 0; i < 3; ++i) {
    o.pose(i) = number(columns_[1 + i], true);
    o.valid[i] = !std::isnan(o.pose(i));
    if (!o.valid[i]) o.pose(i) = 0.0;
    o.tau_command(i) = number(columns_[4 + i], false);
  }
  if (!tension_columns_.empty()) {
    // An empty cell: that line's reading withheld (NaN); all empty: no tensions this row.
    VecX tensions(lines_);
    int empty = 0;
    for (int i = 0; i < lines_; ++i) {
      tensions(i) = number(tension_columns_[i], true);
      empty += std::isnan(tensions(i)) ? 1 : 0;
    }
    if (empty < lines_) o.tensions = tensions;
  }
  checks_.Check(o, where);
  *observation = o;
  return true;
}

std::vector<detectors::Observation> ReadRunDetectionInput(const std::string& path, int lines,
                                                          double max_gap) {
  const output::Hdf5Reader file(path);
  if (!file.Has(std::string(layout::kInputTime.path))) {
    throw InputError(path +
                     ": no /detection/input (the run had no detectors, or an older moorsim "
                     "wrote it): replay needs the samples the detection took");
  }
  const output::TableData time = layout::Read(file, path, layout::kInputTime);
  const output::TableData pose = layout::Read(file, path, layout::kInputPose);
  const output::TableData thrust = layout::Read(file, path, layout::kInputThrust);
  output::TableData tension;
  if (file.Has(std::string(layout::kInputTension.path))) {
    tension = layout::Read(file, path, layout::kInputTension, lines);
  }
  const bool tensions = tension.rows > 0;
  if (pose.rows != time.rows || thrust.rows != time.rows ||
      (tensions && tension.rows != time.rows)) {
    throw InputError(path + ": /detection/input: tables of different lengths");
  }
  StreamChecks checks(max_gap);
  std::vector<detectors::Observation> observations(time.rows);
  for (std::size_t r = 0; r < time.rows; ++r) {
    detectors::Observation& o = observations[r];
    o.t = time.values[r];
    for (int i = 0; i < 3; ++i) {
      const double value = pose.at(r, i);
      o.valid[i] = !std::isnan(value);
      o.pose(i) = o.valid[i] ? value : 0.0;
      o.tau_command(i) = thrust.at(r, i);
    }
    if (tensions) {
      VecX row(static_cast<Eigen::Index>(tension.columns));
      bool any = false;
      for (std::size_t i = 0; i < tension.columns; ++i) {
        row(static_cast<Eigen::Index>(i)) = tension.at(r, i);
        any |= !std::isnan(tension.at(r, i));
      }
      if (any) o.tensions = row;
    }
    checks.Check(o, path + " /detection/input row " + std::to_string(r + 1));
  }
  return observations;
}

}  // namespace moorsim::simulation
