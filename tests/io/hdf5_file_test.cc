// Tests of the run.h5 writer (io/hdf5_file.h). Every file is read back through
// the HDF5 C API, not through the writer, and values are compared bit for bit: the writer
// only moves bytes, so any difference is a bug, not rounding.
#include "io/hdf5_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <hdf5.h>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/hdf5_library.h"

namespace moorsim::output {
namespace {

using ::testing::HasSubstr;

/// Owns an identifier of the reading side.
using Id = internal::Handle;

/// A file in a directory of this test process (ctest runs tests in parallel, and the
/// release and sanitizer builds may run at once), removed when the test ends.
class TempFile {
 public:
  explicit TempFile(const std::string& name) {
    const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                                      ("moorsim_hdf5_file_test_" + std::to_string(getpid()));
    std::filesystem::create_directories(dir);
    path_ = (dir / name).string();
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    std::error_code ignored;
    const std::filesystem::path file(path_);
    std::filesystem::remove(file, ignored);
    std::filesystem::remove(file.parent_path(), ignored);  // only if it is empty
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

Id OpenForReading(const std::string& path) {
  return Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
}

std::vector<hsize_t> Dims(hid_t file, const std::string& dataset_path) {
  Id dataset(H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
  EXPECT_GE(dataset.get(), 0) << dataset_path;
  Id space(H5Dget_space(dataset.get()), H5Sclose);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

template <typename T>
std::vector<T> ReadAll(hid_t file, const std::string& dataset_path, hid_t memory_type) {
  hsize_t count = 1;
  for (const hsize_t d : Dims(file, dataset_path)) count *= d;
  std::vector<T> values(count);
  Id dataset(H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
  if (count > 0) {
    EXPECT_GE(H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  }
  return values;
}

bool HasFileType(hid_t file, const std::string& dataset_path, hid_t expected) {
  Id dataset(H5Dopen2(file, dataset_path.c_str(), H5P_DEFAULT), H5Dclose);
  Id type(H5Dget_type(dataset.get()), H5Tclose);
  return H5Tequal(type.get(), expected) > 0;
}

std::string StringAttribute(hid_t file, const std::string& object_path, const std::string& name) {
  Id attribute(H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
               H5Aclose);
  EXPECT_GE(attribute.get(), 0) << object_path << " " << name;
  Id type(H5Aget_type(attribute.get()), H5Tclose);
  EXPECT_EQ(H5Tget_class(type.get()), H5T_STRING);
  // Fixed-length (stored in the object's header), its size the text's plus the final NUL.
  EXPECT_EQ(H5Tis_variable_str(type.get()), 0);
  EXPECT_EQ(H5Tget_strpad(type.get()), H5T_STR_NULLTERM);
  EXPECT_EQ(H5Tget_cset(type.get()), H5T_CSET_UTF8);
  std::string text(H5Tget_size(type.get()), '\0');
  EXPECT_GE(H5Aread(attribute.get(), type.get(), text.data()), 0);
  EXPECT_EQ(text.back(), '\0');
  return text.substr(0, text.find('\0'));
}

template <typename T>
T NumberAttribute(hid_t file, const std::string& object_path, const std::string& name,
                  hid_t file_type, hid_t memory_type) {
  Id attribute(H5Aopen_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
               H5Aclose);
  EXPECT_GE(attribute.get(), 0) << object_path << " " << name;
  Id type(H5Aget_type(attribute.get()), H5Tclose);
  EXPECT_GT(H5Tequal(type.get(), file_type), 0);
  T value{};
  EXPECT_GE(H5Aread(attribute.get(), memory_type, &value), 0);
  return value;
}

bool HasAttribute(hid_t file, const std::string& object_path, const std::string& name) {
  return H5Aexists_by_name(file, object_path.c_str(), name.c_str(), H5P_DEFAULT) > 0;
}

std::string FileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Row r, column c of the 2-D test signal: smooth values, plus the IEEE special cases in
/// the first row (the shuffle and gzip filters must not touch a single bit of them).
double Value(std::size_t row, std::size_t column) {
  if (row == 0) {
    constexpr std::array<double, 6> kSpecial = {
        std::numeric_limits<double>::quiet_NaN(),  -0.0,
        std::numeric_limits<double>::infinity(),   -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max()};
    return kSpecial[column % kSpecial.size()];
  }
  return std::sin(0.01 * static_cast<double>(row) + static_cast<double>(column)) *
         std::pow(10.0, static_cast<double>(column) - 3.0);
}

std::vector<std::uint64_t> Bits(const std::vector<double>& values) {
  std::vector<std::uint64_t> bits;
  for (const double v : values) bits.push_back(std::bit_cast<std::uint64_t>(v));
  return bits;
}

constexpr std::size_t kColumns = 6;

/// A file with a 2-D float table, 1-D float and int8 tables and attributes, all from fixed
/// data, so two calls give the same logical content.
void WriteReferenceFile(const std::string& path, std::size_t rows, std::size_t chunk_rows) {
  Hdf5File file(path, Hdf5FileOptions{.chunk_rows = chunk_rows});
  file.SetAttribute("/", "scenario_name", std::string("reference"));
  file.SetAttribute("/", "seed", std::int64_t{42});
  file.SetAttribute("/", "failure_time", std::numeric_limits<double>::quiet_NaN());
  const TableId time = file.CreateTable("/time", 0, "s");
  const TableId pose = file.CreateTable("/vessel/pose_true", kColumns, "m,m,m,rad,rad,rad",
                                        {"x", "y", "z", "phi", "theta", "psi"});
  const TableId decision = file.CreateTable("/detectors/glr/decision", 0, "", {}, TableType::kInt8);
  std::vector<double> row(kColumns);
  for (std::size_t r = 0; r < rows; ++r) {
    file.Append(time, 0.1 * static_cast<double>(r));
    for (std::size_t c = 0; c < kColumns; ++c) row[c] = Value(r, c);
    file.Append(pose, row);
    file.Append(decision, static_cast<std::int32_t>(r % 9));
  }
  file.Close();
}

TEST(Hdf5File, TablesLongerThanAChunkReadBackBitExactly) {
  // 2.5 chunks, so the file holds two whole chunks and one partial one.
  const TempFile temp("tables.h5");
  const std::string& path = temp.path();
  constexpr std::size_t kChunk = 16;
  constexpr std::size_t kRows = 40;
  WriteReferenceFile(path, kRows, kChunk);

  const Id file = OpenForReading(path);
  EXPECT_EQ(Dims(file.get(), "/time"), (std::vector<hsize_t>{kRows}));
  EXPECT_EQ(Dims(file.get(), "/vessel/pose_true"), (std::vector<hsize_t>{kRows, kColumns}));
  EXPECT_EQ(Dims(file.get(), "/detectors/glr/decision"), (std::vector<hsize_t>{kRows}));
  EXPECT_TRUE(HasFileType(file.get(), "/time", H5T_IEEE_F64LE));
  EXPECT_TRUE(HasFileType(file.get(), "/vessel/pose_true", H5T_IEEE_F64LE));
  EXPECT_TRUE(HasFileType(file.get(), "/detectors/glr/decision", H5T_STD_I8LE));

  std::vector<double> expected_time;
  std::vector<double> expected_pose;
  std::vector<std::int32_t> expected_decision;
  for (std::size_t r = 0; r < kRows; ++r) {
    expected_time.push_back(0.1 * static_cast<double>(r));
    for (std::size_t c = 0; c < kColumns; ++c) expected_pose.push_back(Value(r, c));
    expected_decision.push_back(static_cast<std::int32_t>(r % 9));
  }
  EXPECT_EQ(Bits(ReadAll<double>(file.get(), "/time", H5T_NATIVE_DOUBLE)), Bits(expected_time));
  EXPECT_EQ(Bits(ReadAll<double>(file.get(), "/vessel/pose_true", H5T_NATIVE_DOUBLE)),
            Bits(expected_pose));
  EXPECT_EQ(ReadAll<std::int32_t>(file.get(), "/detectors/glr/decision", H5T_NATIVE_INT32),
            expected_decision);
}

TEST(Hdf5File, DefaultChunkIsCompressedAndRowCountIsExact) {
  const TempFile temp("default_chunk.h5");
  const std::string& path = temp.path();
  constexpr std::size_t kRows = 2500;  // 2 chunks of 1024 and 452 rows
  {
    Hdf5File file(path);
    const TableId tension = file.CreateTable("/mooring/fairlead_tension", 3, "N");
    for (std::size_t r = 0; r < kRows; ++r) {
      const std::array<double, 3> row = {1e6 + static_cast<double>(r), 2e6,
                                         -static_cast<double>(r)};
      file.Append(tension, row);
      EXPECT_EQ(file.RowCount(tension), r + 1);
    }
  }  // the destructor writes the last partial chunk and closes
  const Id file = OpenForReading(path);
  EXPECT_EQ(Dims(file.get(), "/mooring/fairlead_tension"), (std::vector<hsize_t>{kRows, 3}));
  const std::vector<double> values =
      ReadAll<double>(file.get(), "/mooring/fairlead_tension", H5T_NATIVE_DOUBLE);
  for (std::size_t r = 0; r < kRows; ++r) {
    ASSERT_EQ(values[3 * r], 1e6 + static_cast<double>(r)) << r;
    ASSERT_EQ(values[3 * r + 1], 2e6) << r;
    ASSERT_EQ(values[3 * r + 2], -static_cast<double>(r)) << r;
  }

  Id dataset(H5Dopen2(file.get(), "/mooring/fairlead_tension", H5P_DEFAULT), H5Dclose);
  Id creation(H5Dget_create_plist(dataset.get()), H5Pclose);
  std::array<hsize_t, 2> chunk{};
  ASSERT_EQ(H5Pget_chunk(creation.get(), 2, chunk.data()), 2);
  EXPECT_EQ(chunk[0], 1024u);
  EXPECT_EQ(chunk[1], 3u);
  ASSERT_EQ(H5Pget_nfilters(creation.get()), 2);  // shuffle, then deflate
  EXPECT_EQ(H5Pget_filter2(creation.get(), 0, nullptr, nullptr, nullptr, 0, nullptr, nullptr),
            H5Z_FILTER_SHUFFLE);
  EXPECT_EQ(H5Pget_filter2(creation.get(), 1, nullptr, nullptr, nullptr, 0, nullptr, nullptr),
            H5Z_FILTER_DEFLATE);
}

TEST(Hdf5File, UncompressedWhenGzipLevelIsZero) {
  const TempFile temp("uncompressed.h5");
  const std::string& path = temp.path();
  {
    Hdf5File file(path, Hdf5FileOptions{.gzip_level = 0});
    const TableId time = file.CreateTable("/time", 0, "s");
    file.Append(time, 1.5);
  }
  const Id file = OpenForReading(path);
  Id dataset(H5Dopen2(file.get(), "/time", H5P_DEFAULT), H5Dclose);
  Id creation(H5Dget_create_plist(dataset.get()), H5Pclose);
  EXPECT_EQ(H5Pget_nfilters(creation.get()), 0);
  EXPECT_EQ(ReadAll<double>(file.get(), "/time", H5T_NATIVE_DOUBLE), std::vector<double>{1.5});
}

TEST(Hdf5File, AttributesOfTablesGroupsAndFile) {
  const TempFile temp("attributes.h5");
  const std::string& path = temp.path();
  const std::string long_yaml(100'000, 'y');  // bigger than an object header (64 KiB)
  {
    Hdf5File file(path);
    file.CreateTable("/vessel/pose_true", 6, "m,m,m,rad,rad,rad",
                     {"x", "y", "z", "phi", "theta", "psi"});
    file.CreateTable("/time", 0, "s");
    file.SetAttribute("/", "scenario", long_yaml);
    file.SetAttribute("/", "scenario_name", std::string("thesis_line6 \xc3\xa6"));  // UTF-8
    file.SetAttribute("/", "version", std::string("0.1.0+abc"));
    file.SetAttribute("/", "seed", std::int64_t{-7});
    file.SetAttribute("/", "failure_line", std::int64_t{0});
    file.SetAttribute("/", "failure_time", 1234.5);
    file.SetAttribute("/", "failure_time", 600.25);  // replaces the first value
    file.SetAttribute("/vessel", "frame", std::string("NED"));
    file.SetAttribute("/vessel/pose_true", "sample_rate", 10.0);
    file.SetAttribute("/", "empty", std::string());
  }
  const Id file = OpenForReading(path);
  const hid_t f = file.get();
  EXPECT_EQ(StringAttribute(f, "/vessel/pose_true", "units"), "m,m,m,rad,rad,rad");
  EXPECT_EQ(StringAttribute(f, "/vessel/pose_true", "columns"), "x,y,z,phi,theta,psi");
  EXPECT_EQ(StringAttribute(f, "/time", "units"), "s");
  EXPECT_FALSE(HasAttribute(f, "/time", "columns"));
  EXPECT_EQ(StringAttribute(f, "/", "scenario"), long_yaml);
  EXPECT_EQ(StringAttribute(f, "/", "scenario_name"), "thesis_line6 \xc3\xa6");
  EXPECT_EQ(StringAttribute(f, "/", "version"), "0.1.0+abc");
  EXPECT_EQ(StringAttribute(f, "/", "empty"), "");
  EXPECT_EQ(StringAttribute(f, "/vessel", "frame"), "NED");
  EXPECT_EQ((NumberAttribute<std::int64_t>(f, "/", "seed", H5T_STD_I64LE, H5T_NATIVE_INT64)), -7);
  EXPECT_EQ(
      (NumberAttribute<std::int64_t>(f, "/", "failure_line", H5T_STD_I64LE, H5T_NATIVE_INT64)), 0);
  EXPECT_EQ((NumberAttribute<double>(f, "/", "failure_time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE)),
            600.25);
  EXPECT_EQ((NumberAttribute<double>(f, "/vessel/pose_true", "sample_rate", H5T_IEEE_F64LE,
                                     H5T_NATIVE_DOUBLE)),
            10.0);
}

TEST(Hdf5File, TheFormatChecksumsItsMetadata) {
  // HDF5 1.8's format: superblock version 2 and version-2 object headers, each with its
  // checksum, so that HDF5 refuses damaged metadata instead of reading it (and no
  // open-for-writing mark in the superblock, which 1.10's version 3 has: a killed writer's
  // file still opens).
  const TempFile temp("format.h5");
  {
    Hdf5File file(temp.path());
    file.CreateTable("/time", 0, "s");
  }
  const Id file = OpenForReading(temp.path());
  H5F_info2_t info{};
  ASSERT_GE(H5Fget_info2(file.get(), &info), 0);
  EXPECT_EQ(info.super.version, 2u);
  H5O_info_t object{};
  ASSERT_GE(H5Oget_info_by_name2(file.get(), "/time", &object, H5O_INFO_HDR, H5P_DEFAULT), 0);
  EXPECT_EQ(object.hdr.version, 2u);
}

TEST(Hdf5File, NestedGroupsAreCreatedOnce) {
  const TempFile temp("groups.h5");
  const std::string& path = temp.path();
  {
    Hdf5File file(path);
    file.CreateTable("/detectors/glr/score", 9, "-");
    file.CreateTable("/detectors/glr/decision", 0, "-", {}, TableType::kInt8);
    file.CreateGroup("/detectors/cusum");
    file.CreateGroup("/detectors/cusum");  // existing: no-op
    file.CreateTable("/detectors/cusum/alarm", 0, "-", {}, TableType::kInt8);
    file.CreateTable("/a/b/c/d", 2, "m");
  }
  const Id file = OpenForReading(path);
  for (const char* group :
       {"/detectors", "/detectors/glr", "/detectors/cusum", "/a", "/a/b", "/a/b/c"}) {
    Id object(H5Oopen(file.get(), group, H5P_DEFAULT), H5Oclose);
    EXPECT_EQ(H5Iget_type(object.get()), H5I_GROUP) << group;
  }
  EXPECT_EQ(Dims(file.get(), "/a/b/c/d"), (std::vector<hsize_t>{0, 2}));
  EXPECT_EQ(Dims(file.get(), "/detectors/glr/score"), (std::vector<hsize_t>{0, 9}));
}

TEST(Hdf5File, EmptyTablesHaveZeroRows) {
  const TempFile temp("empty.h5");
  const std::string& path = temp.path();
  {
    Hdf5File file(path);
    file.CreateTable("/time", 0, "s");
    file.CreateTable("/vessel/pose_measured", 3, "m,m,rad");
    file.CreateTable("/detectors/x/alarm", 0, "-", {}, TableType::kInt8);
    file.Flush();
  }
  const Id file = OpenForReading(path);
  EXPECT_EQ(Dims(file.get(), "/time"), (std::vector<hsize_t>{0}));
  EXPECT_EQ(Dims(file.get(), "/vessel/pose_measured"), (std::vector<hsize_t>{0, 3}));
  EXPECT_EQ(Dims(file.get(), "/detectors/x/alarm"), (std::vector<hsize_t>{0}));
  EXPECT_TRUE(ReadAll<double>(file.get(), "/vessel/pose_measured", H5T_NATIVE_DOUBLE).empty());
  EXPECT_EQ(StringAttribute(file.get(), "/vessel/pose_measured", "units"), "m,m,rad");
}

TEST(Hdf5File, FlushedPartialChunkIsCompletedLater) {
  // Flush writes a partial chunk; the rows after it must land behind it, not over it.
  const TempFile temp("flush.h5");
  const std::string& path = temp.path();
  std::vector<double> expected;
  {
    Hdf5File file(path, Hdf5FileOptions{.chunk_rows = 8});
    const TableId time = file.CreateTable("/time", 0, "s");
    for (int r = 0; r < 30; ++r) {
      file.Append(time, static_cast<double>(r));
      expected.push_back(static_cast<double>(r));
      if (r % 5 == 2) file.Flush();
    }
    file.Flush();
    file.Flush();  // nothing new: a no-op
    file.Close();
    file.Close();  // a second Close is a no-op
  }
  const Id file = OpenForReading(path);
  EXPECT_EQ(ReadAll<double>(file.get(), "/time", H5T_NATIVE_DOUBLE), expected);
}

TEST(Hdf5File, UnwritablePathThrowsNamingThePath) {
  const std::string path = "/nonexistent_moorsim_dir/sub/run.h5";
  try {
    Hdf5File file(path);
    FAIL() << "no exception";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr(path));
    EXPECT_THAT(error.what(), HasSubstr("H5Fcreate"));
  }
}

TEST(Hdf5File, BadRowsThrowAndLeaveTheTableUsable) {
  const TempFile temp("bad_rows.h5");
  const std::string& path = temp.path();
  Hdf5File file(path);
  const TableId pose = file.CreateTable("/vessel/pose_measured", 3, "m,m,rad");
  const TableId time = file.CreateTable("/time", 0, "s");
  const TableId alarm = file.CreateTable("/detectors/glr/alarm", 0, "-", {}, TableType::kInt8);

  const std::array<double, 2> two = {1.0, 2.0};
  const std::array<double, 4> four = {1.0, 2.0, 3.0, 4.0};
  const std::array<double, 3> three = {1.0, 2.0, 3.0};
  EXPECT_THROW(file.Append(pose, two), Error);
  EXPECT_THROW(file.Append(pose, four), Error);
  EXPECT_THROW(file.Append(time, three), Error);
  try {
    file.Append(pose, two);
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("/vessel/pose_measured"));
    EXPECT_THAT(error.what(), HasSubstr("row of 2 values, table has 3 columns"));
  }
  EXPECT_THROW(file.Append(pose, std::array<std::int32_t, 3>{1, 2, 3}), Error);  // int -> float
  EXPECT_THROW(file.Append(alarm, 1.0), Error);                                  // float -> int
  EXPECT_THROW(file.Append(alarm, std::int32_t{128}), Error);                    // int8 range
  EXPECT_THROW(file.Append(TableId{99}, 1.0), Error);
  EXPECT_EQ(file.RowCount(pose), 0u);
  EXPECT_EQ(file.RowCount(alarm), 0u);

  file.Append(pose, three);
  file.Append(alarm, std::int32_t{-128});
  EXPECT_EQ(file.RowCount(pose), 1u);
  EXPECT_EQ(file.RowCount(alarm), 1u);
  file.Close();
  EXPECT_THROW(file.Append(pose, three), Error);
  EXPECT_THROW(file.SetAttribute("/", "x", 1.0), Error);
}

TEST(Hdf5File, BadTableDefinitionsThrow) {
  const TempFile temp("bad_tables.h5");
  Hdf5File file(temp.path());
  file.CreateTable("/vessel/pose_true", 6, "m");
  EXPECT_THROW(file.CreateTable("/vessel/pose_true", 6, "m"), Error);    // exists
  EXPECT_THROW(file.CreateTable("/vessel/pose_true/x", 1, "m"), Error);  // parent is a table
  EXPECT_THROW(file.CreateTable("relative", 1, "m"), Error);
  EXPECT_THROW(file.CreateTable("/a//b", 1, "m"), Error);
  EXPECT_THROW(file.CreateTable("/a/", 1, "m"), Error);
  EXPECT_THROW(file.CreateTable("/neg", -1, "m"), Error);
  EXPECT_THROW(file.CreateTable("/names", 2, "m", {"x"}), Error);
  EXPECT_THROW(file.CreateTable("/comma", 2, "m", {"x,1", "y"}), Error);
  EXPECT_THROW(file.SetAttribute("/missing", "a", 1.0), Error);
  try {
    file.SetAttribute("/missing/deeper", "a", 1.0);
    FAIL() << "no exception";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("/missing/deeper: no such group or table"));
  }
}

TEST(Hdf5File, SameDataGivesByteIdenticalFiles) {
  // No creation or modification times are stored, so the whole file repeats, not only
  // the datasets.
  const TempFile temp_first("repeat_1.h5");
  const std::string& first = temp_first.path();
  const TempFile temp_second("repeat_2.h5");
  const std::string& second = temp_second.path();
  WriteReferenceFile(first, 3000, 1024);
  WriteReferenceFile(second, 3000, 1024);
  const std::string first_bytes = FileBytes(first);
  ASSERT_FALSE(first_bytes.empty());
  EXPECT_TRUE(first_bytes == FileBytes(second));

  // Two writes within the same second would repeat even with times stored, so check the
  // cause too: HDF5 reports 0 for every time of an object that does not track them.
  const Id file = OpenForReading(first);
  for (const char* object : {"/", "/time", "/vessel", "/vessel/pose_true", "/detectors",
                             "/detectors/glr", "/detectors/glr/decision"}) {
    H5O_info_t info{};
    ASSERT_GE(H5Oget_info_by_name2(file.get(), object, &info, H5O_INFO_TIME, H5P_DEFAULT), 0);
    EXPECT_EQ(info.ctime, 0) << object;
    EXPECT_EQ(info.mtime, 0) << object;
    EXPECT_EQ(info.atime, 0) << object;
    EXPECT_EQ(info.btime, 0) << object;
  }
}

/// Writes a float table into `path` under a 64 KiB file-size limit, which makes a chunk
/// write fail as a full disk would. Returns 0 if the failure is reported as it should be.
int WriteUntilTheFileIsTooLarge(const std::string& path) {
  std::signal(SIGXFSZ, SIG_IGN);  // write() then fails with EFBIG instead of killing us
  const rlimit limit{64 * 1024, 64 * 1024};
  if (setrlimit(RLIMIT_FSIZE, &limit) != 0) return 10;
  Hdf5File file(path, Hdf5FileOptions{.gzip_level = 0});
  const TableId time = file.CreateTable("/time", 0, "s");
  std::size_t accepted = 0;
  try {
    for (; accepted < 100'000; ++accepted) file.Append(time, static_cast<double>(accepted));
    return 11;  // never failed
  } catch (const Error& error) {
    const std::string message = error.what();
    std::cerr << message << '\n';
    if (message.find(path + ": /time: H5Dwrite failed") == std::string::npos) return 12;
    if (message.find("File too large") == std::string::npos) return 13;
    if (message.find('\n') != std::string::npos) return 14;
  }
  // The row whose chunk could not be written was not taken; the rows before it were.
  if (accepted % 1024 != 1023 || file.RowCount(time) != accepted) return 15;
  try {
    file.Close();
    return 16;
  } catch (const Error&) {
  }
  return 0;
}

TEST(Hdf5FileDeathTest, FailedWriteIsReported) {
  // In a child process that ends with _Exit: after a failed H5Fclose, HDF5 1.10 crashes in
  // its exit handler (CVE-2020-10812, HDFGroup/hdf5#2257; fixed in HDF5 1.14.1).
  const TempFile temp("too_large.h5");
  const std::string& path = temp.path();
  EXPECT_EXIT(std::_Exit(WriteUntilTheFileIsTooLarge(path)), ::testing::ExitedWithCode(0), "");
}

constexpr int kDurableRows = 1030;
constexpr int kDurableFlushEvery = 37;

/// Writes /time (0, 1, 2, ...) and /pose in chunks of 16 rows with durable flushes every 37
/// rows: the last at row 999, after which 31 rows more complete two chunks (written to the
/// file, their index and the tables' extent only to the metadata cache); then it is killed
/// outright.
[[noreturn]] void WriteDurablyAndDie(const std::string& path) {
  Hdf5File file(path, Hdf5FileOptions{.chunk_rows = 16, .durable_flushes = true});
  const TableId time = file.CreateTable("/time", 0, "s");
  const TableId pose = file.CreateTable("/pose", 3, "m,m,rad");
  for (int k = 0; k < kDurableRows; ++k) {
    file.Append(time, static_cast<double>(k));
    file.Append(pose, std::vector<double>{1.0 * k, 2.0 * k, 3.0 * k});
    if ((k + 1) % kDurableFlushEvery == 0) file.Flush();
  }
  std::raise(SIGKILL);
  std::abort();
}

TEST(Hdf5FileDeathTest, ADurableFileKilledOutrightHoldsTheRowsOfItsLastFlush) {
  const TempFile temp("durable.h5");
  const std::string& path = temp.path();
  EXPECT_EXIT(WriteDurablyAndDie(path), ::testing::KilledBySignal(SIGKILL), "");
  const Id file = OpenForReading(path);
  std::vector<double> expected(kDurableRows / kDurableFlushEvery * kDurableFlushEvery);
  for (std::size_t k = 0; k < expected.size(); ++k) expected[k] = static_cast<double>(k);
  EXPECT_EQ(ReadAll<double>(file.get(), "/time", H5T_NATIVE_DOUBLE), expected);
  EXPECT_EQ(ReadAll<double>(file.get(), "/pose", H5T_NATIVE_DOUBLE).size(), 3 * expected.size());
}

TEST(Hdf5File, MovedFileKeepsWriting) {
  const TempFile temp("moved.h5");
  const std::string& path = temp.path();
  {
    Hdf5File original(path);
    const TableId time = original.CreateTable("/time", 0, "s");
    original.Append(time, 1.0);
    Hdf5File moved(std::move(original));
    moved.Append(time, 2.0);
    EXPECT_EQ(moved.path(), path);
  }
  const Id file = OpenForReading(path);
  EXPECT_EQ(ReadAll<double>(file.get(), "/time", H5T_NATIVE_DOUBLE),
            (std::vector<double>{1.0, 2.0}));
}

}  // namespace
}  // namespace moorsim::output
