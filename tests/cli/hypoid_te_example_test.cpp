// examples/hypoid_te: the loaded tooth contact analysis of a hypoid pair with ease-off runs
// through its virtual cylindrical pair, the H sweep moves the contact pattern, and the numbers
// its README states hold. The README quotes three significant digits; the tolerances are half a
// unit of the last one. The first-order estimate of the pattern shift (docs/theory.md (15.24))
// is the light-load centre of the gap; at 300 N m the loaded pattern is wider and its load-
// weighted centre moves less (checked: between 1/2 and 1 of the estimate, same sign).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "support/example_runs.hpp"

namespace {

using namespace geardyn::cli_test;

// The synthetic rig file (te_measured_synthetic.csv) was made as computed x 1.10 + 0.05 um,
// rounded to 0.01 um: the te_correlation table of te_map must give back that relation at every
// point, ratio = 1.10 + 0.05 um / computed within the rounding (0.005 um, with a margin for the
// last digit: 0.0051 um / computed), and the note's least-squares line must give 1.10 and 0.05 um
// within the bound the rounding errors e_i (|e_i| <= 0.0051 um) allow: the gain moves by
// sum (x_i - mean x) e_i / S_xx, the offset by sum e_i (1/n - mean x (x_i - mean x) / S_xx)
// (x_i the computed amplitudes), plus half a unit of the note's fourth digit.
void check_correlation(const fs::path& out, const std::map<std::pair<double, double>, double>& c) {
  auto table = read_csv(out / "te_map" / "te_correlation.csv");
  const auto t = numbers(table["torque_nm"]), order = numbers(table["mesh_order"]);
  const auto computed = numbers(table["computed_0_peak_m"]);
  const auto measured = numbers(table["measured_0_peak_m"]);
  const auto ratio = numbers(table["ratio_measured_to_computed"]);
  const auto db = numbers(table["difference_db"]);
  const auto compared = numbers(table["compared"]);
  ASSERT_EQ(t.size(), 12u);
  const double rounding = 0.0051e-6;
  double mean = 0.0, sum_ratio = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    ASSERT_TRUE(c.count({t[i], order[i]})) << t[i] << " " << order[i];
    EXPECT_EQ(computed[i], c.at({t[i], order[i]}));  // the te_harmonics value, same digits
    EXPECT_EQ(compared[i], 1.0);
    EXPECT_NEAR(ratio[i], 1.10 + 0.05e-6 / computed[i], rounding / computed[i]) << i;
    EXPECT_NEAR(db[i], 20.0 * std::log10(ratio[i]), 1e-12) << i;
    EXPECT_NEAR(measured[i], ratio[i] * computed[i], 1e-12 * measured[i]);
    mean += computed[i] / 12.0;
    sum_ratio += ratio[i];
  }
  // The README's summary: mean ratio 1.43, largest difference +9.89 dB (300 N m, order 2).
  EXPECT_NEAR(sum_ratio / 12.0, 1.43, 0.005);
  EXPECT_NEAR(*std::max_element(db.begin(), db.end()), 9.89, 0.005);
  double sxx = 0.0, gain_bound = 0.0, offset_bound = 0.0;
  for (double x : computed) sxx += (x - mean) * (x - mean);
  for (double x : computed) {
    gain_bound += rounding * std::abs(x - mean) / sxx;
    offset_bound += rounding * std::abs(1.0 / 12.0 - mean * (x - mean) / sxx);
  }
  std::smatch m;
  bool found = false;
  for (const std::string& note : notes_of(out, "te_map")) {
    static const std::regex fit(R"(measured = ([-+0-9.e]+) x computed ([-+0-9.e]+) um)");
    static const std::regex mean_ratio(R"(Mean ratio measured / computed ([0-9.e+-]+);)");
    if (!std::regex_search(note, m, fit)) continue;
    found = true;
    EXPECT_NEAR(std::stod(m[1]), 1.10, gain_bound + 0.0005) << note;
    EXPECT_NEAR(std::stod(m[2]) * 1e-6, 0.05e-6, offset_bound + 0.000005e-6) << note;
    ASSERT_TRUE(std::regex_search(note, m, mean_ratio)) << note;
    EXPECT_NEAR(std::stod(m[1]), sum_ratio / 12.0, 0.0005 * sum_ratio / 12.0) << note;
  }
  EXPECT_TRUE(found);
}

TEST(HypoidTeExample, RunsAndTheSweepOfHMovesThePattern) {
  ProcessResult r;
  const fs::path out = run_example("hypoid_te", r);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(read_json(out / "manifest.json")["status"], "ok");

  auto summary = read_csv(out / "te_map" / "summary.csv");
  const auto pp = numbers(summary["te_peak_peak_m"]);
  const auto khb = numbers(summary["face_load_factor"]);
  ASSERT_EQ(pp.size(), 6u);
  EXPECT_NEAR(pp[0], 2.19e-6, 0.005e-6);  // 50 N m
  EXPECT_NEAR(pp[3], 2.52e-6, 0.005e-6);  // 300 N m
  EXPECT_NEAR(khb[0], 2.60, 0.005);
  EXPECT_NEAR(khb[5], 1.40, 0.005);

  // The first mesh-order harmonic at each torque, and the synthetic rig file against it
  // (te_correlation).
  auto harmonics = read_csv(out / "te_map" / "te_harmonics.csv");
  const auto t = numbers(harmonics["torque_nm"]), order = numbers(harmonics["mesh_order"]);
  const auto amp = numbers(harmonics["amplitude_0_peak_m"]);
  std::map<std::pair<double, double>, double> computed;
  for (std::size_t i = 0; i < t.size(); ++i) computed[{t[i], order[i]}] = amp[i];
  const double h300 = computed[{300.0, 1.0}], h100 = computed[{100.0, 1.0}];
  EXPECT_NEAR(h300, 1.27e-6, 0.005e-6);
  EXPECT_NEAR(h100, 0.371e-6, 0.0005e-6);
  check_correlation(out, computed);

  // The H sweep at 300 N m: the pattern moves to the heel for H > 0 (out of mesh) and to the
  // toe for H < 0, nearly antisymmetrically; the TE's first harmonic is smallest at H = 0 (the
  // pattern runs into the face ends as it moves).
  auto sweep = read_csv(out / "h_sweep" / "sweep.csv");
  const auto h = numbers(sweep["value_m"]);
  const auto face = numbers(sweep["pattern_centre_face_1"]);
  const auto te1 = numbers(sweep["te_harmonic_1_m"]);
  ASSERT_EQ(h.size(), 5u);
  EXPECT_NEAR(face[0], -0.405, 0.0005);
  EXPECT_NEAR(face[1], -0.230, 0.0005);
  EXPECT_NEAR(face[2], -0.002, 0.0005);
  EXPECT_NEAR(face[3], 0.227, 0.0005);
  EXPECT_NEAR(face[4], 0.401, 0.0005);
  EXPECT_NEAR(te1[0], 1.40e-6, 0.005e-6);
  EXPECT_NEAR(te1[2], 1.27e-6, 0.005e-6);
  EXPECT_NEAR(te1[4], 1.47e-6, 0.005e-6);
  for (std::size_t i = 0; i < 5; ++i) {
    if (i != 2) {
      EXPECT_GT(te1[i], te1[2]);
    }
  }
  // First order, light load (the te_at_300 note for H = 0.1 mm: eta_c = 0.313).
  EXPECT_GT(face[3], 0.5 * 0.313);
  EXPECT_LT(face[3], 0.313);
}

}  // namespace
