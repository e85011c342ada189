#include "geardyn/core/table.hpp"

#include <fmt/format.h>

#include <set>
#include <stdexcept>

namespace geardyn {

Column& Table::add(std::string column_name, std::string unit, std::vector<double> values) {
  Column c;
  c.name = std::move(column_name);
  c.unit = std::move(unit);
  c.numbers = std::move(values);
  columns.push_back(std::move(c));
  return columns.back();
}

Column& Table::add_text(std::string column_name, std::vector<std::string> values) {
  Column c;
  c.name = std::move(column_name);
  c.text = true;
  c.texts = std::move(values);
  columns.push_back(std::move(c));
  return columns.back();
}

std::size_t Table::rows() const { return columns.empty() ? 0 : columns.front().size(); }

void Table::validate() const {
  std::set<std::string> names;
  for (const auto& c : columns) {
    if (!names.insert(c.name).second)
      throw std::logic_error(fmt::format("table '{}': column '{}' repeated", name, c.name));
    if (c.size() != rows())
      throw std::logic_error(fmt::format("table '{}': column '{}' has {} rows, expected {}", name,
                                         c.name, c.size(), rows()));
  }
}

const Column& Table::column(const std::string& column_name) const {
  for (const auto& c : columns)
    if (c.name == column_name) return c;
  throw std::out_of_range(fmt::format("table '{}' has no column '{}'", name, column_name));
}

Column& Table::column(const std::string& column_name) {
  return const_cast<Column&>(static_cast<const Table&>(*this).column(column_name));
}

bool Table::has_column(const std::string& column_name) const {
  for (const auto& c : columns)
    if (c.name == column_name) return true;
  return false;
}

}  // namespace geardyn
