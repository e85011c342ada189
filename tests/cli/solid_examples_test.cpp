// End-to-end runs of the solid-component examples: the numbers their READMEs state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

namespace {

using namespace geardyn::cli_test;

/// First-mode frequency of each nodal diameter from a cyclic_modes.csv.
std::map<int, double> first_modes(const fs::path& csv) {
  auto c = read_csv(csv);
  std::map<int, double> out;
  for (std::size_t i = 0; i < c["mode"].size(); ++i)
    if (c["mode"][i] == "1")
      out[std::stoi(c["nodal_diameter"][i])] = std::stod(c["frequency_hz"][i]);
  return out;
}

double worst_relative_error(const fs::path& csv) {
  auto c = read_csv(csv);
  double worst = 0.0;
  for (const auto& e : c["relative_error"]) worst = std::max(worst, std::abs(std::stod(e)));
  return worst;
}

// Annular plate clamped at r = b, free at r = a: b/a = 0.1, a = 0.3 m, h = 0.01 m, steel.
// Reference: A. W. Leissa, "Vibration of Plates", NASA SP-160 (1969), annular plates clamped at
// the inner edge, thin-plate (Kirchhoff) values: ND0 115.60, ND1 95.05, ND2 150.10, ND3
// 333.83 Hz. The issue asks for mesh-converged solid results within 2 %; the solid includes
// shear and rotary inertia (h/a = 1/30), which Kirchhoff theory leaves out, so an exact match is
// not expected (the README shows the mesh convergence: 16 vs 32 radial elements differ by
// < 0.6 %).
TEST(SolidExamples, AnnularPlateMatchesLeissaAndTheFullPlate) {
  const fs::path out = fresh_dir("annular_plate_cyclic");
  const ProcessResult r =
      run("run -q " + kSource + "/examples/annular_plate_cyclic/model.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::map<int, double> leissa = {{0, 115.60}, {1, 95.05}, {2, 150.10}, {3, 333.83}};
  const auto f = first_modes(out / "cyclic" / "cyclic_modes.csv");
  for (const auto& [nd, ref] : leissa) {
    ASSERT_TRUE(f.count(nd)) << "ND " << nd;
    EXPECT_NEAR(f.at(nd), ref, 0.02 * ref) << "ND " << nd;
  }
  // Cyclic symmetry is exact on the same mesh: round-off of the two eigen-solves only (their
  // residuals are ~1e-16; the eigenvalues' condition numbers are moderate), so 1e-8 is loose.
  EXPECT_LT(worst_relative_error(out / "cyclic" / "cyclic_vs_full.csv"), 1e-8);
  // Double modes: every ND between 1 and N/2 - 1 appears twice in the full plate.
  auto full = read_csv(out / "full_plate" / "modes.csv");
  ASSERT_GE(full["frequency_hz"].size(), 7u);
  const double f1a = std::stod(full["frequency_hz"][0]), f1b = std::stod(full["frequency_hz"][1]);
  EXPECT_NEAR(f1a, f.at(1), 1e-8 * f1a);
  EXPECT_NEAR(f1b, f.at(1), 1e-8 * f1b);
  EXPECT_NEAR(std::stod(full["frequency_hz"][2]), f.at(0), 1e-8 * f.at(0));
  // Craig-Bampton (30 modes) + 24 interface modes per ND: a Rayleigh-Ritz approximation from
  // above; the README quotes agreement within 1.1e-6 for the first mode of ND 0-3.
  const auto fr = first_modes(out / "cyclic_reduced" / "cyclic_modes.csv");
  for (int nd = 0; nd <= 3; ++nd) {
    EXPECT_GE(fr.at(nd), f.at(nd) * (1 - 1e-10)) << "ND " << nd;
    EXPECT_LT((fr.at(nd) - f.at(nd)) / f.at(nd), 1e-5) << "ND " << nd;
  }
  auto campbell = read_csv(out / "cyclic" / "cyclic_campbell.csv");
  ASSERT_FALSE(campbell["resonance_speed_rpm"].empty());
  // ND 1 is excited by engine order N - h = 23 at 60 f / 23.
  EXPECT_EQ(campbell["engine_order"][0], "23");
  EXPECT_NEAR(std::stod(campbell["resonance_speed_rpm"][0]), 60.0 * f.at(1) / 23.0, 1e-9 * 300);
  EXPECT_TRUE(fs::exists(out / "cyclic" / "wheel_modes.pvd"));
  EXPECT_TRUE(fs::exists(out / "full_plate" / "modes.msh"));
  // Every step of the ParaView series names its array alike (filters survive stepping) and is
  // binary: no ASCII DataArray.
  int steps = 0;
  for (const auto& entry : fs::directory_iterator(out / "cyclic")) {
    if (entry.path().extension() != ".vtu") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    EXPECT_NE(head.find("Name=\"mode_shape\""), std::string::npos) << entry.path();
    EXPECT_EQ(head.find("format=\"ascii\""), std::string::npos) << entry.path();
    ++steps;
  }
  EXPECT_GT(steps, 1);
}

// A per-analysis `set` that changes a material reaches the solid (it is built again for that
// analysis, not taken from the solids built for the base model): four times the density halves
// every natural frequency of the free-clamped plate, exactly (omega ~ sqrt(E / rho)).
TEST(SolidExamples, AnalysisSetReachesTheSolid) {
  const fs::path dir = fresh_dir("analysis_set_solid");
  const std::string model = R"(version = 1
[[materials]]
name = "steel"
youngs_modulus = 200e9
poisson_ratio = 0.3
density = 7850
[[solids]]
name = "plate"
type = "annular_plate"
material = "steel"
inner_radius = 0.03
outer_radius = 0.3
thickness = 0.01
sectors = 24
radial_elements = 4
circumferential_elements = 2
layers = 1
order = 1
fixed_sets = ["inner"]
[[analyses]]
name = "base"
type = "cyclic_modal"
solid = "plate"
n_modes = 2
[[analyses]]
name = "heavy"
type = "cyclic_modal"
solid = "plate"
n_modes = 2
set = ["materials[0].density=31400"]
)";
  fs::create_directories(dir);
  std::ofstream(dir / "model.toml") << model;
  const ProcessResult r =
      run("run -q " + (dir / "model.toml").string() + " -o " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto base = first_modes(dir / "out" / "base" / "cyclic_modes.csv");
  const auto heavy = first_modes(dir / "out" / "heavy" / "cyclic_modes.csv");
  ASSERT_FALSE(base.empty());
  for (const auto& [nd, f] : base) {
    ASSERT_TRUE(heavy.count(nd)) << "ND " << nd;
    EXPECT_NEAR(heavy.at(nd) / f, 0.5, 1e-9) << "ND " << nd;
  }
}

// The generated gear sector: cyclic symmetry and the full wheel of the same mesh agree (the
// issue's acceptance: "the same frequencies by sector plus cyclic symmetry as by its full-wheel
// mesh"), and the reduced component is written.
TEST(SolidExamples, GearSectorCyclicEqualsFullWheel) {
  const fs::path out = fresh_dir("gear_sector_cyclic");
  const ProcessResult r =
      run("run -q " + kSource + "/examples/gear_sector_cyclic/model.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(worst_relative_error(out / "cyclic" / "cyclic_vs_full.csv"), 1e-8);
  auto cmp = read_csv(out / "sector_reduction" / "reduction_frequencies.csv");
  ASSERT_GE(cmp["error_pct"].size(), 10u);
  for (const auto& e : cmp["error_pct"]) EXPECT_LT(std::abs(std::stod(e)), 0.5);
  EXPECT_TRUE(fs::exists(out / "sector_reduction" / "sector_reduction.h5"));
}

// The damper-ring example: a 40-tooth gear, one tooth per sector, with a split ring in a groove of
// its rim, excited by engine order 38 of its tooth force (nodal diameter 2). The README states
// these numbers. References: the steel ring is held stuck by its centrifugal preload, so the
// friction-damped response is the stuck linear one (the mu -> infinity limit, validated against
// a direct solve in tests/damper: 1e-6 here is the Newton tolerance); the performance curve
// re-traced with the ring's mass matrix scaled must equal the same gear meshed with a ring of the
// scaled density (same mesh: the mass matrices are equal to round-off, 1e-6 leaves room for the
// continuation's points); and the Figure 5-11 shape of A. Durastante, "Simulation of the Dynamic
// Response of Aeronautical Gears Equipped with Damper Rings", MSc thesis, Politecnico di Torino,
// 2018, sec. 5.3: the peak first falls as the ring grows heavier, then rises as it sticks, with an
// interior optimum.
TEST(SolidExamples, DamperRingStuckSteelRingAndAnInteriorMassOptimum) {
  const fs::path out = fresh_dir("damper_ring");
  const ProcessResult r =
      run("run -q " + kSource + "/examples/damper_ring/model.toml -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto res = read_csv(out / "damper" / "resonance.csv");
  ASSERT_EQ(res["curve"].size(), 3u);
  const double damped = std::stod(res["peak_amplitude_m"][0]);
  const double free = std::stod(res["peak_amplitude_m"][1]);
  const double stuck = std::stod(res["peak_amplitude_m"][2]);
  EXPECT_NEAR(damped / stuck, 1.0, 1e-6);
  // The stuck ring adds its mass to the rim: the resonance moves down by 2.5 %.
  EXPECT_NEAR(std::stod(res["speed_shift_vs_free_pct"][2]), -2.5, 0.1);

  auto perf = read_csv(out / "damper" / "performance.csv");
  const std::size_t n = perf["peak_amplitude_m"].size();
  ASSERT_EQ(n, 6u);
  std::size_t best = 0;
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_EQ(perf["status"][i], "ok") << i;
    if (std::stod(perf["peak_amplitude_m"][i]) < std::stod(perf["peak_amplitude_m"][best]))
      best = i;
  }
  EXPECT_GT(best, 0u);
  EXPECT_LT(best, n - 1);
  EXPECT_EQ(perf["optimum"][best], "1");
  const double optimum = std::stod(perf["peak_amplitude_m"][best]);
  EXPECT_LT(optimum, 0.85 * free);
  EXPECT_NEAR(std::stod(perf["peak_amplitude_m"][n - 1]) / stuck, 1.0, 1e-6);

  // The light ring of the optimum, meshed with its own density.
  auto light = read_csv(out / "damper_optimum" / "resonance.csv");
  EXPECT_NEAR(std::stod(light["peak_amplitude_m"][0]) / optimum, 1.0, 1e-6);
  auto pairs = read_csv(out / "damper_optimum" / "contact_pairs.csv");
  ASSERT_FALSE(pairs["slip_fraction"].empty());
  for (std::size_t i = 0; i < pairs["slip_fraction"].size(); ++i) {
    EXPECT_GT(std::stod(pairs["slip_fraction"][i]), 0.5) << i;
    EXPECT_GT(std::stod(pairs["energy_per_cycle_j"][i]), 0.0) << i;
  }
  EXPECT_TRUE(fs::exists(out / "damper_optimum" / "hysteresis_loops.csv"));
  // Stability by the fold count (hbm::fold_unstable, validated against Hill on the Duffing
  // curve in tests/hbm): both damped curves rise and fall without turning, so no point is
  // unstable by a fold.
  for (const char* analysis : {"damper", "damper_optimum"}) {
    auto curve = read_csv(out / analysis / "damped_response.csv");
    ASSERT_FALSE(curve["unstable_fold"].empty()) << analysis;
    for (const auto& v : curve["unstable_fold"]) EXPECT_EQ(v, "0") << analysis;
  }

  // The same analysis on the Craig-Bampton reduced sector (sector faces, contact pairs,
  // excitation and sensor nodes as masters, 40 fixed-interface modes; the ring-mass curve reduces
  // again per mass). Reference: the mesh sector above. Tolerance 1e-3: the fixed-interface modes
  // kept reach 300 kHz, 28 times the 10.9 kHz resonance, so the modal truncation moves the
  // resonance by O((10.9 / 300)^2 x the modal participation of the dropped interior modes) --
  // 5e-5 in speed and 2e-5 in amplitude here.
  const fs::path cb = fresh_dir("damper_ring_cb");
  const ProcessResult rc =
      run("run -q " + kSource + "/examples/damper_ring/model.toml -o " + cb.string() +
          " --only damper --set analyses[0].reduction=craig_bampton");
  ASSERT_EQ(rc.exit_code, 0) << rc.err;
  auto res_cb = read_csv(cb / "damper" / "resonance.csv");
  auto perf_cb = read_csv(cb / "damper" / "performance.csv");
  ASSERT_EQ(res_cb["curve"].size(), 3u);
  ASSERT_EQ(perf_cb["peak_amplitude_m"].size(), n);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::stod(res_cb["peak_amplitude_m"][i]) / std::stod(res["peak_amplitude_m"][i]),
                1.0, 1e-3)
        << res["curve"][i];
    EXPECT_NEAR(std::stod(res_cb["peak_speed_rpm"][i]) / std::stod(res["peak_speed_rpm"][i]), 1.0,
                1e-3)
        << res["curve"][i];
  }
  for (std::size_t i = 0; i < n; ++i)
    EXPECT_NEAR(std::stod(perf_cb["peak_amplitude_m"][i]) / std::stod(perf["peak_amplitude_m"][i]),
                1.0, 1e-3)
        << "ring mass factor " << perf["ring_mass_factor"][i];
  EXPECT_EQ(perf_cb["optimum"][best], "1");
}

// Bad input of a damper-ring response (issue [friction-hbm] sec. 7): the example with one key
// changed is refused before any result is written, exit code 2, naming the key and the reason.
// (Zero friction together with zero preload cannot be written in a model file -- densities and
// speeds are positive -- and is refused by the library: tests/damper.)
TEST(SolidExamples, DamperRingBadInputIsRefusedWithItsKey) {
  std::ifstream in(kSource + "/examples/damper_ring/model.toml");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string example = buffer.str();
  struct Case {
    std::string from, to, key, words;
  };
  const std::vector<Case> cases = {
      // A contact pair index the sector does not have.
      {"performance_values = [0.003, 0.01, 0.03, 0.1, 0.3, 1.0]",
       "performance_values = [0.003, 0.01, 0.03, 0.1, 0.3, 1.0]\nhysteresis_pairs = [10]",
       "analyses[0].hysteresis_pairs[0]", "a contact pair index 0 .. 9"},
      // A gear sector without its groove.
      {"groove = true\ngroove_position = 0.009\ngroove_width = 0.008\ngroove_depth = 0.004\n"
       "ring_width = 0.006\nring_thickness = 0.005\nring_material = \"ring_steel\"\n",
       "", "analyses[0].solid", "groove = true"},
  };
  for (const Case& c : cases) {
    std::string text = example;
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    const fs::path dir = fresh_dir("damper_ring_bad");
    fs::create_directories(dir);
    const fs::path model = dir / "model.toml";
    std::ofstream(model) << text;
    const ProcessResult r = run("run -q " + model.string() + " -o " + (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << c.key << "\n" << r.err;
    EXPECT_NE(r.err.find(c.key), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.words), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out" / "manifest.json")) << c.key;
  }
}

}  // namespace
