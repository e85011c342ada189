#pragma once
// Unit conversions at the edges of geardyn (docs/theory.md, introduction: SI inside; `*_rpm`,
// `*_hz`, `*_deg` keys and result columns that say their unit). One definition of pi and of each
// factor; nothing else in the code base spells them out.
#include <numbers>

namespace geardyn::units {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

inline constexpr double kRadPerSecondPerRpm = kTwoPi / 60.0;  ///< 1 rpm in rad/s
inline constexpr double kRadPerSecondPerHz = kTwoPi;          ///< 1 Hz in rad/s
inline constexpr double kRadPerDegree = kPi / 180.0;          ///< 1 degree in rad

constexpr double rpm_to_rad_per_s(double rpm) { return rpm * kRadPerSecondPerRpm; }
constexpr double rad_per_s_to_rpm(double w) { return w / kRadPerSecondPerRpm; }
constexpr double hz_to_rad_per_s(double f) { return f * kRadPerSecondPerHz; }
constexpr double rad_per_s_to_hz(double w) { return w / kRadPerSecondPerHz; }
constexpr double deg_to_rad(double deg) { return deg * kRadPerDegree; }
constexpr double rad_to_deg(double rad) { return rad / kRadPerDegree; }
/// Revolutions per minute to revolutions per second (a rotation frequency in Hz), and back.
constexpr double rpm_to_hz(double rpm) { return rpm / 60.0; }
constexpr double hz_to_rpm(double f) { return f * 60.0; }

}  // namespace geardyn::units
