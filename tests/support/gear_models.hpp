#pragma once
// Helpers of the gear-analysis tests: model files with their CSV inputs in a fresh folder, tables
// of an AnalysisOutput by name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/parse.hpp"
#include "support/output_tables.hpp"

namespace geardyn::analyses::test {

namespace fs = std::filesystem;

/// A fresh folder under the build tree for one test's files.
inline fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(GEARDYN_BINARY_DIR) / "tests" / "gear_analyses" / "runs" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline fs::path write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// Writes `text` as <dir>/model.toml and reads it (STE / measured files are relative to it).
inline model::Model load(const fs::path& dir, const std::string& text) {
  return analyses::load_model(write_file(dir / "model.toml", text).string());
}

using geardyn::test::table;

/// Row of a table whose text column `key` equals `value` and text column `key2` equals `value2`.
inline std::size_t row_where(const Table& t, const std::string& key, const std::string& value,
                             const std::string& key2 = {}, const std::string& value2 = {}) {
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.column(key).texts[i] == value && (key2.empty() || t.column(key2).texts[i] == value2))
      return i;
  throw std::out_of_range("no row " + key + " = " + value);
}

/// The model-file text of the tooth contact tests' spur pair: 20 / 40 teeth, m = 3 mm, alpha =
/// 20 deg, b = 20 mm, steel (r1 = 30 mm), `torque` on gear 1 [N m], then `extra` (more keys of
/// the pair, its sub-tables, analyses).
inline std::string spur_pair_20_40(const std::string& torque, const std::string& extra = {}) {
  return R"(version = 1
[[gear_pairs]]
name = "spur"
teeth1 = 20
teeth2 = 40
module = 0.003
face_width = 0.02
torque = )" +
         torque + "\n" + extra;
}

}  // namespace geardyn::analyses::test
