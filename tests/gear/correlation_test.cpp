// Correlation with measurements: half-power Q of a synthetic single-degree-of-freedom response
// whose half-power points are known in closed form, peak matching, force scaling, and the
// measured-response CSV reader with its errors.
//
// SDOF receptance (m x'' + c x' + k x = F cos w t), r = f / f_n:
//   |X| k / F = 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2),
// peak at r_p = sqrt(1 - 2 zeta^2), |X|_p k / F = 1 / (2 zeta sqrt(1 - zeta^2));
// |X| = |X|_p / sqrt 2 at r^2 = 1 - 2 zeta^2 -/+ 2 zeta sqrt(1 - zeta^2)   (Ewins, Modal Testing,
// 2nd ed., sec. 2.2 and 4.3), so the half-power Q of the curve is exactly
//   Q_hp = r_p / (r_2 - r_1)   (close to, but not equal to, 1 / (2 zeta)).
#include "geardyn/gear/correlation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"

namespace geardyn::gear {
namespace {

struct Curve {
  std::vector<double> f, a;
};

Curve sdof(double fn, double zeta, double gain, double f0, double f1, double df) {
  Curve c;
  for (double f = f0; f <= f1 + 1e-9; f += df) {
    const double r = f / fn;
    c.f.push_back(f);
    c.a.push_back(gain / std::sqrt((1 - r * r) * (1 - r * r) + (2 * zeta * r) * (2 * zeta * r)));
  }
  return c;
}

double exact_half_power_q(double zeta) {
  const double rp = std::sqrt(1 - 2 * zeta * zeta);
  const double root = 2 * zeta * std::sqrt(1 - zeta * zeta);
  return rp / (std::sqrt(1 - 2 * zeta * zeta + root) - std::sqrt(1 - 2 * zeta * zeta - root));
}

// zeta = 0.01 at f_n = 1000 Hz sampled every 0.25 Hz: the half-power band (20 Hz) holds 80
// samples. Linear interpolation of the crossings errs by ~ a'' df^2 / (8 a') ~ 2e-4 of the band
// and the parabolic peak by less, so Q is compared with 1e-3 relative tolerance.
TEST(Correlation, HalfPowerQOfSdofCurve) {
  const double zeta = 0.01;
  const Curve c = sdof(1000.0, zeta, 1e-6, 900.0, 1100.0, 0.25);
  const PeakEstimate p = estimate_peak(c.f, c.a);
  const double q = exact_half_power_q(zeta);
  std::printf("SDOF zeta = %.3f: Q estimated %.5f, exact half-power %.5f, 1/(2 zeta) = %.1f\n",
              zeta, p.q_factor, q, 0.5 / zeta);
  EXPECT_NEAR(p.q_factor, q, 1e-3 * q);
  EXPECT_NEAR(p.x, 1000.0 * std::sqrt(1 - 2 * zeta * zeta), 0.01);
  EXPECT_NEAR(p.amplitude, 1e-6 / (2 * zeta * std::sqrt(1 - zeta * zeta)), 1e-4 * p.amplitude);
  EXPECT_NEAR(p.damping_ratio, zeta, 2e-3 * zeta);
  EXPECT_GT(p.points_in_band, 70);
}

// Computed response 2 % higher in frequency, 20 % lower in amplitude and with Q 25 % lower than
// the measured one. The mismatches and the force scale follow by construction; tolerances as
// above (sampling of the peaks).
TEST(Correlation, ComparePeaksAndScaleForce) {
  const Curve measured = sdof(1000.0, 0.01, 1e-6, 800.0, 1300.0, 0.25);
  // Same peak amplitude ratio 0.8: gain scaled by 0.8 * (zeta_c / zeta_m) for the new zeta.
  const double zc = 0.0125;
  const Curve computed =
      sdof(1020.0, zc, 1e-6 * 0.8 * zc / 0.01 * std::sqrt(1 - zc * zc) / std::sqrt(1 - 0.01 * 0.01),
           700.0, 1400.0, 0.5);
  const std::vector<PeakComparison> peaks =
      compare_peaks(measured.f, measured.a, computed.f, computed.a);
  ASSERT_EQ(peaks.size(), 1u);
  const PeakComparison& p = peaks[0];
  const double fm = 1000.0 * std::sqrt(1 - 2e-4), fc = 1020.0 * std::sqrt(1 - 2 * zc * zc);
  EXPECT_NEAR(p.x_mismatch, fc / fm - 1.0, 1e-5);
  EXPECT_NEAR(p.amplitude_mismatch, -0.2, 1e-3);
  // Q_hp = r_p / (r_2 - r_1) depends on zeta only.
  EXPECT_NEAR(p.q_mismatch, exact_half_power_q(zc) / exact_half_power_q(0.01) - 1.0, 2e-3);
  const ForceScaling s = scale_force_to_peak(p, 150.0);
  EXPECT_NEAR(s.scale, 1.25, 2e-3);
  EXPECT_NEAR(s.implied_force_n, 187.5, 0.3);
  const Table t = correlation_table(peaks, ResponseAbscissa::FrequencyHz, "m");
  EXPECT_NO_THROW(t.validate());
  EXPECT_TRUE(t.has_column("measured_frequency_hz"));
  EXPECT_TRUE(t.has_column("computed_amplitude_m"));
  EXPECT_NEAR(t.column("amplitude_mismatch_pct").numbers[0], -20.0, 0.1);
  EXPECT_THROW(scale_force_to_peak(p, 0.0), InputError);
}

// Two measured modes: each is matched with its nearest computed peak.
TEST(Correlation, SeveralPeaksAreMatchedByPosition) {
  Curve measured = sdof(1000.0, 0.02, 1e-6, 500.0, 2500.0, 1.0);
  const Curve second = sdof(2000.0, 0.02, 0.5e-6, 500.0, 2500.0, 1.0);
  for (std::size_t i = 0; i < measured.a.size(); ++i) measured.a[i] += second.a[i];
  Curve computed = sdof(1010.0, 0.02, 1e-6, 500.0, 2500.0, 1.0);
  const Curve second_c = sdof(1950.0, 0.02, 0.5e-6, 500.0, 2500.0, 1.0);
  for (std::size_t i = 0; i < computed.a.size(); ++i) computed.a[i] += second_c.a[i];
  const auto peaks = compare_peaks(measured.f, measured.a, computed.f, computed.a);
  ASSERT_EQ(peaks.size(), 2u);
  EXPECT_NEAR(peaks[0].x_mismatch, 0.01, 2e-3);
  EXPECT_NEAR(peaks[1].x_mismatch, -0.025, 2e-3);
  EXPECT_NEAR(estimate_peak(measured.f, measured.a, 1900.0).x, 2000.0, 5.0);
}

TEST(Correlation, MeasuredCsvUnitsAndErrors) {
  const std::string text =
      "# gauge 3\n"
      "speed_rpm, amplitude_um, phase_deg\n"
      "1000, 1.0, 0\n1100, 2.0, -10\n1200, 5.0, -90\n1300, 2.0, -170\n1400, 1.0, -180\n";
  const MeasuredResponse r = parse_measured_response_csv(text, "m.csv");
  EXPECT_EQ(r.abscissa, ResponseAbscissa::SpeedRpm);
  EXPECT_EQ(r.amplitude_unit, "m");
  ASSERT_EQ(r.amplitude.size(), 5u);
  EXPECT_DOUBLE_EQ(r.amplitude[2], 5e-6);
  EXPECT_EQ(r.phase_deg.size(), 5u);
  const MeasuredResponse g =
      parse_measured_response_csv("frequency_hz,amplitude_g\n1,1\n2,2\n3,3\n4,2\n5,1\n", "g.csv");
  EXPECT_EQ(g.amplitude_unit, "m/s^2");
  EXPECT_DOUBLE_EQ(g.amplitude[0], 9.80665);

  auto expect_error = [](const std::string& csv, int line, int column,
                         const std::string& fragment) {
    try {
      (void)parse_measured_response_csv(csv, "m.csv");
      ADD_FAILURE() << "no InputError for " << csv;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().line, line) << e.what();
      EXPECT_EQ(e.where().column, column) << e.what();
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const std::string rows = "1,1\n2,2\n3,3\n4,2\n5,1\n";
  expect_error("speed_rpm,amplitude_um\n1,1\n3,2\n2,3\n4,2\n5,1\n", 4, 1, "increasing");
  expect_error("speed_rpm,amplitude_um\n1,1\n2,-2\n3,3\n4,2\n5,1\n", 3, 3, "amplitude >= 0");
  expect_error("speed_rpm,amplitude_um\n1,1\n2,x\n3,3\n4,2\n5,1\n", 3, 3, "finite number");
  expect_error("speed_rpm,amplitude_parsec\n" + rows, 1, 11, "unit");
  expect_error("speed_rpm,frequency_hz\n1,1\n2,2\n3,3\n4,4\n5,5\n", 1, 11, "one abscissa");
  expect_error("amplitude_m,phase_deg\n" + rows, 1, 1, "speed_rpm or frequency_hz");
  expect_error("speed_rpm,amplitude_m\n1,1\n2,2\n", 3, 0, "at least 5");
  EXPECT_THROW(read_measured_response_csv("/nonexistent/m.csv"), InputError);
  // A curve without an interior maximum has no resonance to estimate.
  const std::vector<double> x{1, 2, 3, 4}, rising{1, 2, 3, 4};
  EXPECT_THROW(estimate_peak(x, rising), InputError);
}

}  // namespace
}  // namespace geardyn::gear
