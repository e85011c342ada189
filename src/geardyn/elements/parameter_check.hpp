#pragma once
// Checks of element parameters, shared by the elements' constructors (internal to elements/):
// an InputError at <key_path>.<name> (just <name> without a key path) at the caller's location,
// with the value found. The future model keys are the parameter names.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>

#include "geardyn/core/error.hpp"

namespace geardyn::elements::detail {

/// A parameter value in messages and descriptions (6 significant digits).
inline std::string format_number(double x) { return fmt::format("{:.6g}", x); }

class ParameterCheck {
 public:
  ParameterCheck(SourceLocation where, std::string key_path)
      : where_(std::move(where)), key_path_(std::move(key_path)) {}

  /// The key of parameter `name`.
  std::string key(const std::string& name) const {
    return key_path_.empty() ? name : key_path_ + "." + name;
  }
  [[noreturn]] void fail(const std::string& name, const std::string& expected,
                         const std::string& found, const std::string& hint = {}) const {
    throw InputError(where_, key(name), expected, found, hint);
  }
  [[noreturn]] void fail(const std::string& name, const std::string& expected, double found,
                         const std::string& hint = {}) const {
    fail(name, expected, format_number(found), hint);
  }
  void require(bool ok, const std::string& name, const std::string& expected, double found,
               const std::string& hint = {}) const {
    if (!ok) fail(name, expected, found, hint);
  }
  void finite(const std::string& name, double value, const std::string& hint = {}) const {
    require(std::isfinite(value), name, "a finite number", value, hint);
  }
  void positive(const std::string& name, double value, const std::string& hint = {}) const {
    require(std::isfinite(value) && value > 0.0, name, "a finite number > 0", value, hint);
  }
  void non_negative(const std::string& name, double value, const std::string& hint = {}) const {
    require(std::isfinite(value) && value >= 0.0, name, "a finite number >= 0", value, hint);
  }

 private:
  SourceLocation where_;
  std::string key_path_;
};

}  // namespace geardyn::elements::detail
