#include "geardyn/io/csv_writer.hpp"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace geardyn::io {

std::string format_number(double value) {
  // std::to_chars without a precision gives the shortest round-trip form, so a CSV reader gets
  // back the very double that was computed; printf's %g would either lose digits or pad noise.
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  // Below 1e-300 in magnitude (subnormals such as 4.9e-324, and -0) is round-off of a zero:
  // written as 0, which every CSV reader parses (std::stod throws out_of_range on subnormals).
  if (std::abs(value) < kZeroBelow) return "0";
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string format_speed_rpm(double value) {
  if (!std::isfinite(value)) return format_number(value);
  std::array<char, 32> buffer{};
  const auto rounded = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                     std::chars_format::general, 12);
  double back = value;
  std::from_chars(buffer.data(), rounded.ptr, back);
  return format_number(back == 0.0 ? 0.0 : back);  // no "-0"
}

std::string csv_field(std::string_view text) {
  const bool needs_quotes = text.find_first_of(",\"\r\n") != std::string_view::npos ||
                            (!text.empty() && (text.front() == ' ' || text.front() == '\t' ||
                                               text.back() == ' ' || text.back() == '\t'));
  if (!needs_quotes) return std::string(text);
  std::string quoted;
  quoted.reserve(text.size() + 2);
  quoted += '"';
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  quoted += '"';
  return quoted;
}

void write_csv(std::ostream& out, const Table& table) {
  table.validate();
  const std::size_t n_cols = table.columns.size();
  for (std::size_t j = 0; j < n_cols; ++j) {
    if (j > 0) out << ',';
    out << csv_field(table.columns[j].name);
  }
  out << '\n';
  const std::size_t n_rows = table.rows();
  std::string line;
  for (std::size_t i = 0; i < n_rows; ++i) {
    line.clear();
    for (std::size_t j = 0; j < n_cols; ++j) {
      if (j > 0) line += ',';
      const Column& c = table.columns[j];
      line += c.text            ? csv_field(c.texts[i])
              : c.unit == "rpm" ? format_speed_rpm(c.numbers[i])
                                : format_number(c.numbers[i]);
    }
    line += '\n';
    out << line;
  }
}

std::string to_csv(const Table& table) {
  std::ostringstream out;
  write_csv(out, table);
  return out.str();
}

void write_csv(const std::filesystem::path& file, const Table& table) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw std::runtime_error(fmt::format("cannot create '{}'", file.string()));
  write_csv(out, table);
  out.flush();
  if (!out) throw std::runtime_error(fmt::format("cannot write '{}'", file.string()));
}

}  // namespace geardyn::io
