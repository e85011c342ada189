#pragma once
// A topological flank modification (gear::TopographyMap, gear/tooth_contact.hpp) read from a CSV
// file: material removed over the roll angle x the face position of one gear's loaded flank.
//
// Format (comma separated, '#' comment lines and blank lines ignored, the first other line is
// the header; units in the column names, case-insensitive; long format, one row per grid point,
// in any order):
//   roll_angle_deg | roll_angle_rad   roll angle xi = rho / r_b of the gear (rho: the roll length
//                                     on its base tangent; r = r_b sqrt(1 + xi^2))
//   face_m | face_mm                  face position y, from the face end where the contact lines
//                                     enter (y = 0) to y = b
//   removed_m | removed_mm | removed_um   material removed normal to the flank (positive: less
//                                     material, as every flank modification)
// The rows form a regular grid: each of the distinct roll angles (>= 2) at each of the distinct
// face positions (>= 2) once. Between the grid points the map is bilinear, beyond its edges it is
// constant (the value at the nearest edge).
#include <filesystem>
#include <string>
#include <string_view>

#include "geardyn/gear/tooth_contact.hpp"

namespace geardyn::gear {

/// Parses a topography CSV document (format above). InputError with file, line, column and the
/// column name for: an unknown, repeated or missing column, a cell that is not a finite number,
/// fewer than 2 roll angles or face positions, a negative roll angle, a missing or repeated grid
/// point, a removal of 1 mm or more (the amounts are micrometres).
TopographyMap parse_topography_csv(std::string_view text, const std::string& file_name);

/// Reads `path` and parses it; InputError when it cannot be read.
TopographyMap read_topography_csv(const std::filesystem::path& path);

}  // namespace geardyn::gear
