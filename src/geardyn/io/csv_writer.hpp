#pragma once
// CSV output of a Table (RFC 4180 quoting, '\n' line ends). The header row holds the column
// names, which carry their unit (`frequency_hz`); numbers are written losslessly, except speeds
// in rpm (format_speed_rpm).
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>

#include "geardyn/core/table.hpp"

namespace geardyn::io {

/// Magnitudes below this are written as "0" by format_number.
inline constexpr double kZeroBelow = 1e-300;

/// Shortest decimal text that reads back to exactly `value` ("0.1", "1e-07", "12345.678").
/// NaN is written as "nan" (whatever its sign bit), infinities as "inf" / "-inf"; a magnitude
/// below kZeroBelow (subnormal round-off, -0) as "0".
std::string format_number(double value);

/// A speed in rpm to 12 significant digits, then in its shortest form: speeds are computed in
/// rad/s, and the round trip through pi/30 would write a requested 3000 rpm as
/// 3000.0000000000005. Twelve digits are far below any meaning a shaft speed has.
std::string format_speed_rpm(double value);

/// `text` as one CSV field: quoted (with inner quotes doubled) when it contains a comma, a
/// double quote, a line break, or leading/trailing blanks; unchanged otherwise.
std::string csv_field(std::string_view text);

/// Writes `table` as CSV: one header row of column names, then `table.rows()` rows.
/// Throws std::logic_error if the table is inconsistent (Table::validate).
void write_csv(std::ostream& out, const Table& table);

/// The CSV text of `table` (see the stream overload).
std::string to_csv(const Table& table);

/// Writes `table` to `file` (created or truncated). Throws std::runtime_error naming the file
/// when it cannot be opened or written.
void write_csv(const std::filesystem::path& file, const Table& table);

}  // namespace geardyn::io
