#include "tools/output/hdf5_reader.h"

#include <hdf5.h>

#include <cstdlib>

#include "core/error.h"

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

Hdf5Reader::Hdf5Reader(const std::string& path) : path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    throw InputError(path + ": not a readable HDF5 file");
  }
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) throw InputError(path + ": cannot open it as an HDF5 file");
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
  if (H5Tget_class(a.type.id) != H5T_STRING || H5Tis_variable_str(a.type.id) <= 0) {
    throw InputError(where + ": not a variable-length string");
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

TableData Hdf5Reader::ReadTable(const std::string& dataset_path) const {
  const std::string where = path_ + ": " + dataset_path;
  if (!Has(dataset_path)) throw InputError(where + ": missing");
  Handle dataset{H5Dopen2(static_cast<hid_t>(file_), dataset_path.c_str(), H5P_DEFAULT), H5Dclose};
  if (dataset.id < 0) throw InputError(where + ": not a dataset");
  Handle space{H5Dget_space(dataset.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  if (rank != 1 && rank != 2) throw InputError(where + ": not a one- or two-dimensional table");
  hsize_t dims[2] = {0, 1};
  H5Sget_simple_extent_dims(space.id, dims, nullptr);
  TableData table;
  table.rows = dims[0];
  table.columns = rank == 2 ? dims[1] : 1;
  table.values.resize(table.rows * table.columns);
  if (!table.values.empty() && H5Dread(dataset.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT,
                                       table.values.data()) < 0) {
    throw InputError(where + ": unreadable (damaged, or a filter this HDF5 lacks)");
  }
  return table;
}

}  // namespace moorsim::output
