#pragma once
// Reading an analysis's output in tests: a table by name, the column names of a table.
#include <stdexcept>
#include <string>
#include <vector>

#include "geardyn/core/table.hpp"

namespace geardyn::test {

/// The table `name` of `out` (std::out_of_range naming it when there is none).
inline const Table& table(const AnalysisOutput& out, const std::string& name) {
  for (const Table& t : out.tables)
    if (t.name == name) return t;
  throw std::out_of_range("no table " + name);
}

/// The column names of `t`, in order.
inline std::vector<std::string> column_names(const Table& t) {
  std::vector<std::string> names;
  for (const auto& c : t.columns) names.push_back(c.name);
  return names;
}

}  // namespace geardyn::test
