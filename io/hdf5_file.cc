#include "io/hdf5_file.h"

#include <hdf5.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <iostream>
#include <limits>
#include <utility>

#include "core/error.h"
#include "io/hdf5_library.h"

namespace moorsim::output {
namespace internal {

// HDF5 prints its error stack to stderr on every failed call unless told not to. The
// setting belongs to the calling thread's error stack (Debian's HDF5 is thread-safe), so
// each thread that touches a file switches it off once.
void PrepareHdf5() {
  // HDF5 closes every file still open at exit. A file whose close failed (a full disk
  // fails the final metadata flush) stays in its table, and HDF5 1.10 then crashes in that
  // exit handler (seen: SIGSEGV in H5F__close_cb after "No space left on device"). Every
  // file is closed explicitly, so the exit handler has nothing to do: switch it off,
  // before the first HDF5 call of the process where possible (afterwards it is a no-op).
  static const bool no_atexit = [] {
    H5dont_atexit();
    return true;
  }();
  (void)no_atexit;
  thread_local bool silenced = false;
  if (!silenced) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    silenced = true;
  }
}

}  // namespace internal

namespace {

using internal::Handle;

/// The outermost and innermost messages of the thread's HDF5 error stack (the innermost
/// one carries the useful detail, e.g. the errno text of a failed open or write) on one
/// line, then clears the stack.
std::string TakeHdf5ErrorText() {
  std::vector<std::string> messages;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        if (error->desc != nullptr && error->desc[0] != '\0') {
          std::string message = error->desc;
          // A failed write's message has a ctime()-style time with its newline inside.
          std::replace(message.begin(), message.end(), '\n', ' ');
          static_cast<std::vector<std::string>*>(data)->push_back(std::move(message));
        }
        return 0;
      },
      &messages);
  H5Eclear2(H5E_DEFAULT);
  if (messages.empty()) return "";
  std::string text = ": " + messages.front();
  if (messages.size() > 1) text += " (" + messages.back() + ")";
  return text;
}

std::string JoinWithCommas(const std::vector<std::string>& names) {
  std::string joined;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) joined += ',';
    joined += names[i];
  }
  return joined;
}

/// "/a/b/c" -> {"/a", "/a/b", "/a/b/c"}; empty if the path is not absolute, is the root
/// itself, or has an empty component ("//", trailing "/").
std::vector<std::string> PathPrefixes(const std::string& path) {
  std::vector<std::string> prefixes;
  if (path.size() < 2 || path.front() != '/' || path.back() == '/') return prefixes;
  for (std::size_t slash = path.find('/', 1); slash != std::string::npos;
       slash = path.find('/', slash + 1)) {
    if (path[slash - 1] == '/') return {};
    prefixes.push_back(path.substr(0, slash));
  }
  prefixes.push_back(path);
  return prefixes;
}

const char* TypeName(TableType type) {
  switch (type) {
    case TableType::kFloat64:
      return "float64";
    case TableType::kInt32:
      return "int32";
    case TableType::kInt8:
      return "int8";
  }
  return "unknown";
}

struct Table {
  std::string path;
  Handle dataset;
  TableType type = TableType::kFloat64;
  int rank = 1;
  std::size_t width = 1;        ///< values per row
  std::size_t chunk_start = 0;  ///< first row of the chunk being buffered
  std::size_t buffered_rows = 0;
  std::size_t rows_written = 0;  ///< rows in the file that hold their final values
  std::vector<double> doubles;   ///< one chunk, allocated on the first row
  std::vector<std::int32_t> ints;
};

}  // namespace

class Hdf5File::Impl {
 public:
  Impl(const std::string& path, const Hdf5FileOptions& options) : path_(path), options_(options) {
    if (options_.chunk_rows == 0) Fail("", "chunk_rows must be >= 1");
    if (options_.gzip_level < 0 || options_.gzip_level > 9) {
      Fail("", "gzip_level " + std::to_string(options_.gzip_level) + " must be in 0..9");
    }
    // A compressed chunk rewritten larger moves, and HDF5 may hand its old place to the
    // next allocation before the next flush, under the rows the file on disk still points
    // to; an uncompressed chunk is rewritten in place.
    compress_ = options_.gzip_level > 0 && !options_.durable_flushes && DeflateEncoderAvailable();

    // A dataset records its creation and modification times unless told not to, and two
    // runs with the same seed would then give different files. Groups (and the root
    // group, created from the file creation list) don't in HDF5 1.10's default format,
    // but are told the same so that a newer format cannot bring the times back.
    Handle fcpl = Make(H5Pcreate(H5P_FILE_CREATE), H5Pclose, "H5Pcreate(H5P_FILE_CREATE)", "");
    Check(H5Pset_obj_track_times(fcpl.get(), false), "H5Pset_obj_track_times", "");
    KeepAttributesInTheHeader(fcpl.get(), "");
    group_creation_ =
        Make(H5Pcreate(H5P_GROUP_CREATE), H5Pclose, "H5Pcreate(H5P_GROUP_CREATE)", "");
    Check(H5Pset_obj_track_times(group_creation_.get(), false), "H5Pset_obj_track_times", "");
    KeepAttributesInTheHeader(group_creation_.get(), "");

    // The HDF5 1.8 format: its superblock (version 2) and object headers (version 2, which
    // hold the attributes and the links) carry checksums, so that damaged metadata are
    // refused by HDF5 instead of read as other values (HDF5 1.8 or later reads these
    // files). Not 1.10's: its superblock (version 3) marks a file open for writing until it
    // is closed, so a file whose writer was killed (run.h5.partial, a live detect.h5) could
    // not be opened without clearing that mark (h5clear).
    Handle access = Make(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "H5Pcreate(H5P_FILE_ACCESS)", "");
    Check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_V18),
          "H5Pset_libver_bounds", "");
    if (options_.durable_flushes) {
      // No metadata-cache evictions (and so no adaptive resizing, which needs them): the
      // file's metadata are written only by H5Fflush, never half-way between two flushes.
      H5AC_cache_config_t config;
      config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
      Check(H5Pget_mdc_config(access.get(), &config), "H5Pget_mdc_config", "");
      config.evictions_enabled = false;
      config.incr_mode = H5C_incr__off;
      config.flash_incr_mode = H5C_flash_incr__off;
      config.decr_mode = H5C_decr__off;
      Check(H5Pset_mdc_config(access.get(), &config), "H5Pset_mdc_config", "");
    }
    file_ = Make(H5Fcreate(path_.c_str(), H5F_ACC_TRUNC, fcpl.get(), access.get()), H5Fclose,
                 "H5Fcreate", "");
  }

  void CreateGroup(const std::string& group_path) {
    const std::vector<std::string> prefixes = PathPrefixes(group_path);
    if (prefixes.empty()) Fail(group_path, "not an absolute path of named groups");
    for (const std::string& prefix : prefixes) {
      if (LinkExists(prefix)) {
        Handle object =
            Make(H5Oopen(file_.get(), prefix.c_str(), H5P_DEFAULT), H5Oclose, "H5Oopen", prefix);
        if (H5Iget_type(object.get()) != H5I_GROUP) Fail(prefix, "exists and is not a group");
      } else {
        Make(H5Gcreate2(file_.get(), prefix.c_str(), H5P_DEFAULT, group_creation_.get(),
                        H5P_DEFAULT),
             H5Gclose, "H5Gcreate2", prefix);  // a temporary: closed at once
      }
    }
  }

  void SetStringAttribute(const std::string& object_path, const std::string& name,
                          const std::string& value) {
    Handle object = OpenObject(object_path);
    SetStringAttribute(object.get(), object_path, name, value);
  }

  void SetNumberAttribute(const std::string& object_path, const std::string& name, hid_t file_type,
                          hid_t memory_type, const void* value) {
    Handle object = OpenObject(object_path);
    Handle attribute = ReplaceAttribute(object.get(), object_path, name, file_type);
    Check(H5Awrite(attribute.get(), memory_type, value), "H5Awrite", object_path, name);
    Check(attribute.Close(), "H5Aclose", object_path, name);
  }

  void WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                    std::size_t count, hid_t file_type, hid_t memory_type, const void* data) {
    const std::vector<std::string> prefixes = PathPrefixes(dataset_path);
    if (prefixes.empty()) Fail(dataset_path, "not an absolute path of named groups");
    if (dims.empty() || dims.size() > 2) Fail(dataset_path, "a dataset has 1 or 2 dimensions");
    std::size_t product = 1;
    for (const std::size_t d : dims) product *= d;
    if (product != count) {
      Fail(dataset_path, std::to_string(count) + " values for " + std::to_string(product));
    }
    if (prefixes.size() > 1) CreateGroup(prefixes[prefixes.size() - 2]);
    if (LinkExists(dataset_path)) Fail(dataset_path, "already exists");
    const std::vector<hsize_t> extent(dims.begin(), dims.end());
    Handle space = Make(H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr),
                        H5Sclose, "H5Screate_simple", dataset_path);
    Handle creation = Make(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate(H5P_DATASET_CREATE)",
                           dataset_path);
    Check(H5Pset_obj_track_times(creation.get(), false), "H5Pset_obj_track_times", dataset_path);
    KeepAttributesInTheHeader(creation.get(), dataset_path);
    Handle dataset = Make(H5Dcreate2(file_.get(), dataset_path.c_str(), file_type, space.get(),
                                     H5P_DEFAULT, creation.get(), H5P_DEFAULT),
                          H5Dclose, "H5Dcreate2", dataset_path);
    if (count > 0) {
      Check(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "H5Dwrite",
            dataset_path);
    }
    Check(dataset.Close(), "H5Dclose", dataset_path);
  }

  void WriteStrings(const std::string& dataset_path, const std::vector<std::string>& values) {
    // Fixed-length, as long as the longest value (see SetStringAttribute for why not
    // variable-length), each value NUL-padded.
    std::size_t longest = 1;
    for (const std::string& v : values) longest = std::max(longest, v.size());
    Handle type = Make(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy", dataset_path);
    Check(H5Tset_size(type.get(), longest), "H5Tset_size", dataset_path);
    Check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "H5Tset_strpad", dataset_path);
    Check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", dataset_path);
    std::vector<char> padded(values.size() * longest, '\0');
    for (std::size_t i = 0; i < values.size(); ++i) {
      std::copy(values[i].begin(), values[i].end(), padded.begin() + i * longest);
    }
    WriteDataset(dataset_path, {values.size()}, values.size(), type.get(), type.get(),
                 padded.data());
  }

  TableId CreateTable(const std::string& dataset_path, int columns, const std::string& units,
                      const std::vector<std::string>& column_names, TableType type) {
    const std::vector<std::string> prefixes = PathPrefixes(dataset_path);
    if (prefixes.empty()) Fail(dataset_path, "not an absolute path of named groups");
    if (columns < 0) Fail(dataset_path, std::to_string(columns) + " columns: must be >= 0");
    if (!column_names.empty() && column_names.size() != static_cast<std::size_t>(columns)) {
      Fail(dataset_path, std::to_string(column_names.size()) + " column names for " +
                             std::to_string(columns) + " columns");
    }
    for (const std::string& name : column_names) {
      if (name.find(',') != std::string::npos) {
        Fail(dataset_path, "column name '" + name + "' contains a comma");
      }
    }
    if (prefixes.size() > 1) CreateGroup(prefixes[prefixes.size() - 2]);
    if (LinkExists(dataset_path)) Fail(dataset_path, "already exists");

    Table table;
    table.path = dataset_path;
    table.type = type;
    table.rank = columns == 0 ? 1 : 2;
    table.width = columns == 0 ? 1 : static_cast<std::size_t>(columns);

    const std::array<hsize_t, 2> initial_dims = {0, table.width};
    const std::array<hsize_t, 2> max_dims = {H5S_UNLIMITED, table.width};
    const std::array<hsize_t, 2> chunk_dims = {options_.chunk_rows, table.width};
    Handle space = Make(H5Screate_simple(table.rank, initial_dims.data(), max_dims.data()),
                        H5Sclose, "H5Screate_simple", dataset_path);

    Handle creation = Make(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "H5Pcreate(H5P_DATASET_CREATE)",
                           dataset_path);
    Check(H5Pset_obj_track_times(creation.get(), false), "H5Pset_obj_track_times", dataset_path);
    KeepAttributesInTheHeader(creation.get(), dataset_path);
    Check(H5Pset_chunk(creation.get(), table.rank, chunk_dims.data()), "H5Pset_chunk",
          dataset_path);
    if (compress_) {
      if (options_.shuffle) Check(H5Pset_shuffle(creation.get()), "H5Pset_shuffle", dataset_path);
      Check(H5Pset_deflate(creation.get(), static_cast<unsigned>(options_.gzip_level)),
            "H5Pset_deflate", dataset_path);
    }
    // Rows are written one whole chunk at a time (plus a final partial chunk), so the
    // chunk cache would only hold a second copy of each chunk.
    Handle access = Make(H5Pcreate(H5P_DATASET_ACCESS), H5Pclose, "H5Pcreate(H5P_DATASET_ACCESS)",
                         dataset_path);
    Check(H5Pset_chunk_cache(access.get(), H5D_CHUNK_CACHE_NSLOTS_DEFAULT, 0,
                             H5D_CHUNK_CACHE_W0_DEFAULT),
          "H5Pset_chunk_cache", dataset_path);

    table.dataset = Make(H5Dcreate2(file_.get(), dataset_path.c_str(), FileType(type), space.get(),
                                    H5P_DEFAULT, creation.get(), access.get()),
                         H5Dclose, "H5Dcreate2", dataset_path);
    SetStringAttribute(table.dataset.get(), dataset_path, "units", units);
    if (!column_names.empty()) {
      SetStringAttribute(table.dataset.get(), dataset_path, "columns",
                         JoinWithCommas(column_names));
    }
    tables_.push_back(std::move(table));
    return TableId{tables_.size() - 1};
  }

  void AppendDoubles(TableId id, std::span<const double> row) {
    Table& table = TableFor(id);
    if (table.type != TableType::kFloat64) {
      Fail(table.path, std::string("holds ") + TypeName(table.type) + ", got float64 values");
    }
    CheckWidth(table, row.size());
    if (table.doubles.empty()) table.doubles.resize(options_.chunk_rows * table.width);
    std::copy(row.begin(), row.end(), table.doubles.begin() + table.buffered_rows * table.width);
    RowAdded(table);
  }

  void AppendInts(TableId id, std::span<const std::int32_t> row) {
    Table& table = TableFor(id);
    if (table.type == TableType::kFloat64) {
      Fail(table.path, "holds float64, got integer values");
    }
    CheckWidth(table, row.size());
    if (table.type == TableType::kInt8) {
      for (const std::int32_t value : row) {
        if (value < std::numeric_limits<std::int8_t>::min() ||
            value > std::numeric_limits<std::int8_t>::max()) {
          Fail(table.path, "value " + std::to_string(value) + " does not fit in int8");
        }
      }
    }
    if (table.ints.empty()) table.ints.resize(options_.chunk_rows * table.width);
    std::copy(row.begin(), row.end(), table.ints.begin() + table.buffered_rows * table.width);
    RowAdded(table);
  }

  std::size_t RowCount(TableId id) {
    const Table& table = TableFor(id);
    return table.chunk_start + table.buffered_rows;
  }

  void Flush() {
    for (Table& table : tables_) WriteBuffered(table);
    Check(H5Fflush(file_.get(), H5F_SCOPE_LOCAL), "H5Fflush", "");
    if (options_.durable_flushes) {
      void* handle = nullptr;
      Check(H5Fget_vfd_handle(file_.get(), H5P_DEFAULT, &handle), "H5Fget_vfd_handle", "");
      if (::fsync(*static_cast<int*>(handle)) != 0) {
        Fail("", std::string("fsync failed: ") + std::strerror(errno));
      }
    }
  }

  /// Writes what is left and closes every identifier, even after a failure; throws the
  /// first failure.
  void Close() {
    std::string first_failure;
    const auto note = [&first_failure](const std::string& failure) {
      if (first_failure.empty()) first_failure = failure;
    };
    for (Table& table : tables_) {
      try {
        WriteBuffered(table);
      } catch (const Error& error) {
        note(error.what());
      }
    }
    for (Table& table : tables_) {
      if (table.dataset.Close() < 0) note(Message(table.path, "H5Dclose", ""));
    }
    group_creation_.Close();
    if (file_.Close() < 0) note(Message("", "H5Fclose", ""));
    if (!first_failure.empty()) throw Error(first_failure);
  }

 private:
  std::string Message(const std::string& object, const std::string& call,
                      const std::string& attribute) const {
    std::string text = path_ + ": ";
    if (!object.empty()) text += object + ": ";
    if (!attribute.empty()) text += "attribute '" + attribute + "': ";
    return text + call + " failed" + TakeHdf5ErrorText();
  }

  [[noreturn]] void Fail(const std::string& object, const std::string& what) const {
    throw Error(path_ + ": " + (object.empty() ? "" : object + ": ") + what);
  }

  Handle Make(hid_t id, Handle::Closer closer, const char* call, const std::string& object,
              const std::string& attribute = "") const {
    if (id < 0) throw Error(Message(object, call, attribute));
    return Handle(id, closer);
  }

  void Check(herr_t status, const char* call, const std::string& object,
             const std::string& attribute = "") const {
    if (status < 0) throw Error(Message(object, call, attribute));
  }

  /// Attributes are kept in the object's header, which HDF5 checksums, up to 64 of them
  /// (HDF5 moves more than 8 by default into "dense" storage, where a long value such as
  /// the scenario's text lies outside any checksum). A value too long for a header message
  /// (64 KiB) still goes to dense storage.
  void KeepAttributesInTheHeader(hid_t creation, const std::string& object) const {
    Check(H5Pset_attr_phase_change(creation, 64, 48), "H5Pset_attr_phase_change", object);
  }

  static bool DeflateEncoderAvailable() {
    if (H5Zfilter_avail(H5Z_FILTER_DEFLATE) <= 0) return false;
    unsigned int config = 0;
    if (H5Zget_filter_info(H5Z_FILTER_DEFLATE, &config) < 0) return false;
    return (config & H5Z_FILTER_CONFIG_ENCODE_ENABLED) != 0;
  }

  static hid_t FileType(TableType type) {
    switch (type) {
      case TableType::kFloat64:
        return H5T_IEEE_F64LE;
      case TableType::kInt32:
        return H5T_STD_I32LE;
      case TableType::kInt8:
        return H5T_STD_I8LE;
    }
    return H5T_IEEE_F64LE;
  }

  /// H5Lexists fails rather than answering "no" when a parent is missing, so each level
  /// is asked in turn.
  bool LinkExists(const std::string& path) const {
    for (const std::string& prefix : PathPrefixes(path)) {
      const htri_t exists = H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT);
      if (exists < 0) throw Error(Message(prefix, "H5Lexists", ""));
      if (exists == 0) return false;
    }
    return true;
  }

  Handle OpenObject(const std::string& object_path) const {
    if (object_path != "/") {
      if (PathPrefixes(object_path).empty()) {
        Fail(object_path, "not an absolute path of named groups");
      }
      if (!LinkExists(object_path)) Fail(object_path, "no such group or table");
    }
    return Make(H5Oopen(file_.get(), object_path.c_str(), H5P_DEFAULT), H5Oclose, "H5Oopen",
                object_path);
  }

  /// A new scalar attribute `name` on `object`, deleting an existing one first.
  Handle ReplaceAttribute(hid_t object, const std::string& object_path, const std::string& name,
                          hid_t file_type) const {
    if (name.empty()) Fail(object_path, "empty attribute name");
    const htri_t exists = H5Aexists(object, name.c_str());
    if (exists < 0) throw Error(Message(object_path, "H5Aexists", name));
    if (exists > 0) Check(H5Adelete(object, name.c_str()), "H5Adelete", object_path, name);
    Handle space = Make(H5Screate(H5S_SCALAR), H5Sclose, "H5Screate", object_path, name);
    return Make(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                H5Aclose, "H5Acreate2", object_path, name);
  }

  void SetStringAttribute(hid_t object, const std::string& object_path, const std::string& name,
                          const std::string& value) const {
    // Fixed-length, its own length plus the terminating NUL: the text is then stored in the
    // attribute itself, inside the checksummed object header (or dense attribute storage),
    // where a variable-length string would keep only a reference into the global heap,
    // which has no checksum and whose damage crashes HDF5's reader.
    Handle type = Make(H5Tcopy(H5T_C_S1), H5Tclose, "H5Tcopy", object_path, name);
    Check(H5Tset_size(type.get(), value.size() + 1), "H5Tset_size", object_path, name);
    Check(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "H5Tset_strpad", object_path, name);
    Check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", object_path, name);
    Handle attribute = ReplaceAttribute(object, object_path, name, type.get());
    Check(H5Awrite(attribute.get(), type.get(), value.c_str()), "H5Awrite", object_path, name);
    Check(attribute.Close(), "H5Aclose", object_path, name);
  }

  Table& TableFor(TableId id) {
    if (id.index >= tables_.size()) {
      Fail("", "no table with id " + std::to_string(id.index) + " (" +
                   std::to_string(tables_.size()) + " tables)");
    }
    return tables_[id.index];
  }

  void CheckWidth(const Table& table, std::size_t values) const {
    if (values != table.width) {
      Fail(table.path, "row of " + std::to_string(values) + " values, table has " +
                           (table.rank == 1 ? std::string("1 value per row")
                                            : std::to_string(table.width) + " columns"));
    }
  }

  /// Counts the row just copied into the buffer and writes the chunk once it is full. If
  /// that write fails, the row is taken back, so the buffer never overflows and the next
  /// Append tries the write again.
  void RowAdded(Table& table) {
    ++table.buffered_rows;
    if (table.buffered_rows < options_.chunk_rows) return;
    try {
      WriteBuffered(table);
    } catch (const Error&) {
      --table.buffered_rows;
      throw;
    }
    table.chunk_start += table.buffered_rows;
    table.buffered_rows = 0;
  }

  /// Writes the buffered rows at their place in the file, growing the dataset if needed.
  /// The buffer keeps them: a partial chunk is written again, whole, when it fills.
  void WriteBuffered(Table& table) {
    const std::size_t end_row = table.chunk_start + table.buffered_rows;
    if (table.buffered_rows == 0 || end_row == table.rows_written) return;
    const hid_t dataset = table.dataset.get();
    const std::array<hsize_t, 2> extent = {end_row, table.width};
    Check(H5Dset_extent(dataset, extent.data()), "H5Dset_extent", table.path);

    const std::array<hsize_t, 2> start = {table.chunk_start, 0};
    const std::array<hsize_t, 2> count = {table.buffered_rows, table.width};
    Handle file_space = Make(H5Dget_space(dataset), H5Sclose, "H5Dget_space", table.path);
    Check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                              nullptr),
          "H5Sselect_hyperslab", table.path);
    Handle memory_space = Make(H5Screate_simple(table.rank, count.data(), nullptr), H5Sclose,
                               "H5Screate_simple", table.path);
    const bool floating = table.type == TableType::kFloat64;
    Check(H5Dwrite(dataset, floating ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT32, memory_space.get(),
                   file_space.get(), H5P_DEFAULT,
                   floating ? static_cast<const void*>(table.doubles.data())
                            : static_cast<const void*>(table.ints.data())),
          "H5Dwrite", table.path);
    table.rows_written = end_row;
  }

  std::string path_;
  Hdf5FileOptions options_;
  bool compress_ = false;
  Handle group_creation_;
  Handle file_;
  std::vector<Table> tables_;  // declared after file_: datasets close before the file
};

Hdf5File::Hdf5File(const std::string& path, const Hdf5FileOptions& options) : path_(path) {
  internal::PrepareHdf5();
  impl_ = std::make_unique<Impl>(path, options);
}

Hdf5File::~Hdf5File() { CloseReportingFailure(); }

void Hdf5File::CloseReportingFailure() noexcept {
  try {
    Close();
  } catch (const std::exception& error) {
    std::cerr << "moorsim: closing " << path_ << " failed: " << error.what() << '\n';
  }
}

Hdf5File::Hdf5File(Hdf5File&& other) noexcept = default;

Hdf5File& Hdf5File::operator=(Hdf5File&& other) noexcept {
  if (this != &other) {
    CloseReportingFailure();
    path_ = std::move(other.path_);
    impl_ = std::move(other.impl_);
  }
  return *this;
}

const std::string& Hdf5File::path() const { return path_; }

Hdf5File::Impl& Hdf5File::Live() {
  internal::PrepareHdf5();
  if (!impl_) throw Error(path_ + ": the file is closed");
  return *impl_;
}

void Hdf5File::CreateGroup(const std::string& group_path) { Live().CreateGroup(group_path); }

void Hdf5File::SetAttribute(const std::string& object_path, const std::string& name,
                            const std::string& value) {
  Live().SetStringAttribute(object_path, name, value);
}

void Hdf5File::WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                            std::span<const double> values) {
  Live().WriteDataset(dataset_path, dims, values.size(), H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                      values.data());
}

void Hdf5File::WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                            std::span<const std::int64_t> values) {
  Live().WriteDataset(dataset_path, dims, values.size(), H5T_STD_I64LE, H5T_NATIVE_INT64,
                      values.data());
}

void Hdf5File::WriteDataset(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                            std::span<const std::uint64_t> values) {
  Live().WriteDataset(dataset_path, dims, values.size(), H5T_STD_U64LE, H5T_NATIVE_UINT64,
                      values.data());
}

void Hdf5File::WriteDataset(const std::string& dataset_path,
                            const std::vector<std::string>& values) {
  Live().WriteStrings(dataset_path, values);
}

void Hdf5File::SetAttribute(const std::string& object_path, const std::string& name, double value) {
  Live().SetNumberAttribute(object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Hdf5File::SetAttribute(const std::string& object_path, const std::string& name,
                            std::int64_t value) {
  Live().SetNumberAttribute(object_path, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void Hdf5File::SetAttribute(const std::string& object_path, const std::string& name,
                            std::uint64_t value) {
  Live().SetNumberAttribute(object_path, name, H5T_STD_U64LE, H5T_NATIVE_UINT64, &value);
}

TableId Hdf5File::CreateTable(const std::string& dataset_path, int columns,
                              const std::string& units,
                              const std::vector<std::string>& column_names, TableType type) {
  return Live().CreateTable(dataset_path, columns, units, column_names, type);
}

void Hdf5File::Append(TableId table, std::span<const double> row) {
  Live().AppendDoubles(table, row);
}

void Hdf5File::Append(TableId table, std::span<const std::int32_t> row) {
  Live().AppendInts(table, row);
}

void Hdf5File::Append(TableId table, double value) {
  Live().AppendDoubles(table, std::span<const double>(&value, 1));
}

void Hdf5File::Append(TableId table, std::int32_t value) {
  Live().AppendInts(table, std::span<const std::int32_t>(&value, 1));
}

std::size_t Hdf5File::RowCount(TableId table) const {
  if (!impl_) throw Error(path_ + ": the file is closed");
  return impl_->RowCount(table);
}

void Hdf5File::Flush() { Live().Flush(); }

void Hdf5File::Close() {
  if (!impl_) return;
  internal::PrepareHdf5();
  // Closed from here on, whatever happens: a failed close is not retried.
  const std::unique_ptr<Impl> impl = std::move(impl_);
  impl->Close();
}

}  // namespace moorsim::output
