// Validation of the modal analysis: Jeffcott rotor and an overhung gyroscopic disk against
// closed-form results, Friswell et al. Example 5.9.1 against the published eigenvalues.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "geardyn/analyses/modal.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/core/error.hpp"
#include "support/output_tables.hpp"
#include "support/rotor_models.hpp"

namespace geardyn::analyses {
namespace {

using C = model::Component;
constexpr double kPi = std::numbers::pi;

using test::column_names;
using test::table;

// Jeffcott rotor (Jeffcott, Phil. Mag. 37 (1919) 304; Friswell et al., Dynamics of Rotating
// Machines, CUP 2010, sec. 3.3): point mass m = 10 kg on an isotropic support k = 1e6 N/m with
// viscous damping c = 2 zeta sqrt(k m), zeta = 0.02. Without disk tilt there is no gyroscopic
// term, so at any speed both lateral modes have
//   omega_n = sqrt(k/m) = 316.227766 rad/s,  lambda = -zeta omega_n +- i omega_n sqrt(1 - zeta^2).
// The numbers are exact up to rounding (2 x 2 problem), hence 1e-10.
TEST(Modal, JeffcottRotorMatchesClosedForm) {
  const double m = 10.0, k = 1e6, zeta = 0.02;
  const auto model = test::jeffcott(m, k, 2.0 * zeta * std::sqrt(k * m));
  const auto system = assembly::build_system(model);
  ASSERT_EQ(system.size(), 2);
  analyses::ModalSettings settings;
  settings.n_modes = 2;
  settings.speed = 3000.0 * 2.0 * kPi / 60.0;
  const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  ASSERT_EQ(r.complex.size(), 2u);
  ASSERT_EQ(r.undamped.size(), 2u);
  const double wn = 316.227766016838;
  for (const Mode& mode : r.complex) {
    EXPECT_NEAR(mode.frequency_hz, wn / (2 * kPi), 1e-10 * wn);
    EXPECT_NEAR(mode.damped_frequency_hz, wn * std::sqrt(1 - zeta * zeta) / (2 * kPi), 1e-10 * wn);
    EXPECT_NEAR(mode.damping_ratio, zeta, 1e-10);
    EXPECT_NEAR(mode.eigenvalue.real(), -zeta * wn, 1e-9 * wn);
    EXPECT_EQ(mode.kind, ModeKind::Lateral);
    EXPECT_LT(mode.residual, 1e-14);
  }
  for (const Mode& mode : r.undamped) {
    EXPECT_NEAR(mode.frequency_hz, wn / (2 * kPi), 1e-10 * wn);
    EXPECT_EQ(mode.damping_ratio, 0.0);
  }

  const AnalysisOutput out =
      modal_output(model, settings, r, Context("modes").with_system(&system));
  EXPECT_EQ(out.type, "modal");
  EXPECT_EQ(out.status, Status::Ok);
  const Table& modes = table(out, "modes");
  EXPECT_EQ(column_names(modes),
            (std::vector<std::string>{"mode", "frequency_hz", "damped_frequency_hz",
                                      "damping_ratio", "log_decrement", "stable", "real", "imag",
                                      "whirl", "kind", "residual"}));
  EXPECT_NO_THROW(modes.validate());
  EXPECT_EQ(modes.rows(), 2u);
  EXPECT_NEAR(modes.column("frequency_hz").numbers[0], 50.32921210448704, 1e-9);
  const Table& undamped = table(out, "undamped_modes");
  EXPECT_EQ(column_names(undamped),
            (std::vector<std::string>{"mode", "frequency_hz", "kind", "residual"}));
  const Table& shapes = table(out, "mode_shapes");
  EXPECT_NO_THROW(shapes.validate());
  EXPECT_EQ(shapes.rows(), 2u);  // 2 modes x 1 node
  EXPECT_FALSE(out.notes.empty());
}

// Overhung disk on a massless cantilever (Friswell et al. 2010, sec. 3.6, "overhung rotor";
// Lalanne & Ferraris, Rotordynamics Prediction in Engineering, 2nd ed., 1998, ch. 2):
//
//    |=========================( disk m, Id, Ip )     spin Omega about z
//    clamped        L
//
// The cantilever's tip stiffness in (u_x, theta_y) is [12EI/L^3, -6EI/L^2; -6EI/L^2, 4EI/L]
// (theta_y = du_x/dz) and in (u_y, theta_x) the same with +6EI/L^2 (theta_x = -du_y/dz). For a
// circular whirl at w the gyroscopic moment Ip Omega w adds to (forward) or subtracts from
// (backward) the tilt stiffness, so the natural frequencies are the positive roots of
//   (k11 - m w^2)(k22 - Id w^2 +- Ip Omega w) - k12^2 = 0   (+ forward, - backward).
// The roots come from the companion matrix (independent of the solver under test). Both are
// exact up to rounding; 1e-9 covers the conditioning of the quartic.
std::vector<double> positive_roots(double a4, double a3, double a2, double a1, double a0) {
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  companion(0, 0) = -a3 / a4;
  companion(0, 1) = -a2 / a4;
  companion(0, 2) = -a1 / a4;
  companion(0, 3) = -a0 / a4;
  companion(1, 0) = companion(2, 1) = companion(3, 2) = 1.0;
  const Eigen::EigenSolver<Eigen::Matrix4d> es(companion, false);
  std::vector<double> roots;
  for (int i = 0; i < 4; ++i)
    if (std::abs(es.eigenvalues()[i].imag()) < 1e-9 * std::abs(es.eigenvalues()[i]) &&
        es.eigenvalues()[i].real() > 0.0)
      roots.push_back(es.eigenvalues()[i].real());
  std::sort(roots.begin(), roots.end());
  return roots;
}

model::Model overhung_disk(double spin_ratio, double k11, double k12, double k22, double m,
                           double Id, double Ip) {
  model::Model model;
  model.nodes.push_back(test::spinning_node("disk", spin_ratio));
  model::Disk d;
  d.node = "disk";
  d.mass = m;
  d.diametral_inertia = Id;
  d.polar_inertia = Ip;
  model.disks.push_back(d);
  model::Bearing b;
  b.node = "disk";
  auto K = test::diagonal6(k11, k11, 0, k22, k22, 0);
  auto at = [&](C r, C c) -> double& {
    return K[static_cast<std::size_t>(r) * 6 + static_cast<std::size_t>(c)];
  };
  at(C::Ux, C::Ry) = at(C::Ry, C::Ux) = -k12;
  at(C::Uy, C::Rx) = at(C::Rx, C::Uy) = k12;
  b.stiffness = {K};
  model.bearings.push_back(b);
  model.constraints.push_back(test::fix("disk", {C::Uz, C::Rz}));
  return model;
}

TEST(Modal, OverhungGyroscopicDiskSplitsForwardUpBackwardDown) {
  const double E = 2.1e11, d = 0.03, L = 0.3;
  const double EI = E * kPi * std::pow(d, 4) / 64.0;
  const double k11 = 12 * EI / std::pow(L, 3), k12 = 6 * EI / (L * L), k22 = 4 * EI / L;
  const double m = 5.0, Id = 0.02, Ip = 0.04;
  const double Omega = 10000.0 * 2 * kPi / 60.0;
  for (double spin : {1.0, -1.0}) {
    const auto model = overhung_disk(spin, k11, k12, k22, m, Id, Ip);
    const auto system = assembly::build_system(model);
    ASSERT_EQ(system.size(), 4);
    analyses::ModalSettings settings;
    settings.n_modes = 4;
    settings.speed = Omega;
    const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    ASSERT_EQ(r.complex.size(), 4u);

    const double a = Ip * Omega;  // |spin| = Omega
    // (k11 - m w^2)(k22 - Id w^2 + s a w) - k12^2, expanded in powers of w, s = +1 / -1.
    auto roots = [&](double s) {
      return positive_roots(m * Id, -m * s * a, -(m * k22 + Id * k11), s * a * k11,
                            k11 * k22 - k12 * k12);
    };
    const auto fwd = roots(+1.0), bwd = roots(-1.0);
    ASSERT_EQ(fwd.size(), 2u);
    ASSERT_EQ(bwd.size(), 2u);
    std::vector<double> forward, backward;
    for (const Mode& mode : r.complex) {
      EXPECT_NEAR(mode.damping_ratio, 0.0, 1e-12);  // undamped
      EXPECT_NE(mode.whirl, Whirl::None);
      (mode.whirl == Whirl::Forward ? forward : backward).push_back(mode.eigenvalue.imag());
    }
    ASSERT_EQ(forward.size(), 2u) << "spin " << spin;
    ASSERT_EQ(backward.size(), 2u) << "spin " << spin;
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(forward[static_cast<std::size_t>(j)], fwd[static_cast<std::size_t>(j)],
                  1e-9 * fwd[static_cast<std::size_t>(j)]);
      EXPECT_NEAR(backward[static_cast<std::size_t>(j)], bwd[static_cast<std::size_t>(j)],
                  1e-9 * bwd[static_cast<std::size_t>(j)]);
    }
    // The split: each forward mode above the non-rotating frequency, each backward one below.
    for (int j = 0; j < 2; ++j) {
      const double w0 = r.undamped[static_cast<std::size_t>(2 * j)].frequency_hz * 2 * kPi;
      EXPECT_GT(forward[static_cast<std::size_t>(j)], w0);
      EXPECT_LT(backward[static_cast<std::size_t>(j)], w0);
    }
  }
}

}  // namespace
}  // namespace geardyn::analyses

namespace geardyn::analyses {
namespace {

// Friswell, Penny, Garvey & Lees, Dynamics of Rotating Machines (CUP 2010), Example 5.9.1:
//
//   bearing          disk 1             disk 2          bearing
//   k = 1 MN/m     D 280 mm           D 350 mm         k = 1 MN/m
//      ^                |                 |                ^
//      o------o-------[ o ]-----o-------[ o ]------o-------o
//     0.0   0.25      0.50    0.75      1.00     1.25    1.50 m
//
// Steel shaft D 50 mm (E 211 GPa, G 81.2 GPa, rho 7810 kg/m^3), 6 Timoshenko elements with
// kappa = 0.8863, disks 70 mm thick on a 50 mm bore, undamped isotropic bearings. Published
// |lambda| at 4000 rpm [rad/s]: 85.389, 87.796, 251.785, 294.713, 600.179, 827.075, in
// backward / forward pairs. Tolerance 2e-5: about one unit in the last published digit plus the
// rounding of kappa in the book (the same figure the fe element validation uses).
TEST(Modal, FriswellExample591FrequenciesAndWhirlAt4000Rpm) {
  model::Model model;
  model.materials.push_back(test::friswell_steel());
  model::Shaft s;
  s.name = "shaft";
  s.material = "steel";
  s.shear_coefficient = 0.8863;
  model::ShaftElement e;
  e.length = 1.5;
  e.outer_diameter = 0.05;
  e.divisions = 6;
  s.elements.push_back(e);
  model.shafts.push_back(s);
  for (const auto& [node, diameter] : {std::pair{"shaft.2", 0.28}, std::pair{"shaft.4", 0.35}}) {
    const double ro = diameter / 2, ri = 0.025, h = 0.07;
    const double mass = 7810 * kPi * (ro * ro - ri * ri) * h;
    model::Disk d;
    d.node = node;
    d.mass = mass;
    d.polar_inertia = mass * (ro * ro + ri * ri) / 2;
    d.diametral_inertia = mass * (3 * (ro * ro + ri * ri) + h * h) / 12;
    model.disks.push_back(d);
  }
  for (const char* node : {"shaft.0", "shaft.6"}) {
    model::Bearing b;
    b.node = node;
    b.stiffness = {test::diagonal6(1e6, 1e6, 0, 0, 0, 0)};
    model.bearings.push_back(b);
  }
  const auto system = assembly::build_system(model);
  analyses::ModalSettings settings;
  settings.n_modes = 12;
  settings.speed = 4000.0 * 2 * kPi / 60;
  const ModalResult r = run_modal(model, settings, Context("modal").with_system(&system));
  ASSERT_EQ(r.status, Status::Ok) << r.message;
  std::vector<const Mode*> lateral;
  for (const Mode& m : r.complex)
    if (!m.rigid_body && m.kind == ModeKind::Lateral) lateral.push_back(&m);
  ASSERT_GE(lateral.size(), 6u);
  const double published[] = {85.389, 87.796, 251.785, 294.713, 600.179, 827.075};
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(std::abs(lateral[i]->eigenvalue), published[i], 2e-5 * published[i])
        << "mode " << i + 1;
    EXPECT_EQ(lateral[i]->whirl, i % 2 == 0 ? Whirl::Backward : Whirl::Forward) << "mode " << i + 1;
  }
}

}  // namespace
}  // namespace geardyn::analyses
