// examples/backrest_adjuster: the drivetrain transient of a motor, two gear stages with backlash
// and IMPACT tooth contact and an elastic coupling, against its variant with a steel link; the
// numbers its README states hold.
//   * Statics: a moment balance through the gear ratios; the static solve stops at
//     |r| <= 1e-9 x the largest static force (106 N), which leaves the holding torque within
//     ~1e-8 N m of -0.1 N m.
//   * Mode 2 (the backrest on its coupling): a deterministic eigen-solve of the tangent
//     matrices; the README's four digits, checked to half a unit of the last one.
//   * Peaks: the adaptive integration (rtol 1e-4) moves them by < 0.2 % when tightened tenfold
//     (measured when the README was written); 3 % covers that and the README's rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "support/example_runs.hpp"

namespace {

using namespace geardyn::cli_test;

std::map<std::string, std::map<std::string, double>> summary(const fs::path& dir) {
  auto t = read_csv(dir / "summary.csv");
  std::map<std::string, std::map<std::string, double>> s;
  for (std::size_t i = 0; i < t["channel"].size(); ++i)
    for (const char* q : {"min", "max", "peak", "rms"}) s[t["channel"][i]][q] = std::stod(t[q][i]);
  return s;
}

TEST(BackrestExample, StaticsModesAndPeaksAsTheReadmeSays) {
  ProcessResult r;
  const fs::path out = run_example("backrest_adjuster", r);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  struct Case {
    const char* name;
    double mode2_hz, mode2_zeta;
    double motor_acc, coupling, mesh1, mesh2, backrest_acc, stop, mesh2_min;
  };
  const Case cases[] = {
      {"with_elastic_part", 25.34, 0.646, 1.67e4, 8.18, 115.0, 289.0, 1990.0, 690.0, 106.418},
      {"steel_link", 120.65, 0.068, 5.26e4, 15.4, 215.0, 543.0, 1730.0, 699.0, 0.0}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path dir = out / c.name;
    // Statics: motor holding torque -3 N m / 30; tooth forces 0.1 N m / r_b1, 0.5 N m / r_b1.
    auto st = read_csv(dir / "static_equilibrium.csv");
    const auto values = numbers(st["value"]);
    bool held = false;
    for (std::size_t i = 0; i < values.size(); ++i)
      if (st["element"][i] == "motor 'motor' (held)") {
        EXPECT_NEAR(values[i], -0.1, 1e-8);
        held = true;
      }
    EXPECT_TRUE(held);
    // Mode 2 and its damping ratio.
    auto eig = read_csv(dir / "eigen.csv");
    const auto f = numbers(eig["undamped_natural_frequency_hz"]);
    const auto zeta = numbers(eig["damping_ratio"]);
    ASSERT_GE(f.size(), 2u);
    EXPECT_NEAR(f[1], c.mode2_hz, 0.005);
    EXPECT_NEAR(zeta[1], c.mode2_zeta, 0.0005);
    // Peaks.
    auto s = summary(dir);
    auto near = [](double got, double want) { EXPECT_NEAR(got, want, 0.03 * want); };
    near(s["motor_end_rad_per_s2"]["peak"], c.motor_acc);
    near(s["coupling_mz_nm"]["peak"], c.coupling);
    near(s["stage1_mesh_force_n"]["peak"], c.mesh1);
    near(s["stage2_mesh_force_n"]["peak"], c.mesh2);
    near(s["backrest_end_rad_per_s2"]["peak"], c.backrest_acc);
    near(s["end_stop_torque_nm"]["peak"], c.stop);
    EXPECT_NEAR(s["stage2_mesh_force_n"]["min"], c.mesh2_min, 1e-3 * 106.418);
  }
  // The start-up acceleration of the motor's node: (T_stall - T_hold) / J with J the rotor and
  // motor inertia 6e-6 kg m^2 plus that node's share of the motor shaft (less than the whole
  // shaft's polar inertia, 20 mm of d = 4 mm steel); the pinion sits behind the shaft's
  // compliance and does not move at t = 0+.
  const double J_shaft = 7850.0 * M_PI * std::pow(0.004, 4) / 32.0 * 0.02;
  const double J = 4e-6 + 2e-6;
  const double a = summary(out / "with_elastic_part")["motor_end_rad_per_s2"]["max"];
  EXPECT_LE(a, 0.1 / J);
  EXPECT_GT(a, 0.1 / (J + J_shaft));
}

}  // namespace
