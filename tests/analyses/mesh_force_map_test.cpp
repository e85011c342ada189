// The force map of a gear pair for the drivetrain's tooth-contact element
// (analyses/mesh_force_map.hpp, docs/theory.md §16.6) from each STE source, through the model
// file:
//   * the loaded tooth contact analysis: the map's points are the LTCA's loaded TE at its
//     torques (the same computation: 1e-12), the element's static solution reproduces them, and
//     between torques it stays within the interpolation bound of a concave approach-force
//     curve (below);
//   * the synthetic ISO 6336 STE and a one-torque STE are the linear mesh k = F_s / (e - e_g)
//     (A. Durastante, "Simulation of the Dynamic Response of Aeronautical Gears Equipped with
//     Damper Rings", MSc thesis, Politecnico di Torino, 2018, sec. 3.1-3.2);
//   * a multi-torque STE file gives one curve per torque; a non-monotone one is an error at the
//     pair's ste_file.
//
// Pair: spur z1 = 20, z2 = 40, m = 3 mm, b = 20 mm (tests/support/gear_models.hpp).
#include "geardyn/analyses/mesh_force_map.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "geardyn/analyses/tooth_contact.hpp"
#include "geardyn/core/error.hpp"
#include "support/gear_models.hpp"

namespace geardyn::analyses {
namespace {

using namespace test;
constexpr double kPi = std::numbers::pi;

const std::string kTipRelief = R"(ste_source = "tooth_contact"
[gear_pairs.flank1]
tip_relief = 8e-6
tip_relief_start_diameter = 0.0625
[gear_pairs.contact]
positions = 16
slices = 12
)";

Eigen::VectorXd vec(double a, double b) {
  Eigen::VectorXd x(2);
  x << a, b;
  return x;
}

// Newton on F(delta, theta) = target (the law is piecewise linear and monotone).
double solve_approach(const elements::GearMeshContact& c, double theta, double target) {
  double delta = c.unloaded_te(theta) + target / c.map().mean_stiffness();
  elements::ElementForce out;
  for (int it = 0; it < 60; ++it) {
    c.evaluate(vec(delta, theta), vec(0.0, 0.0), 0.0, out);
    const double r = out.force(0) - target;
    if (std::abs(r) < 1e-13 * target) return delta;
    delta -= r / out.stiffness(0, 0);
  }
  ADD_FAILURE() << "Newton did not converge";
  return delta;
}

// LTCA route. (a) At the map's torques T_j = (0.25, 0.5, 1, 1.5, 2) x 120 N m the map is the
// LTCA's loaded TE and unloaded TE at every position (an independent solve of the same model:
// 1e-12), its curve at the pair's torque is the pair's STE (contact_ste), and the element's static
// solution for F_j = T_j / r_b1 at the grid angles is that TE (1e-12: a piecewise-linear law).
// (b) At T = 90 N m, between the map's 60 and 120 N m, the static solution is the chord of the
// approach-force curve d(F). That curve is concave (the mesh stiffens with load: Hertzian
// flattening, and the tip relief lets more of the profile carry load; checked on the data), so
// the true d(F) lies between the chord and the lesser of the neighbouring chords' extensions
// (those from 30-60 and 120-180 N m): the bound the test uses, per angle. It must be tight
// enough to matter: below 1 % of the elastic approach (it is 0.4-0.6 %, the error 0.15-0.2 %).
TEST(MeshForceMap, LtcaMapReproducesTheContactAnalysisAtItsTorques) {
  const model::Model m = load(fresh_dir("map_ltca"), spur_pair_20_40("120", kTipRelief));
  const PairModel pm = build_pair_model(m, 0);
  const elements::MeshForceMap map = mesh_force_map(m, pm);
  ASSERT_EQ(map.forces_n.size(), 5u);
  EXPECT_EQ(map.mesh_cycles, 1);
  EXPECT_NEAR(map.period_rad, 2.0 * kPi / 20, 1e-15);
  EXPECT_EQ(map.reference, 2);
  const auto tc = build_tooth_contact_model(m, pm);
  const std::vector<double> factors{0.25, 0.5, 1.0, 1.5, 2.0};
  const auto map_ptr = std::make_shared<const elements::MeshForceMap>(map);
  const elements::GearMeshContact contact("mesh", map_ptr, {});
  const int n = map.angles();
  ASSERT_EQ(n, 16);
  for (std::size_t j = 0; j < factors.size(); ++j) {
    const gear::ToothContactResult r = tc->contact->solve(factors[j] * 120.0);
    ASSERT_EQ(r.status, Status::Ok);
    EXPECT_NEAR(map.forces_n[j] / r.force_n, 1.0, 1e-12);
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_NEAR(map.approach_m[j][k], r.te_m[k], 1e-12 * r.te_m[k]);
      EXPECT_NEAR(map.unloaded_te_m[k], r.unloaded_te_m[k], 1e-12 * r.te_m[k]);
      const double theta = map.angle(i) + 3.0 * map.period_rad;
      EXPECT_NEAR(solve_approach(contact, theta, map.forces_n[j]) / r.te_m[k], 1.0, 1e-12);
      if (j == 2) {
        EXPECT_NEAR(map.approach_m[j][k], pm.ste->ste_m()[k], 1e-12 * r.te_m[k]);
        EXPECT_NEAR(map.unloaded_te_m[k], pm.ste->geometric_te_m()[k], 1e-12 * r.te_m[k]);
      }
    }
  }
  const gear::ToothContactResult mid = tc->contact->solve(90.0);
  ASSERT_EQ(mid.status, Status::Ok);
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    std::array<double, 5> f{}, d{};
    for (std::size_t j = 0; j < 5; ++j) {
      f[j] = map.forces_n[j];
      d[j] = map.approach_m[j][k];
    }
    for (std::size_t j = 1; j + 1 < d.size(); ++j)  // concave: slopes d' decreasing
      ASSERT_LT((d[j + 1] - d[j]) / (f[j + 1] - f[j]), (d[j] - d[j - 1]) / (f[j] - f[j - 1]))
          << "angle " << i;
    const double fm = mid.force_n;
    auto line = [&](std::size_t a, std::size_t b) {
      return d[a] + (d[b] - d[a]) / (f[b] - f[a]) * (fm - f[a]);
    };
    const double chord = line(1, 2);
    const double bound = std::min(line(0, 1), line(2, 3)) - chord;
    const double found = solve_approach(contact, map.angle(i), fm);
    EXPECT_NEAR(found, chord, 1e-12 * chord);
    EXPECT_GE(mid.te_m[k], chord - 1e-12 * chord) << "angle " << i;
    EXPECT_LE(mid.te_m[k] - chord, bound + 1e-12 * chord) << "angle " << i;
    EXPECT_LT(bound, 0.01 * (chord - map.unloaded_te_m[k])) << "angle " << i;
  }
}

// The synthetic ISO 6336 STE: one force F_s, the pair's STE as the approach and no unloaded TE,
// so the element is F = k(theta) delta with k = F_s / e: the same numbers (1e-12).
TEST(MeshForceMap, IsoSteIsALinearMesh) {
  const model::Model m =
      load(fresh_dir("map_iso"), spur_pair_20_40("120", "ste_source = \"iso\"\n"));
  const PairModel pm = build_pair_model(m, 0);
  const elements::MeshForceMap map = mesh_force_map(m, pm);
  ASSERT_EQ(map.forces_n.size(), 1u);
  EXPECT_NEAR(map.forces_n[0] / pm.static_force_n, 1.0, 1e-15);
  const elements::GearMeshContact contact("mesh",
                                          std::make_shared<const elements::MeshForceMap>(map), {});
  for (int i = 0; i < map.angles(); ++i) {
    const double e = pm.ste->ste_m()[static_cast<std::size_t>(i)];
    EXPECT_EQ(map.unloaded_te_m[static_cast<std::size_t>(i)], 0.0);
    EXPECT_NEAR(map.stiffness_at_node(i) / (pm.static_force_n / e), 1.0, 1e-12);
    EXPECT_NEAR(contact.static_force(vec(0.5 * e, map.angle(i))) / (0.5 * pm.static_force_n), 1.0,
                1e-12);
  }
}

// A two-torque STE file (100 and 300 N m, e in um at 0, 6, 12 deg of the 18 deg mesh cycle):
// one approach curve per torque, forces T / r_b1; a curve that is not monotone in the torque
// is an error at the pair's ste_file.
TEST(MeshForceMap, SteFileTorquesAndNonMonotoneFile) {
  const fs::path dir = fresh_dir("map_ste_file");
  write_file(dir / "ste.csv",
             "angle_deg, ste_um@100Nm, ste_um@300Nm\n0, 2, 5\n6, 3, 7\n12, 2.5, 6\n");
  write_file(dir / "bad.csv",
             "angle_deg, ste_um@100Nm, ste_um@300Nm\n0, 2, 5\n6, 3, 2.9\n12, 2.5, 6\n");
  const model::Model m = load(dir, spur_pair_20_40("200", "ste_file = \"ste.csv\"\n"));
  const PairModel pm = build_pair_model(m, 0);
  const elements::MeshForceMap map = mesh_force_map(m, pm);
  ASSERT_EQ(map.forces_n.size(), 2u);
  EXPECT_NEAR(map.forces_n[0] * pm.base_radius1_m, 100.0, 1e-12);
  EXPECT_NEAR(map.forces_n[1] * pm.base_radius1_m, 300.0, 1e-12);
  ASSERT_EQ(map.angles(), 3);
  const double e100[] = {2e-6, 3e-6, 2.5e-6}, e300[] = {5e-6, 7e-6, 6e-6};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(map.approach_m[0][i], e100[i], 1e-18);
    EXPECT_NEAR(map.approach_m[1][i], e300[i], 1e-18);
  }
  const model::Model bad = load(dir, spur_pair_20_40("200", "ste_file = \"bad.csv\"\n"));
  const PairModel pm_bad = build_pair_model(bad, 0);
  try {
    (void)mesh_force_map(bad, pm_bad);
    ADD_FAILURE() << "no error for a non-monotone STE file";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_pairs[0].ste_file");
    EXPECT_NE(e.expected().find("monotone"), std::string::npos) << e.expected();
  }
}

// Pitch deviations on the pinion: the LTCA runs over the hunting period lcm(20, 40) = 40 mesh
// cycles (2 pinion turns), and so does the map: period 40 x 2 pi / 20, 40 x 8 angles, the LTCA's
// numbers over all cycles (1e-12); the unloaded TE differs between cycles by the deviations.
TEST(MeshForceMap, PitchDeviationsGiveTheHuntingPeriod) {
  std::string deviations = "pitch_deviations = [4e-6";
  for (int t = 1; t < 20; ++t) deviations += t % 3 == 0 ? ", -3e-6" : ", 0";
  const model::Model m = load(fresh_dir("map_hunting"), spur_pair_20_40("120", R"(
[gear_pairs.flank1]
)" + deviations + R"(]
[gear_pairs.contact]
positions = 8
slices = 8
)"));
  const PairModel pm = build_pair_model(m, 0);
  const elements::MeshForceMap map = mesh_force_map(m, pm);
  EXPECT_EQ(map.mesh_cycles, 40);
  EXPECT_NEAR(map.period_rad, 40.0 * 2.0 * kPi / 20.0, 1e-13);
  ASSERT_EQ(map.angles(), 320);
  const auto tc = build_tooth_contact_model(m, pm);
  const gear::ToothContactResult r = tc->contact->solve(120.0);
  ASSERT_EQ(r.te_m.size(), 320u);
  double spread = 0.0;
  for (std::size_t i = 0; i < 320; ++i) {
    EXPECT_NEAR(map.approach_m[2][i], r.te_m[i], 1e-12 * r.te_m[i]);
    spread = std::max(spread, std::abs(map.unloaded_te_m[i] - map.unloaded_te_m[i % 8]));
  }
  EXPECT_GT(spread, 1e-6);
}

// An imported LTCA table (100 and 300 N m at 0, 6, 12 deg): its torques become the map's
// forces. Without a stiffness column the TE is all elastic (e_g = 0); with one, e_g = e - F / k
// of the lowest torque (gear/ltca_table.hpp), the same numbers (1e-15 relative on the um-level
// values).
TEST(MeshForceMap, LtcaTableTorques) {
  const fs::path dir = fresh_dir("map_ltca_table");
  write_file(dir / "te.csv",
             "angle_deg, torque_nm, te_um\n0, 100, 3\n6, 100, 3.2\n12, 100, 3.1\n"
             "0, 300, 7\n6, 300, 7.5\n12, 300, 7.2\n");
  write_file(dir / "tek.csv",
             "angle_deg, torque_nm, te_um, stiffness_n_per_um\n0, 100, 3, 400\n6, 100, 3.2, 380\n"
             "12, 100, 3.1, 390\n0, 300, 7, 420\n6, 300, 7.5, 400\n12, 300, 7.2, 410\n");
  for (const std::string file : {"te.csv", "tek.csv"}) {
    const model::Model m = load(dir, spur_pair_20_40("200", "ltca_file = \"" + file + "\"\n"));
    const PairModel pm = build_pair_model(m, 0);
    const elements::MeshForceMap map = mesh_force_map(m, pm);
    ASSERT_EQ(map.forces_n.size(), 2u);
    EXPECT_NEAR(map.forces_n[1] * pm.base_radius1_m, 300.0, 1e-12);
    ASSERT_EQ(map.angles(), 3);
    const double te100[] = {3e-6, 3.2e-6, 3.1e-6}, k100[] = {400e6, 380e6, 390e6};
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_NEAR(map.approach_m[0][i], te100[i], 1e-15 * 1e-5);
      const double eg = file == "te.csv" ? 0.0 : te100[i] - map.forces_n[0] / k100[i];
      EXPECT_NEAR(map.unloaded_te_m[i], eg, 1e-15 * 1e-5) << file;
    }
  }
}

// A [[gear_meshes]] entry: without [gear_meshes.contact] gear_pair, its constant `stiffness` (a
// linear mesh with one angle and no unloaded TE, period 2 pi / teeth1); with it, the named pair's
// map; with neither, an error at its stiffness.
TEST(MeshForceMap, GearMeshesEntryUsesItsPairOrItsStiffness) {
  const double rb1 = 0.03, rb2 = 0.06, alpha = 20.0 * kPi / 180.0;
  const std::string rotor = fmt::format(R"(
[[nodes]]
name = "g1"
position = [0.0, 0.0, 0.0]
[[nodes]]
name = "g2"
position = [{:.17g}, 0.0, 0.0]
[[disks]]
node = "g1"
mass = 1.0
diametral_inertia = 1.0
polar_inertia = 0.002
[[disks]]
node = "g2"
mass = 1.0
diametral_inertia = 1.0
polar_inertia = 0.03
[[gear_meshes]]
name = "mesh"
gear1 = "g1"
gear2 = "g2"
type = "spur"
teeth1 = 20
teeth2 = 40
base_radius1 = {}
base_radius2 = {}
pressure_angle_deg = 20
stiffness = 3e8
)",
                                        (rb1 + rb2) / std::cos(alpha), rb1, rb2);
  model::Model m =
      load(fresh_dir("map_gear_meshes"), spur_pair_20_40("120", "ste_source = \"iso\"\n") + rotor);
  const elements::MeshForceMap constant = mesh_force_map(m, 0);
  ASSERT_EQ(constant.angles(), 1);
  EXPECT_NEAR(constant.period_rad, 2.0 * kPi / 20, 1e-15);
  EXPECT_NEAR(constant.mean_stiffness() / 3e8, 1.0, 1e-12);
  EXPECT_EQ(constant.unloaded_te_m[0], 0.0);

  model::MeshContactSpec contact;
  contact.gear_pair = "spur";
  m.gear_meshes[0].contact = contact;
  const elements::MeshForceMap from_pair = mesh_force_map(m, 0);
  const elements::MeshForceMap direct = mesh_force_map(m, build_pair_model(m, 0));
  EXPECT_EQ(from_pair.approach_m, direct.approach_m);
  EXPECT_EQ(from_pair.forces_n, direct.forces_n);

  m.gear_meshes[0].contact.reset();
  m.gear_meshes[0].stiffness = std::numeric_limits<double>::quiet_NaN();
  try {
    (void)mesh_force_map(m, 0);
    ADD_FAILURE() << "no error without stiffness and gear pair";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_meshes[0].stiffness");
  }
}

}  // namespace
}  // namespace geardyn::analyses
