// End-to-end run of examples/spiral_bevel_gear_sector: the numbers its README states.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"

namespace {

using namespace geardyn::cli_test;

double num(const std::string& s) { return std::stod(s); }

/// Row index of the first row where every (column, value) matches.
std::size_t find_row(std::map<std::string, std::vector<std::string>>& csv,
                     const std::vector<std::pair<std::string, std::string>>& keys) {
  const std::size_t n = csv.begin()->second.size();
  for (std::size_t i = 0; i < n; ++i) {
    bool ok = true;
    for (const auto& [col, value] : keys) ok = ok && csv[col][i] == value;
    if (ok) return i;
  }
  ADD_FAILURE() << "no row with " << keys.front().first << " = " << keys.front().second;
  return 0;
}

// The pinion: 24 teeth, one tooth per sector (N = 24), nodal diameters 2 and 3, engine orders
// k = h (backward wave, standing under the mesh) and k = N - h (forward wave, the mesh
// frequency in the stationary frame), docs/theory.md §10, §12.3.
TEST(SpiralBevelExample, EngineOrderResonancesAndHarmonics) {
  const fs::path out = fresh_dir("spiral_bevel_gear_sector");
  const ProcessResult r =
      run("run -q " + kSource + "/examples/spiral_bevel_gear_sector/model.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const auto manifest = read_json(out / "manifest.json");
  for (const auto& a : manifest["analyses"]) EXPECT_EQ(a["status"], "ok") << a["name"];

  // (1) The harmonic forces of the forced response are those mesh_harmonics tabulates (the
  // same computation, analyses::tooth_force_over_revolution; CSV digits: 1e-12).
  auto forces = read_csv(out / "forced" / "harmonic_forces.csv");
  auto harmonics = read_csv(out / "harmonics" / "harmonics.csv");
  std::map<int, double> tangential;
  for (const auto& [h, k] : std::vector<std::pair<int, int>>{{2, 2}, {2, 22}, {3, 3}, {3, 21}}) {
    const std::size_t i = find_row(
        forces, {{"nodal_diameter", std::to_string(h)}, {"engine_order", std::to_string(k)}});
    const std::size_t j = find_row(
        harmonics, {{"nodal_diameter", std::to_string(h)}, {"engine_order", std::to_string(k)}});
    tangential[k] = num(forces["tangential_n"][i]);
    EXPECT_NEAR(tangential[k], num(harmonics["tangential_n"][j]), 1e-12 * tangential[k]) << k;
    EXPECT_NEAR(num(forces["axial_n"][i]), num(harmonics["axial_n"][j]),
                1e-12 * std::abs(num(harmonics["axial_n"][j])))
        << k;
  }
  // (2) k = h: the window's closed-form coefficient (gear/load_window.hpp) on the mean
  // tangential force, A_k = 2 F_t |W_k|, W_k = (1/N) sinc(k p / 2) sinc(k L / 2), p = 2 pi / N,
  // L = (CR - 1) p. The 5 % / 1.5 % STE fluctuation at orders N, 2N adds F_N W_{k -+ N}, about
  // 1e-3 of A_k (|W_{2-24}|, |W_{2+24}| ~ 6e-4 against W_2 ~ 0.04, times the 2.5 % complex
  // amplitude): tolerance 0.3 %. k = N - h sits near the zeros of the sinc factors, so there the
  // fluctuation matters and the ratio A_{N-h} / A_h is small (2 %; README).
  auto geometry = read_csv(out / "pair" / "gear_geometry.csv");
  auto tooth = read_csv(out / "pair" / "tooth_forces.csv");
  const double cr = num(geometry["total_contact_ratio"][0]);
  const double ft = num(tooth["tangential_force_n"][0]);
  const int n = 24;
  const double p = kTwoPi / n, l = (cr - 1.0) * p;
  auto sinc = [](double x) { return std::sin(x) / x; };
  for (int h : {2, 3}) {
    const double a = 2.0 * ft * std::abs(sinc(h * p / 2) * sinc(h * l / 2)) / n;
    EXPECT_NEAR(tangential[h], a, 3e-3 * a) << "h = " << h;
    EXPECT_LT(tangential[n - h] / tangential[h], 0.05) << "h = " << h;
  }

  // (3) Resonance speeds W = 60 f / k [rpm] with f the first mode of ND h from the Campbell
  // analysis (same sector, its own eigen-solve: 1e-8 relative), both orders listed, the N - h
  // ones inside 1000 .. 30000 rpm and the k = h ones far above.
  auto modes = read_csv(out / "campbell" / "cyclic_modes.csv");
  auto res = read_csv(out / "forced" / "cyclic_resonances.csv");
  for (int h : {2, 3}) {
    const double f = num(modes["frequency_hz"][find_row(
        modes, {{"nodal_diameter", std::to_string(h)}, {"mode", "1"}})]);
    for (int k : {h, n - h}) {
      const std::size_t i = find_row(res, {{"nodal_diameter", std::to_string(h)},
                                           {"engine_order", std::to_string(k)},
                                           {"mode", "1"}});
      EXPECT_NEAR(num(res["resonance_speed_rpm"][i]), 60.0 * f / k, 1e-8 * 60.0 * f / k);
      EXPECT_EQ(res["order_rule"][i], k == h ? "h" : "N-h");
      EXPECT_EQ(res["wave"][i], k == h ? "backward" : "forward");
      EXPECT_EQ(res["in_range"][i], k == h ? "0" : "1");
    }
  }

  // (4) The computed peaks of the N - h curves: at the resonance speed (parabolic refinement
  // on a 50 rpm grid: 0.1 %), with the half-power Q of the assumed Q = 40 (isolated mode; the
  // crossings are interpolated linearly over 5 and 13 samples: 3 %).
  auto peaks = read_csv(out / "forced" / "cyclic_response_peaks.csv");
  auto campbell = read_csv(out / "campbell" / "cyclic_campbell.csv");
  for (int h : {2, 3}) {
    const std::size_t i =
        find_row(peaks, {{"sensor", "excitation_uz"},
                         {"curve", "ND " + std::to_string(h) + " EO " + std::to_string(n - h)}});
    const std::size_t c = find_row(
        campbell, {{"nodal_diameter", std::to_string(h)}, {"engine_order", std::to_string(n - h)}});
    const double w = num(campbell["resonance_speed_rpm"][c]);
    EXPECT_NEAR(num(peaks["speed_rpm"][i]), w, 1e-3 * w) << "h = " << h;
    EXPECT_NEAR(num(peaks["q_factor"][i]), 40.0, 0.03 * 40.0) << "h = " << h;
  }
  EXPECT_TRUE(fs::exists(out / "campbell" / "wheel_modes.pvd"));
}

}  // namespace
