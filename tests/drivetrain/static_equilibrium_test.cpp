// Static equilibrium under load by load control (docs/theory.md §16.11; M. A. Crisfield,
// "Non-linear Finite Element Analysis of Solids and Structures", Vol. 1, 1991, incremental load
// control) on examples/ptu_runup: a 13/39 hypoid mesh with backlash, four preloaded
// taper-roller bearings, a reduced housing and cover on six preloaded bolts, at 100, 300, 600,
// 900 N m (before this solver the static solve stalled at 600 N m) and 20 kN m (where the
// full-load increment fails and load control halves it). Checks, each against a closed form:
// - torque balance across a frictionless mesh (virtual work): the driver holds
//   T_in = T_out r_b1 / r_b2, to 1e-8 relative (the task's bound). The stopping test alone
//   (|r|_inf below 1e-9 of the largest load, 1.1e4 N: 1.1e-5 N m at the wheel's spin) only
//   guarantees 1e-7 on the smallest pinion torque, 33 N m; Newton's last, quadratically
//   converging step leaves far less (observed 1e-11), so 1e-8 holds with margin;
// - the VDI 2230 joint diagram (VDI 2230 Part 1, "Systematic calculation of highly stressed
//   bolted joints", 2015) with load introduction n = 1: with the joint closed the bolt takes the
//   share Phi = k_S / (k_S + k_P) of the external axial load F_A = F_S - F_P:
//   F_S - F_V = Phi (F_S - F_P), to 1e-6 of the preload (the residual tolerance is 1e-9 of the
//   load scale);
// - a load torque on a shaft nothing holds (the mesh removed) has no equilibrium: exit 1, the
//   message names the load factor reached, the load and the advice's model keys;
// - in process, a shaft on a bushing: moment balance about the axis (driver + bushing + load =
//   0), the table's units per coordinate (N for forces, N m for moments), and without the
//   bushing's torsion the failure names the unheld spin by node and component;
// - a hypoid mesh whose pitch point is off the wheel's transverse plane is a located error.
#include "geardyn/drivetrain/static_equilibrium.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/drivetrain/builder.hpp"
#include "support/example_runs.hpp"

namespace {

using namespace geardyn::cli_test;

constexpr double kRb1 = 0.030533333333, kRb2 = 0.0916;  // gear_meshes[0].base_radius1/2 [m]
constexpr double kPreload = 15000.0;                    // bolts[*].preload [N]
constexpr double kBolt = 5.0e7, kClamp = 2.5e8;         // bolts[*] k_S, k_P [N/m]

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A copy of examples/ptu_runup in a fresh folder with model.toml passed through `edit`.
fs::path ptu_copy(const std::string& name, std::string (*edit)(std::string)) {
  const fs::path dir = fresh_dir(name);
  fs::create_directories(dir);
  const fs::path src = fs::path(kSource) / "examples" / "ptu_runup";
  for (const char* f : {"housing.bdf", "cover.bdf"}) fs::copy_file(src / f, dir / f);
  std::ofstream(dir / "model.toml") << edit(read_text(src / "model.toml"));
  return dir;
}

std::string unchanged(std::string text) { return text; }

// The run-up's static start (bolts not yet active) and the assembled unit (every bolt tightened
// at t = 0), both at load torque T on the wheel; a short run (the static state is its first
// sample).
ProcessResult run_ptu(const fs::path& dir, double torque) {
  return run("run -q " + (dir / "model.toml").string() + " -o " + (dir / "out").string() +
             " --only runup assembled --set analyses[1].enabled=true" +
             " --set loads[0].torque=" + std::to_string(-torque) +
             " --set analyses[0].duration=0.002 --set analyses[0].modes=0 --set "
             "'analyses[0].frf_excitation=\"\"'" +
             " --set analyses[0].spectrum_start=0");
}

double holding_torque(const fs::path& csv) {
  auto t = read_csv(csv);
  for (std::size_t i = 0; i < t["element"].size(); ++i)
    if (t["element"][i] == "driver 'input'") return std::stod(t["value"][i]);
  ADD_FAILURE() << "no holding torque in " << csv;
  return 0.0;
}

TEST(StaticEquilibrium, PtuUnderLoadBalancesTheTorqueAcrossTheMeshAndFollowsTheJointDiagram) {
  const fs::path dir = ptu_copy("static_ptu", unchanged);
  for (double torque : {100.0, 300.0, 600.0, 900.0, 20000.0}) {
    SCOPED_TRACE("load torque " + std::to_string(torque) + " N m");
    const ProcessResult r = run_ptu(dir, torque);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const double expected = torque * kRb1 / kRb2;
    for (const char* analysis : {"runup", "assembled"}) {
      const double held = holding_torque(dir / "out" / analysis / "static_equilibrium.csv");
      EXPECT_NEAR(held, expected, 1e-8 * expected) << analysis;
    }
    // The assembled unit's first sample is its static equilibrium.
    auto th = read_csv(dir / "out" / "assembled" / "time_history.csv");
    const double phi = kBolt / (kBolt + kClamp);
    for (int b = 1; b <= 6; ++b) {
      const std::string bolt = "bolt" + std::to_string(b);
      const double fs_ = numbers(th[bolt + "_bolt_force_n"]).at(0);
      const double fp = numbers(th[bolt + "_clamp_force_n"]).at(0);
      EXPECT_GT(fp, 0.0) << bolt << " joint open";
      EXPECT_NEAR(fs_ - kPreload, phi * (fs_ - fp), 1e-6 * kPreload) << bolt;
    }
  }
}

std::string without_mesh(std::string text) {
  const auto i = text.find("\n[[gear_meshes]]");
  const auto j = text.find("# ---- Housing-side nodes");
  if (i == std::string::npos || j == std::string::npos || j < i) return text;
  text.erase(i + 1, j - i - 1);
  // The run-up's order analysis follows the pinion angle of the mesh removed.
  for (const char* key : {"\norder_channels =", "\norder_reference =", "\norders ="}) {
    const auto k = text.find(key);
    if (k != std::string::npos) text.erase(k + 1, text.find('\n', k + 1) - k);
  }
  return text;
}

TEST(StaticEquilibrium, ALoadTorqueOnAShaftNothingHoldsFailsNamingTheLoadAndTheKeys) {
  const fs::path dir = ptu_copy("static_ptu_unheld", without_mesh);
  ASSERT_EQ(read_text(dir / "model.toml").find("[[gear_meshes]]\nname"), std::string::npos);
  const ProcessResult r = run_ptu(dir, 300.0);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("static equilibrium not reached: load factor 0 "), std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("acting there: load 'output'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("loads[].torque"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("[[drivers]]"), std::string::npos) << r.err;
}

// The hypoid mesh is located at its mid-face pitch point, r_b1 / cos(alpha_t) from the pinion's
// node; moving the wheel shaft 5 mm along its axis puts that point 5 mm off the wheel's
// transverse plane (tolerance 1e-3 r_p2 = 0.1 mm): a located error at gear2 with the distance.
TEST(StaticEquilibrium, AHypoidMeshWhosePitchPointMissesTheWheelIsALocatedError) {
  const fs::path dir = ptu_copy("static_ptu_hypoid_off", unchanged);
  const ProcessResult r =
      run("run -q " + (dir / "model.toml").string() + " -o " + (dir / "out").string() +
          " --only runup --set analyses[0].duration=0.002 --set analyses[0].modes=0 --set "
          "'analyses[0].frf_excitation=\"\"'" +
          " --set analyses[0].spectrum_start=0 --set shafts[1].origin=[0.0,0.0,-0.085]");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("model.toml:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("key 'gear_meshes[0].gear2'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(", 0.0050003"), std::string::npos)
      << r.err;  // 5 mm + the 0.3 um z of the pitch point
  EXPECT_NE(r.err.find(" m from that point"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("in mesh 'hypoid'"), std::string::npos) << r.err;
}

// One shaft s.0 - s.1 (torsional stiffness k_t = G J / L), held by a speed driver at s.0 and a
// 6-DOF bushing from ground at s.1, a load torque T at s.1.
std::string bushing_model(double ktzz) {
  return fmt::format(R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 2.1e11
poisson_ratio = 0.3
density = 7850
[[shafts]]
name = "s"
material = "steel"
[[shafts.elements]]
length = 0.2
outer_diameter = 0.04
[[bushings]]
name = "mount"
node2 = "s.1"
kxx = 1e7
kyy = 2e7
kzz = 3e7
ktxx = 1e5
ktyy = 2e5
ktzz = {}
[[drivers]]
name = "d"
node = "s.0"
type = "speed"
time = [0.0]
speed_rpm = [0.0]
[[loads]]
name = "brake"
node = "s.1"
torque = -10.0
)",
                     ktzz);
}

TEST(StaticEquilibrium, ShaftOnABushingBalancesMomentsAndTabulatesUnitsPerCoordinate) {
  const geardyn::model::Model m = geardyn::analyses::parse_model(bushing_model(1e4), "model.toml");
  const geardyn::fe::LinearSystem sys = geardyn::assembly::build_system(m);
  geardyn::drivetrain::DrivetrainSystem system(geardyn::drivetrain::build_drivetrain(m, sys, {}));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.size());
  const auto st = geardyn::drivetrain::solve_static(system, 0.0, zero, zero);
  ASSERT_EQ(st.status, geardyn::Status::Ok) << st.message;
  EXPECT_EQ(st.load_factor, 1.0);
  const auto rows = geardyn::drivetrain::static_table(system, sys.dofs, 0.0, zero, st, {"d"});
  ASSERT_EQ(rows.size(), 7u);  // six bushing coordinates and the driver
  const char* units[7] = {"N", "N", "N", "N m", "N m", "N m", "N m"};
  for (std::size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(rows[i].unit, units[i]) << i;
  // Moment balance about the shaft axis on the shaft: driver + (minus the bushing's internal
  // moment) + load = 0, to the static tolerance (1e-9 of the 10 N m load).
  const double driver = rows[6].value, bushing = rows[5].value;
  EXPECT_NEAR(driver - bushing - 10.0, 0.0, 1e-8);
  // Two torsion springs in parallel on the loaded end: the bushing takes k_tz / (k_t + k_tz) of
  // the load, k_t = G J / L of the uniform shaft (G = E / 2 (1 + nu), J = pi d^4 / 32), exact for
  // the shaft element's torsion; 1e-8 relative as above.
  const double G = 2.1e11 / (2.0 * 1.3), J = std::numbers::pi * std::pow(0.04, 4) / 32.0;
  const double k_t = G * J / 0.2, k_tz = 1e4;
  EXPECT_NEAR(bushing, -10.0 * k_tz / (k_t + k_tz), 1e-8 * 10.0);
  EXPECT_NEAR(driver, 10.0 * k_t / (k_t + k_tz), 1e-8 * 10.0);
}

TEST(StaticEquilibrium, AnUnheldSpinFailsNamingItsNodeAndComponent) {
  // No driver and no torsion in the bushing: nothing holds the shaft's spin against the load.
  std::string text = bushing_model(0.0);
  text.erase(text.find("[[drivers]]"), text.find("[[loads]]") - text.find("[[drivers]]"));
  const geardyn::model::Model m = geardyn::analyses::parse_model(text, "model.toml");
  const geardyn::fe::LinearSystem sys = geardyn::assembly::build_system(m);
  geardyn::drivetrain::DrivetrainSystem system(geardyn::drivetrain::build_drivetrain(m, sys, {}));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.size());
  geardyn::drivetrain::StaticOptions options;
  options.equation_names = geardyn::drivetrain::equation_names(sys.dofs);
  const auto st = geardyn::drivetrain::solve_static(system, 0.0, zero, zero, options);
  ASSERT_EQ(st.status, geardyn::Status::NotConverged);
  EXPECT_EQ(st.load_factor, 0.0);
  EXPECT_NE(st.message.find("rz), acting there: load 'brake'"), std::string::npos) << st.message;
  EXPECT_NE(st.message.find("node 's."), std::string::npos) << st.message;
}

}  // namespace
