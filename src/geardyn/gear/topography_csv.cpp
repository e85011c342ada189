#include "geardyn/gear/topography_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "geardyn/core/text.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/gear/ste.hpp"

namespace geardyn::gear {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);
constexpr double kMaxRemovalM = 1e-3;  // modifications are micrometres; 1 mm is a unit mistake

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

std::vector<double> distinct(const NumericCsv& csv, std::size_t col) {
  std::vector<double> v;
  for (const auto& row : csv.rows) v.push_back(row[col]);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

std::size_t position(const std::vector<double>& axis, double value) {
  return static_cast<std::size_t>(std::lower_bound(axis.begin(), axis.end(), value) - axis.begin());
}

}  // namespace

TopographyMap parse_topography_csv(std::string_view text, const std::string& file_name) {
  const NumericCsv csv = parse_numeric_csv(text, file_name, 4);
  std::size_t roll = kNone, face = kNone, removed = kNone;
  double roll_factor = 1.0, face_factor = 1.0, removed_factor = 1.0;
  for (std::size_t i = 0; i < csv.names.size(); ++i) {
    const std::string n = lower(csv.names[i]);
    std::size_t* slot = nullptr;
    if (n == "roll_angle_deg" || n == "roll_angle_rad") {
      slot = &roll;
      roll_factor = n == "roll_angle_deg" ? units::kPi / 180.0 : 1.0;
    } else if (n == "face_m" || n == "face_mm") {
      slot = &face;
      face_factor = n == "face_mm" ? 1e-3 : 1.0;
    } else if (n == "removed_m" || n == "removed_mm" || n == "removed_um") {
      slot = &removed;
      removed_factor = n == "removed_um" ? 1e-6 : n == "removed_mm" ? 1e-3 : 1.0;
    } else {
      throw InputError(csv.at_header(i), csv.names[i],
                       "roll_angle_deg or roll_angle_rad, face_m or face_mm, removed_um, "
                       "removed_mm or removed_m",
                       fmt::format("'{}'", shorten(csv.names[i], 43)),
                       "the column names carry the quantity and its unit (docs/input-files.md)");
    }
    if (*slot != kNone)
      throw InputError(csv.at_header(i), csv.names[i], "each quantity in one column",
                       fmt::format("a second one (after '{}')", csv.names[*slot]));
    *slot = i;
  }
  const SourceLocation header{csv.file, csv.header_line, 1};
  for (const auto& [col, what] :
       {std::pair{roll, "a roll_angle_deg or roll_angle_rad column"},
        std::pair{face, "a face_m or face_mm column"},
        std::pair{removed, "a removed_um, removed_mm or removed_m column"}})
    if (col == kNone) throw InputError(header, "header", what, "none");
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    if (csv.rows[r][roll] < 0.0)
      throw InputError(csv.at(r, roll), csv.names[roll], "a roll angle >= 0",
                       fmt::format("{}", csv.rows[r][roll]));
    if (!(std::abs(csv.rows[r][removed] * removed_factor) < kMaxRemovalM))
      throw InputError(
          csv.at(r, removed), csv.names[removed],
          "a removal well below 1 mm (flank modifications are micrometres)",
          fmt::format("{} ({} m)", csv.rows[r][removed], csv.rows[r][removed] * removed_factor),
          "check the unit in the column name");
  }
  const std::vector<double> rolls = distinct(csv, roll), faces = distinct(csv, face);
  for (const auto& [axis, col] : {std::pair{&rolls, roll}, std::pair{&faces, face}})
    if (axis->size() < 2)
      throw InputError(csv.at_header(col), csv.names[col], "at least 2 distinct values (a grid)",
                       fmt::format("{}", axis->size()));
  std::vector<std::size_t> row_of(rolls.size() * faces.size(), kNone);
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const std::size_t k =
        position(rolls, csv.rows[r][roll]) * faces.size() + position(faces, csv.rows[r][face]);
    if (row_of[k] != kNone)
      throw InputError(csv.at(r, roll), csv.names[roll],
                       "each (roll angle, face position) point once (a regular grid)",
                       fmt::format("a repeat of line {}", csv.row_lines[row_of[k]]));
    row_of[k] = r;
  }
  TopographyMap map;
  map.removed_m.resize(static_cast<Eigen::Index>(rolls.size()),
                       static_cast<Eigen::Index>(faces.size()));
  for (std::size_t i = 0; i < rolls.size(); ++i)
    for (std::size_t k = 0; k < faces.size(); ++k) {
      const std::size_t r = row_of[i * faces.size() + k];
      if (r == kNone)
        throw InputError(header, "rows",
                         fmt::format("a regular grid: each of the {} roll angles at each of the "
                                     "{} face positions",
                                     rolls.size(), faces.size()),
                         fmt::format("no row at {} = {}, {} = {}", csv.names[roll], rolls[i],
                                     csv.names[face], faces[k]));
      map.removed_m(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) =
          csv.rows[r][removed] * removed_factor;
    }
  for (double v : rolls) map.roll_angle_rad.push_back(v * roll_factor);
  for (double v : faces) map.face_m.push_back(v * face_factor);
  return map;
}

TopographyMap read_topography_csv(const std::filesystem::path& path) {
  const std::optional<std::string> text = try_read_file(path);
  if (!text)
    throw InputError(SourceLocation{path.string(), 0, 0}, "topography_file", "a readable CSV file",
                     "a file that cannot be opened");
  return parse_topography_csv(*text, path.string());
}

}  // namespace geardyn::gear
