// The element library of hbm/element_library.hpp (issue #18) against closed forms, the existing
// AFT laws it wraps, finite differences and its own time-domain law.
//
// References and tolerances (each test says which applies):
//   * Griffin, "Friction damping of resonant stresses in gas turbine engine airfoils", J. Eng.
//     Power 102 (1980) 329-333: the Jenkins element under u = X cos theta has
//     k_eq = (k / pi)(beta - sin 2 beta / 2), W = 4 F (X - F / k), beta = arccos(1 - 2F / (kX)),
//     and sticks over the share beta / pi of the period (the force swings by 2F from each
//     reversal within 1 - cos theta = 2F / (kX)). Sampled kinks carry an O((2 pi / n)^2) error:
//     2.4e-6 at n = 4096, 1e-5 asserted (as tests/hbm/jenkins_test.cpp); the stick share is
//     counted in samples, so it is within 2 / n of beta / pi.
//   * The AFT of u^3 for u = A cos(theta - phi): u^3 = (3/4) A^3 cos(theta - phi)
//     + (1/4) A^3 cos 3(theta - phi) (cos^3 x = (3 cos x + cos 3x) / 4). Harmonic 3 aliases onto
//     harmonic n_time - 3, so with H = 1 the AFT is exact for n_time = 5 > (3 + 1) 1 and folds
//     the 1/4 onto harmonic 1 for n_time = 4: both to round-off (1e-14).
//   * The unilateral spring under u = a cos theta, closed over |theta| < theta_c = arccos(g/a):
//     mean = (k / pi)(a sin theta_c - g theta_c), first cosine coefficient
//     (k a / pi)(theta_c - sin theta_c cos theta_c) (direct integration). The trapezoidal rule
//     on periodic samples errs only in the cells of the two kinks, by at most J h^2 / 8 each (J
//     the slope jump, h = 2 pi / n): bounds derived in the test.
//   * Central differences of harmonic_force check the analytic AFT Jacobians and df/domega.
//     Piecewise-linear laws (Jenkins, gap, 1D friction) are linear in w between switches, so
//     the differences are exact up to round-off eps |f| / h ~ 1e-10 relative; smooth laws (2D
//     radial return, polynomial, tanh) add O(h^2) truncation, ~1e-10 for the relative steps
//     used. 1e-7 is asserted for all (margin for the conditioning of the projections).
//   * time_force marched over the AFT samples reproduces loop() to round-off: the slider-position
//     predictor k (u_j - s_{j-1}) equals the AFT's T_{j-1} + k (u_j - u_{j-1}) to a few eps k |u|
//     per step, so 1e-11 of the force scale over ~1e3 steps.
#include "geardyn/hbm/element_library.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/elements/contact_law.hpp"
#include "geardyn/elements/gap_contact.hpp"
#include "geardyn/hbm/element_system.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"

namespace geardyn::hbm {
namespace {

constexpr double kPi = std::numbers::pi;

// A generic multi-harmonic motion of amplitude ~x on one coordinate (H >= 3): a mean, three
// harmonics, no symmetry; `shift` varies the phases between coordinates.
Eigen::VectorXd generic_motion(const HarmonicBasis& b, double x, double mean, double shift) {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(b.size());
  c[0] = mean;
  c[HarmonicBasis::cos_index(1)] = x * std::cos(shift);
  c[HarmonicBasis::sin_index(1)] = x * std::sin(shift);
  c[HarmonicBasis::cos_index(2)] = 0.13 * x;
  c[HarmonicBasis::sin_index(2)] = -0.07 * x;
  c[HarmonicBasis::cos_index(3)] = 0.05 * x * std::cos(3.0 * shift);
  c[HarmonicBasis::sin_index(3)] = 0.04 * x;
  return c;
}

Eigen::VectorXd stack(const std::vector<Eigen::VectorXd>& blocks) {
  Eigen::Index size = 0;
  for (const auto& b : blocks) size += b.size();
  Eigen::VectorXd w(size);
  Eigen::Index at = 0;
  for (const auto& b : blocks) {
    w.segment(at, b.size()) = b;
    at += b.size();
  }
  return w;
}

Eigen::VectorXd force_of(const NonlinearElement& e, const HarmonicBasis& b,
                         const Eigen::VectorXd& w, double omega) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(w.size());
  e.harmonic_force(b, w, omega, f, nullptr, nullptr);
  return f;
}

double relative(const Eigen::MatrixXd& a, const Eigen::MatrixXd& reference) {
  return (a - reference).cwiseAbs().maxCoeff() /
         std::max(reference.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
}

struct DerivativeErrors {
  double jacobian = 0.0;  ///< max |J - J_fd| / max |J_fd|
  double omega = 0.0;     ///< max |df/domega - fd| / max |fd| (0 / 0 = 0: both exactly zero)
};

// Central differences of harmonic_force in each coefficient (step h_w) and in omega (h_omega).
DerivativeErrors derivative_errors(const NonlinearElement& e, const HarmonicBasis& b,
                                   const Eigen::VectorXd& w, double omega, double h_w,
                                   double h_omega) {
  const Eigen::Index m = w.size();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m), d = Eigen::VectorXd::Zero(m);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, m);
  e.harmonic_force(b, w, omega, f, &J, &d);
  EXPECT_LE(relative(f, force_of(e, b, w, omega)), 0.0) << "the force depends on the request";
  Eigen::MatrixXd J_fd(m, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    Eigen::VectorXd wp = w, wm = w;
    wp[i] += h_w;
    wm[i] -= h_w;
    J_fd.col(i) = (force_of(e, b, wp, omega) - force_of(e, b, wm, omega)) / (2.0 * h_w);
  }
  const Eigen::VectorXd d_fd =
      (force_of(e, b, w, omega + h_omega) - force_of(e, b, w, omega - h_omega)) / (2.0 * h_omega);
  return {relative(J, J_fd), relative(d, d_fd)};
}

// The force samples of the last of `periods` periods of time_force marched over the AFT samples
// of w, from initial_state(mean of each coordinate): where the AFT marches start.
Eigen::MatrixXd marched_loop(const NonlinearElement& e, const HarmonicBasis& b,
                             const Eigen::VectorXd& w, double omega, int periods) {
  const Eigen::MatrixXd u = sample_coordinates(b, w), v = sample_velocities(b, w, omega);
  const int n = b.time_samples(), s = b.size();
  Eigen::VectorXd mean(e.size());
  for (int k = 0; k < e.size(); ++k) mean[k] = w[k * s];
  Eigen::VectorXd state = e.initial_state(mean);
  Eigen::MatrixXd f(n, e.size());
  ElementStep step;
  for (int p = 0; p < periods; ++p)
    for (int j = 0; j < n; ++j) {
      e.time_force(u.row(j).transpose(), v.row(j).transpose(), 2.0 * kPi * j / n, omega, state,
                   step);
      state = step.state;
      if (p == periods - 1) f.row(j) = step.force.transpose();
    }
  return f;
}

// Elements used by several tests. Jenkins: k = 1e5 N/m, F = 10 N (F/k = 0.1 mm).
constexpr double kJ = 1e5, kSlip = 10.0;
// Friction contact: k_t = 1e5 N/m, k_n = 2e5 N/m, mu = 0.3, N_0 = 20 N (mu N_0 = 6 N at a
// tangential excursion of 0.06 mm; lift-off at v = -0.1 mm).
FrictionContact contact(int directions, double normal_stiffness = 2e5) {
  return {directions, normal_stiffness, 1e5, 0.3, 20.0};
}

std::shared_ptr<const elements::ContactLaw> linear_law(double k, double c) {
  return std::make_shared<elements::LinearContactLaw>(
      elements::LinearLawParameters{k, c, elements::Tension::allowed});
}

// The dead-zone spring-damper written by hand: f = k (u -+ b) + c v outside |u| <= b.
class DeadZone final : public PointwiseElement {
 public:
  DeadZone(double k, double c, double b) : k_(k), c_(c), b_(b) {}
  int size() const override { return 1; }
  std::string describe() const override { return "dead zone"; }
  bool velocity_dependent() const override { return true; }
  void pointwise(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double, double,
                 ElementStep& out) const override {
    if (std::abs(u[0]) <= b_) return;
    out.force[0] = k_ * (u[0] - (u[0] > 0.0 ? b_ : -b_)) + c_ * v[0];
    out.stiffness(0, 0) = k_;
    out.damping(0, 0) = c_;
  }

 private:
  double k_, c_, b_;
};

TEST(ElementLibrary, AftJacobianAndOmegaDerivativeMatchFiniteDifferences) {
  const HarmonicBasis b(3, 256);
  const double omega = 150.0, X = 5e-4;
  const Eigen::VectorXd w1 = generic_motion(b, X, 0.2 * X, 0.3);
  struct Case {
    std::shared_ptr<const NonlinearElement> element;
    Eigen::VectorXd w;
  };
  std::vector<Case> cases;
  cases.push_back({std::make_shared<JenkinsElementHb>("root", JenkinsElement{kJ, kSlip}), w1});
  // 2D contact, variable normal load without lift-off (v amplitude 0.05 mm < 0.1 mm).
  cases.push_back({std::make_shared<FrictionContactHb>("2d", contact(1)),
                   stack({generic_motion(b, 5e-5, 0.0, 1.1), generic_motion(b, 3e-4, 0.0, 0.2)})});
  // 3D contact with lift-off over part of the period (v amplitude 0.15 mm > 0.1 mm).
  cases.push_back({std::make_shared<FrictionContactHb>("3d", contact(2)),
                   stack({generic_motion(b, 1.5e-4, 0.0, 1.1), generic_motion(b, 3e-4, 0.0, 0.2),
                          generic_motion(b, 2e-4, 0.0, 1.7)})});
  // 3D contact in stick and 2D slip, variable normal load without lift-off.
  cases.push_back({std::make_shared<FrictionContactHb>("3d stick-slip", contact(2)),
                   stack({generic_motion(b, 5e-5, 0.0, 1.1), generic_motion(b, 1e-4, 0.0, 0.2),
                          generic_motion(b, 5e-5, 0.0, 1.7)})});
  cases.push_back({std::make_shared<PolynomialSpring>(
                       "poly", std::map<int, double>{{1, 1e4}, {2, 3e7}, {3, 2e11}}),
                   w1});
  cases.push_back({std::make_shared<UnilateralSpringHb>("gap", 2e5, 0.3 * X, 40.0), w1});
  cases.push_back({std::make_shared<TanhCoulomb>("tanh", kSlip, 0.1 * omega * X), w1});
  cases.push_back(
      {std::make_shared<ForceElementAdapter>(
           "play", std::make_shared<elements::GapContact>(elements::GapContact::end_play(
                       "play", 0.4 * X, linear_law(2e5, 40.0), linear_law(3e5, 20.0)))),
       w1});
  for (const Case& c : cases) {
    const double h_w = 1e-6 * c.w.cwiseAbs().maxCoeff();
    const DerivativeErrors e = derivative_errors(*c.element, b, c.w, omega, h_w, 1e-6 * omega);
    EXPECT_LE(e.jacobian, 1e-7) << c.element->describe();
    EXPECT_LE(e.omega, 1e-7) << c.element->describe();
  }
}

TEST(ElementLibrary, JenkinsMatchesGriffinClosedForms) {
  const HarmonicBasis b(1, 4096);
  const JenkinsElementHb jenkins("root", {kJ, kSlip});
  for (double X : {1.5e-4, 3e-4, 2e-3}) {
    const Eigen::VectorXd w = X * Eigen::VectorXd::Unit(b.size(), HarmonicBasis::cos_index(1));
    const double beta = std::acos(1.0 - 2.0 * kSlip / (kJ * X));
    const double k_eq = kJ / kPi * (beta - 0.5 * std::sin(2.0 * beta));
    const double energy = 4.0 * kSlip * (X - kSlip / kJ);
    const Eigen::VectorXd f = force_of(jenkins, b, w, 100.0);
    EXPECT_NEAR(f[HarmonicBasis::cos_index(1)] / X, k_eq, 1e-5 * kJ) << X;
    const ElementLoop loop = jenkins.loop(b, w, 100.0);
    EXPECT_NEAR(loop.energy_per_cycle, energy, 1e-5 * energy) << X;
    EXPECT_NEAR(loop.stick_fraction, beta / kPi, 2.0 / b.time_samples()) << X;
    EXPECT_DOUBLE_EQ(loop.stick_fraction + loop.slip_fraction, 1.0);
    EXPECT_TRUE(std::isnan(loop.open_fraction));
  }
  // Below the slip amplitude F / k: the linear spring, no loss.
  const Eigen::VectorXd stuck = 0.5 * kSlip / kJ * Eigen::VectorXd::Unit(b.size(), 1);
  const ElementLoop loop = jenkins.loop(b, stuck, 100.0);
  EXPECT_DOUBLE_EQ(loop.stick_fraction, 1.0);
  EXPECT_NEAR(loop.energy_per_cycle, 0.0, 1e-14 * kSlip * kSlip / kJ);
}

TEST(ElementLibrary, FrictionContactWithConstantNormalLoadIsJenkins) {
  // k_n = 0: N = N_0 always, slip limit mu N_0 = 6 N; the tangential law is Jenkins.
  const HarmonicBasis b(3, 256);
  const FrictionContact c = contact(1, 0.0);
  const FrictionContactHb fc("fc", c);
  const JenkinsElementHb jenkins(
      "j", {c.tangential_stiffness, c.friction_coefficient * c.normal_preload});
  const int s = b.size();
  const double omega = 80.0;
  for (double X : {3e-5, 2e-4}) {  // stuck and slipping
    const Eigen::VectorXd u = generic_motion(b, X, 0.1 * X, 0.4);
    const Eigen::VectorXd w = stack({generic_motion(b, 1e-4, 0.0, 1.0), u});
    Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * s), fj = Eigen::VectorXd::Zero(s);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * s, 2 * s), Jj = Eigen::MatrixXd::Zero(s, s);
    fc.harmonic_force(b, w, omega, f, &J, nullptr);
    jenkins.harmonic_force(b, u, omega, fj, &Jj, nullptr);
    // The same march (friction_contact.cpp reproduces jenkins.cpp): round-off only.
    EXPECT_LE(relative(f.tail(s), fj), 1e-14) << X;
    EXPECT_LE(relative(J.bottomRightCorner(s, s), Jj), 1e-14) << X;
    EXPECT_EQ(f.head(s).cwiseAbs().maxCoeff(), 0.0);  // N - N_0 = 0
    EXPECT_EQ(J.leftCols(s).cwiseAbs().maxCoeff(), 0.0);
    const ElementLoop a = fc.loop(b, w, omega), l = jenkins.loop(b, u, omega);
    EXPECT_DOUBLE_EQ(a.stick_fraction, l.stick_fraction);
    EXPECT_DOUBLE_EQ(a.open_fraction, 0.0);
    EXPECT_NEAR(a.energy_per_cycle, l.energy_per_cycle, 1e-14 * kSlip * X);
    // The time-domain laws too, sample by sample.
    EXPECT_LE(
        relative(marched_loop(fc, b, w, omega, 3).col(1), marched_loop(jenkins, b, u, omega, 3)),
        1e-14);
  }
}

TEST(ElementLibrary, TimeMarchReproducesTheAftLoop) {
  const HarmonicBasis b(3, 256);
  const double omega = 150.0, X = 5e-4;
  const Eigen::VectorXd w1 = generic_motion(b, X, 0.2 * X, 0.3);
  struct Case {
    std::shared_ptr<const NonlinearElement> element;
    Eigen::VectorXd w;
    int periods;
  };
  const std::vector<Case> cases = {
      // 1D slip closes the loop after one period: the third period is the steady one.
      {std::make_shared<JenkinsElementHb>("root", JenkinsElement{kJ, kSlip}), w1, 3},
      {std::make_shared<FrictionContactHb>("2d", contact(1)),
       stack({generic_motion(b, 5e-5, 0.0, 1.1), generic_motion(b, 3e-4, 0.0, 0.2)}), 3},
      // Lift-off erases the slider's memory every period: steady from the second period.
      {std::make_shared<FrictionContactHb>("3d lift-off", contact(2)),
       stack({generic_motion(b, 1.5e-4, 0.0, 1.1), generic_motion(b, 3e-4, 0.0, 0.2),
              generic_motion(b, 2e-4, 0.0, 1.7)}),
       3},
      // Stick and 2D slip without lift-off: the memory fades by mu N / |T*| per slip sample
      // (here by ~1e-5 per period: the AFT closes to 1e-12 after 5 periods); 8 are marched.
      {std::make_shared<FrictionContactHb>("3d", contact(2)),
       stack({generic_motion(b, 5e-5, 0.0, 1.1), generic_motion(b, 1e-4, 0.0, 0.2),
              generic_motion(b, 5e-5, 0.0, 1.7)}),
       8},
      {std::make_shared<UnilateralSpringHb>("gap", 2e5, 0.3 * X, 40.0), w1, 1},
      {std::make_shared<TanhCoulomb>("tanh", kSlip, 0.1 * omega * X), w1, 1},
  };
  for (const Case& c : cases) {
    const ElementLoop loop = c.element->loop(b, c.w, omega);
    const Eigen::MatrixXd marched = marched_loop(*c.element, b, c.w, omega, c.periods);
    EXPECT_LE(relative(marched, loop.force), 1e-11) << c.element->describe();
    EXPECT_LE(relative(loop.displacement, sample_coordinates(b, c.w)), 0.0);
  }
}

// Central differences of time_force's force in u at a fixed committed state.
Eigen::MatrixXd step_stiffness_fd(const NonlinearElement& e, const Eigen::VectorXd& u,
                                  const Eigen::VectorXd& state, double h) {
  const Eigen::Index n = u.size();
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd K(n, n);
  ElementStep plus, minus;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::VectorXd up = u, um = u;
    up[i] += h;
    um[i] -= h;
    e.time_force(up, v, 0.0, 1.0, state, plus);
    e.time_force(um, v, 0.0, 1.0, state, minus);
    K.col(i) = (plus.force - minus.force) / (2.0 * h);
  }
  return K;
}

TEST(ElementLibrary, TimeStepTangentsAreTheReturnMappingDerivatives) {
  // Jenkins: tangent k in stick, 0 in slip, slider moved by the slip.
  const JenkinsElementHb jenkins("root", {kJ, kSlip});
  const Eigen::VectorXd s0 = Eigen::VectorXd::Constant(1, 1e-5);
  ElementStep step;
  jenkins.time_force(Eigen::VectorXd::Constant(1, 5e-5), Eigen::VectorXd::Zero(1), 0.0, 1.0, s0,
                     step);
  EXPECT_DOUBLE_EQ(step.force[0], kJ * 4e-5);
  EXPECT_DOUBLE_EQ(step.stiffness(0, 0), kJ);
  EXPECT_DOUBLE_EQ(step.state[0], s0[0]);
  jenkins.time_force(Eigen::VectorXd::Constant(1, -2e-4), Eigen::VectorXd::Zero(1), 0.0, 1.0, s0,
                     step);
  EXPECT_DOUBLE_EQ(step.force[0], -kSlip);
  EXPECT_EQ(step.stiffness(0, 0), 0.0);
  EXPECT_NEAR(step.state[0], -2e-4 + kSlip / kJ, 1e-20);  // spring at its limit: s = u - T / k
  // 3D contact, variable normal load: stick, slip (radial return) and lift-off. The law is
  // smooth away from the switches; relative step 1e-6 gives O(1e-12) truncation, 1e-7 allowed.
  const FrictionContactHb fc("3d", contact(2));
  const Eigen::VectorXd s = Eigen::Vector2d(1e-5, -2e-5);
  for (const Eigen::Vector3d& u : {Eigen::Vector3d(2e-5, 3e-5, -1e-5),     // stick
                                   Eigen::Vector3d(2e-5, 3e-4, 1e-4),      // slip
                                   Eigen::Vector3d(-2e-4, 3e-4, 1e-4)}) {  // lift-off
    const Eigen::VectorXd uu = u;
    fc.time_force(uu, Eigen::VectorXd::Zero(3), 0.0, 1.0, s, step);
    const Eigen::MatrixXd fd = step_stiffness_fd(fc, uu, s, 1e-6 * uu.norm());
    EXPECT_LE((step.stiffness - fd).cwiseAbs().maxCoeff(), 1e-7 * 2e5) << u.transpose();
    // The committed slider reproduces the force: T = k_t (u_t - s) unless lifted off.
    if (u[0] > -1e-4) {
      EXPECT_LE((1e5 * (uu.tail(2) - step.state) - step.force.tail(2)).norm(), 1e-12 * 6.0);
    }
  }
}

TEST(ElementLibrary, CubicSpringAftIsExactAboveTheAliasingBound) {
  const double alpha = 3e9, A = 2e-3, phi = 0.7;
  const PolynomialSpring cubic("cubic", {{3, alpha}});
  EXPECT_EQ(cubic.degree(), 3);
  const double scale = alpha * A * A * A;
  auto coefficients = [&](int harmonics, int n) {
    const HarmonicBasis b(harmonics, n);
    Eigen::VectorXd w = Eigen::VectorXd::Zero(b.size());
    w[HarmonicBasis::cos_index(1)] = A * std::cos(phi);
    w[HarmonicBasis::sin_index(1)] = A * std::sin(phi);
    return force_of(cubic, b, w, 1.0);
  };
  // H = 1, n = 5 > (3 + 1) 1: exact.
  Eigen::VectorXd exact(3);
  exact << 0.0, 0.75 * scale * std::cos(phi), 0.75 * scale * std::sin(phi);
  EXPECT_LE((coefficients(1, 5) - exact).cwiseAbs().maxCoeff(), 1e-14 * scale);
  // n = 4 = (3 + 1) 1: harmonic 3 folds onto harmonic 4 - 3 = 1 as cos 3(theta - phi) sampled
  // at theta_j = pi j / 2 equals cos(theta_j + 3 phi) there: + (1/4)(cos 3phi, -sin 3phi).
  Eigen::VectorXd aliased = exact;
  aliased[1] += 0.25 * scale * std::cos(3.0 * phi);
  aliased[2] -= 0.25 * scale * std::sin(3.0 * phi);
  EXPECT_LE((coefficients(1, 4) - aliased).cwiseAbs().maxCoeff(), 1e-14 * scale);
  // H = 3 at the default sampling: both harmonics, nothing else.
  const Eigen::VectorXd f = coefficients(3, default_time_samples(3, cubic.degree()));
  Eigen::VectorXd full = Eigen::VectorXd::Zero(7);
  full.head(3) = exact;
  full[HarmonicBasis::cos_index(3)] = 0.25 * scale * std::cos(3.0 * phi);
  full[HarmonicBasis::sin_index(3)] = 0.25 * scale * std::sin(3.0 * phi);
  EXPECT_LE((f - full).cwiseAbs().maxCoeff(), 1e-14 * scale);
}

TEST(ElementLibrary, UnilateralSpringMeanForceMatchesClosedForm) {
  const double k = 2e5, a = 1e-3;
  const HarmonicBasis b(1, 4096);
  const double h = 2.0 * kPi / b.time_samples();
  const Eigen::VectorXd w = a * Eigen::VectorXd::Unit(b.size(), HarmonicBasis::cos_index(1));
  for (double g : {0.4 * a, -0.3 * a, -1.5 * a, 1.2 * a}) {
    const UnilateralSpringHb spring("stop", k, g);
    double mean = 0.0, first = 0.0, mean_bound = 1e-14 * k * a, first_bound = mean_bound;
    if (g <= -a) {  // always closed: k (u - g)
      mean = -k * g;
      first = k * a;
    } else if (g < a) {
      const double tc = std::acos(g / a), sc = std::sin(tc), cc = std::cos(tc);
      mean = k / kPi * (a * sc - g * tc);
      first = k * a / kPi * (tc - sc * cc);
      // Two kinks of slope jump k a sin(theta_c) (mean: / 2 pi) and k a sin cos (a_1: / pi).
      // (1.1: margin for the O(h^3) terms of the curvature jump at the kinks.)
      mean_bound += 1.1 * 2.0 * k * a * sc * h * h / 8.0 / (2.0 * kPi);
      first_bound += 1.1 * 2.0 * k * a * std::abs(sc * cc) * h * h / 8.0 / kPi;
    }
    const Eigen::VectorXd f = force_of(spring, b, w, 1.0);
    EXPECT_NEAR(f[0], mean, mean_bound) << "gap " << g;
    EXPECT_NEAR(f[HarmonicBasis::cos_index(1)], first, first_bound) << "gap " << g;
    const ElementLoop loop = spring.loop(b, w, 1.0);
    const double open = g <= -a ? 0.0 : (g >= a ? 1.0 : 1.0 - std::acos(g / a) / kPi);
    EXPECT_NEAR(loop.open_fraction, open, 2.0 / b.time_samples()) << "gap " << g;
  }
  // A negative gap preloads the spring at u = 0 by k |gap|.
  ElementStep step;
  UnilateralSpringHb("preloaded", k, -0.3 * a)
      .time_force(Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1), 0.0, 1.0, Eigen::VectorXd(),
                  step);
  EXPECT_DOUBLE_EQ(step.force[0], 0.3 * k * a);
}

TEST(ElementLibrary, AdaptedEndPlayIsTheDeadZoneSpring) {
  const double k = 2e5, c = 40.0, play = 2e-4, omega = 150.0;
  const ForceElementAdapter adapter(
      "play", std::make_shared<elements::GapContact>(elements::GapContact::end_play(
                  "play", play, linear_law(k, c), linear_law(k, c))));
  const DeadZone hand(k, c, play);
  const HarmonicBasis b(3, 256);
  const Eigen::VectorXd w = generic_motion(b, 5e-4, 1e-4, 0.3);
  const int s = b.size();
  Eigen::VectorXd fa = Eigen::VectorXd::Zero(s), fh = fa, da = fa, dh = fa;
  Eigen::MatrixXd Ja = Eigen::MatrixXd::Zero(s, s), Jh = Ja;
  adapter.harmonic_force(b, w, omega, fa, &Ja, &da);
  hand.harmonic_force(b, w, omega, fh, &Jh, &dh);
  // The same law evaluated through the contact law's penetration and rate: round-off only.
  EXPECT_LE(relative(fa, fh), 1e-14);
  EXPECT_LE(relative(Ja, Jh), 1e-14);
  EXPECT_LE(relative(da, dh), 1e-14);
  EXPECT_NE(adapter.describe().find("play"), std::string::npos);
}

TEST(ElementLibrary, ConstructorsNameTheBadKey) {
  auto key_of = [](auto make) {
    try {
      make();
    } catch (const InputError& e) {
      return e.key_path();
    }
    return std::string("no error");
  };
  ElementSource at;
  at.key_path = "nonlinear_elements[2]";
  EXPECT_EQ(key_of([] { JenkinsElementHb("j", {0.0, 1.0}); }), "stiffness");
  EXPECT_EQ(key_of([&] {
              JenkinsElementHb("j", {1.0, -1.0}, at);
            }),
            "nonlinear_elements[2].slip_force");
  FrictionContact bad = contact(2);
  bad.friction_coefficient = -0.1;
  EXPECT_EQ(key_of([&] { FrictionContactHb("c", bad, {}, at); }),
            "nonlinear_elements[2].friction_coefficient");
  bad = contact(2);
  bad.normal_preload = std::nan("");
  EXPECT_EQ(key_of([&] { FrictionContactHb("c", bad); }), "normal_preload");
  EXPECT_EQ(key_of([] { FrictionContactHb("c", contact(1), {0, 1e-12}); }), "max_periods");
  EXPECT_EQ(key_of([] { PolynomialSpring("p", {}); }), "coefficients");
  EXPECT_EQ(key_of([] { PolynomialSpring("p", {{0, 1.0}}); }), "coefficients");
  EXPECT_EQ(key_of([] { UnilateralSpringHb("u", 1.0, std::nan("")); }), "gap");
  EXPECT_EQ(key_of([] { UnilateralSpringHb("u", 1.0, 0.0, -1.0); }), "damping");
  EXPECT_EQ(key_of([] { TanhCoulomb("t", 1.0, 0.0); }), "regularisation_velocity");
  EXPECT_EQ(key_of([] { ForceElementAdapter("a", nullptr); }), "element");
  // A motion of the wrong size, or not finite.
  const JenkinsElementHb j("j", {1.0, 1.0});
  const HarmonicBasis b(1, 16);
  EXPECT_THROW(force_of(j, b, Eigen::VectorXd::Zero(5), 1.0), InputError);
  EXPECT_THROW(force_of(j, b, Eigen::VectorXd::Constant(3, std::nan("")), 1.0), NumericalError);
}

// SDOF Jenkins oscillator (tests/hbm/friction_oscillator_test.cpp, issue #5):
//   m q'' + c q' + k q + T(q) = f cos(Omega t), m = 1 kg, k = 1 N/m, c = 0.01 N s/m,
//   k_t = 1 N/m, f = 0.05 N.
constexpr double kM = 1.0, kK = 1.0, kC = 0.01, kKt = 1.0, kF = 0.05;

ElementHarmonicBalance jenkins_oscillator(const HarmonicBasis& basis, double slip_force) {
  ElementSystem sys;
  sys.M = Eigen::MatrixXd::Constant(1, 1, kM);
  sys.C = Eigen::MatrixXd::Constant(1, 1, kC);
  sys.K = Eigen::MatrixXd::Constant(1, 1, kK);
  sys.elements.push_back(
      {std::make_shared<JenkinsElementHb>("slider", JenkinsElement{kKt, slip_force}), "slider",
       Eigen::MatrixXd::Ones(1, 1)});
  sys.excitation = kF * Eigen::VectorXd::Unit(3, HarmonicBasis::cos_index(1));
  sys.excitation_harmonics = 1;
  return ElementHarmonicBalance(std::move(sys), basis);
}

TEST(ElementLibrary, ElementBalanceEqualsTheJenkinsForceOfHarmonicBalance) {
  // The same oscillator through HarmonicBalance + jenkins_force (harmonic_balance.hpp): the
  // residual and Jacobian at a slipping state agree to round-off.
  const HarmonicBasis basis(3, 256);
  const double slip = 0.02;
  const ElementHarmonicBalance eb = jenkins_oscillator(basis, slip);
  const HarmonicBalance hb(Eigen::MatrixXd::Constant(1, 1, kM), Eigen::MatrixXd::Constant(1, 1, kC),
                           Eigen::MatrixXd::Constant(1, 1, kK), basis,
                           {jenkins_force(0, -1, {kKt, slip})},
                           kF * Eigen::VectorXd::Unit(basis.size(), HarmonicBasis::cos_index(1)));
  const Eigen::VectorXd X = generic_motion(basis, 0.3, 0.01, 0.5);
  Eigen::MatrixXd Je, Jh;
  const Eigen::VectorXd Re = eb.residual(X, 1.1, &Je), Rh = hb.residual(X, 1.1, &Jh);
  EXPECT_LE(relative(Re, Rh), 1e-13);
  EXPECT_LE(relative(Je, Jh), 1e-13);
}

// Largest first-harmonic amplitude along a sweep and the largest frequency gap around it.
struct Peak {
  double amplitude = 0.0, omega = 0.0, gap = 0.0;
};

TEST(ElementLibrary, JenkinsOscillatorTendsToItsLinearLimits) {
  // Slip force 1e6 N never slips (|T| <= k_t |q| < 10 N): the stuck system k + k_t. Slip force
  // 0: the free system k. Every point must equal the linear FRF f / |k_eff - m W^2 + i c W| to
  // the Newton tolerance (1e-9 relative), and the largest amplitude traced the linear peak
  // f / (c sqrt(k_eff / m - c^2 / (4 m^2))) within the drop of the nearest sample below it.
  const HarmonicBasis basis(3, 1024);
  for (const auto& [slip, k_eff] : {std::pair{1e6, kK + kKt}, std::pair{0.0, kK}}) {
    const ElementHarmonicBalance hb = jenkins_oscillator(basis, slip);
    ContinuationOptions o;
    o.omega_start = 0.6;
    o.omega_end = 1.8;
    o.x_scale = 5.0;  // the peak amplitudes are 3.5 (stuck) and 5 (free)
    o.step = 1e-3;
    o.max_step = 1e-3;
    o.tolerance = 1e-12;
    const Eigen::VectorXd X0 =
        kF / (kK + kKt - 0.36) * Eigen::VectorXd::Unit(hb.size(), HarmonicBasis::cos_index(1));
    const ContinuationResult r = continue_in_frequency(hb, X0, o);
    ASSERT_EQ(r.status, Status::Ok) << r.message;
    Peak peak;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      const auto& p = r.points[i];
      const double a =
          std::hypot(p.X[HarmonicBasis::cos_index(1)], p.X[HarmonicBasis::sin_index(1)]);
      const double exact =
          kF / std::abs(std::complex<double>(k_eff - kM * p.omega * p.omega, kC * p.omega));
      EXPECT_NEAR(a, exact, 1e-9 * exact) << "slip " << slip << " omega " << p.omega;
      EXPECT_NEAR(p.X[HarmonicBasis::cos_index(3)], 0.0, 1e-9 * exact);
      if (a > peak.amplitude && i > 0 && i + 1 < r.points.size())
        peak = {a, p.omega,
                std::max(p.omega - r.points[i - 1].omega, r.points[i + 1].omega - p.omega)};
    }
    // |D|^2 = D_min^2 + m^2 (W^2 - W_p^2)^2, D_min = c sqrt(k/m - c^2 / (4 m^2)): a sample within
    // delta = gap / 2 of W_p is below the peak by at most (1/2) (2 m W_p delta / D_min)^2.
    const double d_min = kC * std::sqrt(k_eff / kM - kC * kC / (4.0 * kM * kM));
    const double w_p = std::sqrt(k_eff / kM - kC * kC / (2.0 * kM * kM));
    const double exact_peak = kF / d_min;
    const double drop = 0.5 * std::pow(2.0 * kM * w_p * 0.5 * peak.gap / d_min, 2);
    EXPECT_LE(peak.amplitude, exact_peak * (1.0 + 1e-9)) << "slip " << slip;
    // (1.1: the next order in delta; 1e-9: the Newton tolerance.)
    EXPECT_GE(peak.amplitude, exact_peak * (1.0 - 1.1 * drop - 1e-9)) << "slip " << slip;
    EXPECT_LT(drop, 1e-2) << "the sweep is too coarse at the peak";
  }
}

}  // namespace
}  // namespace geardyn::hbm
