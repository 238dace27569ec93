// Small synthetic outputs for the tests of `moorsim compare`: HDF5 files of a few named
// tables, written through the project's writer, shaped like a run.h5.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "io/hdf5_file.h"

namespace moorsim::testing {

/// One table: `columns` = 0 for a one-dimensional table; values row-major.
struct SyntheticTable {
  std::string path;
  int columns = 0;
  std::vector<double> values;
  std::vector<std::string> column_names;
  output::TableType type = output::TableType::kFloat64;
};

inline void WriteTables(const std::filesystem::path& path,
                        const std::vector<SyntheticTable>& tables) {
  output::Hdf5File file(path.string());
  for (const SyntheticTable& t : tables) {
    const output::TableId id = file.CreateTable(t.path, t.columns, "-", t.column_names, t.type);
    const std::size_t width = t.columns == 0 ? 1 : static_cast<std::size_t>(t.columns);
    for (std::size_t i = 0; i < t.values.size(); i += width) {
      if (t.type == output::TableType::kFloat64 && t.columns == 0) {
        file.Append(id, t.values[i]);
      } else if (t.type == output::TableType::kFloat64) {
        file.Append(id, std::span<const double>(t.values.data() + i, width));
      } else if (t.columns == 0) {
        file.Append(id, static_cast<std::int32_t>(t.values[i]));
      } else {
        const std::vector<std::int32_t> row(t.values.begin() + i, t.values.begin() + i + width);
        file.Append(id, std::span<const std::int32_t>(row));
      }
    }
  }
  file.Close();
}

/// A run of 5 rows, t = 0..4 s: /time, /vessel/pose_true (x, y, z, phi, theta, psi; row k
/// holds 10 k + column) and a detector's decisions (0, 0, 0, 1, 1).
inline std::vector<SyntheticTable> SyntheticRun() {
  std::vector<double> pose;
  for (int row = 0; row < 5; ++row) {
    for (int column = 0; column < 6; ++column) pose.push_back(10.0 * row + column);
  }
  return {{"/time", 0, {0, 1, 2, 3, 4}, {}, output::TableType::kFloat64},
          {"/vessel/pose_true",
           6,
           pose,
           {"x", "y", "z", "phi", "theta", "psi"},
           output::TableType::kFloat64},
          {"/detectors/glr/decision", 0, {0, 0, 0, 1, 1}, {}, output::TableType::kInt8}};
}

}  // namespace moorsim::testing
