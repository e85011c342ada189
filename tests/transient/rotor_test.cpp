// LinearRotorSystem: speed profile, unbalance force, consistency with the frequency-domain model
// of fe::LinearSystem (unbalance_load, K_at, C_at), and the steady state of a time integration
// against the direct harmonic solution (two independent methods).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "geardyn/core/progress.hpp"
#include "geardyn/fe/linear_system.hpp"
#include "geardyn/transient/integrator.hpp"
#include "geardyn/transient/linear_rotor_system.hpp"
#include "support/transient_rotor_models.hpp"

namespace geardyn::transient {
namespace {

using namespace std::complex_literals;
constexpr double kPi = std::numbers::pi;

TEST(SpeedProfile, SpeedAccelerationAndAngleOfALinearRunUp) {
  const SpeedProfile p = SpeedProfile::run_up(100.0, 300.0, 2.0);
  EXPECT_DOUBLE_EQ(p.speed(0.0), 100.0);
  EXPECT_DOUBLE_EQ(p.speed(1.0), 200.0);
  EXPECT_DOUBLE_EQ(p.speed(5.0), 300.0);  // held after the ramp
  EXPECT_DOUBLE_EQ(p.acceleration(1.0), 100.0);
  EXPECT_DOUBLE_EQ(p.acceleration(3.0), 0.0);
  // Theta(t) = W0 t + (W1 - W0) t^2 / (2 T) inside the ramp, then + W1 (t - T).
  EXPECT_DOUBLE_EQ(p.angle(1.0), 100.0 + 50.0);
  EXPECT_DOUBLE_EQ(p.angle(3.0), 200.0 + 200.0 + 300.0);
  const SpeedProfile c = SpeedProfile::constant(50.0);
  EXPECT_TRUE(c.is_constant());
  EXPECT_DOUBLE_EQ(c.angle(2.0), 100.0);
  EXPECT_DOUBLE_EQ(c.acceleration(1.0), 0.0);
}

// The force of an unbalance is minus its mass times the acceleration of its position
// m_e [cos psi, sin psi] relative to the node: check by a central second difference of the
// position, during a run-up, for positive and negative speed ratios.
TEST(LinearRotorSystem, UnbalanceForceIsMinusMassTimesAcceleration) {
  for (double ratio : {1.0, -2.5}) {
    const model::Model model = testing::jeffcott(10.0, 1e6, 0.02, 1e-4, ratio);
    const fe::LinearSystem system = fe::assemble(model);
    const SpeedProfile profile = SpeedProfile::run_up(50.0, 450.0, 1.0);
    LinearRotorSystem rotor(model, system, profile);
    const int ex = system.dofs.dof(0, model::Component::Ux);
    const int ey = system.dofs.dof(0, model::Component::Uy);
    const double phase = model.unbalances[0].phase;
    auto position = [&](double t) -> Eigen::Vector2d {
      const double psi = ratio * profile.angle(t) + (ratio < 0 ? -phase : phase);
      return Eigen::Vector2d(std::cos(psi), std::sin(psi)) * 1e-4;
    };
    for (double t : {0.1, 0.37, 0.8}) {
      // Truncation ~ (psi' d)^2 / 12 < 1e-7 with psi' <= 1125 rad/s; rounding
      // ~ 4 eps |m_e| / d^2 ~ 1e-7 absolute against forces >= 0.25 N: tolerance 2e-6.
      const double d = 1e-6;
      const Eigen::Vector2d acceleration =
          (position(t + d) - 2.0 * position(t) + position(t - d)) / (d * d);
      const Eigen::VectorXd f = rotor.external_force(t);
      const Eigen::Vector2d expected = -acceleration;
      EXPECT_NEAR(f[ex], expected[0], 2e-6 * expected.norm()) << "ratio " << ratio << " t " << t;
      EXPECT_NEAR(f[ey], expected[1], 2e-6 * expected.norm()) << "ratio " << ratio << " t " << t;
    }
  }
}

TEST(LinearRotorSystem, ConstantSpeedForceMatchesFrequencyDomainUnbalanceLoad) {
  for (double ratio : {1.0, -1.0}) {
    model::Model model = testing::jeffcott(10.0, 1e6, 0.02, 1e-4, ratio);
    model.unbalances[0].phase = 0.9;
    const fe::LinearSystem system = fe::assemble(model);
    const double speed = 321.0, w = std::abs(ratio) * speed;
    LinearRotorSystem rotor(model, system, SpeedProfile::constant(speed));
    const Eigen::VectorXcd F = fe::unbalance_load(model, system, speed, std::abs(ratio));
    for (double t : {0.0, 0.0123, 0.5}) {
      const Eigen::VectorXd expected = (F * std::exp(1i * w * t)).real();
      EXPECT_LT((rotor.external_force(t) - expected).norm(), 1e-12 * expected.norm())
          << "ratio " << ratio << " t " << t;
    }
  }
}

TEST(LinearRotorSystem, ResidualAndTangentUseTheSpeedDependentMatricesOfTheModel) {
  // A bearing tabulated at two speeds: the residual at constant speed W must be
  // M a + (C_at(W) + W G) v + K_at(W) q - f(t), and the run-up tangent must equal
  // c_m M + c_c (C_at(W(t)) + W(t) G) + c_k K_at(W(t)).
  model::Model model = testing::flexible_rotor(1.0);
  model::Bearing& b = model.bearings[1];
  b.speeds = {0.0, 400.0};
  b.stiffness = {testing::diagonal6(2e7, 5e7), testing::diagonal6(4e7, 3e7)};
  b.damping = {testing::diagonal6(2e3, 3e3), testing::diagonal6(1e3, 1e3)};
  b.stiffness[1][1] = 5e6;  // cross-coupled k_xy at speed
  const fe::LinearSystem system = fe::assemble(model);
  ASSERT_FALSE(system.speed_bearings.empty());
  const int n = system.size();
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(n, -1e-5, 2e-5);
  const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, 3e-3, -1e-3);
  const Eigen::VectorXd a = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const double t = 0.37;
  {
    const double W = 150.0;
    LinearRotorSystem rotor(model, system, SpeedProfile::constant(W));
    Eigen::VectorXd r;
    rotor.residual(t, q, v, a, r);
    const Eigen::VectorXd expected = system.M * a + (system.C_at(W) + W * system.G) * v +
                                     system.K_at(W) * q - rotor.external_force(t);
    EXPECT_LT((r - expected).norm(), 1e-12 * (system.K_at(W) * q).norm());
    EXPECT_TRUE(rotor.is_linear_time_invariant());
  }
  {
    const SpeedProfile profile = SpeedProfile::run_up(100.0, 500.0, 1.0);
    LinearRotorSystem rotor(model, system, profile);
    EXPECT_FALSE(rotor.is_linear_time_invariant());
    const double W = profile.speed(t);
    Eigen::VectorXd r;
    rotor.residual(t, q, v, a, r);
    const Eigen::VectorXd expected = system.M * a + (system.C_at(W) + W * system.G) * v +
                                     system.K_at(W) * q - rotor.external_force(t);
    EXPECT_LT((r - expected).norm(), 1e-12 * (system.K_at(W) * q).norm());
    SparseMatrix S;
    rotor.tangent(t, q, v, 3.0, 2.0, 0.5, S);
    const Eigen::MatrixXd S_expected = Eigen::MatrixXd(
        3.0 * system.M + 2.0 * (system.C_at(W) + W * system.G) + 0.5 * system.K_at(W));
    EXPECT_LT((Eigen::MatrixXd(S) - S_expected).norm(), 1e-12 * S_expected.norm());
  }
}

// Complex amplitude X of x(t) = Re(X exp(i w t)) by least squares over the samples.
std::complex<double> fit_phasor(const std::vector<double>& t, const std::vector<double>& x,
                                double w) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(t.size()), 2);
  Eigen::VectorXd b(static_cast<Eigen::Index>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    A(k, 0) = std::cos(w * t[i]);
    A(k, 1) = std::sin(w * t[i]);
    b[k] = x[i];
  }
  const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(b);
  return {ab[0], -ab[1]};  // a cos + b sin = Re((a - i b) e^{i w t})
}

TEST(LinearRotorSystem, SteadyStateMatchesDirectHarmonicSolution) {
  // Flexible rotor (gyroscopic disk, anisotropic bearings, Rayleigh damping) at constant speed
  // W = 300 rad/s, both spin senses. Frequency domain: X = D(w)^{-1} F with
  // D = K - w^2 M + i w (C + W G), F = fe::unbalance_load; time domain: trapezoidal rule from
  // rest for 6 s (the slowest free decay, Rayleigh alpha / 2 = 3 1/s, leaves < 2e-8), phasor
  // fitted over the last 0.5 s. With h = 5e-5 s, w h = 0.015: the trapezoidal frequency
  // warping (w h)^2 / 12 = 1.9e-5 times |d ln D / d ln w| (a few) stays below 2e-4;
  // tolerance 1e-3 on the complex amplitude.
  for (double ratio : {1.0, -1.0}) {
    const model::Model model = testing::flexible_rotor(ratio);
    const fe::LinearSystem system = fe::assemble(model);
    ASSERT_GT(system.G.norm(), 0.0) << "the disk must bring gyroscopic coupling";
    const double W = 300.0, w = W;
    const Eigen::VectorXcd F = fe::unbalance_load(model, system, W, 1.0);
    const Eigen::MatrixXcd D =
        Eigen::MatrixXcd(system.K.cast<std::complex<double>>()) -
        w * w * Eigen::MatrixXcd(system.M.cast<std::complex<double>>()) +
        1i * w * Eigen::MatrixXcd((system.C + W * system.G).cast<std::complex<double>>());
    const Eigen::VectorXcd X = D.partialPivLu().solve(F);

    LinearRotorSystem rotor(model, system, SpeedProfile::constant(W));
    IntegratorOptions o;
    o.scheme = Scheme::Newmark;
    o.time_step = 5e-5;
    o.num_steps = 120000;
    const std::vector<int> outputs = {
        system.dofs.dof(system.dofs.node_index("s.2"), model::Component::Ux),
        system.dofs.dof(system.dofs.node_index("s.2"), model::Component::Uy),
        system.dofs.dof(system.dofs.node_index("s.1"), model::Component::Ry)};
    std::vector<double> ts;
    std::vector<std::vector<double>> xs(outputs.size());
    Eigen::VectorXd q = Eigen::VectorXd::Zero(system.size()), v = q;
    const auto summary = integrate(
        rotor, o, q, v,
        [&](int, double t, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
            const Eigen::VectorXd&) {
          if (t < 5.5) return;
          ts.push_back(t);
          for (std::size_t i = 0; i < outputs.size(); ++i) xs[i].push_back(qs[outputs[i]]);
        },
        null_progress());
    ASSERT_EQ(summary.status, Status::Ok) << summary.brief_report();
    EXPECT_EQ(summary.factorizations, 1);
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const std::complex<double> fitted = fit_phasor(ts, xs[i], w);
      const std::complex<double> expected = X[outputs[i]];
      EXPECT_LT(std::abs(fitted - expected), 1e-3 * std::abs(expected))
          << "ratio " << ratio << " output " << i << ": " << fitted << " vs " << expected;
      RecordProperty("ratio" + std::to_string(static_cast<int>(ratio)) + "_output" +
                         std::to_string(i) + "_relative_error",
                     std::to_string(std::abs(fitted - expected) / std::abs(expected)));
    }
  }
}

TEST(LinearRotorSystem, GyroscopicRunUpReusesTheFactorisationAndTracksTheHarmonicResponse) {
  // Flexible rotor run up from 100 to 400 rad/s in 8 s, far below its first critical speed:
  // the disk's response follows the steady harmonic response at the current speed (checked at
  // three times to 2 %, the lag of the decaying free response being ~0.5 %). W G changes every
  // step, so the integrator runs modified Newton and refactorises only when the stale
  // gyroscopic term slows the iterations down.
  const model::Model model = testing::flexible_rotor(1.0);
  const fe::LinearSystem system = fe::assemble(model);
  const SpeedProfile profile = SpeedProfile::run_up(100.0, 400.0, 8.0);
  LinearRotorSystem rotor(model, system, profile);
  IntegratorOptions o;
  o.scheme = Scheme::GeneralizedAlpha;
  o.rho_infinity = 0.9;
  o.time_step = 1e-4;
  o.num_steps = 80000;
  const int ex = system.dofs.dof(system.dofs.node_index("s.2"), model::Component::Ux);
  const int ey = system.dofs.dof(system.dofs.node_index("s.2"), model::Component::Uy);
  std::vector<double> ts, xs, ys;
  Eigen::VectorXd q = Eigen::VectorXd::Zero(system.size()), v = q;
  const auto summary = integrate(
      rotor, o, q, v,
      [&](int, double t, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
          const Eigen::VectorXd&) {
        ts.push_back(t);
        xs.push_back(qs[ex]);
        ys.push_back(qs[ey]);
      },
      null_progress());
  ASSERT_EQ(summary.status, Status::Ok) << summary.brief_report();
  EXPECT_LT(summary.factorizations, o.num_steps / 100) << summary.brief_report();
  EXPECT_LE(summary.max_iterations_in_step, 6) << summary.brief_report();
  RecordProperty("run_up_summary", summary.brief_report());
  for (double t_check : {3.0, 5.0, 7.5}) {
    const double W = profile.speed(t_check);
    const Eigen::VectorXcd F = fe::unbalance_load(model, system, W, 1.0);
    const Eigen::MatrixXcd D =
        Eigen::MatrixXcd(system.K.cast<std::complex<double>>()) -
        W * W * Eigen::MatrixXcd(system.M.cast<std::complex<double>>()) +
        1i * W * Eigen::MatrixXcd((system.C + W * system.G).cast<std::complex<double>>());
    const Eigen::VectorXcd X = D.partialPivLu().solve(F);
    // Largest excursions of x and y over one period around t_check.
    double x_max = 0.0, y_max = 0.0;
    for (std::size_t k = 0; k < ts.size(); ++k) {
      if (std::abs(ts[k] - t_check) > kPi / W) continue;
      x_max = std::max(x_max, std::abs(xs[k]));
      y_max = std::max(y_max, std::abs(ys[k]));
    }
    EXPECT_NEAR(x_max / std::abs(X[ex]), 1.0, 0.02) << "t = " << t_check;
    EXPECT_NEAR(y_max / std::abs(X[ey]), 1.0, 0.02) << "t = " << t_check;
  }
}

TEST(LinearRotorSystem, UnknownUnbalanceIsAnInputError) {
  const model::Model model = testing::jeffcott(10.0, 1e6, 0.02, 1e-4);
  const fe::LinearSystem system = fe::assemble(model);
  EXPECT_THROW(LinearRotorSystem(model, system, SpeedProfile::constant(1.0), {"nope"}), InputError);
}

}  // namespace
}  // namespace geardyn::transient
