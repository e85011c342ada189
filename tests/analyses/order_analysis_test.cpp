// The order_analysis analysis through the model file, on synthetic records written as CSV:
//  - validation (issue #17): a run-up with a linear speed ramp and known order amplitudes (orders
//    13 and 26 of a pinion, amplitudes rising with speed), with a 1 pulse/rev tacho column: the
//    order cuts recover the amplitudes within 1 % away from the ends (computed order tracking,
//    K. R. Fyfe, E. D. S. Munck, "Analysis of computed order tracking", Mech. Syst. Signal
//    Process. 11 (1997) 187-205);
//  - a stationary sine reads its amplitude and the PSD integrates to its variance (Parseval for
//    the Welch estimate: P. D. Welch, "The use of fast Fourier transform for the estimation of
//    power spectra", IEEE Trans. Audio Electroacoust. 15 (1967) 70-73);
//  - bad records give located errors before anything runs.
#include "geardyn/analyses/order_analysis.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/analyses/registry.hpp"
#include "geardyn/analyses/run_analysis.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/io/time_history_h5.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using test::fresh_dir;
using test::load;
using test::table;
using test::write_file;

constexpr double kPi = std::numbers::pi;
constexpr double kFs = 20480.0;  // order 26 at 55 rev/s is 1430 Hz: 14 samples per cycle

// Linear ramp n(t) = 15 + 5 t [rev/s] (900 -> 3300 rpm in 8 s).
constexpr double kN0 = 15.0;
constexpr double kAcc = 5.0;
constexpr double kDuration = 8.0;

double theta(double t) { return 2 * kPi * (kN0 * t + 0.5 * kAcc * t * t); }
// Known amplitudes, linear in the speed n [rpm]: order 13 from 1.0 at 900 rpm to 3.0 at 3300
// rpm, order 26 a constant 0.5.
double amplitude13(double rpm) { return 1.0 + 2.0 * (rpm - 900.0) / 2400.0; }
constexpr double kAmplitude26 = 0.5;

std::string run_up_csv() {
  std::string s = "time_s,tacho_v,housing_acc_m_per_s2\n";
  const auto n = static_cast<int>(kDuration * kFs);
  for (int j = 0; j < n; ++j) {
    const double t = j / kFs;
    const double th = theta(t);
    const double rpm = 60.0 * (kN0 + kAcc * t);
    const double x =
        amplitude13(rpm) * std::cos(13 * th + 0.4) + kAmplitude26 * std::cos(26 * th - 1.0);
    s += fmt::format("{:.17g},{:.17g},{:.17g}\n", t, 5.0 * std::cos(th), x);
  }
  return s;
}

std::string model_text(const std::string& extra) {
  return R"(version = 1
# A model of record analyses only: no structure needed.
[[analyses]]
name = "runup"
type = "order_analysis"
record_file = "record.csv"
)" + extra;
}

Outcome run_first(const model::Model& m) {
  check_inputs(m, {});
  return type_of(m.analyses[0]).run(m, m.analyses[0], Context(m, m.analyses[0]));
}

TEST(OrderAnalysis, RunUpOrderCutsRecoverKnownAmplitudesWithinOnePercent) {
  const auto dir = fresh_dir("order_analysis_runup");
  write_file(dir / "record.csv", run_up_csv());
  const model::Model m = load(dir, model_text(R"(tacho_column = "tacho_v"
pulses_per_revolution = 1
orders = [13, 26]
revolutions_per_block = 4
)"));
  const AnalysisOutput out = run_first(m).output;
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  const Table& cuts = table(out, "order_cuts");
  const auto& speed = cuts.column("speed_rpm").numbers;
  const auto& a13 = cuts.column("order_13_housing_acc_m_per_s2").numbers;
  const auto& a26 = cuts.column("order_26_housing_acc_m_per_s2").numbers;
  ASSERT_GT(speed.size(), 80u);  // about 340 revolutions between the first and last pulse
  // Away from the ends (the first and last block): within 1 % (the issue's criterion). Sources
  // of error: the 4-point interpolation (omega h <= 0.45: < 1e-3), the amplitude's change within
  // a block (linear in speed, the block's mean speed is its harmonic mean over the angle: the
  // difference is second order in the 9 % speed change per block at 900 rpm, < 1e-3).
  double worst = 0.0;
  for (std::size_t b = 1; b + 1 < speed.size(); ++b) {
    EXPECT_NEAR(a13[b] / amplitude13(speed[b]), 1.0, 0.01) << speed[b] << " rpm";
    EXPECT_NEAR(a26[b] / kAmplitude26, 1.0, 0.01) << speed[b] << " rpm";
    worst = std::max({worst, std::abs(a13[b] / amplitude13(speed[b]) - 1.0),
                      std::abs(a26[b] / kAmplitude26 - 1.0)});
  }
  RecordProperty("worst_relative_error", std::to_string(worst));
  EXPECT_NEAR(speed.front(), 900.0, 150.0);
  EXPECT_NEAR(speed.back(), 3300.0, 150.0);
  // The waterfall, order map, levels, bands and PSD are there, with their plots.
  for (const char* name : {"waterfall_housing_acc_m_per_s2", "order_map_housing_acc_m_per_s2",
                           "levels", "third_octave", "psd"})
    EXPECT_NO_THROW(table(out, name)) << name;
  bool lines = false;
  for (const Plot& p : out.plots)
    if (p.name == "waterfall_housing_acc_m_per_s2")
      lines = p.traces.size() == 3 && p.traces[1].name == "order 13" && p.traces[0].is_heatmap();
  EXPECT_TRUE(lines);
}

TEST(OrderAnalysis, StationarySineReadsItsAmplitudeAndPsdIntegratesToTheVariance) {
  // 1500 rpm from an angle column; order 13 at 325 Hz = bin 65 of the 4096-sample blocks.
  const auto dir = fresh_dir("order_analysis_stationary");
  std::string s = "time_s,angle_rad,acc_m_per_s2\n";
  const int n = 4 * 20480;
  for (int j = 0; j < n; ++j) {
    const double t = j / kFs;
    const double th = 2 * kPi * 25.0 * t;
    s += fmt::format("{:.17g},{:.17g},{:.17g}\n", t, th, 2.0 * std::sin(13 * th));
  }
  write_file(dir / "record.csv", s);
  const model::Model m = load(dir, model_text(R"(angle_column = "angle_rad"
orders = [13]
db_reference = 1e-6
)"));
  const AnalysisOutput out = run_first(m).output;
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  // On an order bin and a frequency bin: the coherent-gain corrected reading is exact to the
  // interpolation error (omega h = 0.1: 6e-7) and rounding.
  for (double a : table(out, "order_cuts").column("order_13_acc_m_per_s2").numbers)
    EXPECT_NEAR(a, 2.0, 1e-5);
  const Table& w = table(out, "waterfall_acc_m_per_s2");
  const auto& f = w.column("frequency_hz").numbers;
  const auto& amp = w.column("amplitude_acc_m_per_s2").numbers;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (std::abs(f[i] - 325.0) < 1e-9) {
      EXPECT_NEAR(amp[i], 2.0, 1e-9);
    }
  // Parseval for Welch: for an on-bin sine every Hann segment holds exactly A^2/2, so the
  // PSD's integral equals the variance A^2/2 = 2 to rounding.
  const Table& psd = table(out, "psd");
  double total = 0.0;
  const auto& pf = psd.column("frequency_hz").numbers;
  for (double p : psd.column("psd_acc_m_per_s2").numbers) total += p * (pf[1] - pf[0]);
  EXPECT_NEAR(total, 2.0, 1e-9);
  // The overall level: RMS 2 / sqrt 2 re 1e-6 -> 20 lg(1.41421e6) = 123.01 dB.
  for (double db : table(out, "levels").column("level_acc_m_per_s2_db").numbers)
    EXPECT_NEAR(db, 20 * std::log10(std::sqrt(2.0) / 1e-6), 1e-6);
  // The 315 Hz band (282 .. 355 Hz) holds the whole sine: its level is the overall level.
  const Table& bands = table(out, "third_octave");
  const auto& nominal = bands.column("nominal_hz").numbers;
  for (std::size_t i = 0; i < nominal.size(); ++i)
    if (nominal[i] == 315.0) {
      EXPECT_NEAR(bands.column("level_acc_m_per_s2_db").numbers[i],
                  20 * std::log10(std::sqrt(2.0) / 1e-6), 1e-3);
    }
}

TEST(OrderAnalysis, ReadsGeardynsTimeHistoryH5) {
  // The same stationary order-13 sine as above, written by io::write_time_history_h5 (as
  // drivetrain_transient writes long records): the order cut reads the amplitude.
  const auto dir = fresh_dir("order_analysis_h5");
  const int n = 2 * 20480;
  std::vector<double> time(static_cast<std::size_t>(n));
  Eigen::MatrixXd values(n, 2);
  for (int j = 0; j < n; ++j) {
    const double t = j / kFs;
    const double th = 2 * kPi * 25.0 * t;
    time[static_cast<std::size_t>(j)] = t;
    values(j, 0) = th;
    values(j, 1) = 2.0 * std::sin(13 * th);
  }
  io::write_time_history_h5(dir / "record.h5", kFs, time,
                            {{"pinion_angle_rad", "rad"}, {"acc_m_per_s2", "m/s^2"}}, values,
                            static_cast<std::size_t>(n), {});
  const model::Model m = load(dir, R"(version = 1
# A model of record analyses only: no structure needed.
[[analyses]]
name = "h5"
type = "order_analysis"
record_file = "record.h5"
angle_column = "pinion_angle_rad"
orders = [13]
)");
  const AnalysisOutput out = run_first(m).output;
  ASSERT_EQ(out.status, Status::Ok) << out.message;
  for (double a : table(out, "order_cuts").column("order_13_acc_m_per_s2").numbers)
    EXPECT_NEAR(a, 2.0, 1e-5);  // as the CSV record above
}

// The located errors, all from check_inputs (before any analysis runs).
InputError check_error(const std::string& csv, const std::string& keys) {
  const auto dir = fresh_dir("order_analysis_errors");
  if (!csv.empty()) write_file(dir / "record.csv", csv);
  const model::Model m = load(dir, model_text(keys));
  try {
    check_inputs(m, {});
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for " << keys;
  return InputError({}, "", "", "");
}

std::string ramp_csv(int rows, int bad_row = -1) {
  std::string s = "time_s,angle_rad,tacho_v,acc_m_per_s2\n";
  for (int j = 0; j < rows; ++j) {
    const double t = (j == bad_row ? j - 2 : j) / 1000.0;
    s += fmt::format("{},{},{},{}\n", t, 2 * kPi * 10 * t, 0.0, std::sin(j * 0.3));
  }
  return s;
}

TEST(OrderAnalysis, BadRecordsGiveLocatedErrors) {
  const std::string angle = "angle_column = \"angle_rad\"\norders = [1]\nblock_length = 64\n";
  InputError e = check_error("", angle);
  EXPECT_EQ(e.key_path(), "analyses[0].record_file");
  EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();

  e = check_error(ramp_csv(2000), "angle_column = \"speed\"\norders = [1]\n");
  EXPECT_EQ(e.key_path(), "analyses[0].angle_column");
  EXPECT_NE(std::string(e.what()).find("acc_m_per_s2"), std::string::npos) << e.what();

  // Row 100 (file line 102: header on line 1, rows from line 2) goes back in time.
  e = check_error(ramp_csv(2000, 100), angle);
  EXPECT_EQ(e.where().line, 102);
  EXPECT_NE(e.where().file.find("record.csv"), std::string::npos);
  EXPECT_NE(std::string(e.what()).find("strictly increasing time"), std::string::npos);

  e = check_error(ramp_csv(2000), "tacho_column = \"tacho_v\"\norders = [1]\n");
  EXPECT_EQ(e.key_path(), "analyses[0].tacho_column");
  EXPECT_NE(std::string(e.what()).find("0 pulses"), std::string::npos) << e.what();

  // An angle column that decreases at row 10 (line 12).
  std::string csv = ramp_csv(2000);
  {
    std::string s = "time_s,angle_rad,tacho_v,acc_m_per_s2\n";
    for (int j = 0; j < 2000; ++j)
      s += fmt::format("{},{},0,{}\n", j / 1000.0, j == 10 ? 0.0 : 0.1 * j, std::sin(j * 0.3));
    csv = s;
  }
  e = check_error(csv, angle);
  EXPECT_EQ(e.where().line, 12);
  EXPECT_NE(std::string(e.what()).find("increases"), std::string::npos) << e.what();

  // 600 rpm throughout: a range of 1000 .. 2000 rpm is not covered, and the message says what is.
  e = check_error(ramp_csv(2000), angle + "speed_range_rpm = [1000, 2000]\n");
  EXPECT_EQ(e.key_path(), "analyses[0].speed_range_rpm");
  EXPECT_NE(std::string(e.what()).find("600.0 .. 600.0 rpm"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace geardyn::analyses
