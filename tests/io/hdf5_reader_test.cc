// Tests of the HDF5 reader (io/hdf5_reader.h) on what the writer gives and on what
// damage makes of it: string attributes of the current (fixed-length) and earlier
// (variable-length) files, flipped bits in the file's metadata, a damaged dimension.
#include "io/hdf5_reader.h"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "io/hdf5_file.h"
#include "tests/support/sanitized.h"
#include "tests/support/scratch_directory.h"

namespace moorsim::output {
namespace {

class Hdf5ReaderTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = moorsim::testing::FreshDirectory("hdf5_reader_test"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

std::string Bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST_F(Hdf5ReaderTest, ReadsStringAttributesOfTheWriterAndOfEarlierFiles) {
  const std::string path = Path("strings.h5");
  {
    Hdf5File file(path);
    file.SetAttribute("/", "scenario", std::string("mooring: {lines: []}\n"));
    file.SetAttribute("/", "empty", std::string());
    file.Close();
  }
  {
    // Earlier versions wrote variable-length strings: still read.
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, H5T_VARIABLE);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const hid_t space = H5Screate(H5S_SCALAR);
    const hid_t attribute = H5Acreate2(file, "overrides", type, space, H5P_DEFAULT, H5P_DEFAULT);
    const char* text = "simulation.duration=30";
    EXPECT_GE(H5Awrite(attribute, type, &text), 0);
    H5Aclose(attribute);
    H5Sclose(space);
    H5Tclose(type);
    H5Fclose(file);
  }
  const Hdf5Reader reader(path);
  EXPECT_EQ(reader.StringAttribute("/", "scenario"), "mooring: {lines: []}\n");
  EXPECT_EQ(reader.StringAttribute("/", "empty"), "");
  EXPECT_EQ(reader.StringAttribute("/", "overrides"), "simulation.duration=30");
}

TEST_F(Hdf5ReaderTest, EveryFlippedBitOfTheRootHeaderIsRefusedOrChangesNothing) {
  // The root group's header holds the attributes (the scenario's text, or in the format
  // of earlier versions its reference into the global heap) within the file's first
  // kilobyte. Each of those bytes with one bit flipped (bit 0 of byte 0, bit 1 of byte 1,
  // ...): the read either
  // fails with an InputError naming the file or gives the values written, never other
  // values, and never crashes (HDF5 1.10's reader crashed on a damaged reference into the
  // global heap, where variable-length strings lived).
  const std::string original_path = Path("original.h5");
  {
    Hdf5File file(original_path);
    file.SetAttribute("/", "scenario", std::string("failure: {line: 6, time: 400}\n"));
    file.SetAttribute("/", "scenario_path", std::string("scenarios/library/thesis_line6.yaml"));
    const TableId time = file.CreateTable("/time", 0, "s");
    for (int t = 0; t < 4; ++t) file.Append(time, static_cast<double>(t));
    file.Close();
  }
  const std::string original = Bytes(original_path);
  const std::string path = Path("flipped.h5");
  int refused = 0;
  const std::size_t bytes = std::min<std::size_t>(original.size(), 1024);
  // Every byte; every fourth under the sanitizers.
  const std::size_t stride = moorsim::testing::CaseCount(1, 4);
  for (std::size_t byte = 0; byte < bytes; byte += stride) {
    const std::size_t bit = 8 * byte + byte % 8;
    std::string damaged = original;
    damaged[byte] ^= static_cast<char>(1u << (byte % 8));
    WriteBytes(path, damaged);
    try {
      const Hdf5Reader reader(path);
      EXPECT_EQ(reader.StringAttribute("/", "scenario"), "failure: {line: 6, time: 400}\n")
          << "bit " << bit;
      EXPECT_EQ(reader.StringAttribute("/", "scenario_path"), "scenarios/library/thesis_line6.yaml")
          << "bit " << bit;
      EXPECT_EQ(reader.ReadTable("/time").values, (std::vector<double>{0, 1, 2, 3}))
          << "bit " << bit;
    } catch (const InputError& error) {
      ++refused;
      EXPECT_EQ(std::string(error.what()).rfind(path + ": ", 0), 0u) << error.what();
    }
  }
  // Most of them are checksummed metadata.
  EXPECT_GT(refused, static_cast<int>(bytes / stride) / 2);
}

TEST_F(Hdf5ReaderTest, ADimensionBeyondWhatTheFileHoldsIsRefusedBeforeReading) {
  // A chunked dataset of 2^40 rows that holds no chunk: what a damaged dimension looks
  // like. Reading it would ask for 8 TiB.
  const std::string path = Path("huge.h5");
  {
    const hid_t file = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hsize_t dims[1] = {hsize_t{1} << 40};
    const hsize_t chunk[1] = {1024};
    const hid_t space = H5Screate_simple(1, dims, nullptr);
    const hid_t creation = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_chunk(creation, 1, chunk);
    const hid_t dataset =
        H5Dcreate2(file, "/time", H5T_IEEE_F64LE, space, H5P_DEFAULT, creation, H5P_DEFAULT);
    ASSERT_GE(dataset, 0);
    H5Dclose(dataset);
    H5Pclose(creation);
    H5Sclose(space);
    H5Fclose(file);
  }
  const Hdf5Reader reader(path);
  try {
    reader.ReadTable("/time");
    FAIL() << "read";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), path + ": /time: more elements than a file of " +
                                             std::to_string(std::filesystem::file_size(path)) +
                                             " bytes holds (damaged)");
  }
}

// A file without checksums (as earlier versions wrote them): a damaged size in its global
// heap, where its text attributes live, sends HDF5 reading it into a crash or an endless
// loop. The reader reads such a file in a child process first, and refuses it instead.
// (moorsim's own files keep their text attributes in checksummed object headers.)
TEST_F(Hdf5ReaderTest, DamageThatCrashesOrHangsHdf5InAFileWithoutChecksumsIsRefused) {
  const std::string golden = Bytes(MOORSIM_SOURCE_DIR "/tests/data/golden/seed_tapm_line6_run.h5");
  ASSERT_EQ(golden[8], '\0') << "the golden file is in the format without checksums";
  const std::size_t heap = golden.find("GCOL");
  ASSERT_NE(heap, std::string::npos);
  // The collection's header is 16 bytes; its first object's size sits 8 bytes into the
  // object's own 16-byte header.
  const std::size_t first_object_size = heap + 16 + 8;
  const auto with_size = [&](std::uint64_t size) {
    std::string bytes = golden;
    for (int i = 0; i < 8; ++i) bytes[first_object_size + i] = static_cast<char>(size >> (8 * i));
    return bytes;
  };
  const std::string intact = Path("intact.h5");
  WriteBytes(intact, golden);
  EXPECT_NE(Hdf5Reader(intact).StringAttribute("/", "scenario"), "");
  const std::vector<std::pair<std::uint64_t, std::string>> cases = {
      {200000, "damaged HDF5 file (HDF5 crashed reading it"},
      {~std::uint64_t{15}, "damaged HDF5 file (HDF5 did not finish reading it in 10 s)"},
  };
  for (const auto& [size, message] : cases) {
    const std::string path = Path("heap_" + std::to_string(size) + ".h5");
    WriteBytes(path, with_size(size));
    try {
      const Hdf5Reader reader(path);
      reader.StringAttribute("/", "scenario");
      ADD_FAILURE() << path << ": read";
    } catch (const InputError& error) {
      EXPECT_EQ(std::string(error.what()).rfind(path + ": " + message, 0), 0u) << error.what();
    }
  }
}

}  // namespace
}  // namespace moorsim::output
