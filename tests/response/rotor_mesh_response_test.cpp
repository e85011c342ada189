// Mesh-order forced response of a geared rotor (response/rotor_mesh_response): the modal-reduced
// solver against the direct sparse solve on the same model, its convergence as modes are added,
// and the load vector of the mesh force.
//
// Model: examples/geared_rotor_hcf/model.toml (after Hong, Jiang, Xu, Ma, Chinese J. Aeronautics
// 2020):
//
//     support_A        support_B
//        |  bearing_1      |  bearing_2
//   hpr.0 o==o=====o=========o====o hpr.14   high-pressure rotor along z, 1.0 x speed
//   (bevel |        disk      disk
//    gear) |
//    driven_gear o==o driven shaft along x, 40/36 x speed, bearing_3
//
// a 40/36-tooth spiral bevel mesh (k = 1e7 N/m) couples the two shafts; Rayleigh damping 1 % at
// 100 Hz and 1 kHz, gyroscopic terms at the running speed. About 140 free DOFs.
#include "geardyn/response/rotor_mesh_response.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/parse.hpp"

namespace geardyn::response {
namespace {

constexpr double kPi = units::kPi;

model::Model example() {
  return analyses::load_model(std::string(GEARDYN_SOURCE_DIR) +
                              "/examples/geared_rotor_hcf/model.toml");
}

// Largest deviation over speeds, orders and sensors, relative to each sensor's largest
// direct amplitude (a pointwise relative error would blow up at anti-resonances).
double curve_error(const RotorForcedResult& a, const RotorForcedResult& b) {
  double worst = 0.0;
  for (std::size_t h = 0; h < a.displacement.size(); ++h)
    for (Eigen::Index s = 0; s < a.displacement[h].cols(); ++s) {
      const double scale = b.displacement[h].col(s).cwiseAbs().maxCoeff();
      worst = std::max(
          worst,
          (a.displacement[h].col(s) - b.displacement[h].col(s)).cwiseAbs().maxCoeff() / scale);
    }
  return worst;
}

RotorForcedSettings settings_for(const model::Model& m, const fe::LinearSystem& system,
                                 const Eigen::VectorXd& speeds) {
  RotorForcedSettings s;
  s.gear_mesh = "central_bevel_pair";
  s.harmonics = {{1, {100.0, 0.0}}, {2, std::polar(30.0, 0.7)}};
  s.sensors = rotor_sensors(m, system);
  s.speeds = speeds;
  return s;
}

// The mesh load is the element's vector v: the mesh element adds k v v^T to K (gear_mesh_element
// .hpp), so assembling with stiffness k and with 0 must differ by exactly k v v^T.
TEST(RotorMeshForced, MeshLoadIsTheLineOfActionVectorOfTheMeshElement) {
  model::Model m = example();
  const fe::LinearSystem with = fe::assemble(m);
  const double k = m.gear_meshes[0].stiffness;
  m.gear_meshes[0].stiffness = 0.0;
  const fe::LinearSystem without = fe::assemble(m);
  const Eigen::VectorXd v = mesh_load(m, with, 0);
  const Eigen::MatrixXd diff = Eigen::MatrixXd(with.K - without.K);
  EXPECT_LT((diff - k * v * v.transpose()).cwiseAbs().maxCoeff(), 1e-9 * k);
  // Translation part at gear 1 is the unit line of action.
  const auto eq = with.dofs.node_dofs(with.dofs.node_index("hpr.0"));
  EXPECT_NEAR(Eigen::Vector3d(v[eq[0]], v[eq[1]], v[eq[2]]).norm(), 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(mesh_frequency_per_speed(m, with, 0), 40.0);
}

// (3) Modal-reduced vs direct sparse LU on 40 speeds covering mesh frequencies 30 .. 900 Hz
// (order 1) and twice that (order 2). With every mode in the basis the projection is a change of
// basis, exact up to round-off: 1e-8. Truncated bases that span the excitation band (30 modes
// reach 3 kHz, above the highest excitation frequency 1.8 kHz; fewer modes leave resonances of
// the band out and the error is O(1)) must converge as modes are added, the static-correction
// vector must not make it worse, and 30 modes must be within 1e-3 of the largest response of
// each sensor (a response accuracy well below the 1 % of a damping estimate).
TEST(RotorMeshForced, ModalReducedConvergesToDirectSparse) {
  const model::Model m = example();
  const fe::LinearSystem system = fe::assemble(m);
  const Eigen::VectorXd speeds =
      Eigen::VectorXd::LinSpaced(40, 2 * kPi * 30 / 40.0, 2 * kPi * 900 / 40.0);
  RotorForcedSettings s = settings_for(m, system, speeds);
  s.method = RotorForcedMethod::Direct;
  const RotorForcedResult direct = run_mesh_forced_response(m, system, s);

  s.method = RotorForcedMethod::ModalReduced;
  s.n_modes = system.size();
  s.residual_vectors = false;
  const double e_all = curve_error(run_mesh_forced_response(m, system, s), direct);
  EXPECT_LT(e_all, 1e-8);

  double previous = 1e300;
  for (int n : {30, 40, 60, 90}) {
    s.n_modes = n;
    s.residual_vectors = false;
    const double e_plain = curve_error(run_mesh_forced_response(m, system, s), direct);
    s.residual_vectors = true;
    const RotorForcedResult corrected = run_mesh_forced_response(m, system, s);
    const double e_corr = curve_error(corrected, direct);
    std::printf("n_modes %d: error %.3e plain, %.3e with residual vector (%d vectors, %.0f Hz)\n",
                n, e_plain, e_corr, corrected.basis_size, corrected.highest_mode_hz);
    EXPECT_LE(e_corr, e_plain * 1.0001);
    EXPECT_LT(e_plain, previous * 1.0001);
    previous = e_plain;
    EXPECT_LT(e_corr, 1e-3);
  }
}

// Resonance table: on a fine grid around the first resonances both solvers find the same peaks,
// with a resolvable half-power Q; amplitudes within the modal error bound above.
TEST(RotorMeshForced, ResonanceTableAgreesBetweenSolvers) {
  const model::Model m = example();
  const fe::LinearSystem system = fe::assemble(m);
  const Eigen::VectorXd speeds =
      Eigen::VectorXd::LinSpaced(600, 2 * kPi * 30 / 40.0, 2 * kPi * 400 / 40.0);
  RotorForcedSettings s = settings_for(m, system, speeds);
  s.harmonics = {{1, {100.0, 0.0}}};
  s.n_modes = 30;
  const RotorForcedResult modal = run_mesh_forced_response(m, system, s);
  s.method = RotorForcedMethod::Direct;
  const RotorForcedResult direct = run_mesh_forced_response(m, system, s);
  ASSERT_FALSE(direct.peaks.empty());
  ASSERT_EQ(modal.peaks.size(), direct.peaks.size());
  int resolved = 0;
  for (std::size_t i = 0; i < direct.peaks.size(); ++i) {
    EXPECT_EQ(modal.peaks[i].sensor, direct.peaks[i].sensor);
    EXPECT_NEAR(modal.peaks[i].speed, direct.peaks[i].speed, 1e-4 * direct.peaks[i].speed);
    EXPECT_NEAR(modal.peaks[i].amplitude, direct.peaks[i].amplitude,
                1e-3 * direct.peaks[i].amplitude);
    if (direct.peaks[i].resolved) {
      ++resolved;
      EXPECT_NEAR(modal.peaks[i].q_factor, direct.peaks[i].q_factor,
                  1e-3 * direct.peaks[i].q_factor);
    }
  }
  EXPECT_GT(resolved, 0);
  const Table t = direct.resonance_table();
  EXPECT_NO_THROW(t.validate());
  EXPECT_NO_THROW(direct.response_table().validate());
  std::printf("%s\n", direct.brief_report().c_str());
  std::printf("%s\n", modal.brief_report().c_str());
}

// (4) Bad input.
TEST(RotorMeshForced, BadInputIsRefused) {
  model::Model m = example();
  const fe::LinearSystem system = fe::assemble(m);
  RotorForcedSettings s = settings_for(m, system, Eigen::Vector3d(10.0, 20.0, 30.0));
  s.gear_mesh = "no_such_mesh";
  EXPECT_THROW(run_mesh_forced_response(m, system, s), InputError);
  s = settings_for(m, system, Eigen::Vector3d(10.0, 30.0, 20.0));  // not increasing
  EXPECT_THROW(run_mesh_forced_response(m, system, s), InputError);
  s = settings_for(m, system, Eigen::Vector3d(10.0, 20.0, 30.0));
  s.harmonics = {{1, 1.0}, {1, 2.0}};  // repeated order
  EXPECT_THROW(run_mesh_forced_response(m, system, s), InputError);
  s.harmonics = {{0, 1.0}};
  EXPECT_THROW(run_mesh_forced_response(m, system, s), InputError);
  EXPECT_THROW(rotor_sensors(m, system, {"no_such_sensor"}), InputError);
  m.gear_meshes[0].teeth1 = 0;
  s = settings_for(m, system, Eigen::Vector3d(10.0, 20.0, 30.0));
  EXPECT_THROW(run_mesh_forced_response(m, system, s), InputError);
}

}  // namespace
}  // namespace geardyn::response
