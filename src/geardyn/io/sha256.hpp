#pragma once
// SHA-256 (FIPS 180-4) through OpenSSL's EVP interface; used to record which model file a set of
// results came from.
#include <filesystem>
#include <string>
#include <string_view>

namespace geardyn::io {

/// Lower-case hex SHA-256 of `data` (64 characters).
std::string sha256_hex(std::string_view data);

/// Lower-case hex SHA-256 of the bytes of `file`, read in blocks. Throws std::runtime_error
/// naming the file when it cannot be opened or read, or when OpenSSL fails.
std::string sha256_file(const std::filesystem::path& file);

}  // namespace geardyn::io
