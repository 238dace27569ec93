// SHA-256 against the FIPS 180-4 examples, of bytes and of a file.
#include "core/sha256.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace moorsim {
namespace {

TEST(Sha256, MatchesTheStandardsExamples) {
  EXPECT_EQ(Sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(Sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(Sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, OfAFileIsOfItsBytesAndNoneWithoutTheFile) {
  const std::filesystem::path path =
      std::filesystem::path(::testing::TempDir()) / "sha256_test_file";
  // Longer than the read buffer, so that the file is hashed in pieces.
  const std::string bytes(200000, 'x');
  std::ofstream(path, std::ios::binary) << bytes;
  EXPECT_EQ(FileSha256(path.string()), Sha256Hex(bytes));
  std::filesystem::remove(path);
  EXPECT_EQ(FileSha256(path.string()), std::nullopt);
}

}  // namespace
}  // namespace moorsim
