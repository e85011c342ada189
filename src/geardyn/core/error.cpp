#include "geardyn/core/error.hpp"

#include <fmt/format.h>

namespace geardyn {
namespace {

std::string format_input_error(const SourceLocation& where, const std::string& key_path,
                               const std::string& expected, const std::string& found,
                               const std::string& hint) {
  std::string location = where.file.empty() ? std::string("<model>") : where.file;
  if (where.line > 0) location += fmt::format(":{}", where.line);
  if (where.line > 0 && where.column > 0) location += fmt::format(":{}", where.column);
  std::string message =
      fmt::format("{}: key '{}': expected {}, found {}", location, key_path, expected, found);
  if (!hint.empty()) message += fmt::format(" ({})", hint);
  return message;
}

}  // namespace

InputError::InputError(SourceLocation where, std::string key_path, std::string expected,
                       std::string found, std::string hint)
    : std::runtime_error(format_input_error(where, key_path, expected, found, hint)),
      where_(std::move(where)),
      key_path_(std::move(key_path)),
      expected_(std::move(expected)),
      found_(std::move(found)),
      hint_(std::move(hint)) {}

NumericalError::NumericalError(std::string analysis, std::string message)
    : std::runtime_error(fmt::format("analysis '{}': {}", analysis, message)),
      analysis_(std::move(analysis)) {}

}  // namespace geardyn
