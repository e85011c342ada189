// STE input: CSV layouts and units, resampling, shift, torque interpolation, geometric TE and
// every documented input error (with its line and column). Values are chosen so the expected
// results follow by hand (linear data is reproduced exactly by linear interpolation).
#include "geardyn/gear/ste.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"

namespace geardyn::gear {
namespace {

constexpr double kPi = std::numbers::pi;

SteReadOptions options_for(int teeth) {
  SteReadOptions o;
  o.teeth = teeth;
  return o;
}

// Expects parse_ste_csv to throw an InputError at `line` (and `column` when > 0) whose message
// mentions `fragment`.
void expect_error(const std::string& text, const SteReadOptions& o, int line, int column,
                  const std::string& fragment) {
  try {
    (void)parse_ste_csv(text, "ste.csv", o);
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "ste.csv");
    EXPECT_EQ(e.where().line, line) << e.what();
    if (column > 0) {
      EXPECT_EQ(e.where().column, column) << e.what();
    }
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SteCurve, FromSamplesEvaluatesPeriodically) {
  const SteCurve c = SteCurve::from_samples({1e-6, 2e-6, 3e-6, 2e-6}, SteInterpolation::Linear);
  EXPECT_DOUBLE_EQ(c.ste_at(0.0), 1e-6);
  EXPECT_DOUBLE_EQ(c.ste_at(0.125), 1.5e-6);
  EXPECT_DOUBLE_EQ(c.ste_at(0.875), 1.5e-6);  // wraps from sample 3 to sample 0
  EXPECT_DOUBLE_EQ(c.ste_at(1.125), 1.5e-6);
  EXPECT_DOUBLE_EQ(c.ste_at(-0.875), 1.5e-6);
  const SteCurve h = SteCurve::from_samples({1e-6, 2e-6}, SteInterpolation::Hold);
  EXPECT_DOUBLE_EQ(h.ste_at(0.49), 1e-6);
  EXPECT_DOUBLE_EQ(h.ste_at(0.51), 2e-6);
  // mean of 1/e for the Hold steps: (1/1e-6 + 1/2e-6) / 2.
  EXPECT_NEAR(h.mean_inverse_elastic_per_m(), 0.75e6, 1e-6);
  // Linear between 1 and 2 (and back): mean of 1/e is ln(2) / (2 - 1) per micrometre.
  const SteCurve l = SteCurve::from_samples({1e-6, 2e-6}, SteInterpolation::Linear);
  EXPECT_NEAR(l.mean_inverse_elastic_per_m(), std::log(2.0) * 1e6, 1e-6);
}

TEST(SteCurve, ShiftMovesTheContactEntry) {
  const SteCurve c = SteCurve::from_samples({1e-6, 2e-6, 3e-6, 4e-6}, SteInterpolation::Hold);
  const SteCurve s = c.shifted(0.25);
  EXPECT_DOUBLE_EQ(s.ste_m()[0], 2e-6);
  EXPECT_DOUBLE_EQ(s.ste_m()[3], 1e-6);
  EXPECT_EQ(c.resampled(8).size(), 8u);
}

TEST(SteCurve, RejectsNonPositiveOrInfiniteStiffness) {
  EXPECT_THROW(SteCurve::from_samples({1e-6}), InputError);
  EXPECT_THROW(SteCurve::from_samples({1e-6, 0.0}), InputError);
  EXPECT_THROW(SteCurve::from_samples({1e-6, -1e-6}), InputError);
  EXPECT_THROW(SteCurve::from_samples({1e-6, std::nan("")}), InputError);
  // With an unloaded TE, only the elastic part e - e_g must be positive.
  EXPECT_NO_THROW(SteCurve::from_samples({-1e-6, 1e-6}, SteInterpolation::Linear, {-2e-6, 0.0}));
  EXPECT_THROW(SteCurve::from_samples({1e-6, 1e-6}, SteInterpolation::Linear, {0.0, 1e-6}),
               InputError);
  EXPECT_THROW(SteCurve::from_samples({1e-6, 1e-6}, SteInterpolation::Linear, {0.0}), InputError);
}

// 20 teeth: one mesh period is 18 degrees. A closed cycle (last row at 18 deg) with values
// linear in the angle: resampling at the 4 data intervals reproduces the first 4 rows.
TEST(SteCsv, ClosedCycleInDegreesAndMicrometres) {
  const std::string text =
      "# STE of a 20-tooth pinion\n"
      "angle_deg, ste_um\n"
      "10.0, 2.0\n"
      "14.5, 2.5\n"
      "19.0, 3.0\n"
      "23.5, 3.5\n"
      "28.0, 2.0\n";
  const SteTable t = parse_ste_csv(text, "ste.csv", options_for(20));
  ASSERT_EQ(t.curves.size(), 1u);
  const SteCurve& c = t.curves[0];
  ASSERT_EQ(c.size(), 4u);
  EXPECT_NEAR(c.ste_m()[0], 2.0e-6, 1e-18);
  EXPECT_NEAR(c.ste_m()[1], 2.5e-6, 1e-18);
  EXPECT_NEAR(c.ste_m()[3], 3.5e-6, 1e-18);
  EXPECT_TRUE(std::isnan(c.torque_nm()));
}

// The open form (last row one spacing before the period) in radians and an angular STE in
// microradians: e [m] = e [urad] * 1e-6 * r_b. Period 2 pi / 16.
TEST(SteCsv, OpenCycleAngularSteNeedsBaseRadius) {
  const double p = 2.0 * kPi / 16.0;
  std::string text = "angle_rad,ste_urad\n";
  for (int i = 0; i < 8; ++i) {
    char row[64];
    std::snprintf(row, sizeof row, "%.17g,%d\n", i * p / 8.0, 10 + i);
    text += row;
  }
  SteReadOptions o = options_for(16);
  expect_error(text, o, 1, 11, "base radius");
  o.base_radius_m = 0.05;
  const SteTable t = parse_ste_csv(text, "ste.csv", o);
  ASSERT_EQ(t.curves[0].size(), 8u);
  EXPECT_NEAR(t.curves[0].ste_m()[3], 13.0e-6 * 0.05, 1e-15);
  // Open form: between the last row and the period the curve wraps to the first value.
  EXPECT_NEAR(t.curves[0].ste_at(7.5 / 8.0), 0.5 * (17.0 + 10.0) * 1e-6 * 0.05, 1e-15);
}

TEST(SteCsv, TimeAbscissaUsesTheMeshPeriod) {
  const std::string text = "time_ms, ste_nm\n0, 100\n0.25, 200\n0.5, 300\n0.75, 200\n";
  SteReadOptions o;
  expect_error(text, o, 1, 1, "mesh period");
  o.mesh_period_s = 1e-3;
  const SteTable t = parse_ste_csv(text, "ste.csv", o);
  EXPECT_NEAR(t.curves[0].ste_m()[2], 300e-9, 1e-20);
}

// Wide layout: one column per torque. At 150 N m the curve is the mean of the 100 and 200 N m
// curves; outside [100, 300] N m an error unless extrapolation is asked for.
TEST(SteCsv, TorqueColumnsInterpolateLinearly) {
  const std::string text =
      "angle_deg, ste_um@100Nm, ste_um@200Nm, ste_um@0.3kNm\n"
      "0, 1.0, 2.0, 2.8\n"
      "6, 1.2, 2.4, 3.4\n"
      "12, 1.1, 2.2, 3.0\n";
  const SteTable t = parse_ste_csv(text, "ste.csv", options_for(20));
  ASSERT_EQ(t.curves.size(), 3u);
  EXPECT_DOUBLE_EQ(t.curves[2].torque_nm(), 300.0);
  const SteCurve c = t.at_torque(150.0);
  EXPECT_NEAR(c.ste_m()[1], 1.8e-6, 1e-18);
  EXPECT_DOUBLE_EQ(c.torque_nm(), 150.0);
  const SteCurve c250 = t.at_torque(250.0);
  EXPECT_NEAR(c250.ste_m()[0], 2.4e-6, 1e-18);
  EXPECT_THROW(t.at_torque(400.0), InputError);
  EXPECT_THROW(t.at_torque(50.0), InputError);
  EXPECT_NEAR(t.at_torque(400.0, true).ste_m()[0], 3.6e-6, 1e-18);  // 2.0 + 2 * 0.8
  // Extrapolating down to 0 N m from the 100/200 N m curves gives e = 0: infinite stiffness.
  EXPECT_THROW(t.at_torque(0.0, true), InputError);
}

// Long layout: a torque column, one block per torque; same curves as the wide layout.
TEST(SteCsv, TorqueColumnLayout) {
  const std::string text =
      "angle_deg, torque_nm, ste_um\n"
      "0, 200, 2.0\n6, 200, 2.4\n12, 200, 2.2\n"
      "0, 100, 1.0\n6, 100, 1.2\n12, 100, 1.1\n";
  const SteTable t = parse_ste_csv(text, "ste.csv", options_for(20));
  ASSERT_EQ(t.curves.size(), 2u);
  EXPECT_DOUBLE_EQ(t.curves[0].torque_nm(), 100.0);
  EXPECT_NEAR(t.at_torque(150.0).ste_m()[1], 1.8e-6, 1e-18);
  expect_error(
      "angle_deg, torque_nm, ste_um\n0, 100, 1\n6, 100, 1\n12, 100, 1\n0, 200, 2\n6, 200, 2\n"
      "12, 200, 2\n0, 100, 1\n6, 100, 1\n12, 100, 1\n",
      options_for(20), 8, 4, "contiguous");
}

TEST(SteCsv, GeometricTeAndShift) {
  const std::string text =
      "angle_deg, ste_um, geometric_te_um\n"
      "0, 2.0, 0.5\n"
      "9, 3.0, 0.5\n"
      "18, 2.0, 0.5\n";
  SteReadOptions o = options_for(20);
  o.samples = 4;
  o.shift = 0.25;
  const SteTable t = parse_ste_csv(text, "ste.csv", o);
  const SteCurve& c = t.curves[0];
  ASSERT_TRUE(c.has_geometric_te());
  EXPECT_NEAR(c.ste_m()[0], 2.5e-6, 1e-18);  // data at a quarter of the cycle
  EXPECT_NEAR(c.ste_m()[1], 3.0e-6, 1e-18);
  EXPECT_NEAR(c.geometric_te_m()[0], 0.5e-6, 1e-18);
  EXPECT_NEAR(c.mean_elastic_m(), (2.5 + 3.0 + 2.5 + 2.0) / 4.0 * 1e-6 - 0.5e-6, 1e-18);
}

TEST(SteCsv, ErrorsNameFileLineAndColumn) {
  const SteReadOptions o = options_for(20);
  // Non-monotonic angle at line 4, column 1.
  expect_error("angle_deg,ste_um\n0,1\n6,1\n5,1\n18,1\n", o, 4, 1, "strictly increasing");
  // Span of 20 deg with 20 teeth (period 18 deg): neither closed nor open.
  expect_error("angle_deg,ste_um\n0,1\n10,1\n20,1\n", o, 4, 1, "one mesh period");
  // Garbage and NaN cells.
  expect_error("angle_deg,ste_um\n0,1\n6,abc\n12,1\n", o, 3, 3, "finite number");
  expect_error("angle_deg,ste_um\n0,1\n6, nan\n12,1\n", o, 3, 4, "finite number");
  expect_error("angle_deg,ste_um\n0,1\n6,1e999\n12,1\n", o, 3, 3, "finite number");
  // Zero or negative STE: infinite or negative stiffness.
  expect_error("angle_deg,ste_um\n0,1\n6,0\n12,1\n", o, 3, 3, "positive");
  expect_error("angle_deg,ste_um\n0,1\n6,-2\n12,1\n", o, 3, 3, "positive");
  // Too few rows.
  expect_error("angle_deg,ste_um\n0,1\n9,1\n", o, 3, 0, "at least 3");
  // Wrong field count.
  expect_error("angle_deg,ste_um\n0,1\n6,1,7\n12,1\n", o, 3, 1, "comma-separated");
  // Header problems.
  expect_error("angle_deg,ste_furlong\n0,1\n6,1\n12,1\n", o, 1, 11, "unit");
  expect_error("angle_deg,ste_um,temperature_c\n0,1,2\n6,1,2\n12,1,2\n", o, 1, 18, "temperature_c");
  expect_error("position,ste_um\n0,1\n6,1\n12,1\n", o, 1, 1, "angle_rad");
  expect_error("angle_deg,ste_um,ste_um\n0,1,1\n6,1,1\n12,1,1\n", o, 1, 18, "repeated");
  // Inconsistent torque columns.
  expect_error("angle_deg,ste_um,ste_um@100Nm\n0,1,1\n6,1,1\n12,1,1\n", o, 1, 18, "without torque");
  expect_error("angle_deg,ste_um@100Nm,ste_mm@0.1kNm\n0,1,1\n6,1,1\n12,1,1\n", o, 1, 24,
               "each torque once");
  expect_error("angle_deg,ste_um@-5Nm\n0,1\n6,1\n12,1\n", o, 1, 11, "torque label");
  expect_error("angle_deg,torque_nm,ste_um@100Nm\n0,1,1\n6,1,1\n12,1,1\n", o, 1, 11, "exactly one");
  // Missing tooth count with an angle abscissa.
  expect_error("angle_deg,ste_um\n0,1\n6,1\n12,1\n", SteReadOptions{}, 1, 1, "tooth count");
  // Empty document.
  expect_error("# nothing\n\n", o, 0, 0, "header");
  // Bad options.
  SteReadOptions bad = o;
  bad.shift = 1.0;
  EXPECT_THROW((void)parse_ste_csv("angle_deg,ste_um\n0,1\n6,1\n12,1\n", "ste.csv", bad),
               InputError);
}

TEST(SteCsv, CrLfBomAndMissingFile) {
  const std::string text =
      "\xEF\xBB\xBF"
      "angle_deg,ste_um\r\n0,1\r\n6,2\r\n12,3\r\n";
  const SteTable t = parse_ste_csv(text, "ste.csv", options_for(20));
  EXPECT_NEAR(t.curves[0].ste_m()[2], 3e-6, 1e-18);
  EXPECT_THROW(read_ste_csv("/nonexistent/ste.csv", options_for(20)), InputError);
}

}  // namespace
}  // namespace geardyn::gear
