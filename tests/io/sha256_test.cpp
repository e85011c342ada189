// SHA-256 test vectors from FIPS 180-2, Appendix B (B.1 "abc", B.2 the 448-bit message, B.3 one
// million 'a'), and the well-known digest of the empty message. Exact equality: a hash is exact.
#include "geardyn/io/sha256.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace geardyn::io {
namespace {

TEST(Sha256, Fips180Vectors) {
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(Sha256, FileReadInBlocks) {
  // One million 'a' spans several 64 KiB read blocks, so the incremental path is exercised.
  const std::filesystem::path dir =
      std::filesystem::path(GEARDYN_BINARY_DIR) / "test-output" / "io" / "sha256";
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "million_a.txt";
  {
    std::ofstream out(file, std::ios::binary);
    out << std::string(1000000, 'a');
  }
  EXPECT_EQ(sha256_file(file), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  std::filesystem::remove(file);
}

TEST(Sha256, MissingFileNamesThePath) {
  const std::string path = "/nonexistent-geardyn-folder/model.toml";
  try {
    sha256_file(path);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geardyn::io
