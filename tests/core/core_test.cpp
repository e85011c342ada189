// The core module: unit conversions, error messages, tables and the one peak table.
// References: exact definitions (1 rpm = 2 pi / 60 rad/s, 1 Hz = 2 pi rad/s, 180 deg = pi rad);
// the message format of README.md, "Using it" (file:line:column, key, expected, found, hint).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "geardyn/core/error.hpp"
#include "geardyn/core/peak_table.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn {
namespace {

TEST(Units, ConversionsAreTheExactDefinitions) {
  using namespace units;
  EXPECT_EQ(kPi, std::numbers::pi);
  EXPECT_EQ(kTwoPi, 2.0 * std::numbers::pi);
  // 60 rpm is one revolution per second; rounding of the factor allows one ulp.
  EXPECT_NEAR(rpm_to_rad_per_s(60.0), kTwoPi, 1e-15);
  EXPECT_NEAR(rad_per_s_to_rpm(kTwoPi), 60.0, 1e-13);
  EXPECT_NEAR(hz_to_rad_per_s(1.0), kTwoPi, 0.0);
  EXPECT_NEAR(rad_per_s_to_hz(kTwoPi), 1.0, 0.0);
  EXPECT_NEAR(deg_to_rad(180.0), kPi, 1e-15);
  EXPECT_NEAR(rad_to_deg(kPi / 2.0), 90.0, 1e-13);
  // Round trips stay within a few ulps over the speed range of geared rotors.
  for (double rpm : {1.0, 3000.0, 12345.6, 60000.0})
    EXPECT_NEAR(rad_per_s_to_rpm(rpm_to_rad_per_s(rpm)), rpm, 1e-15 * rpm);
}

TEST(Errors, InputErrorSaysFileLineKeyExpectedAndFound) {
  const InputError e({"gearbox.toml", 12, 5}, "bearings[1].kxx", "a number >= 0", "-3",
                     "stiffness is in N/m");
  EXPECT_STREQ(e.what(),
               "gearbox.toml:12:5: key 'bearings[1].kxx': expected a number >= 0, found -3 "
               "(stiffness is in N/m)");
  EXPECT_EQ(e.key_path(), "bearings[1].kxx");
  EXPECT_EQ(e.where().line, 12);
  const InputError no_file({}, "version", "1", "2");
  EXPECT_STREQ(no_file.what(), "<model>: key 'version': expected 1, found 2");
  const NumericalError n("modes", "the eigensolver did not converge");
  EXPECT_STREQ(n.what(), "analysis 'modes': the eigensolver did not converge");
}

TEST(Tables, ColumnsAreCheckedAndFoundByName) {
  Table t;
  t.name = "modes";
  t.add("frequency_hz", "Hz", {1.0, 2.0});
  t.add_text("shape", {"bending", "torsion"});
  EXPECT_EQ(t.rows(), 2u);
  EXPECT_NO_THROW(t.validate());
  EXPECT_TRUE(t.has_column("shape"));
  EXPECT_EQ(t.column("frequency_hz").unit, "Hz");
  EXPECT_THROW((void)t.column("damping"), std::out_of_range);
  t.add("damping_ratio", "", {0.01});  // one row short
  EXPECT_THROW(t.validate(), std::logic_error);
  Table r;
  r.add("x", "", {1.0});
  r.add("x", "", {2.0});
  EXPECT_THROW(r.validate(), std::logic_error);
}

TEST(PeakTable, OneColumnSetWithTheSingleModeDampingEstimate) {
  PeakRow resolved;
  resolved.sensor = "bearing_x";
  resolved.curve = "1";
  resolved.location = 100.0;
  resolved.amplitude = 2e-5;
  resolved.amplitude_unit = "m";
  resolved.half_power_low = 99.0;
  resolved.half_power_high = 101.0;
  resolved.q_factor = 50.0;
  resolved.points_in_band = 9;
  resolved.resolved = true;
  PeakRow coarse = resolved;  // too few samples in the band: Q not reported
  coarse.curve = "sum";
  coarse.points_in_band = 1;
  coarse.resolved = false;
  const Table t = peak_table("peaks", "Resonance peaks", frequency_axis(), {resolved, coarse});
  EXPECT_NO_THROW(t.validate());
  const std::vector<std::string> names = {"peak",
                                          "sensor",
                                          "curve",
                                          "frequency_hz",
                                          "amplitude",
                                          "amplitude_unit",
                                          "half_power_low_frequency_hz",
                                          "half_power_high_frequency_hz",
                                          "q_factor",
                                          "damping_ratio",
                                          "points_in_band",
                                          "resolved"};
  ASSERT_EQ(t.columns.size(), names.size());
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(t.columns[i].name, names[i]);
  EXPECT_EQ(t.column("peak").numbers, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(t.column("q_factor").numbers[0], 50.0);
  // zeta = 1 / (2 Q) for a single mode with light damping (half-power bandwidth 2 zeta f).
  EXPECT_DOUBLE_EQ(t.column("damping_ratio").numbers[0], 0.01);
  EXPECT_TRUE(std::isnan(t.column("q_factor").numbers[1]));
  EXPECT_TRUE(std::isnan(t.column("damping_ratio").numbers[1]));
  EXPECT_EQ(t.column("resolved").numbers, (std::vector<double>{1.0, 0.0}));
  EXPECT_EQ(t.column("frequency_hz").unit, "Hz");
  const Table s = peak_table("p", "", speed_axis(), {});
  EXPECT_TRUE(s.has_column("half_power_high_speed_rpm"));
  EXPECT_EQ(s.rows(), 0u);
}

}  // namespace
}  // namespace geardyn
