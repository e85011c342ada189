// Modal damping: ratios per mode, per band and by default reach the complex modes exactly,
// rigid-body modes stay undamped.
#include "geardyn/assembly/modal_damping.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

using C = model::Component;

// Modal damping is diagonal in the undamped modal coordinates (Clough & Penzien, Dynamics of
// Structures, 2nd ed., sec. 12-6): mode r becomes an SDOF with exactly zeta_r, so
// -Re(lambda)/|lambda| = zeta_r and |lambda| = omega_r up to rounding.
TEST(ModalDamping, DefaultRatioReachesEveryMode) {
  auto model = test::jeffcott(10.0, 1e6, 0.0);
  model.damping.modal_ratio = 0.05;
  const auto system = assembly::build_system(model);
  ASSERT_TRUE(system.has_modal_damping());
  EXPECT_EQ(system.modal_coefficients.size(), 2);
  analyses::ModalSettings settings;
  settings.n_modes = 2;
  const auto r = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  for (const auto& mode : r.complex) {
    EXPECT_NEAR(mode.damping_ratio, 0.05, 1e-12);
    EXPECT_NEAR(std::abs(mode.eigenvalue), std::sqrt(1e5), 1e-9 * std::sqrt(1e5));
  }
}

// Two uncoupled DOFs with different stiffness: omega_1 = sqrt(k1/m) = 100, omega_2 = 300 rad/s.
model::Model two_frequencies() {
  model::Model model;
  model.nodes.push_back(test::spinning_node("a", 0.0));
  model::PointMass pm;
  pm.node = "a";
  pm.mass = 2.0;
  model.point_masses.push_back(pm);
  model::Bearing b;
  b.node = "a";
  b.stiffness = {test::diagonal6(2.0 * 100 * 100, 2.0 * 300 * 300, 0, 0, 0, 0)};
  model.bearings.push_back(b);
  model.constraints.push_back(test::fix("a", {C::Uz, C::Rx, C::Ry, C::Rz}));
  return model;
}

TEST(ModalDamping, BandsAndPerModeRatios) {
  auto model = two_frequencies();
  model.damping.bands = {{0.0, 200.0, 0.01}, {200.0, 1e9, 0.1}};  // rad/s
  analyses::ModalSettings settings;
  settings.n_modes = 2;
  {
    const auto system = assembly::build_system(model);
    const auto r = run_modal(model, settings, Context("modal").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_NEAR(r.complex[0].damping_ratio, 0.01, 1e-12);
    EXPECT_NEAR(r.complex[1].damping_ratio, 0.1, 1e-12);
  }
  model.damping.modal_ratios = {0.03};  // overrides the band for the first mode only
  {
    const auto system = assembly::build_system(model);
    const auto r = run_modal(model, settings, Context("modal").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    EXPECT_NEAR(r.complex[0].damping_ratio, 0.03, 1e-12);
    EXPECT_NEAR(r.complex[1].damping_ratio, 0.1, 1e-12);
  }
  EXPECT_DOUBLE_EQ(assembly::modal_damping_ratio(model.damping, 5, 250.0), 0.1);
  EXPECT_DOUBLE_EQ(assembly::modal_damping_ratio(model.damping, 5, 2e9), 0.0);  // default ratio
}

// Two masses joined by a spring, free in x:  (m)--k--(m). Rigid translation (omega = 0) and
// the elastic mode omega^2 = 2 k / m. The rigid-body mode must get c = 0 (no damping of rigid
// motion) and the elastic one exactly its ratio.
// On a fine mesh real modes keep their damping: the rigid-body decision is made from the mode's
// shape, not from a limit on omega^2 that grows with refinement (at about 1500 elements the old
// limit, 1e-10 max K_ii / M_ii, passed the first lateral pair of this rotor, which then got no
// damping). Friswell et al. 2010, Example 5.9.1 at 3000 elements: free axially and in torsion,
// so exactly two rigid-body modes; every other mode gets 2 zeta omega exactly.
TEST(ModalDamping, RealModesOfAFineMeshKeepTheirDamping) {
  model::Model model = test::friswell_591(3000);
  model.damping.modal_ratio = 0.01;
  model.damping.modal_modes = 8;
  fe::LinearSystem system = fe::assemble(model);
  const auto summary = assembly::apply_modal_damping(model, system, {});
  EXPECT_EQ(summary.rigid_body_modes, 2);
  int damped = 0;
  for (Eigen::Index r = 0; r < system.modal_coefficients.size(); ++r)
    if (system.modal_coefficients[r] > 0.0) ++damped;
  EXPECT_EQ(damped, 6);
  // The first lateral pair (Friswell: 86.66 rad/s at rest, within 1e-3 on any mesh) is damped.
  double lowest_damped = INFINITY;
  for (Eigen::Index r = 0; r < system.modal_coefficients.size(); ++r)
    if (system.modal_coefficients[r] > 0.0)
      lowest_damped = std::min(lowest_damped, system.modal_coefficients[r] / (2.0 * 0.01));
  EXPECT_NEAR(lowest_damped, 86.66, 0.1);
}

TEST(ModalDamping, RigidBodyModeGetsNoDamping) {
  model::Model model;
  model.nodes.push_back(test::spinning_node("a", 0.0));
  model.nodes.push_back(test::spinning_node("b", 0.0));
  for (const char* n : {"a", "b"}) {
    model::PointMass pm;
    pm.node = n;
    pm.mass = 3.0;
    model.point_masses.push_back(pm);
    model.constraints.push_back(test::fix(n, {C::Uy, C::Uz, C::Rx, C::Ry, C::Rz}));
  }
  model::Bearing spring;
  spring.node = "a";
  spring.node2 = "b";
  spring.stiffness = {test::diagonal6(6e4, 0, 0, 0, 0, 0)};
  model.bearings.push_back(spring);
  model.damping.modal_ratio = 0.02;
  fe::LinearSystem system = fe::assemble(model);
  const auto summary = assembly::apply_modal_damping(model, system, {});
  EXPECT_EQ(summary.modes, 2);
  EXPECT_EQ(summary.rigid_body_modes, 1);
  ASSERT_EQ(system.modal_coefficients.size(), 2);
  const double omega = std::sqrt(2.0 * 6e4 / 3.0);
  EXPECT_EQ(system.modal_coefficients[0], 0.0);
  EXPECT_NEAR(system.modal_coefficients[1], 2.0 * 0.02 * omega, 1e-10 * omega);

  // In the quadratic problem the undamped rigid-body motion is a double root lambda = 0
  // (x = x0 + v t), so the complex modes are 0, 0 and the elastic pair.
  analyses::ModalSettings settings;
  settings.n_modes = 3;
  const auto r = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(r.complex.size(), 3u) << r.message;
  EXPECT_TRUE(r.complex[0].rigid_body);
  EXPECT_TRUE(r.complex[1].rigid_body);
  EXPECT_FALSE(r.complex[2].rigid_body);
  EXPECT_NEAR(r.complex[2].damping_ratio, 0.02, 1e-10);
  EXPECT_NEAR(std::abs(r.complex[2].eigenvalue), omega, 1e-10 * omega);
}

TEST(ModalDamping, NoModalDampingLeavesTheBasisEmpty) {
  const auto system = assembly::build_system(test::jeffcott(1.0, 1.0, 0.1));
  EXPECT_FALSE(system.has_modal_damping());
  EXPECT_EQ(system.modal_basis.size(), 0);
}

TEST(ModalDamping, NegativeRatioIsAnInputError) {
  auto model = test::jeffcott(1.0, 1.0, 0.0);
  model.damping.modal_ratios = {0.01, -0.02};
  EXPECT_THROW(assembly::build_system(model), InputError);
}

}  // namespace
}  // namespace geardyn::analyses
