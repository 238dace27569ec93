// Reading back what Hdf5File wrote (run.h5): string and numeric attributes and whole
// numeric tables, for `moorsim detect`, which replays a run's recorded detection input.
// Every failure is an InputError naming the file and the object, since the file is the
// user's input here.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace moorsim::output {

/// A numeric table read whole: rows x columns values, row-major (columns = 1 for a
/// one-dimensional dataset).
struct TableData {
  std::size_t rows = 0;
  std::size_t columns = 0;
  std::vector<double> values;
  double at(std::size_t row, std::size_t column) const { return values[row * columns + column]; }
};

class Hdf5Reader {
 public:
  /// Opens `path` read-only; throws InputError "<path>: ..." if it is not a readable HDF5
  /// file.
  explicit Hdf5Reader(const std::string& path);
  ~Hdf5Reader();
  Hdf5Reader(const Hdf5Reader&) = delete;
  Hdf5Reader& operator=(const Hdf5Reader&) = delete;

  const std::string& path() const { return path_; }
  /// Whether the group or dataset `object_path` exists (every parent must exist too).
  bool Has(const std::string& object_path) const;
  /// The string attribute `name` of `object_path` ("/" the file itself).
  std::string StringAttribute(const std::string& object_path, const std::string& name) const;
  /// A numeric attribute, converted to double (integers of up to 2^53 exactly).
  double NumberAttribute(const std::string& object_path, const std::string& name) const;
  /// The whole one- or two-dimensional dataset at `dataset_path`, converted to double.
  TableData ReadTable(const std::string& dataset_path) const;

 private:
  std::string path_;
  long long file_ = -1;  // hid_t
};

}  // namespace moorsim::output
