#include "tools/output/hdf5_reader.h"

#include <hdf5.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <utility>

#include "core/error.h"
#include "tools/output/hdf5_library.h"

namespace moorsim::output {

namespace {

// Closes an HDF5 handle with `close` when it leaves scope.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t)) : id(id), close_(close) {}
  ~Handle() {
    if (id >= 0) close_(id);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  const hid_t id;

 private:
  herr_t (*close_)(hid_t);
};

// The attribute `name` of `object_path` and its type; throws "<where>: missing".
class Attribute {
 public:
  Attribute(hid_t file, const std::string& object_path, const std::string& name,
            const std::string& where)
      : attribute(
            H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
            H5Aclose),
        type(attribute.id >= 0 ? H5Aget_type(attribute.id) : -1, H5Tclose) {
    if (attribute.id < 0) throw InputError(where + ": missing");
  }
  Handle attribute;
  Handle type;
};

}  // namespace

namespace {

/// Whether the file at `path` carries the HDF5 signature where HDF5 looks for it: at offset
/// 0, or after a user block of 512, 1024, 2048, ... bytes.
bool HasHdf5Signature(const std::string& path) {
  constexpr std::string_view kSignature("\x89HDF\r\n\x1a\n", 8);
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return false;
  for (std::uintmax_t offset = 0; offset + kSignature.size() <= size;
       offset = offset == 0 ? 512 : 2 * offset) {
    char bytes[kSignature.size()] = {};
    if (!in.seekg(static_cast<std::streamoff>(offset)).read(bytes, sizeof bytes)) return false;
    if (std::string_view(bytes, sizeof bytes) == kSignature) return true;
  }
  return false;
}

/// The memory type a fixed-length string of `file_type` is read into: its size and
/// character set, NUL-padded (a NUL-terminated type of the same size would drop the last
/// character of a value that fills it).
hid_t FixedStringMemoryType(hid_t file_type) {
  const hid_t memory = H5Tcopy(H5T_C_S1);
  H5Tset_size(memory, std::max<std::size_t>(H5Tget_size(file_type), 1));
  H5Tset_strpad(memory, H5T_STR_NULLPAD);
  H5Tset_cset(memory, H5Tget_cset(file_type));
  return memory;
}

/// One fixed-length string of `size` bytes read with FixedStringMemoryType: up to its first
/// NUL.
std::string FixedStringValue(const char* text, std::size_t size) {
  return std::string(text, std::find(text, text + size, '\0'));
}

}  // namespace

bool LooksLikeHdf5(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".h5" || extension == ".hdf5" || HasHdf5Signature(path);
}

Hdf5Reader::Hdf5Reader(const std::string& path) : path_(path) {
  internal::PrepareHdf5();
  std::error_code error;
  file_bytes_ = std::filesystem::file_size(path, error);
  if (file_bytes_ == 0 && !error) throw InputError(path + ": empty (0 bytes), not an HDF5 file");
  if (!HasHdf5Signature(path)) {
    throw InputError(path + ": damaged or not an HDF5 file (no HDF5 signature)");
  }
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw InputError(path + ": damaged HDF5 file (HDF5 cannot open it)");
}

Hdf5Reader::~Hdf5Reader() {
  if (file_ >= 0) H5Fclose(static_cast<hid_t>(file_));
}

bool Hdf5Reader::Has(const std::string& object_path) const {
  if (object_path == "/") return true;
  // Every prefix must exist before H5Lexists may be asked about the next.
  for (std::size_t slash = object_path.find('/', 1);; slash = object_path.find('/', slash + 1)) {
    const std::string prefix = object_path.substr(0, slash);
    if (H5Lexists(static_cast<hid_t>(file_), prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
  }
}

std::string Hdf5Reader::StringAttribute(const std::string& object_path,
                                        const std::string& name) const {
  const std::string where = path_ + ": " + object_path + " attribute '" + name + "'";
  const Attribute a(static_cast<hid_t>(file_), object_path, name, where);
  const Handle& attribute = a.attribute;
  if (H5Tget_class(a.type.id) != H5T_STRING) throw InputError(where + ": not a string");
  if (H5Tis_variable_str(a.type.id) <= 0) {
    const Handle memory{FixedStringMemoryType(a.type.id), H5Tclose};
    std::vector<char> text(std::max<std::size_t>(H5Tget_size(a.type.id), 1));
    if (H5Aread(attribute.id, memory.id, text.data()) < 0) {
      throw InputError(where + ": unreadable");
    }
    return FixedStringValue(text.data(), text.size());
  }
  Handle memory{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(memory.id, H5T_VARIABLE);
  H5Tset_cset(memory.id, H5T_CSET_UTF8);
  char* text = nullptr;
  if (H5Aread(attribute.id, memory.id, &text) < 0) throw InputError(where + ": unreadable");
  std::string value = text == nullptr ? std::string() : std::string(text);
  H5free_memory(text);
  return value;
}

double Hdf5Reader::NumberAttribute(const std::string& object_path, const std::string& name) const {
  const std::string where = path_ + ": " + object_path + " attribute '" + name + "'";
  const Attribute a(static_cast<hid_t>(file_), object_path, name, where);
  const Handle& attribute = a.attribute;
  const H5T_class_t kind = H5Tget_class(a.type.id);
  if (kind != H5T_FLOAT && kind != H5T_INTEGER) throw InputError(where + ": not a number");
  double value = 0.0;
  if (H5Aread(attribute.id, H5T_NATIVE_DOUBLE, &value) < 0) {
    throw InputError(where + ": unreadable");
  }
  return value;
}

bool Hdf5Reader::HasAttribute(const std::string& object_path, const std::string& name) const {
  return H5Aexists_by_name(static_cast<hid_t>(file_), object_path.c_str(), name.c_str(),
                           H5P_DEFAULT) > 0;
}

namespace {

// An open dataset with its type and dimensions; throws "<where>: missing" or
// "<where>: not a dataset".
class Dataset {
 public:
  Dataset(const Hdf5Reader& reader, hid_t file, const std::string& path)
      : dataset(reader.Has(path) ? H5Dopen2(file, path.c_str(), H5P_DEFAULT) : -1, H5Dclose),
        type(dataset.id >= 0 ? H5Dget_type(dataset.id) : -1, H5Tclose),
        space(dataset.id >= 0 ? H5Dget_space(dataset.id) : -1, H5Sclose),
        where_(reader.path() + ": " + path) {
    if (!reader.Has(path)) throw InputError(where_ + ": missing");
    if (dataset.id < 0) throw InputError(where_ + ": not a dataset");
    const int rank = H5Sget_simple_extent_ndims(space.id);
    if (rank < 0) throw InputError(where_ + ": unreadable dataspace");
    dims.resize(static_cast<std::size_t>(rank));
    if (rank > 0 && H5Sget_simple_extent_dims(space.id, dims.data(), nullptr) < 0) {
      throw InputError(where_ + ": unreadable dataspace");
    }
    // Deflate packs at most 1032 bytes into one: a dataset beyond that (a damaged
    // dimension) is refused before its memory is asked for. Elements are read as at most
    // 8 bytes or as stored.
    const std::uintmax_t element = std::max<std::size_t>(H5Tget_size(type.id), 1);
    const std::uintmax_t most = 1032 * std::max<std::uintmax_t>(reader.file_bytes(), 1) / element;
    for (const hsize_t d : dims) {
      if (d != 0 && count_ > most / d) {
        throw InputError(where_ + ": more elements than a file of " +
                         std::to_string(reader.file_bytes()) + " bytes holds (damaged)");
      }
      count_ *= d;
    }
  }

  /// The number of elements.
  std::size_t Count() const { return count_; }

  bool Numeric() const {
    const H5T_class_t kind = H5Tget_class(type.id);
    return kind == H5T_FLOAT || kind == H5T_INTEGER;
  }

  /// Reads every element converted to `memory_type` into `out` (Count() elements).
  void Read(hid_t memory_type, void* out) const {
    if (Count() > 0 && H5Dread(dataset.id, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0) {
      throw InputError(where_ + ": unreadable (damaged, or a filter this HDF5 lacks)");
    }
  }

  /// Every element of a numeric dataset, converted to `memory_type` (which must be T's);
  /// throws "<where>: not numeric" for any other dataset.
  template <class T>
  std::vector<T> ReadNumbers(hid_t memory_type) const {
    if (!Numeric()) throw InputError(where_ + ": not numeric");
    std::vector<T> values(Count());
    Read(memory_type, values.data());
    return values;
  }

  Handle dataset;
  Handle type;
  Handle space;
  std::vector<hsize_t> dims;

 private:
  std::string where_;
  std::size_t count_ = 1;
};

}  // namespace

TableData Hdf5Reader::ReadTable(const std::string& dataset_path) const {
  const std::string where = path_ + ": " + dataset_path;
  const Dataset d(*this, static_cast<hid_t>(file_), dataset_path);
  if (d.dims.size() != 1 && d.dims.size() != 2) {
    throw InputError(where + ": not a one- or two-dimensional table");
  }
  return ReadArray(dataset_path);
}

TableData Hdf5Reader::ReadArray(const std::string& dataset_path) const {
  const Dataset d(*this, static_cast<hid_t>(file_), dataset_path);
  TableData table;
  table.rows = d.dims.empty() ? 1 : d.dims[0];
  table.columns = 1;
  for (std::size_t i = 1; i < d.dims.size(); ++i) table.columns *= d.dims[i];
  table.values = d.ReadNumbers<double>(H5T_NATIVE_DOUBLE);
  return table;
}

std::vector<std::int64_t> Hdf5Reader::ReadSignedIntegers(const std::string& dataset_path) const {
  return Dataset(*this, static_cast<hid_t>(file_), dataset_path)
      .ReadNumbers<std::int64_t>(H5T_NATIVE_INT64);
}

std::vector<std::uint64_t> Hdf5Reader::ReadUnsignedIntegers(const std::string& dataset_path) const {
  return Dataset(*this, static_cast<hid_t>(file_), dataset_path)
      .ReadNumbers<std::uint64_t>(H5T_NATIVE_UINT64);
}

std::vector<std::string> Hdf5Reader::ReadStrings(const std::string& dataset_path) const {
  const std::string where = path_ + ": " + dataset_path;
  const Dataset d(*this, static_cast<hid_t>(file_), dataset_path);
  if (H5Tget_class(d.type.id) != H5T_STRING) throw InputError(where + ": not a string dataset");
  const std::size_t n = d.Count();
  std::vector<std::string> values;
  values.reserve(n);
  if (H5Tis_variable_str(d.type.id) > 0) {
    const Handle memory{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(memory.id, H5T_VARIABLE);
    H5Tset_cset(memory.id, H5Tget_cset(d.type.id));
    std::vector<char*> texts(n, nullptr);
    d.Read(memory.id, texts.data());
    for (char* text : texts) {
      values.emplace_back(text == nullptr ? "" : text);
      H5free_memory(text);
    }
    return values;
  }
  const std::size_t size = H5Tget_size(d.type.id);
  std::vector<char> buffer(n * size);
  const Handle memory{FixedStringMemoryType(d.type.id), H5Tclose};
  d.Read(memory.id, buffer.data());
  for (std::size_t i = 0; i < n; ++i) values.push_back(FixedStringValue(&buffer[i * size], size));
  return values;
}

std::vector<DatasetInfo> Hdf5Reader::ListDatasets() const {
  // Every link's path, and whether it is a hard link (a soft link may dangle).
  std::vector<std::pair<std::string, bool>> links;
  const herr_t visited = H5Lvisit(
      static_cast<hid_t>(file_), H5_INDEX_NAME, H5_ITER_INC,
      [](hid_t, const char* name, const H5L_info_t* info, void* data) -> herr_t {
        static_cast<std::vector<std::pair<std::string, bool>>*>(data)->emplace_back(
            std::string("/") + name, info->type == H5L_TYPE_HARD);
        return 0;
      },
      &links);
  if (visited < 0) throw InputError(path_ + ": damaged (its groups cannot be listed)");
  std::vector<DatasetInfo> datasets;
  for (const auto& [name, hard] : links) {
    const Handle object{H5Oopen(static_cast<hid_t>(file_), name.c_str(), H5P_DEFAULT), H5Oclose};
    if (object.id < 0 && hard)
      throw InputError(path_ + ": " + name + ": damaged (cannot be opened)");
    if (object.id < 0 || H5Iget_type(object.id) != H5I_DATASET) continue;
    const Dataset d(*this, static_cast<hid_t>(file_), name);
    DatasetInfo info;
    info.path = name;
    info.dims.assign(d.dims.begin(), d.dims.end());
    switch (H5Tget_class(d.type.id)) {
      case H5T_FLOAT:
        info.element = ElementClass::kFloat;
        break;
      case H5T_INTEGER:
        info.element = H5Tget_sign(d.type.id) == H5T_SGN_NONE ? ElementClass::kUnsignedInteger
                                                              : ElementClass::kSignedInteger;
        break;
      case H5T_STRING:
        info.element = ElementClass::kString;
        break;
      default:
        info.element = ElementClass::kOther;
    }
    datasets.push_back(std::move(info));
  }
  std::sort(datasets.begin(), datasets.end(),
            [](const DatasetInfo& a, const DatasetInfo& b) { return a.path < b.path; });
  return datasets;
}

}  // namespace moorsim::output
