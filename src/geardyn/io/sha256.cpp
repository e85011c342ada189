#include "geardyn/io/sha256.hpp"

#include <fmt/format.h>
#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <memory>
#include <stdexcept>

namespace geardyn::io {
namespace {

struct DigestContextDeleter {
  void operator()(EVP_MD_CTX* context) const { EVP_MD_CTX_free(context); }
};
using DigestContext = std::unique_ptr<EVP_MD_CTX, DigestContextDeleter>;

// Incremental SHA-256; `what` names the input in error messages.
class Sha256 {
 public:
  explicit Sha256(std::string what) : what_(std::move(what)), context_(EVP_MD_CTX_new()) {
    if (!context_ || EVP_DigestInit_ex(context_.get(), EVP_sha256(), nullptr) != 1) fail("init");
  }
  void update(const void* data, std::size_t size) {
    if (EVP_DigestUpdate(context_.get(), data, size) != 1) fail("update");
  }
  std::string hex_digest() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
    unsigned int length = 0;
    if (EVP_DigestFinal_ex(context_.get(), digest.data(), &length) != 1) fail("final");
    std::string hex;
    hex.reserve(2 * length);
    for (unsigned int i = 0; i < length; ++i) hex += fmt::format("{:02x}", digest[i]);
    return hex;
  }

 private:
  [[noreturn]] void fail(const char* step) const {
    throw std::runtime_error(
        fmt::format("SHA-256 of {}: OpenSSL EVP digest {} failed", what_, step));
  }
  std::string what_;
  DigestContext context_;
};

}  // namespace

std::string sha256_hex(std::string_view data) {
  Sha256 sha("a string");
  sha.update(data.data(), data.size());
  return sha.hex_digest();
}

std::string sha256_file(const std::filesystem::path& file) {
  const std::string what = fmt::format("'{}'", file.string());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot open {} to compute its SHA-256", what));
  Sha256 sha(what);
  std::array<char, 1 << 16> block{};
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const std::streamsize n = in.gcount();
    if (n > 0) sha.update(block.data(), static_cast<std::size_t>(n));
  }
  if (in.bad()) throw std::runtime_error(fmt::format("cannot read {}", what));
  return sha.hex_digest();
}

}  // namespace geardyn::io
