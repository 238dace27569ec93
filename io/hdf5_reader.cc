#include "io/hdf5_reader.h"

#include <hdf5.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <set>
#include <string_view>
#include <thread>
#include <utility>

#include "core/error.h"
#include "io/hdf5_library.h"

namespace moorsim::output {

namespace {

using internal::Handle;

// The attribute `name` of `object_path` and its type; throws "<where>: missing".
class Attribute {
 public:
  Attribute(hid_t file, const std::string& object_path, const std::string& name,
            const std::string& where)
      : attribute(
            H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
            H5Aclose),
        type(attribute.get() >= 0 ? H5Aget_type(attribute.get()) : -1, H5Tclose) {
    if (attribute.get() < 0) throw InputError(where + ": missing");
  }
  Handle attribute;
  Handle type;
};

}  // namespace

namespace {

/// Where the file at `path` carries the HDF5 signature, if it does: at offset 0, or after a
/// user block of 512, 1024, 2048, ... bytes (where HDF5 looks for it).
std::optional<std::uintmax_t> Hdf5SignatureOffset(const std::string& path) {
  constexpr std::string_view kSignature("\x89HDF\r\n\x1a\n", 8);
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (error) return std::nullopt;
  for (std::uintmax_t offset = 0; offset + kSignature.size() <= size;
       offset = offset == 0 ? 512 : 2 * offset) {
    char bytes[kSignature.size()] = {};
    if (!in.seekg(static_cast<std::streamoff>(offset)).read(bytes, sizeof bytes)) break;
    if (std::string_view(bytes, sizeof bytes) == kSignature) return offset;
  }
  return std::nullopt;
}

bool HasHdf5Signature(const std::string& path) { return Hdf5SignatureOffset(path).has_value(); }

/// The superblock's version (the byte after the signature), -1 if unreadable. Versions 0
/// and 1 carry no checksums (HDF5's format before 1.8, as earlier moorsim versions wrote
/// it); version 2 checksums the superblock and the object headers but not the v1 B-trees
/// that index chunked datasets; version 3 (1.10's) checksums every index.
int SuperblockVersion(const std::string& path, std::uintmax_t signature_offset) {
  std::ifstream in(path, std::ios::binary);
  char version = 0;
  if (!in.seekg(static_cast<std::streamoff>(signature_offset + 8)).read(&version, 1)) return -1;
  return static_cast<unsigned char>(version);
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

namespace {

// Reads every attribute of the object `object_path` (what HDF5 can crash on in a damaged
// file without checksums; the values are not kept).
void ReadEveryAttribute(const Hdf5Reader& reader, hid_t file, const std::string& object_path) {
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  hsize_t index = 0;
  H5Aiterate_by_name(file, object_path.c_str(), H5_INDEX_NAME, H5_ITER_NATIVE, &index, collect,
                     &names, H5P_DEFAULT);
  for (const std::string& name : names) {
    try {
      reader.StringAttribute(object_path, name);
    } catch (const InputError&) {
      try {
        reader.NumberAttribute(object_path, name);
      } catch (const InputError&) {
      }
    }
  }
}

}  // namespace

void Hdf5Reader::ReadWhole() const {
  const hid_t file = static_cast<hid_t>(file_);
  ReadEveryAttribute(*this, file, "/");
  for (const DatasetInfo& dataset : ListDatasets()) {
    ReadEveryAttribute(*this, file, dataset.path);
    try {
      if (dataset.element == ElementClass::kString) {
        ReadStrings(dataset.path);
      } else if (dataset.element != ElementClass::kOther) {
        ReadArray(dataset.path);
      }
    } catch (const InputError&) {
    }
  }
}

namespace {

// A file whose indexes are not all checksummed is read whole once in a child process before
// this process reads it: damage in its heaps or B-trees can crash HDF5 itself or send it
// into an endless loop,
// and a child that dies, or has not finished in 10 s plus a second per 20 MB, is then
// reported as damage instead. Each file (as it is: device, inode, size, modification
// time) once per process.
void CheckInAChildProcess(const std::string& path) {
  static std::mutex mutex;
  static std::set<std::string> checked;
  const std::lock_guard<std::mutex> guard(mutex);
  std::error_code error;
  // The file as it is now: a file rewritten at the same path is checked again.
  struct stat file {};
  if (::stat(path.c_str(), &file) != 0) return;  // HDF5's open then says what is wrong
  const std::string key = std::to_string(file.st_dev) + ":" + std::to_string(file.st_ino) + ":" +
                          std::to_string(file.st_size) + ":" + std::to_string(file.st_mtim.tv_sec) +
                          "." + std::to_string(file.st_mtim.tv_nsec);
  if (checked.count(key) > 0) return;
  const pid_t child = ::fork();
  if (child < 0) return;  // no process to spare: read it here, as any HDF5 tool would
  if (child == 0) {
    try {
      const Hdf5Reader reader(path, Hdf5Reader::kInThisProcess);
      reader.ReadWhole();
    } catch (...) {
    }
    ::_exit(0);  // no exit handlers: the parent's buffers and HDF5's state are the parent's
  }
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  const auto limit = std::chrono::seconds(10 + (error ? 0 : bytes / 20'000'000));
  const auto deadline = std::chrono::steady_clock::now() + limit;
  int status = 0;
  pid_t done = 0;
  while ((done = ::waitpid(child, &status, WNOHANG)) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      throw InputError(path + ": damaged HDF5 file (HDF5 did not finish reading it in " +
                       std::to_string(limit.count()) + " s)");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  // The child ends with 0 whatever it read; anything else is a crash (a sanitizer's runtime
  // reports one with an exit status).
  if (done == child && (WIFSIGNALED(status) || WEXITSTATUS(status) != 0)) {
    const std::string how = WIFSIGNALED(status)
                                ? std::string(strsignal(WTERMSIG(status)))
                                : "exit status " + std::to_string(WEXITSTATUS(status));
    throw InputError(path + ": damaged HDF5 file (HDF5 crashed reading it: " + how + ")");
  }
  checked.insert(key);
}

}  // namespace

bool LooksLikeHdf5(const std::string& path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  return extension == ".h5" || extension == ".hdf5" || HasHdf5Signature(path);
}

Hdf5Reader::Hdf5Reader(const std::string& path) : Hdf5Reader(path, kAfterACheck) {}

Hdf5Reader::Hdf5Reader(const std::string& path, Check check) : path_(path) {
  internal::PrepareHdf5();
  std::error_code error;
  file_bytes_ = std::filesystem::file_size(path, error);
  if (file_bytes_ == 0 && !error) throw InputError(path + ": empty (0 bytes), not an HDF5 file");
  const std::optional<std::uintmax_t> signature = Hdf5SignatureOffset(path);
  if (!signature) throw InputError(path + ": damaged or not an HDF5 file (no HDF5 signature)");
  if (check == kAfterACheck && SuperblockVersion(path, *signature) < 3) {
    CheckInAChildProcess(path);
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
  if (H5Tget_class(a.type.get()) != H5T_STRING) throw InputError(where + ": not a string");
  if (H5Tis_variable_str(a.type.get()) <= 0) {
    const Handle memory{FixedStringMemoryType(a.type.get()), H5Tclose};
    std::vector<char> text(std::max<std::size_t>(H5Tget_size(a.type.get()), 1));
    if (H5Aread(attribute.get(), memory.get(), text.data()) < 0) {
      throw InputError(where + ": unreadable");
    }
    return FixedStringValue(text.data(), text.size());
  }
  Handle memory{H5Tcopy(H5T_C_S1), H5Tclose};
  H5Tset_size(memory.get(), H5T_VARIABLE);
  H5Tset_cset(memory.get(), H5T_CSET_UTF8);
  char* text = nullptr;
  if (H5Aread(attribute.get(), memory.get(), &text) < 0) throw InputError(where + ": unreadable");
  std::string value = text == nullptr ? std::string() : std::string(text);
  H5free_memory(text);
  return value;
}

double Hdf5Reader::NumberAttribute(const std::string& object_path, const std::string& name) const {
  const std::string where = path_ + ": " + object_path + " attribute '" + name + "'";
  const Attribute a(static_cast<hid_t>(file_), object_path, name, where);
  const Handle& attribute = a.attribute;
  const H5T_class_t kind = H5Tget_class(a.type.get());
  if (kind != H5T_FLOAT && kind != H5T_INTEGER) throw InputError(where + ": not a number");
  const Handle space{H5Aget_space(attribute.get()), H5Sclose};
  if (space.get() < 0 || H5Sget_simple_extent_npoints(space.get()) != 1) {
    throw InputError(where + ": not one number");
  }
  double value = 0.0;
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) {
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
        type(dataset.get() >= 0 ? H5Dget_type(dataset.get()) : -1, H5Tclose),
        space(dataset.get() >= 0 ? H5Dget_space(dataset.get()) : -1, H5Sclose),
        where_(reader.path() + ": " + path) {
    if (!reader.Has(path)) throw InputError(where_ + ": missing");
    if (dataset.get() < 0) throw InputError(where_ + ": not a dataset");
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) throw InputError(where_ + ": unreadable dataspace");
    dims.resize(static_cast<std::size_t>(rank));
    if (rank > 0 && H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
      throw InputError(where_ + ": unreadable dataspace");
    }
    // Deflate packs at most 1032 bytes into one: a dataset beyond that (a damaged
    // dimension) is refused before its memory is asked for. Elements are read as at most
    // 8 bytes or as stored.
    const std::uintmax_t element = std::max<std::size_t>(H5Tget_size(type.get()), 1);
    const std::uintmax_t most = 1032 * std::max<std::uintmax_t>(reader.file_bytes(), 1) / element;
    for (const hsize_t d : dims) {
      if (d != 0 && count_ > most / d) {
        throw InputError(where_ + ": more elements than a file of " +
                         std::to_string(reader.file_bytes()) + " bytes holds (damaged)");
      }
      count_ *= d;
    }
    CheckChunkIndex(reader.file_bytes());
  }

  /// The number of elements.
  std::size_t Count() const { return count_; }

  bool Numeric() const {
    const H5T_class_t kind = H5Tget_class(type.get());
    return kind == H5T_FLOAT || kind == H5T_INTEGER;
  }

  /// A chunked dataset's index (a B-tree without checksums in HDF5's formats before 1.10):
  /// every chunk the dimensions need is there once, at its own place, within the file. A
  /// damaged index otherwise reads as fill values (zeros) or as another chunk's rows.
  void CheckChunkIndex(std::uintmax_t file_bytes) const {
    const Handle creation{H5Dget_create_plist(dataset.get()), H5Pclose};
    if (creation.get() < 0 || H5Pget_layout(creation.get()) != H5D_CHUNKED || count_ == 0) return;
    const int rank = static_cast<int>(dims.size());
    std::vector<hsize_t> chunk(dims.size());
    if (H5Pget_chunk(creation.get(), rank, chunk.data()) != rank) {
      throw InputError(where_ + ": unreadable chunk layout (damaged)");
    }
    std::uintmax_t expected = 1;
    for (std::size_t k = 0; k < dims.size(); ++k) {
      if (chunk[k] == 0) throw InputError(where_ + ": unreadable chunk layout (damaged)");
      expected *= (dims[k] + chunk[k] - 1) / chunk[k];
    }
    hsize_t chunks = 0;
    if (H5Dget_num_chunks(dataset.get(), space.get(), &chunks) < 0 || chunks != expected) {
      throw InputError(where_ + ": " + std::to_string(chunks) + " chunks where its " +
                       std::to_string(expected) + " are needed (damaged)");
    }
    std::set<std::vector<hsize_t>> seen;
    std::vector<hsize_t> offset(dims.size());
    for (hsize_t i = 0; i < chunks; ++i) {
      unsigned filter_mask = 0;
      haddr_t address = 0;
      hsize_t size = 0;
      bool good = H5Dget_chunk_info(dataset.get(), space.get(), i, offset.data(), &filter_mask,
                                    &address, &size) >= 0 &&
                  size > 0 && address + size <= file_bytes;
      for (std::size_t k = 0; good && k < dims.size(); ++k) {
        good = offset[k] % chunk[k] == 0 && offset[k] < dims[k];
      }
      if (!good || !seen.insert(offset).second) {
        throw InputError(where_ + ": chunk " + std::to_string(i) + " misplaced (damaged)");
      }
    }
  }

  /// Reads every element converted to `memory_type` into `out` (Count() elements).
  void Read(hid_t memory_type, void* out) const {
    if (Count() > 0 &&
        H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out) < 0) {
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
  if (H5Tget_class(d.type.get()) != H5T_STRING) throw InputError(where + ": not a string dataset");
  const std::size_t n = d.Count();
  std::vector<std::string> values;
  values.reserve(n);
  if (H5Tis_variable_str(d.type.get()) > 0) {
    const Handle memory{H5Tcopy(H5T_C_S1), H5Tclose};
    H5Tset_size(memory.get(), H5T_VARIABLE);
    H5Tset_cset(memory.get(), H5Tget_cset(d.type.get()));
    std::vector<char*> texts(n, nullptr);
    d.Read(memory.get(), texts.data());
    for (char* text : texts) {
      values.emplace_back(text == nullptr ? "" : text);
      H5free_memory(text);
    }
    return values;
  }
  const std::size_t size = H5Tget_size(d.type.get());
  std::vector<char> buffer(n * size);
  const Handle memory{FixedStringMemoryType(d.type.get()), H5Tclose};
  d.Read(memory.get(), buffer.data());
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
    if (object.get() < 0 && hard)
      throw InputError(path_ + ": " + name + ": damaged (cannot be opened)");
    if (object.get() < 0 || H5Iget_type(object.get()) != H5I_DATASET) continue;
    const Dataset d(*this, static_cast<hid_t>(file_), name);
    DatasetInfo info;
    info.path = name;
    info.dims.assign(d.dims.begin(), d.dims.end());
    switch (H5Tget_class(d.type.get())) {
      case H5T_FLOAT:
        info.element = ElementClass::kFloat;
        break;
      case H5T_INTEGER:
        info.element = H5Tget_sign(d.type.get()) == H5T_SGN_NONE ? ElementClass::kUnsignedInteger
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
