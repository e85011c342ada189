// The nonlinear drivetrain system (docs/theory.md §16.9-16.12): placement of elements, speed
// drivers and load torques on spins, static equilibrium, linearisation, and a run-up through
// resonance on the actual spin.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/modal.hpp"
#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/drivetrain/builder.hpp"
#include "geardyn/drivetrain/linearisation.hpp"
#include "geardyn/drivetrain/static_equilibrium.hpp"
#include "geardyn/transient/integrator.hpp"
#include "geardyn/transient/linear_rotor_system.hpp"
#include "support/rotor_models.hpp"
#include "support/transient_rotor_models.hpp"

namespace geardyn::drivetrain {
namespace {

using model::Component;

/// Two disks a and b (polar inertias J_a, J_b) on a torsional spring k_t; only rz free.
model::Model two_inertias(double J_a, double J_b, double k_t) {
  model::Model m;
  for (const char* name : {"a", "b"}) {
    m.nodes.push_back(test::spinning_node(name, 1.0));
    model::Disk d;
    d.name = std::string("disk_") + name;
    d.node = name;
    d.mass = 1.0;
    d.polar_inertia = std::string(name) == "a" ? J_a : J_b;
    d.diametral_inertia = 0.5 * d.polar_inertia;
    m.disks.push_back(d);
    m.constraints.push_back(test::fix(
        name, {Component::Ux, Component::Uy, Component::Uz, Component::Rx, Component::Ry}));
  }
  model::Coupling c;
  c.name = "shaft";
  c.node1 = "a";
  c.node2 = "b";
  c.stiffness.assign(144, 0.0);
  c.stiffness[5 * 12 + 5] = c.stiffness[11 * 12 + 11] = k_t;
  c.stiffness[5 * 12 + 11] = c.stiffness[11 * 12 + 5] = -k_t;
  m.couplings.push_back(c);
  return m;
}

model::DriverSpec speed_driver(const std::string& node, std::vector<double> t,
                               std::vector<double> w) {
  model::DriverSpec d;
  d.name = "motor";
  d.node = node;
  d.kind = model::DriverKind::Speed;
  d.times = std::move(t);
  d.speeds = std::move(w);
  return d;
}

// Statics of a held input and a load torque: the shaft twists by T / k_t and the driver supplies
// -T (moment balance), exactly (a linear problem: to round-off).
TEST(DrivetrainStatic, HeldInputAndLoadTorqueTwistTheShaftByTorqueOverStiffness) {
  const double k_t = 2.0e4, T = -150.0;
  model::Model m = two_inertias(0.01, 0.05, k_t);
  m.drivers.push_back(speed_driver("a", {0.0}, {0.0}));
  model::LoadTorqueSpec load;
  load.name = "brake";
  load.node = "b";
  load.torque = T;
  m.loads.push_back(load);
  const fe::LinearSystem sys = assembly::build_system(m);
  DrivetrainSystem system(build_drivetrain(m, sys, {}));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.size());
  const StaticResult st = solve_static(system, 0.0, zero, zero);
  ASSERT_EQ(st.status, Status::Ok) << st.message;
  const int a = sys.dofs.dof(sys.dofs.node_index("a"), Component::Rz);
  const int b = sys.dofs.dof(sys.dofs.node_index("b"), Component::Rz);
  EXPECT_NEAR(st.q[a], 0.0, 1e-14);
  EXPECT_NEAR(st.q[b] - st.q[a], T / k_t, 1e-12 * std::abs(T / k_t));
  ASSERT_EQ(st.held_torques.size(), 1U);
  EXPECT_NEAR(st.held_torques[0], -T, 1e-9 * std::abs(T));
}

// A speed ramp through the servo row: the driven spin follows theta(t) = alpha t^2 / 2, and the
// driven-through disk lags by the quasi-static twist J_b alpha / k_t about which it oscillates at
// omega_b = sqrt(k_t / J_b) (its free response to the sudden acceleration).
// Tracking: Newmark (alpha_f = 0) reproduces the quadratic exactly (Newton tolerance only);
// generalised-alpha imposes the servo row at q_{n+1-af} = (1 - af) q_{n+1} + af q_n, which
// differs from theta(t_{n+1-af}) by af (1 - af) alpha h^2 / 2: its O(h^2) tracking offset.
TEST(DrivetrainRunUp, SpeedDriverFollowsTheRampAndTheShaftTwistsByInertiaTimesAcceleration) {
  for (const auto scheme : {transient::Scheme::Newmark, transient::Scheme::GeneralizedAlpha}) {
    const double J_b = 0.05, k_t = 2.0e4, alpha = 1000.0, T_end = 0.3;
    model::Model m = two_inertias(0.01, J_b, k_t);
    m.drivers.push_back(speed_driver("a", {0.0, T_end}, {0.0, alpha * T_end}));
    const fe::LinearSystem sys = assembly::build_system(m);
    DrivetrainSystem system(build_drivetrain(m, sys, {}));
    const int a = sys.dofs.dof(sys.dofs.node_index("a"), Component::Rz);
    const int b = sys.dofs.dof(sys.dofs.node_index("b"), Component::Rz);
    transient::IntegratorOptions o;
    o.scheme = scheme;
    o.time_step = 1e-4;
    o.num_steps = 2500;
    o.rho_infinity = 0.9;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(system.size()), v = q;
    double max_track = 0.0, twist_sum = 0.0;
    int twist_n = 0;
    NullProgress progress;
    const double omega_b = std::sqrt(k_t / J_b);
    const auto summary = transient::integrate(
        system, o, q, v,
        [&](int, double t, const Eigen::VectorXd& qq, const Eigen::VectorXd&,
            const Eigen::VectorXd&) {
          max_track = std::max(max_track, std::abs(qq[a] - 0.5 * alpha * t * t));
          // Average the twist over whole periods of the free oscillation (t > 0.02 s).
          if (t > 0.02 && t <= 0.02 + 20.0 * 2.0 * std::numbers::pi / omega_b) {
            twist_sum += qq[a] - qq[b];
            ++twist_n;
          }
        },
        progress);
    ASSERT_EQ(summary.status, Status::Ok) << summary.message;
    const double af = scheme == transient::Scheme::Newmark ? 0.0 : o.parameters().alpha_f;
    const double offset = af * (1.0 - af) * alpha * o.time_step * o.time_step / 2.0;
    // Newton tolerance 1e-10 relative to the angle (<= 32 rad here) on top of the offset.
    EXPECT_LT(max_track, offset * 1.01 + 1e-8) << to_string(scheme);
    // Mean twist over 20 periods of the free oscillation, from ~2000 samples: the window's
    // fractional sample ~ 1 / 2000 and the period error (h omega_b)^2 / 12 ~ 3e-4 per period.
    EXPECT_NEAR(twist_sum / twist_n, J_b * alpha / k_t, 1.5e-3 * J_b * alpha / k_t)
        << to_string(scheme);
  }
}

// Linearisation at an operating point whose contacts are all closed equals the linear modal
// analysis of the same model with the contacts replaced by their (linear) springs, to 1e-9
// (both solve the same matrices; the tolerance covers the eigen-solvers' round-off).
TEST(DrivetrainLinearisation, ClosedContactsGiveTheModesOfTheLinearModel) {
  model::Model m = test::friswell_591(6);
  const double k_c = 4.0e6, c_c = 300.0, k_S = 2.0e7, k_P = 6.0e7;
  model::ContactSpec stop;
  stop.name = "stop";
  stop.node2 = "shaft.3";
  stop.direction = {1.0, 0.0, 0.0};
  stop.kind = model::ContactKind::Stop;
  stop.gap = -2e-5;  // interference: closed at rest
  stop.law.type = model::ContactLawKind::Linear;
  stop.law.stiffness = k_c;
  stop.law.damping = c_c;
  model::BoltSpec bolt;
  bolt.name = "B1";
  bolt.node2 = "shaft.2";
  bolt.axis = {0.0, 1.0, 0.0};
  bolt.bolt_stiffness = k_S;
  bolt.clamp_stiffness = k_P;
  bolt.preload = 5000.0;
  model::Model nl = m;
  nl.contacts.push_back(stop);
  nl.bolts.push_back(bolt);
  // Reference: linear bearings of the same stiffness on the same DOFs.
  model::Model lin = m;
  model::Bearing b1;
  b1.name = "stop_spring";
  b1.node = "shaft.3";
  b1.stiffness = {test::diagonal6(k_c, 0, 0, 0, 0, 0)};
  b1.damping = {test::diagonal6(c_c, 0, 0, 0, 0, 0)};
  model::Bearing b2;
  b2.name = "bolt_spring";
  b2.node = "shaft.2";
  b2.stiffness = {test::diagonal6(0, k_S + k_P, 0, 0, 0, 0)};
  b2.damping = {test::diagonal6(0, 0, 0, 0, 0, 0)};
  lin.bearings.push_back(b1);
  lin.bearings.push_back(b2);

  const fe::LinearSystem sys = assembly::build_system(nl);
  DrivetrainSystem system(build_drivetrain(nl, sys, {}));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(system.size());
  const StaticResult st = solve_static(system, 0.0, zero, zero);
  ASSERT_EQ(st.status, Status::Ok) << st.message;
  const Linearisation L = linearise(system, 0.0, st.q, zero, 8);
  ASSERT_EQ(L.status, Status::Ok) << L.message;

  const fe::LinearSystem lsys = assembly::build_system(lin);
  analyses::ModalSettings ms;
  ms.n_modes = 8;
  ms.complex_modes = true;
  analyses::Context ctx("modal");
  ctx.with_system(&lsys);
  const analyses::ModalResult ref = analyses::run_modal(lin, ms, ctx);
  ASSERT_EQ(ref.status, Status::Ok) << ref.message;
  std::vector<std::complex<double>> expected;
  for (const auto& mode : ref.complex)
    if (!mode.rigid_body) expected.push_back(mode.eigenvalue);
  ASSERT_GE(expected.size(), 4U);
  ASSERT_GE(L.modes.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const std::complex<double> got = L.modes[k].eigenvalue;
    EXPECT_LT(std::abs(got - expected[k]), 1e-9 * std::abs(expected[k]))
        << "mode " << k + 1 << ": " << got << " vs " << expected[k];
  }
}

// Passage through resonance of a Jeffcott rotor at constant angular acceleration, the spin a
// state driven by a speed driver and the unbalance turning with the actual angle. Reference: the
// linear rotor model with the same run-up prescribed (transient::LinearRotorSystem), integrated
// with a step 10x smaller (converged: the peak changes by < 1e-4 between the two references).
// Both give the classical delayed, reduced peak (F.M. Lewis, "Vibration during acceleration
// through a critical speed", Trans. ASME 54 (1932) 253-261).
TEST(DrivetrainRunUp, JeffcottPassageThroughResonanceMatchesTheLinearRotorRunUp) {
  const double m = 10.0, k = 4.0e5, zeta = 0.02, me = 1e-4;
  const double wn = std::sqrt(k / m), alpha = 0.5 * wn * wn * 0.05;  // slow enough to ring up
  const double T = 2.0 * wn / alpha;
  model::Model model = transient::testing::jeffcott(m, k, zeta, me);
  model.constraints[0].dofs = {Component::Uz, Component::Rx, Component::Ry};
  model::Disk disk;
  disk.name = "hub";
  disk.node = "disk";
  disk.mass = 0.0;
  disk.polar_inertia = 0.02;
  disk.diametral_inertia = 0.01;
  model.disks.push_back(disk);
  model.drivers.push_back(speed_driver("disk", {0.0, T}, {0.0, alpha * T}));
  const fe::LinearSystem sys = assembly::build_system(model);
  DrivetrainSystem system(build_drivetrain(model, sys, {}));
  const int x = sys.dofs.dof(0, Component::Ux), y = sys.dofs.dof(0, Component::Uy);
  auto run_peak = [&](transient::SecondOrderSystem& s, double h, int ex, int ey, double& at) {
    transient::IntegratorOptions o;
    o.time_step = h;
    o.num_steps = static_cast<int>(std::round(T / h));
    o.rho_infinity = 1.0;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(s.size()), v = q;
    double peak = 0.0;
    NullProgress progress;
    const auto sum = transient::integrate(
        s, o, q, v,
        [&](int, double t, const Eigen::VectorXd& qq, const Eigen::VectorXd&,
            const Eigen::VectorXd&) {
          const double r = std::hypot(qq[ex], qq[ey]);
          if (r > peak) {
            peak = r;
            at = alpha * t;
          }
        },
        progress);
    EXPECT_EQ(sum.status, Status::Ok) << sum.message;
    return peak;
  };
  const double h = 2.0 * std::numbers::pi / wn / 200.0;
  double at = 0.0, at_ref = 0.0;
  const double peak = run_peak(system, h, x, y, at);
  model::Model linear = transient::testing::jeffcott(m, k, zeta, me);
  const fe::LinearSystem lsys = assembly::build_system(linear);
  transient::LinearRotorSystem ref(linear, lsys,
                                   transient::SpeedProfile::run_up(0.0, alpha * T, T));
  const double peak_ref = run_peak(ref, h / 10.0, 0, 1, at_ref);
  // Steady resonance amplitude me / (2 zeta m) is not reached at this acceleration (Lewis).
  EXPECT_LT(peak_ref, me / (2.0 * zeta * m));
  EXPECT_GT(at_ref, wn);  // the peak is delayed past the critical speed
  // Step h vs h/10: the trapezoidal rule's period error (h omega)^2 / 12 ~ 1e-4 of a cycle per
  // cycle accumulates over the ~tens of cycles of the passage: 2e-3 on the peak and its speed.
  EXPECT_NEAR(peak, peak_ref, 2e-3 * peak_ref);
  EXPECT_NEAR(at, at_ref, 2e-3 * at_ref);
}

// Speed-dependent bearings follow the actual speed (issue #16, item 1): a rotor on a bearing
// tabulated at 0 and 400 rad/s, built at rest and evaluated spinning at W = 150 rad/s, has the
// residual M a + (C_at(W) + W G) v + K_at(W) q of the linear rotor model at W (the same algebra,
// to round-off), and its tangent includes d(K_b q + C_b v)/dW on the driver's column: compared
// with central differences of the residual in v, exact here (the residual is quadratic in v
// inside one table segment), so to 1e-7 of the column's size (difference round-off).
TEST(DrivetrainSystem, SpeedDependentBearingsFollowTheActualSpeed) {
  model::Model m = transient::testing::flexible_rotor(1.0);
  m.unbalances.clear();
  m.constraints.front().dofs = {Component::Uz};
  model::Bearing& b = m.bearings[1];
  b.speeds = {0.0, 400.0};
  b.stiffness = {transient::testing::diagonal6(2e7, 5e7), transient::testing::diagonal6(4e7, 3e7)};
  b.damping = {transient::testing::diagonal6(2e3, 3e3), transient::testing::diagonal6(1e3, 1e3)};
  b.stiffness[1][1] = 5e6;  // cross-coupled k_xy at speed
  m.drivers.push_back(speed_driver("s.0", {0.0, 1.0}, {0.0, 300.0}));
  const fe::LinearSystem sys = assembly::build_system(m);
  ASSERT_EQ(sys.speed_bearings.size(), 1U);
  DrivetrainSystem system(build_drivetrain(m, sys, {}));
  ASSERT_EQ(system.parts().speed_bearings.size(), 1U);
  const int n = system.size();
  const double W = 150.0;
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, -1e-5, 2e-5);
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const Eigen::VectorXd v = rigid_spin(sys, W) + Eigen::VectorXd::LinSpaced(n, 3e-3, -1e-3);
  const double omega = system.reference_speed(v);
  Eigen::VectorXd r;
  system.free_residual(0.2, q, v, a, r);
  const Eigen::VectorXd expected =
      sys.M * a + (sys.C_at(omega) + omega * sys.G) * v + sys.K_at(omega) * q;
  EXPECT_LT((r - expected).norm(), 1e-12 * (sys.K_at(omega) * q).norm());

  SparseMatrix S;
  system.tangent(0.2, q, v, 0.0, 1.0, 0.0, S);
  const Eigen::MatrixXd St(S);
  const int driven = system.held_equations().front();
  for (int j = 0; j < n; ++j) {
    const double h = 1e-3 * std::max(1.0, std::abs(v[j]));
    Eigen::VectorXd vp = v, vm = v, rp, rm;
    vp[j] += h;
    vm[j] -= h;
    system.free_residual(0.2, q, vp, a, rp);
    system.free_residual(0.2, q, vm, a, rm);
    Eigen::VectorXd fd = (rp - rm) / (2.0 * h);
    Eigen::VectorXd col = St.col(j);
    fd[driven] = col[driven] = 0.0;  // the servo row is not the free residual
    EXPECT_LT((col - fd).norm(), 1e-7 * std::max(1.0, fd.norm())) << "column " << j;
  }
}

}  // namespace
}  // namespace geardyn::drivetrain
