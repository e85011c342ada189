// Static equilibrium under load by load control (docs/theory.md §16.11; M. A. Crisfield,
// "Non-linear Finite Element Analysis of Solids and Structures", Vol. 1, 1991, incremental load
// control) on examples/ptu_runup: a 13/39 hypoid mesh with backlash, four preloaded
// taper-roller bearings, a reduced housing and cover on six preloaded bolts. Before load control
// the solve stalled at 600 N m. Checks, each against a closed form:
// - torque balance across a frictionless mesh (virtual work): the driver holds
//   T_in = T_out r_b1 / r_b2, to 1e-8 relative (the equilibrium's residual is below 1e-9 of the
//   largest load, 1.1e4 N, i.e. 1e-5 N m on a torque of 30-300 N m: 1e-7 relative at the worst
//   before round-off; the observed error is 1e-11);
// - the VDI 2230 joint diagram (VDI 2230 Part 1, "Systematic calculation of highly stressed
//   bolted joints", 2015) with load introduction n = 1: with the joint closed the bolt takes the
//   share Phi = k_S / (k_S + k_P) of the external axial load F_A = F_S - F_P:
//   F_S - F_V = Phi (F_S - F_P), to 1e-6 of the preload (the residual tolerance is 1e-9 of the
//   load scale);
// - a load torque on a shaft nothing holds (the mesh removed) has no equilibrium: exit 1, the
//   message names the load factor reached, the load and the advice's model keys.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
             " --set analyses[0].duration=0.002 --set analyses[0].modes=0" +
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
  for (double torque : {100.0, 300.0, 600.0, 900.0}) {
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
  return text.erase(i + 1, j - i - 1);
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

}  // namespace
