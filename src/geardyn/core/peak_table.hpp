#pragma once
// The one resonance-peak table: every analysis that reports peaks of a response curve writes
// them with these columns, so a user (or a script) reads all of them the same way.
//
//   peak, sensor, curve, <x>, amplitude, amplitude_unit, half_power_low_<x>, half_power_high_<x>,
//   q_factor, damping_ratio, points_in_band, resolved
//
// <x> is the abscissa of the curve with its unit ("frequency_hz" or "speed_rpm"). The half-power
// points are where the amplitude falls to peak / sqrt(2) on either side; Q = x / (x2 - x1) and
// the damping ratio 1 / (2 Q) (the single-mode estimate) are reported only when both points are
// found with enough samples between them (`resolved`), else left empty (NaN).
#include <limits>
#include <string>
#include <vector>

#include "geardyn/core/table.hpp"

namespace geardyn {

/// One peak, with its location and half-power points in the unit of the table's abscissa.
struct PeakRow {
  std::string sensor;  ///< the sensor (or measured channel) whose curve peaks
  std::string curve;   ///< which curve of that sensor ("1", "EO 12", "sum", ...)
  double location = std::numeric_limits<double>::quiet_NaN();  ///< peak abscissa
  double amplitude = std::numeric_limits<double>::quiet_NaN();
  std::string amplitude_unit;  ///< "m", "rad", "N", "m/s^2", ...
  double half_power_low = std::numeric_limits<double>::quiet_NaN();   ///< NaN: not found
  double half_power_high = std::numeric_limits<double>::quiet_NaN();  ///< NaN: not found
  double q_factor = std::numeric_limits<double>::quiet_NaN();         ///< NaN: unresolved
  int points_in_band = 0;  ///< samples between the half-power points
  bool resolved = false;   ///< both points found with enough samples between them
};

/// The abscissa of a peak table: its column stem with unit, e.g. {"frequency", "hz", "Hz"}.
struct PeakAxis {
  std::string stem = "frequency";  ///< "frequency" or "speed"
  std::string suffix = "hz";       ///< "hz" or "rpm"
  std::string unit = "Hz";         ///< for the manifest
};

/// The frequency axis [Hz] and the speed axis [rpm].
PeakAxis frequency_axis();
PeakAxis speed_axis();

/// The peak table `name` (a CSV file name) with caption `title`, one row per peak in the order
/// given, numbered from 1.
Table peak_table(std::string name, std::string title, const PeakAxis& axis,
                 const std::vector<PeakRow>& peaks);

}  // namespace geardyn
