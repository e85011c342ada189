// Time integrators on systems with closed-form solutions.
//
//   SDOF:   m q'' + c q' + k q = f(t)          |--/\/\/--[ m ]--> q
//                                              |---[ c ]--
// References: free damped vibration and steady harmonic response, e.g. Rao, Mechanical
// Vibrations, 5th ed., eqs. 2.72 and 3.30; numerical properties of the schemes from Chung &
// Hulbert, J. Appl. Mech. 60 (1993) 371 (second order, spectral radius rho_inf at infinite
// frequency) and Hughes, The Finite Element Method, 1987, sec. 9.1 (trapezoidal rule: energy
// conserving, period elongation (omega h)^2 / 12).
#include "geardyn/transient/integrator.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "geardyn/core/progress.hpp"
#include "matrix_system.hpp"

namespace geardyn::transient {
namespace {

using testing::MatrixSystem;
constexpr double kPi = std::numbers::pi;

Eigen::MatrixXd scalar(double x) { return Eigen::MatrixXd::Constant(1, 1, x); }

IntegratorOptions options_for(Scheme scheme, double rho, double h, int steps) {
  IntegratorOptions o;
  o.scheme = scheme;
  o.rho_infinity = rho;
  o.time_step = h;
  o.num_steps = steps;
  return o;
}

// Largest |q_h(t_k) - q(t_k)| over a run of the free damped SDOF from q0 = 1, v0 = 0.
double free_vibration_error(Scheme scheme, double rho, double h) {
  const double m = 2.0, wn = 2 * kPi * 1.5, zeta = 0.05;
  const double k = m * wn * wn, c = 2 * zeta * m * wn;
  const double wd = wn * std::sqrt(1 - zeta * zeta);
  MatrixSystem system(scalar(m), scalar(c), scalar(k));
  Eigen::VectorXd q = Eigen::VectorXd::Ones(1), v = Eigen::VectorXd::Zero(1);
  double error = 0.0;
  const double duration = 2.0;
  const int steps = static_cast<int>(std::lround(duration / h));
  const auto summary = integrate(
      system, options_for(scheme, rho, h, steps), q, v,
      [&](int, double t, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
          const Eigen::VectorXd&) {
        const double exact =
            std::exp(-zeta * wn * t) * (std::cos(wd * t) + zeta * wn / wd * std::sin(wd * t));
        error = std::max(error, std::abs(qs[0] - exact));
      },
      null_progress());
  EXPECT_EQ(summary.status, Status::Ok) << summary.brief_report();
  EXPECT_EQ(summary.factorizations, 1) << "linear time-invariant: factor once";
  EXPECT_EQ(summary.newton_iterations, steps) << "one correction per step";
  return error;
}

TEST(Integrator, ObservedConvergenceOrderIsTwo) {
  // Three step sizes h, h/2, h/4 with omega_n h = 0.19 .. 0.047 (asymptotic range): the error
  // ratio of successive halvings is 2^p. Second order within 0.1 (pre-asymptotic terms are
  // O(h^3)).
  struct Case {
    Scheme scheme;
    double rho;
  };
  for (const Case& c : {Case{Scheme::Newmark, 1.0}, Case{Scheme::GeneralizedAlpha, 0.9},
                        Case{Scheme::GeneralizedAlpha, 0.5}, Case{Scheme::GeneralizedAlpha, 0.0}}) {
    const double e1 = free_vibration_error(c.scheme, c.rho, 0.02);
    const double e2 = free_vibration_error(c.scheme, c.rho, 0.01);
    const double e3 = free_vibration_error(c.scheme, c.rho, 0.005);
    const double p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e3);
    EXPECT_NEAR(p1, 2.0, 0.1) << to_string(c.scheme) << " rho " << c.rho << " errors " << e1 << " "
                              << e2 << " " << e3;
    EXPECT_NEAR(p2, 2.0, 0.1) << to_string(c.scheme) << " rho " << c.rho;
    RecordProperty(std::string(to_string(c.scheme)) + "_rho" + std::to_string(c.rho) + "_order",
                   fmt::format("{:.4f} {:.4f}", p1, p2));
  }
}

// Spectral radius of the one-step amplification matrix of the undamped SDOF q'' + w^2 q = 0 at
// w h = `wh`, built column by column from the scaled states (q, h v, h^2 a).
double spectral_radius(Scheme scheme, double rho, double wh) {
  const double h = 1.0, w = wh / h;
  MatrixSystem system(scalar(1.0), scalar(0.0), scalar(w * w));
  Eigen::Matrix3d A;
  for (int j = 0; j < 3; ++j) {
    Eigen::VectorXd q = Eigen::VectorXd::Constant(1, j == 0 ? 1.0 : 0.0);
    Eigen::VectorXd v = Eigen::VectorXd::Constant(1, j == 1 ? 1.0 / h : 0.0);
    IntegratorOptions o = options_for(scheme, rho, h, 1);
    o.initial_acceleration = Eigen::VectorXd::Constant(1, j == 2 ? 1.0 / (h * h) : 0.0);
    Eigen::VectorXd a_end;
    integrate(
        system, o, q, v,
        [&](int, double, const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::VectorXd& a) {
          a_end = a;
        },
        null_progress());
    A.col(j) << q[0], h * v[0], h * h * a_end[0];
  }
  return A.eigenvalues().cwiseAbs().maxCoeff();
}

TEST(Integrator, GeneralizedAlphaDampsHighFrequenciesToRhoInfinity) {
  // Chung & Hulbert: spectral radius -> rho_inf as w h -> infinity. At w h = 1e6 the
  // amplification matrix is within O(1/(w h)) of its limit, which has the triple eigenvalue
  // -rho_inf; a triple eigenvalue moves by O(perturbation^(1/3)) = O(1e-2), hence 2e-2.
  for (double rho : {0.0, 0.3, 0.6, 0.9, 1.0}) {
    const double radius = spectral_radius(Scheme::GeneralizedAlpha, rho, 1e6);
    EXPECT_NEAR(radius, rho, 2e-2) << "rho " << rho;
    RecordProperty("radius_at_1e6_rho" + std::to_string(rho), std::to_string(radius));
  }
  // Low frequencies are hardly damped: at w h = 0.05 the radius is 1 - O((w h)^3).
  for (double rho : {0.0, 0.5, 0.9})
    EXPECT_GT(spectral_radius(Scheme::GeneralizedAlpha, rho, 0.05), 1.0 - 1e-4) << "rho " << rho;
  // Damping increases monotonically with frequency for rho_inf < 1.
  EXPECT_LT(spectral_radius(Scheme::GeneralizedAlpha, 0.5, 10.0),
            spectral_radius(Scheme::GeneralizedAlpha, 0.5, 1.0));
  // The trapezoidal rule has no numerical damping at any frequency.
  for (double wh : {0.01, 1.0, 100.0, 1e6})
    EXPECT_NEAR(spectral_radius(Scheme::Newmark, 1.0, wh), 1.0, 1e-9) << "w h " << wh;
}

// Amplitude of the steady response by a least-squares fit of a cos + b sin over whole periods.
double fitted_amplitude(const std::vector<double>& t, const std::vector<double>& x, double w) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(t.size()), 2);
  Eigen::VectorXd b(static_cast<Eigen::Index>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    A(static_cast<Eigen::Index>(i), 0) = std::cos(w * t[i]);
    A(static_cast<Eigen::Index>(i), 1) = std::sin(w * t[i]);
    b[static_cast<Eigen::Index>(i)] = x[i];
  }
  const Eigen::Vector2d ab = A.colPivHouseholderQr().solve(b);
  return ab.norm();
}

TEST(Integrator, ForcedSdofSteadyAmplitudeMatchesAnalytic) {
  // m q'' + c q' + k q = F cos(W t), f_n = 5 Hz, zeta = 0.05, W = 2 pi 3 Hz.
  // Steady amplitude X = F / sqrt((k - m W^2)^2 + (c W)^2) (Rao eq. 3.30).
  // Transient decays as exp(-zeta w_n t): after 10 s it is below 1e-6 of the initial.
  // Step h = 1e-3 s: W h = 0.019; the trapezoidal rule maps the response at W to the exact one
  // at (2/h) tan(W h / 2) = W (1 + (W h)^2 / 12), which shifts X by about
  // (d ln|D| / d ln W) (W h)^2 / 12 ~ 5e-5 relative here; generalised-alpha's forced response
  // error is of the same order. Tolerance 3e-4.
  const double m = 1.5, wn = 2 * kPi * 5.0, zeta = 0.05, F = 20.0, W = 2 * kPi * 3.0;
  const double k = m * wn * wn, c = 2 * zeta * m * wn;
  const double X = F / std::hypot(k - m * W * W, c * W);
  for (Scheme scheme : {Scheme::Newmark, Scheme::GeneralizedAlpha}) {
    MatrixSystem system(scalar(m), scalar(c), scalar(k), [&](double t) {
      return Eigen::VectorXd::Constant(1, F * std::cos(W * t));
    });
    Eigen::VectorXd q = Eigen::VectorXd::Zero(1), v = Eigen::VectorXd::Zero(1);
    std::vector<double> ts, xs;
    const double h = 1e-3;
    const int steps = 12000;
    const double fit_from = 12.0 - 2.0;  // last 2 s = 6 whole periods
    const auto summary = integrate(
        system, options_for(scheme, 0.8, h, steps), q, v,
        [&](int, double t, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
            const Eigen::VectorXd&) {
          if (t > fit_from + 1e-9) {
            ts.push_back(t);
            xs.push_back(qs[0]);
          }
        },
        null_progress());
    ASSERT_EQ(summary.status, Status::Ok);
    const double amplitude = fitted_amplitude(ts, xs, W);
    EXPECT_NEAR(amplitude / X, 1.0, 3e-4) << to_string(scheme) << ": " << amplitude << " vs " << X;
    RecordProperty(std::string(to_string(scheme)) + "_amplitude_ratio",
                   fmt::format("{:.8f}", amplitude / X));
  }
}

TEST(Integrator, TrapezoidalRuleConservesEnergyOfUndampedSystem) {
  // Three masses in a chain between walls, no damping, random initial state, h large compared
  // with the highest period (w_max h ~ 3.5): the trapezoidal rule conserves
  // E = 1/2 v'Mv + 1/2 q'Kq exactly (Hughes sec. 9.1); only rounding (~1e-16 per step,
  // growing like sqrt(steps)) may change it. Generalised-alpha with rho_inf = 0.5 must lose
  // energy instead (numerical dissipation).
  Eigen::MatrixXd M = Eigen::Vector3d(1.0, 2.0, 0.5).asDiagonal();
  Eigen::MatrixXd K(3, 3);
  const double k = 1e4;
  K << 2 * k, -k, 0, -k, 2 * k, -k, 0, -k, 2 * k;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd q0(3), v0(3);
  for (int i = 0; i < 3; ++i) {
    q0[i] = 0.01 * u(rng);
    v0[i] = u(rng);
  }
  MatrixSystem system(M, Eigen::MatrixXd::Zero(3, 3), K);
  const double e0 = system.energy(q0, v0);
  double worst = 0.0;
  Eigen::VectorXd q = q0, v = v0;
  auto summary = integrate(
      system, options_for(Scheme::Newmark, 1.0, 0.02, 20000), q, v,
      [&](int, double, const Eigen::VectorXd& qs, const Eigen::VectorXd& vs,
          const Eigen::VectorXd&) {
        worst = std::max(worst, std::abs(system.energy(qs, vs) - e0) / e0);
      },
      null_progress());
  ASSERT_EQ(summary.status, Status::Ok);
  EXPECT_LT(worst, 1e-11);
  RecordProperty("trapezoidal_energy_drift", fmt::format("{:.3g}", worst));

  q = q0;
  v = v0;
  summary = integrate(system, options_for(Scheme::GeneralizedAlpha, 0.5, 0.02, 200), q, v, {},
                      null_progress());
  ASSERT_EQ(summary.status, Status::Ok);
  EXPECT_LT(system.energy(q, v), 0.9 * e0);
}

TEST(Integrator, StaleTangentCostsIterationsNotAccuracy) {
  // The same damped 2-DOF system, once as linear time-invariant with the exact tangent and once
  // declared time-varying with a tangent 30 % too stiff: modified Newton must reach the same
  // answer to its tolerance, taking several iterations per step.
  Eigen::MatrixXd M = Eigen::Vector2d(1.0, 3.0).asDiagonal();
  Eigen::MatrixXd K(2, 2), C(2, 2);
  K << 3e3, -1e3, -1e3, 1e3;
  C = 1e-3 * K;
  auto force = [](double t) { return Eigen::Vector2d(std::sin(20 * t), 0.0).eval(); };
  double q_max = 0.0;
  auto run = [&](bool lti, double scale, IntegrationSummary& summary) {
    MatrixSystem system(M, C, K, [&](double t) { return Eigen::VectorXd(force(t)); });
    system.lti = lti;
    system.tangent_scale = scale;
    Eigen::VectorXd q = Eigen::VectorXd::Zero(2), v = Eigen::VectorXd::Zero(2);
    IntegratorOptions o = options_for(Scheme::GeneralizedAlpha, 0.8, 2e-3, 500);
    o.newton_tolerance = 1e-12;
    summary = integrate(
        system, o, q, v,
        [&](int, double, const Eigen::VectorXd& qs, const Eigen::VectorXd&,
            const Eigen::VectorXd&) { q_max = std::max(q_max, qs.lpNorm<Eigen::Infinity>()); },
        null_progress());
    return q;
  };
  IntegrationSummary exact, stale;
  const Eigen::VectorXd q_exact = run(true, 1.0, exact);
  const Eigen::VectorXd q_stale = run(false, 1.3, stale);
  ASSERT_EQ(stale.status, Status::Ok) << stale.brief_report();
  // Each step stops within 1e-12 x max|q| of its solution; over 500 steps of a stable scheme
  // these add up to at most ~500 x 1e-12 x max|q|.
  EXPECT_LT((q_stale - q_exact).lpNorm<Eigen::Infinity>(), 1e-9 * q_max);
  EXPECT_GT(stale.newton_iterations, 2 * stale.steps_taken);
  EXPECT_GE(stale.factorizations, 1);
}

TEST(Integrator, LowRankDampingMatchesAssembledDamping) {
  // C = U diag(c) U^T given as a low-rank term (Woodbury in the solver) or assembled: same run.
  Eigen::MatrixXd M = Eigen::Vector3d(1.0, 1.0, 2.0).asDiagonal();
  Eigen::MatrixXd K(3, 3);
  K << 2e4, -1e4, 0, -1e4, 2e4, -1e4, 0, -1e4, 1e4;
  Eigen::MatrixXd U(3, 2);
  U << 1, 0.5, 0.2, -1, 0.3, 0.7;
  const Eigen::Vector2d c(3.0, 0.0);  // a zero coefficient must be allowed
  auto force = [](double t) { return Eigen::Vector3d(0, 0, std::cos(50 * t)).eval(); };
  MatrixSystem low_rank(M, Eigen::MatrixXd::Zero(3, 3), K,
                        [&](double t) { return Eigen::VectorXd(force(t)); });
  low_rank.set_low_rank_damping(U, c);
  MatrixSystem assembled(M, U * c.asDiagonal() * U.transpose(), K,
                         [&](double t) { return Eigen::VectorXd(force(t)); });
  Eigen::VectorXd q1 = Eigen::VectorXd::Zero(3), v1 = q1, q2 = q1, v2 = q1;
  const auto o = options_for(Scheme::Newmark, 1.0, 1e-3, 1000);
  const auto s1 = integrate(low_rank, o, q1, v1, {}, null_progress());
  const auto s2 = integrate(assembled, o, q2, v2, {}, null_progress());
  ASSERT_EQ(s1.status, Status::Ok);
  ASSERT_EQ(s2.status, Status::Ok);
  EXPECT_NE(s1.solver.find("Woodbury"), std::string::npos) << s1.solver;
  EXPECT_LT((q1 - q2).norm(), 1e-10 * q2.norm());
  EXPECT_LT((v1 - v2).norm(), 1e-10 * v2.norm());
}

TEST(Integrator, ConsistentInitialAccelerationSolvesTheEquationOfMotion) {
  // M a0 = f(0) - C v0 - K q0.
  Eigen::MatrixXd M = Eigen::Vector2d(2.0, 4.0).asDiagonal();
  Eigen::MatrixXd K(2, 2), C(2, 2);
  K << 10, -2, -2, 5;
  C << 1, 0, 0, 2;
  MatrixSystem system(M, C, K, [](double) { return Eigen::Vector2d(3.0, -1.0).eval(); });
  Eigen::VectorXd q = Eigen::Vector2d(0.1, -0.2), v = Eigen::Vector2d(1.0, 0.5);
  const Eigen::VectorXd expected = M.inverse() * (Eigen::Vector2d(3.0, -1.0) - C * v - K * q);
  Eigen::VectorXd a0;
  integrate(
      system, options_for(Scheme::Newmark, 1, 1e-3, 1), q, v,
      [&](int step, double, const Eigen::VectorXd&, const Eigen::VectorXd&,
          const Eigen::VectorXd& a) {
        if (step == 0) a0 = a;
      },
      null_progress());
  EXPECT_LT((a0 - expected).norm(), 1e-14 * expected.norm());
}

TEST(Integrator, ReportsDivergenceWithStepAndTime) {
  // Negative stiffness (a statically unstable system): q'' = w^2 q. With w h = 1.999 the
  // trapezoidal rule amplifies the growing root by (1 + wh/2) / (1 - wh/2) ~ 4000 per step.
  MatrixSystem unstable(scalar(1.0), scalar(0.0), scalar(-1.999 * 1.999));
  Eigen::VectorXd q = Eigen::VectorXd::Ones(1), v = Eigen::VectorXd::Zero(1);
  auto summary =
      integrate(unstable, options_for(Scheme::Newmark, 1, 1.0, 10), q, v, {}, null_progress());
  EXPECT_EQ(summary.status, Status::Diverged);
  EXPECT_EQ(summary.steps_taken, 0);
  EXPECT_NE(summary.message.find("step 1"), std::string::npos) << summary.message;

  // A residual that turns NaN after t = 0.05 s.
  MatrixSystem nan_force(scalar(1.0), scalar(0.1), scalar(100.0), [](double t) {
    return Eigen::VectorXd::Constant(1, t > 0.05 ? std::nan("") : 1.0);
  });
  q = Eigen::VectorXd::Zero(1);
  v = Eigen::VectorXd::Zero(1);
  summary = integrate(nan_force, options_for(Scheme::GeneralizedAlpha, 0.9, 0.01, 100), q, v, {},
                      null_progress());
  EXPECT_EQ(summary.status, Status::Diverged);
  EXPECT_NE(summary.message.find("t = 0.06"), std::string::npos) << summary.message;
  EXPECT_TRUE(q.allFinite()) << "the last accepted state is kept";
}

TEST(Integrator, SingularMassIsReported) {
  MatrixSystem massless(scalar(0.0), scalar(0.0), scalar(1.0));
  Eigen::VectorXd q = Eigen::VectorXd::Ones(1), v = Eigen::VectorXd::Zero(1);
  const auto summary =
      integrate(massless, options_for(Scheme::Newmark, 1, 0.1, 10), q, v, {}, null_progress());
  EXPECT_EQ(summary.status, Status::Singular);
  EXPECT_NE(summary.message.find("mass"), std::string::npos);
}

TEST(Integrator, InvalidOptionsAreListed) {
  IntegratorOptions o;
  o.rho_infinity = 1.5;
  o.num_steps = 0;
  const auto problems = o.validate();
  EXPECT_EQ(problems.size(), 3u);  // rho, time_step (NaN), num_steps
  MatrixSystem system(scalar(1.0), scalar(0.0), scalar(1.0));
  Eigen::VectorXd q = Eigen::VectorXd::Zero(1), v = q;
  EXPECT_THROW(integrate(system, o, q, v, {}, null_progress()), std::invalid_argument);
}

}  // namespace
}  // namespace geardyn::transient
