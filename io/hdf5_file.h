// Writer for the simulator's time-series output (run.h5, docs/design.md section 7): an HDF5
// file of growing tables, one row per output sample, with units and column names as
// attributes.
//
// Why buffered, chunked tables: a 3-hour run at 10 Hz has 108 000 rows in each of a dozen
// tables. Rows are kept in memory per table until a chunk is full (1024 rows by default)
// and then written as one whole chunk, so memory stays at one chunk per table whatever
// the run length, and every HDF5 write covers exactly one chunk (no read-modify-write of
// compressed chunks).
//
// Reproducibility: no object in the file records a creation or modification time, and
// gzip is deterministic, so the same rows written in the same order give a byte-identical
// file.
//
// Damage: the file is in HDF5 1.8's format, whose superblock and object headers carry
// checksums; string attributes are fixed-length and kept in their object's header, so a
// flipped bit in the scenario's text or in the structure is refused by the reader
// (Hdf5Reader) instead of being read as other values (variable-length strings live in the
// global heap, which has no checksum). The chunk indexes of this format have no checksums:
// the reader checks each table's index against its dimensions, and reads a file whole in a
// child process first, so that damage HDF5 would crash or hang on is refused too. Not 1.10's
// format: its superblock marks a file open for writing until it is closed, and a file
// whose writer was killed would not open. HDF5 1.8 or later reads these files.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace moorsim::output {

/// Element type of a table in the file.
enum class TableType {
  kFloat64,  ///< IEEE 754 binary64, little endian
  kInt32,    ///< signed 32-bit little endian
  kInt8,     ///< signed 8-bit (flags, decisions, line numbers)
};

/// Names a table of one Hdf5File; returned by CreateTable, valid until the file closes.
struct TableId {
  std::size_t index = 0;
};

struct Hdf5FileOptions {
  /// Rows per chunk; also the number of rows buffered in memory per table.
  std::size_t chunk_rows = 1024;
  /// gzip (deflate) level 1..9, 0 = no compression. If this HDF5 build has no deflate
  /// encoder the tables are written uncompressed.
  int gzip_level = 4;
  /// Byte-shuffle filter before gzip: groups the bytes of equal significance, so the
  /// slowly varying sign and exponent bytes compress well (on a simulated 3-hour run the
  /// file was 15 % smaller and written faster). Ignored without compression.
  bool shuffle = true;
  /// For a file written for months and killed at any moment (a live monitor): HDF5's
  /// metadata reach the file only at Flush (metadata-cache evictions off), every Flush ends
  /// with an fsync, and tables are stored uncompressed (gzip_level is ignored) so that a
  /// chunk rewritten by a later Flush keeps its place. After the first Flush the file then
  /// opens whenever the process is killed or the power fails, and holds every row up to the
  /// last Flush.
  bool durable_flushes = false;
};

/// An HDF5 file being written. Every failure (the file cannot be created, an HDF5 call
/// fails, a row of the wrong width) throws moorsim::Error naming the file, the object and
/// the HDF5 call. HDF5's own printing of error stacks is switched off in each thread that
/// uses an Hdf5File (the failure is in the exception instead).
///
/// Memory: one chunk (chunk_rows x columns values) per table, whatever the run length.
/// Until Flush or Close, up to one chunk of rows per table exists only in memory.
///
/// Not thread-safe: one thread writes one file (several threads may write several files).
class Hdf5File {
 public:
  /// Creates `path`, truncating an existing file.
  explicit Hdf5File(const std::string& path, const Hdf5FileOptions& options = {});
  /// Closes the file (see Close); a failure is reported on stderr, never thrown.
  ~Hdf5File();

  Hdf5File(Hdf5File&&) noexcept;
  Hdf5File& operator=(Hdf5File&&) noexcept;
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;

  const std::string& path() const;

  /// Creates the group `group_path` ("/detectors/cusum") and any missing parents; an
  /// existing group is left as it is.
  void CreateGroup(const std::string& group_path);

  /// Sets (or replaces) the attribute `name` of the existing group or table `object_path`;
  /// "/" is the file itself. Strings are stored as fixed-length UTF-8 scalars (their length),
  /// doubles as IEEE 754 binary64 and integers as signed or unsigned 64-bit (pass an std::int64_t
  /// or std::uint64_t: a plain int is ambiguous between the numeric overloads on purpose).
  void SetAttribute(const std::string& object_path, const std::string& name,
                    const std::string& value);
  void SetAttribute(const std::string& object_path, const std::string& name, double value);
  void SetAttribute(const std::string& object_path, const std::string& name, std::int64_t value);
  /// Unsigned 64-bit (seeds: 2^63 and above stay positive).
  void SetAttribute(const std::string& object_path, const std::string& name, std::uint64_t value);

  /// Writes a whole dataset of known size at once (no chunks, no compression): `dims` is
  /// {rows} or {rows, columns}, `values` row-major with as many values as dims multiply
  /// to. Missing parent groups are created; an existing dataset is an error. For tables
  /// written once, such as a campaign's results.
  void WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                    std::span<const double> values);
  void WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                    std::span<const std::int64_t> values);
  void WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                    std::span<const std::uint64_t> values);
  /// A one-dimensional dataset of UTF-8 strings (fixed-length: the longest value's, NUL-padded).
  void WriteDataset(const std::string& dataset_path, const std::vector<std::string>& values);
  /// Creates an empty, extendible table at `dataset_path` (absolute, e.g.
  /// "/vessel/pose_true"; missing parent groups are created). `columns` > 0 gives a
  /// rows x columns dataset, `columns` == 0 a one-dimensional dataset of rows. `units` is
  /// stored as the attribute "units" ("m,m,m,rad,rad,rad", or "s"); `column_names`, if not
  /// empty, must have one name per column (none may contain a comma) and is stored
  /// comma-joined as the attribute "columns".
  TableId CreateTable(const std::string& dataset_path, int columns, const std::string& units,
                      const std::vector<std::string>& column_names = {},
                      TableType type = TableType::kFloat64);

  /// Appends one row: `columns` values, or one value for a one-dimensional table. The
  /// double overloads need a kFloat64 table; the integer overloads a kInt32 or kInt8 table
  /// (values outside the type's range throw).
  void Append(TableId table, std::span<const double> row);
  void Append(TableId table, std::span<const std::int32_t> row);
  void Append(TableId table, double value);
  void Append(TableId table, std::int32_t value);

  /// Rows appended to `table` so far (written or still buffered).
  std::size_t RowCount(TableId table) const;

  /// Writes every buffered row and asks HDF5 to flush the file to disk, so a reader (or a
  /// crash) sees every row appended so far. Rows of an incomplete chunk stay buffered as
  /// well and are written again with the rest of their chunk.
  void Flush();

  /// Writes the remaining rows and closes the file. Later calls of anything but path(),
  /// Close() and the destructor throw.
  void Close();

 private:
  class Impl;
  Impl& Live();  // the open file, or throws
  void CloseReportingFailure() noexcept;

  std::string path_;
  std::unique_ptr<Impl> impl_;  // null once closed
};

}  // namespace moorsim::output
