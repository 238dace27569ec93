// Reading back what Hdf5File wrote (run.h5, campaign.h5): string and numeric attributes,
// whole numeric tables and string datasets, and the list of every dataset in a file, for
// `moorsim detect`, which replays a run's recorded detection input, and `moorsim compare`.
// Every failure is an InputError naming the file and the object, since the file is the
// user's input here.
#pragma once

#include <cstddef>
#include <cstdint>
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

/// How a dataset's elements are stored.
enum class ElementClass {
  kFloat,
  kSignedInteger,
  kUnsignedInteger,
  kString,
  kOther,  ///< compound, enum, opaque, reference, ...: nothing this reader converts
};

/// One dataset of a file, as ListDatasets finds it.
struct DatasetInfo {
  std::string path;  ///< absolute, "/vessel/pose_true"
  ElementClass element = ElementClass::kOther;
  std::vector<std::size_t> dims;  ///< empty for a scalar dataset
};

/// Whether the input `path` is to be read as an HDF5 file: it has an HDF5 name (.h5, .hdf5)
/// or carries the HDF5 signature. A damaged or empty run.h5 is then reported as such by
/// Hdf5Reader instead of being read as text.
bool LooksLikeHdf5(const std::string& path);

class Hdf5Reader {
 public:
  /// Opens `path` read-only; throws InputError "<path>: ..." if it is empty, has no HDF5
  /// signature, or HDF5 cannot open it (damaged).
  /// A file whose indexes are not all checksummed (every format before HDF5 1.10's: the
  /// files moorsim writes, and those earlier versions wrote) is first read whole in a child
  /// process, so that damage that would crash or hang HDF5 is an InputError too.
  explicit Hdf5Reader(const std::string& path);
  /// kInThisProcess: without that check (what the child itself does).
  enum Check { kAfterACheck, kInThisProcess };
  Hdf5Reader(const std::string& path, Check check);
  ~Hdf5Reader();
  Hdf5Reader(const Hdf5Reader&) = delete;
  Hdf5Reader& operator=(const Hdf5Reader&) = delete;

  const std::string& path() const { return path_; }
  /// The file's size [bytes] when it was opened.
  std::uintmax_t file_bytes() const { return file_bytes_; }
  /// Whether the group or dataset `object_path` exists (every parent must exist too).
  bool Has(const std::string& object_path) const;
  /// The string attribute `name` of `object_path` ("/" the file itself).
  std::string StringAttribute(const std::string& object_path, const std::string& name) const;
  /// A numeric attribute, converted to double (integers of up to 2^53 exactly).
  double NumberAttribute(const std::string& object_path, const std::string& name) const;
  /// Whether `object_path` (which must exist) has the attribute `name`.
  bool HasAttribute(const std::string& object_path, const std::string& name) const;
  /// The whole one- or two-dimensional dataset at `dataset_path`, converted to double.
  TableData ReadTable(const std::string& dataset_path) const;
  /// A numeric dataset of any rank, converted to double: rows = the first dimension (1 for a
  /// scalar), columns = the product of the others (1 for a one-dimensional dataset).
  TableData ReadArray(const std::string& dataset_path) const;
  /// A numeric dataset of any rank, flattened row-major, converted to 64-bit integers
  /// (exact for every integer type; a float is truncated, so read floats with ReadArray).
  std::vector<std::int64_t> ReadSignedIntegers(const std::string& dataset_path) const;
  std::vector<std::uint64_t> ReadUnsignedIntegers(const std::string& dataset_path) const;
  /// A string dataset of any rank (fixed or variable length), flattened row-major.
  std::vector<std::string> ReadStrings(const std::string& dataset_path) const;
  /// Every dataset of the file, reached through hard or soft links from the root, in path
  /// order; a path that names no dataset (a dangling link, a group) is left out.
  std::vector<DatasetInfo> ListDatasets() const;
  /// Reads every attribute of the root and of every dataset, and every dataset, keeping
  /// nothing: whether HDF5 can read the whole file.
  void ReadWhole() const;

 private:
  std::string path_;
  std::uintmax_t file_bytes_ = 0;
  long long file_ = -1;  // hid_t
};

}  // namespace moorsim::output
