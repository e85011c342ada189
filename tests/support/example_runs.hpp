#pragma once
// Helpers of the example tests (tests/cli/*_example_test.cpp): run an example's model file
// through the geardyn program into a fresh results folder, and read a CSV column as numbers.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cli/cli_support.hpp"

namespace geardyn::cli_test {

/// `geardyn run -q examples/<example>/model.toml` into a fresh folder named `example`; the
/// program's result (exit code, stdout, stderr) in `result`.
inline fs::path run_example(const std::string& example, ProcessResult& result) {
  const fs::path out = fresh_dir(example);
  result = run("run -q " + kSource + "/examples/" + example + "/model.toml -o " + out.string());
  return out;
}

/// The cells of a CSV column as numbers.
inline std::vector<double> numbers(const std::vector<std::string>& cells) {
  std::vector<double> v;
  for (const auto& c : cells) v.push_back(std::stod(c));
  return v;
}

/// The notes of analysis `name` in a results folder's manifest.
inline std::vector<std::string> notes_of(const fs::path& out, const std::string& name) {
  const nlohmann::json manifest = read_json(out / "manifest.json");
  for (const auto& a : manifest["analyses"])
    if (a["name"] == name) return a["notes"].get<std::vector<std::string>>();
  ADD_FAILURE() << "no analysis " << name << " in " << out;
  return {};
}

}  // namespace geardyn::cli_test
