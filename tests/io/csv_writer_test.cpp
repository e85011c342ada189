#include "geardyn/io/csv_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace geardyn::io {
namespace {

TEST(FormatNumber, ShortestRoundTripText) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(1.0), "1");
  EXPECT_EQ(format_number(-2.5), "-2.5");
  EXPECT_EQ(format_number(0.0), "0");
  EXPECT_EQ(format_number(1e-7), "1e-07");
  EXPECT_EQ(format_number(1234.5), "1234.5");
  EXPECT_EQ(format_number(6.02214076e23), "6.02214076e+23");
}

// Round-off of a zero (a subnormal such as 4.9e-324, or -0) is written as 0, so that readers
// that reject subnormals (std::stod: out_of_range) read every cell; 1e-300 and above are kept.
TEST(FormatNumber, MagnitudesBelow1e300AreWrittenAsZero) {
  const double smallest = std::numeric_limits<double>::denorm_min();  // 4.9e-324
  EXPECT_EQ(format_number(smallest), "0");
  EXPECT_EQ(format_number(-smallest), "0");
  EXPECT_EQ(format_number(5e-318), "0");
  EXPECT_EQ(format_number(std::numeric_limits<double>::min()), "0");  // 2.2e-308, normal
  EXPECT_EQ(format_number(-0.0), "0");
  EXPECT_EQ(format_number(9.99e-301), "0");
  EXPECT_EQ(format_number(1e-300), "1e-300");
  EXPECT_EQ(format_number(-2.5e-300), "-2.5e-300");
  EXPECT_NO_THROW((void)std::stod(format_number(smallest)));
}

TEST(FormatNumber, NonFiniteValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(format_number(nan), "nan");
  EXPECT_EQ(format_number(-nan), "nan");  // the sign bit of a NaN carries no meaning
  EXPECT_EQ(format_number(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(format_number(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(FormatNumber, ReadsBackToTheSameDouble) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int i = 0; i < 10000; ++i) {
    const double x = std::ldexp(mantissa(rng), exponent(rng));
    const std::string text = format_number(x);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
  }
  // 0.1 + 0.2 is not 0.3 in binary; the text must keep the difference.
  EXPECT_EQ(std::strtod(format_number(0.1 + 0.2).c_str(), nullptr), 0.1 + 0.2);
}

TEST(CsvField, QuotesOnlyWhenNeeded) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field(""), "");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field("cr\rhere"), "\"cr\rhere\"");
  EXPECT_EQ(csv_field(" padded"), "\" padded\"");
  EXPECT_EQ(csv_field("padded "), "\"padded \"");
  EXPECT_EQ(csv_field("inner space"), "inner space");
}

TEST(WriteCsv, HeaderAndRows) {
  Table t;
  t.name = "modes";
  t.add("mode", "", {1, 2, 3});
  t.add("frequency_hz", "Hz", {12.5, 0.1 + 0.2, std::numeric_limits<double>::quiet_NaN()});
  t.add_text("whirl", {"forward", "backward, weak", "say \"x\""});
  EXPECT_EQ(to_csv(t),
            "mode,frequency_hz,whirl\n"
            "1,12.5,forward\n"
            "2,0.30000000000000004,\"backward, weak\"\n"
            "3,nan,\"say \"\"x\"\"\"\n");
}

// Speeds are computed in rad/s; a requested speed must come back as it was typed.
TEST(FormatSpeedRpm, RequestedSpeedsComeBackExactly) {
  const double to_si = std::numbers::pi / 30.0;
  for (double rpm : {3000.0, 36900.0, 4321.5, 1e-3, 123456.789}) {
    const double w = rpm * to_si;
    EXPECT_EQ(format_speed_rpm(w / to_si), format_number(rpm)) << rpm;
    EXPECT_EQ(format_speed_rpm(w * (30.0 / std::numbers::pi)), format_number(rpm)) << rpm;
  }
  EXPECT_EQ(format_speed_rpm(-0.0), "0");
  EXPECT_EQ(format_speed_rpm(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(format_speed_rpm(2368.4210526315787), "2368.42105263");  // 12 digits
  Table t;
  t.name = "speeds";
  t.add("speed_rpm", "rpm", {3000.0 * to_si * (30.0 / std::numbers::pi)});
  EXPECT_EQ(to_csv(t), "speed_rpm\n3000\n");
}

TEST(WriteCsv, EmptyTableHasHeaderOnly) {
  Table t;
  t.name = "empty";
  t.add("time_s", "s");
  t.add("x_m", "m");
  EXPECT_EQ(to_csv(t), "time_s,x_m\n");
}

TEST(WriteCsv, InconsistentTableIsRejected) {
  Table t;
  t.name = "bad";
  t.add("a", "", {1, 2});
  t.add("b", "", {1});
  EXPECT_THROW(to_csv(t), std::logic_error);
}

TEST(WriteCsv, UnwritableFileNamesThePath) {
  Table t;
  t.name = "t";
  t.add("a", "", {1});
  const std::filesystem::path file = "/nonexistent-geardyn-folder/sub/t.csv";
  try {
    write_csv(file, t);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace geardyn::io
