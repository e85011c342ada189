// The node-to-node friction contact of hbm/friction_contact.hpp (2D and 3D, variable normal load,
// lift-off) and the unilateral spring: against the Jenkins element, closed forms derived below,
// and finite differences of the analytic AFT Jacobian.
//
// Contact used throughout unless a test says otherwise: k_t = 1e5 N/m, k_n = 2e5 N/m, mu = 0.3,
// N_0 = 100 N (friction limit mu N_0 = 30 N, reached at a tangential excursion of 0.3 mm).
#include "geardyn/hbm/friction_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"
#include "geardyn/hbm/jenkins.hpp"

namespace geardyn::hbm {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kt = 1e5, kn = 2e5, mu = 0.3, N0 = 100.0;

FrictionContact contact(int directions, double normal_stiffness = kn) {
  return {directions, normal_stiffness, kt, mu, N0};
}

// x cos(theta) in the HarmonicBasis layout.
Eigen::VectorXd cosine(const HarmonicBasis& b, double x) {
  return x * Eigen::VectorXd::Unit(b.size(), HarmonicBasis::cos_index(1));
}
Eigen::VectorXd sine(const HarmonicBasis& b, double x) {
  return x * Eigen::VectorXd::Unit(b.size(), HarmonicBasis::sin_index(1));
}
Eigen::VectorXd stack(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  Eigen::VectorXd w(a.size() + b.size());
  w << a, b;
  return w;
}
Eigen::VectorXd stack(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                      const Eigen::VectorXd& c) {
  Eigen::VectorXd w(a.size() + b.size() + c.size());
  w << a, b, c;
  return w;
}

double max_abs(const Eigen::MatrixXd& a) { return a.cwiseAbs().maxCoeff(); }

// Fourier coefficients a_0, a_1 of the clipped cosine f(theta) = max(p + q cos theta, 0),
// |p| < q > 0. f > 0 on |theta| < phi, cos phi = -p / q, so
//   a_0 = (1 / 2 pi) int_{-phi}^{phi} (p + q cos) = (p phi + q sin phi) / pi,
//   a_1 = (1 / pi) int_{-phi}^{phi} (p + q cos) cos = (2 p sin phi + q (phi + sin phi cos phi)) /
//   pi,
// and f = 0 on the share 1 - phi / pi of the period.
struct ClippedCosine {
  double a0, a1, zero_share;
};
ClippedCosine clipped_cosine(double p, double q) {
  const double phi = std::acos(-p / q);
  return {(p * phi + q * std::sin(phi)) / kPi,
          (2.0 * p * std::sin(phi) + q * (phi + std::sin(phi) * std::cos(phi))) / kPi,
          1.0 - phi / kPi};
}

// ---------------------------------------------------------------------------------------------
// Source: the law itself (header of friction_contact.hpp) and the Jenkins element of jenkins.hpp,
// which is its special case k_n = 0, one direction, slip force mu N_0. The element performs the
// same floating-point operations as jenkins.cpp in that case, so 1e-12 of the force and stiffness
// scales is asserted (the agreement is exact in practice). The normal displacement is nonzero on
// purpose: with k_n = 0 it must change nothing.
TEST(FrictionContact, OneDirectionWithConstantLoadIsTheJenkinsElement) {
  const HarmonicBasis b(3, 512);
  Eigen::VectorXd v(b.size()), slipping(b.size()), stuck(b.size());
  v << 1e-4, 3e-4, 0.0, 0.0, -1e-4, 0.0, 0.0;
  slipping << 2e-5, 6e-4, -1e-4, 1.5e-4, 2e-4, -8e-5, 5e-5;
  stuck = 0.2 * slipping;
  stuck[0] = 1e-3;  // a static offset: the element sticks about it
  const int m = b.size();
  for (const Eigen::VectorXd& u : {slipping, stuck}) {
    const ContactResponse r = friction_contact_response(contact(1, 0.0), b, stack(v, u));
    const JenkinsResponse j = jenkins_response({kt, mu * N0}, b, u);
    ASSERT_TRUE(r.loop_closed);
    EXPECT_LT(max_abs(r.coefficients.tail(m) - j.coefficients), 1e-12 * mu * N0);
    EXPECT_LT(max_abs(r.force.col(1) - j.force), 1e-12 * mu * N0);
    EXPECT_LT(max_abs(r.jacobian.bottomRightCorner(m, m) - j.jacobian), 1e-12 * kt);
    EXPECT_EQ(max_abs(r.coefficients.head(m)), 0.0);  // constant load: no normal force change
    EXPECT_EQ(max_abs(r.jacobian.leftCols(m)), 0.0);
    EXPECT_EQ(max_abs(r.jacobian.topRows(m)), 0.0);
    EXPECT_NEAR(r.energy_per_cycle, j.energy_per_cycle, 1e-12 * mu * N0 * 1e-3);
    EXPECT_EQ(r.stick_fraction, j.stick_fraction);
    EXPECT_EQ(r.lift_off_fraction, 0.0);
  }
}

// Source: isotropy of the law. A 3D contact driven along a fixed unit direction e, u = e s(t),
// never leaves that line (the predictor and the return are along e), so T = e T_Jenkins(s).
// The rotation by e rounds each sample: 1e-12 of the scales again.
TEST(FrictionContact, ThreeDimensionalContactAlongALineIsTheJenkinsElement) {
  const HarmonicBasis b(3, 512);
  Eigen::VectorXd s(b.size());
  s << 2e-5, 6e-4, -1e-4, 1.5e-4, 2e-4, -8e-5, 5e-5;
  const double angle = 0.7;
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(b.size());
  const ContactResponse r = friction_contact_response(
      contact(2, 0.0), b, stack(v, std::cos(angle) * s, std::sin(angle) * s));
  const JenkinsResponse j = jenkins_response({kt, mu * N0}, b, s);
  EXPECT_LT(max_abs(r.force.col(1) - std::cos(angle) * j.force), 1e-12 * mu * N0);
  EXPECT_LT(max_abs(r.force.col(2) - std::sin(angle) * j.force), 1e-12 * mu * N0);
  EXPECT_NEAR(r.energy_per_cycle, j.energy_per_cycle, 1e-12 * mu * N0 * 1e-3);
  EXPECT_EQ(r.stick_fraction, j.stick_fraction);
}

// Central differences of the force coefficients, column by column.
Eigen::MatrixXd central_differences(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                                    const Eigen::VectorXd& x, double h) {
  Eigen::MatrixXd J(f(x).size(), x.size());
  for (int c = 0; c < x.size(); ++c) {
    const Eigen::VectorXd e = h * Eigen::VectorXd::Unit(x.size(), c);
    J.col(c) = (f(x + e) - f(x - e)) / (2.0 * h);
  }
  return J;
}

// Source: Ceres-style check of an analytic Jacobian against central differences (STYLE.md (e)).
// Multi-harmonic motions (H = 3 .. 5, amplitudes ~1 mm against the 0.3 mm slip excursion) that
// stick and slip several times per period under a varying normal load, with and without lift-off.
// Step h = 1e-10 m = 1e-7 of the amplitudes. Between switches the march is smooth, so the
// truncation error is O(h^2) relative ~1e-14; round-off in the coefficients (~1e-16 * 100 N) over
// 2h gives ~1e-9 of the Jacobian's scale. A sample whose stick/slip/lift-off state flips inside
// +-h would break this (an O(1) jump), so the test asserts that every perturbed evaluation has
// the same per-sample states, i.e. that the points are away from switches. Asserted: 1e-6 of the
// largest Jacobian entry.
struct JacobianCase {
  const char* name;
  int directions, harmonics;
  Eigen::VectorXd w;
  bool lift_off;
};

void expect_jacobian_matches_differences(const JacobianCase& test) {
  SCOPED_TRACE(test.name);
  const HarmonicBasis b(test.harmonics, 512);
  const FrictionContact c = contact(test.directions);
  const ContactResponse r = friction_contact_response(c, b, test.w);
  ASSERT_TRUE(r.loop_closed);
  ASSERT_GT(r.stick_fraction, 0.02);
  ASSERT_GT(r.slip_fraction, 0.02);
  if (test.lift_off) {
    ASSERT_GT(r.lift_off_fraction, 0.02);
  } else {
    ASSERT_EQ(r.lift_off_fraction, 0.0);
  }
  bool same_states = true;
  const Eigen::MatrixXd fd = central_differences(
      [&](const Eigen::VectorXd& w) {
        const ContactResponse p = friction_contact_response(c, b, w);
        same_states = same_states && p.state == r.state;
        return p.coefficients;
      },
      test.w, 1e-10);
  ASSERT_TRUE(same_states) << "a perturbation moved a sample across a switch: choose other points";
  const double scale = max_abs(r.jacobian);
  EXPECT_LT(max_abs(r.jacobian - fd), 1e-6 * scale);
}

TEST(FrictionContact, AnalyticJacobianMatchesFiniteDifferences) {
  Eigen::VectorXd v3(7), u3(7);
  v3 << 2e-5, 1.5e-4, -5e-5, 4e-5, 3e-5, -2e-5, 1e-5;
  u3 << 3e-5, 8e-4, -2e-4, 2e-4, 3e-4, -1e-4, 6e-5;
  Eigen::VectorXd v4(9), u4(9), u4b(9);
  v4 << 1e-4, 8e-4, 2e-4, -1e-4, 1.5e-4, 5e-5, -6e-5, 3e-5, 2e-5;
  u4 << -4e-5, 5e-4, 6e-4, -2e-4, 1e-4, 1.2e-4, 2e-4, -5e-5, 4e-5;
  u4b << 1e-5, -3e-4, 7e-4, 2.5e-4, -1e-4, 6e-5, 1.5e-4, 8e-5, -3e-5;
  Eigen::VectorXd v5(11), u5(11), u5b(11);
  v5 << -3e-5, 1e-4, 1.2e-4, -6e-5, 2e-5, 3e-5, -2e-5, 1e-5, 2e-5, -1e-5, 5e-6;
  u5 << 2e-5, 9e-4, -1e-4, 1e-4, -2e-4, 1.5e-4, 5e-5, -4e-5, 6e-5, 3e-5, -2e-5;
  u5b << -1e-5, 2e-4, 8e-4, -1.5e-4, 1e-4, 5e-5, 1.2e-4, 3e-5, -4e-5, 2e-5, 2e-5;
  const JacobianCase cases[] = {
      {"2D, stick-slip, H = 3", 1, 3, stack(v3, u3), false},
      {"2D, lift-off, H = 4", 1, 4, stack(v4, u4), true},
      {"3D, stick-slip, H = 5", 2, 5, stack(v5, u5, u5b), false},
      {"3D, lift-off, H = 4", 2, 4, stack(v4, u4, u4b), true},
  };
  for (const JacobianCase& test : cases) expect_jacobian_matches_differences(test);
}

// Source: closed form derived here (the circular orbit of a 2D Jenkins slider; cf. Sanliturk &
// Ewins, J. Sound Vib. 193 (1996) 511-523, for circular and elliptical orbits).
//
//        u = X (cos t, sin t)          slider s, spring k_t from s to u, |T| = k_t |u - s|
//          .---.                       In steady slip |u - s| = a = mu N / k_t, and the slider
//        /   s  \  u                   moves along T (parallel to u - s). By symmetry s runs on a
//       |    o---+-->                  circle of radius r_s at the rate of u, so its velocity is
//        \  r_s /                      tangent to that circle: u - s is perpendicular to s's
//          '---'                       radius and X^2 = r_s^2 + a^2. Work of T on u = work on s
//                                      (T . dT / k_t integrates to 0): W = mu N 2 pi r_s.
//   W = 2 pi mu N sqrt(X^2 - (mu N / k_t)^2),  |T| = mu N throughout, for X > mu N / k_t.
//
// The sampled radial return (backward Euler, step D = 2 pi / n) has its own steady state: s_j
// lies on the chord from s_{j-1} to u_j at distance a from u_j, so the chord of angle D extended
// by a reaches the drive circle: X^2 = r^2 + a^2 + 2 a r sin(D/2); T_j is parallel to the chord
// s_{j-1} s_j, and the trapezoidal T . du = T . ds over consecutive chords turned by D gives
// W_n = n mu N 2 r sin(D/2) cos^2(D/2). Against W_n: round-off and loop closure only, 1e-10
// asserted. Against the continuous W the error is first order (the backward-Euler lag of the
// slider, not O(D^2)): expanding r and W_n,
//   W_n / W - 1 = -a D / (2 r_s) + (a^2 / (8 r_s^2) - 7 / 24) D^2 + O(D^3),
// so with the first-order term removed the remainder (0.28 D^2 here) is asserted below D^2 / 2.
TEST(FrictionContact, CircularOrbitDissipatesTheClosedFormEnergy) {
  const double F = mu * N0, a = F / kt, X = 3.0 * a;
  const double r_s = std::sqrt(X * X - a * a), exact = 2.0 * kPi * F * r_s;
  for (int n : {1024, 2048, 4096}) {
    SCOPED_TRACE(n);
    const HarmonicBasis b(1, n);
    const double D = 2.0 * kPi / n;
    const ContactResponse r = friction_contact_response(
        contact(2, 0.0), b, stack(Eigen::VectorXd::Zero(b.size()), cosine(b, X), sine(b, X)));
    ASSERT_TRUE(r.loop_closed);
    EXPECT_EQ(r.slip_fraction, 1.0);
    EXPECT_LT(max_abs(r.force.rightCols(2).rowwise().norm().array() - F), 1e-12 * F);
    const double r_n =
        -a * std::sin(D / 2) + std::sqrt(X * X - a * a * std::pow(std::cos(D / 2), 2));
    const double sampled = n * F * 2.0 * r_n * std::sin(D / 2) * std::pow(std::cos(D / 2), 2);
    EXPECT_NEAR(r.energy_per_cycle, sampled, 1e-10 * exact);
    const double leading = -a * D / (2.0 * r_s);
    EXPECT_NEAR((r.energy_per_cycle - exact) / exact, leading, 0.5 * D * D);
  }
}

// Source: the march's contraction rate (same geometry as above). Near the slip threshold the 2D
// slider forgets its start slowly: a perturbation of the leash angle decays by
// exp(-2 pi sqrt(X^2 - a^2) / a) per period, 0.41 for X = 1.01 a, so a 1e-12 closure needs ~40
// periods. With the default 16 the response must say the loop did not close (and how far it
// was); allowed 100 periods it closes. Counts and flags: exact checks.
TEST(FrictionContact, ALoopThatHasNotClosedIsReported) {
  const double a = mu * N0 / kt, X = 1.01 * a;
  const HarmonicBasis b(1, 512);
  const Eigen::VectorXd w = stack(Eigen::VectorXd::Zero(b.size()), cosine(b, X), sine(b, X));
  const ContactResponse unclosed = friction_contact_response(contact(2, 0.0), b, w);
  EXPECT_FALSE(unclosed.loop_closed);
  EXPECT_EQ(unclosed.periods_marched, 16);
  EXPECT_GT(unclosed.closure_error, 1e-12);
  const ContactResponse closed = friction_contact_response(contact(2, 0.0), b, w, {100, 1e-12});
  EXPECT_TRUE(closed.loop_closed);
  EXPECT_GT(closed.periods_marched, 16);
  EXPECT_LT(closed.periods_marched, 100);
  EXPECT_LE(closed.closure_error, 1e-12);
}

// Source: closed form (clipped_cosine above). The normal law alone, v = V cos theta with
// k_n V = 2 N_0 > N_0: the contact opens for |theta| > phi = arccos(-N_0 / (k_n V)) = 2 pi / 3.
// No tangential motion. The coefficients are those of N - N_0: a_0(N) - N_0 and a_1(N).
// Tolerance: the DFT is the trapezoidal rule, whose error for a function with a kink between
// samples is at most |jump of f'| D^2 / 8 per kink (D = 2 pi / n); two kinks of jump
// k_n V sin phi give |error(a_0)| <= k_n V D^2 / (8 pi) and |error(a_1)| <= k_n V D^2 / (4 pi):
// k_n V D^2 / 4 is asserted (1.2e-4 N at n = 4096), and the error at n = 512 must be larger.
// The lift-off share counts samples, so it is within 1 / n.
TEST(FrictionContact, NormalLoadWithLiftOffMatchesTheClippedCosine) {
  const double V = 2.0 * N0 / kn;
  const ClippedCosine exact = clipped_cosine(N0, kn * V);
  auto error = [&](int n) {
    const HarmonicBasis b(3, n);
    const ContactResponse r = friction_contact_response(
        contact(1), b, stack(cosine(b, V), Eigen::VectorXd::Zero(b.size())));
    EXPECT_NEAR(r.lift_off_fraction, exact.zero_share, 1.0 / n);
    EXPECT_EQ(max_abs(r.force.col(1)), 0.0);
    return std::max(std::abs(r.coefficients[0] + N0 - exact.a0),
                    std::abs(r.coefficients[HarmonicBasis::cos_index(1)] - exact.a1));
  };
  const double D = 2.0 * kPi / 4096;
  const double fine = error(4096);
  EXPECT_LT(fine, kn * V * D * D / 4.0);
  EXPECT_GT(error(512), fine);
}

// Source: closed form derived here along the lines of Yang, Chu & Menq, J. Sound Vib. 210 (1998)
// 461-481 (in-phase normal and tangential motion). With u = U x, v = V x, x = cos theta, the
// state is a function of x on its way down (theta in [0, pi]) and up. Limit L(x) = mu (N_0 +
// k_n V x), stick slope dT/dx = k_t U > mu k_n V (assumed: stick outruns the limit). Lift-off
// below x_c = -N_0 / (k_n V); x_lo = max(-1, x_c).
//   down from (1, L(1)): stick T = L(1) + k_t U (x - 1) until it meets -L at
//        x_1 = (k_t U - 2 mu N_0 - mu k_n V) / (k_t U + mu k_n V), then slip T = -L(x) to x_lo;
//   up from (x_lo, -L(x_lo)) (0 after lift-off): stick until it meets +L at
//        x_2 = (k_t U x_lo + L(x_lo) + mu N_0) / (k_t U - mu k_n V), then slip T = L(x) to 1.
// The loop in the (x, T) plane is the quadrilateral (x_lo, -L(x_lo)), (x_2, L(x_2)), (1, L(1)),
// (x_1, -L(x_1)) (a triangle with lift-off: x_2 = x_c), and W = U * its area.
// Tolerance: the sampled march switches from stick to slip at the first sample past x_1 or x_2,
// and trapezoidal integration cuts the kinks; each of the <= 4 kinks costs at most
// U (k_t U + mu k_n V) D^2 (D = 2 pi / n bounds the step in x), which is asserted.
double in_phase_energy(double U, double V) {
  auto L = [&](double x) { return mu * (N0 + kn * V * x); };
  const double x_lo = std::max(-1.0, -N0 / (kn * V));
  const double x1 = (kt * U - 2.0 * mu * N0 - mu * kn * V) / (kt * U + mu * kn * V);
  const double x2 = (kt * U * x_lo + L(x_lo) + mu * N0) / (kt * U - mu * kn * V);
  EXPECT_GT(kt * U, mu * kn * V);
  EXPECT_GT(x1, x_lo);
  EXPECT_LT(x2, 1.0);
  const double x[4] = {x_lo, x2, 1.0, x1};
  const double T[4] = {-L(x_lo), L(x2), L(1.0), -L(x1)};
  double twice_area = 0.0;  // shoelace
  for (int i = 0; i < 4; ++i) twice_area += x[i] * T[(i + 1) % 4] - x[(i + 1) % 4] * T[i];
  return U * 0.5 * std::abs(twice_area);
}

TEST(FrictionContact, InPhaseVariableNormalLoadDissipatesTheClosedFormEnergy) {
  const int n = 4096;
  const double D = 2.0 * kPi / n;
  const HarmonicBasis b(3, n);
  struct Motion {
    double U, V;
    bool lift_off;
  };
  for (const Motion& motion : {Motion{5e-4, 2e-4, false}, Motion{1e-3, 8e-4, true}}) {
    SCOPED_TRACE(motion.lift_off ? "with lift-off" : "without lift-off");
    const ContactResponse r =
        friction_contact_response(contact(1), b, stack(cosine(b, motion.V), cosine(b, motion.U)));
    ASSERT_TRUE(r.loop_closed);
    EXPECT_EQ(r.lift_off_fraction > 0.0, motion.lift_off);
    const double exact = in_phase_energy(motion.U, motion.V);
    const double bound = 4.0 * motion.U * (kt * motion.U + mu * kn * motion.V) * D * D;
    EXPECT_NEAR(r.energy_per_cycle, exact, bound);
  }
}

// Source: the law's limits. A friction limit no motion reaches (mu = 1e12) is the linear spring
// k_t (u - mean(u)) in each direction (stick everywhere, no dissipation): the stick march sums
// n increments, so round-off of ~n eps relative; 1e-11 of k_t |u| asserted. No friction (mu = 0)
// or no normal load (N_0 = 0, k_n = 0: open everywhere) transmits no tangential force at all.
TEST(FrictionContact, LimitsOfTheFrictionForce) {
  const HarmonicBasis b(3, 256);
  Eigen::VectorXd v(b.size()), u1(b.size()), u2(b.size());
  v << 1e-5, 1e-4, 0.0, 0.0, 5e-5, 0.0, 0.0;
  u1 << 2e-3, 1e-3, 0.0, 0.0, 4e-4, 0.0, 0.0;
  u2 << -1e-3, 0.0, 7e-4, 2e-4, 0.0, 0.0, -1e-4;
  const Eigen::VectorXd w = stack(v, u1, u2);
  const int m = b.size();
  FrictionContact c = contact(2);
  c.friction_coefficient = 1e12;
  const ContactResponse stuck = friction_contact_response(c, b, w);
  EXPECT_EQ(stuck.stick_fraction, 1.0);
  EXPECT_NEAR(stuck.energy_per_cycle, 0.0, 1e-11 * kt * 1e-3 * 1e-3);
  for (int d = 0; d < 2; ++d) {
    Eigen::VectorXd expected = kt * w.segment((1 + d) * m, m);
    expected[0] = 0.0;
    EXPECT_LT(max_abs(stuck.coefficients.segment((1 + d) * m, m) - expected), 1e-11 * kt * 1e-3);
    Eigen::MatrixXd stiffness = kt * Eigen::MatrixXd::Identity(m, m);
    stiffness(0, 0) = 0.0;  // the mean position follows a_0
    EXPECT_LT(max_abs(stuck.jacobian.block((1 + d) * m, (1 + d) * m, m, m) - stiffness),
              1e-11 * kt);
  }

  c.friction_coefficient = 0.0;
  const ContactResponse free = friction_contact_response(c, b, w);
  EXPECT_EQ(max_abs(free.force.rightCols(2)), 0.0);
  EXPECT_EQ(max_abs(free.jacobian.bottomRows(2 * m)), 0.0);
  EXPECT_EQ(free.energy_per_cycle, 0.0);

  const ContactResponse open = friction_contact_response({2, 0.0, kt, mu, 0.0}, b, w);
  EXPECT_EQ(open.lift_off_fraction, 1.0);
  EXPECT_EQ(max_abs(open.force), 0.0);
  EXPECT_EQ(max_abs(open.jacobian), 0.0);
}

// Source: STYLE.md (bad input is an InputError naming the key). Not numerical: exact checks.
template <typename Call>
std::string key_of(Call call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.key_path();
  }
  return "(no InputError)";
}

TEST(FrictionContact, InvalidInputNamesTheKey) {
  const HarmonicBasis b(2, 64);
  const Eigen::VectorXd w2 = Eigen::VectorXd::Zero(2 * b.size());
  auto response = [&](FrictionContact c, const Eigen::VectorXd& w) {
    return [c, w, &b] { (void)friction_contact_response(c, b, w); };
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(key_of(response({0, kn, kt, mu, N0}, w2)), "tangential_directions");
  EXPECT_EQ(key_of(response({3, kn, kt, mu, N0}, w2)), "tangential_directions");
  EXPECT_EQ(key_of(response({1, kn, 0.0, mu, N0}, w2)), "tangential_stiffness");
  EXPECT_EQ(key_of(response({1, kn, inf, mu, N0}, w2)), "tangential_stiffness");
  EXPECT_EQ(key_of(response({1, -1.0, kt, mu, N0}, w2)), "normal_stiffness");
  EXPECT_EQ(key_of(response({1, kn, kt, -0.1, N0}, w2)), "friction_coefficient");
  EXPECT_EQ(key_of(response({1, kn, kt, nan, N0}, w2)), "friction_coefficient");
  EXPECT_EQ(key_of(response({1, kn, kt, mu, -1.0}, w2)), "normal_preload");
  EXPECT_EQ(key_of(response(contact(2), w2)), "w");  // 3D needs 3 blocks
  EXPECT_EQ(key_of([&] {
              (void)friction_contact_response(contact(1), b, w2, {0, 1e-12});
            }),
            "max_periods");
  EXPECT_EQ(key_of([&] {
              (void)friction_contact_response(contact(1), b, w2, {16, -1.0});
            }),
            "closure_tolerance");
  EXPECT_EQ(key_of([] { (void)friction_contact_force({0, 1, 2}, contact(1)); }), "coordinates");
  EXPECT_EQ(key_of([] { (void)friction_contact_force({0, -1}, contact(1)); }), "coordinates[1]");
  EXPECT_EQ(key_of([] { (void)friction_contact_force({2, 1, 2}, contact(2)); }), "coordinates[2]");
  EXPECT_EQ(key_of([] { (void)unilateral_spring(-1, kn, 0.0); }), "dof");
  EXPECT_EQ(key_of([] { (void)unilateral_spring(0, 0.0, 0.0); }), "stiffness");
  EXPECT_EQ(key_of([&] { (void)unilateral_spring(0, kn, nan); }), "gap");
  EXPECT_EQ(key_of([&] { (void)unilateral_spring_response(kn, 0.0, b, w2); }), "q");
  // An X too short for the contact's DOFs is found when the force is evaluated.
  const NonlinearForce force = friction_contact_force({0, 4}, contact(1));
  Eigen::VectorXd F = Eigen::VectorXd::Zero(2 * b.size());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2 * b.size(), 2 * b.size());
  EXPECT_EQ(key_of([&] { force(b, w2, F, J); }), "coordinates");
}

// Source: closed form (clipped_cosine: k max(V cos theta - g, 0) is max(p + q cos theta, 0) with
// p = -k g, q = k V), for an open gap (g > 0) and a preloaded contact (g < 0). Tolerance as for
// the normal load above: k V D^2 / 4. Jacobian: the force is piecewise linear in the samples, so
// central differences are exact up to round-off (~1e-16 * k V / h relative to k: 1e-8 for
// h = 1e-8 V) while no sample crosses the gap; 1e-6 of k asserted.
TEST(UnilateralSpring, ClippedCosineAndJacobian) {
  const int n = 4096;
  const double D = 2.0 * kPi / n;
  const HarmonicBasis b(3, n);
  const double V = 1e-3;
  for (double gap : {4e-4, -3e-4}) {
    SCOPED_TRACE(gap);
    const ClippedCosine exact = clipped_cosine(-kn * gap, kn * V);
    const UnilateralResponse r = unilateral_spring_response(kn, gap, b, cosine(b, V));
    EXPECT_NEAR(r.coefficients[0], exact.a0, kn * V * D * D / 4.0);
    EXPECT_NEAR(r.coefficients[HarmonicBasis::cos_index(1)], exact.a1, kn * V * D * D / 4.0);
    EXPECT_NEAR(r.contact_fraction, 1.0 - exact.zero_share, 1.0 / n);
  }
  const HarmonicBasis coarse(3, 256);
  Eigen::VectorXd q(coarse.size());
  q << 1e-4, 8e-4, 2e-4, -1e-4, 1.5e-4, 5e-5, -6e-5;
  const double gap = 3e-4;
  const Eigen::MatrixXd fd = central_differences(
      [&](const Eigen::VectorXd& x) {
        return unilateral_spring_response(kn, gap, coarse, x).coefficients;
      },
      q, 1e-8 * V);
  const UnilateralResponse r = unilateral_spring_response(kn, gap, coarse, q);
  ASSERT_GT(r.contact_fraction, 0.1);
  ASSERT_LT(r.contact_fraction, 0.9);
  EXPECT_LT(max_abs(r.jacobian - fd), 1e-6 * kn);
}

// Source: harmonic_balance.hpp (the DOF-major layout) and the element's own response. The
// adapters inside a HarmonicBalance: a 3D contact on DOFs (3, 0, 2) and a gap spring on DOF 1 of
// a 4-DOF system. The residual's nonlinear part must equal the element's coefficients placed on
// those DOFs, and the assembled Jacobian dR/dX must match central differences of the residual
// (same step and argument as the element test: 1e-6 of the largest entry).
TEST(FrictionContact, AdaptersAssembleIntoTheHarmonicBalance) {
  const HarmonicBasis b(3, 256);
  const int s = b.size(), dofs = 4;
  Eigen::VectorXd v(s), u1(s), u2(s), q(s);
  v << -3e-5, 1e-4, 1.2e-4, -6e-5, 2e-5, 3e-5, -2e-5;
  u1 << 2e-5, 9e-4, -1e-4, 1e-4, -2e-4, 1.5e-4, 5e-5;
  u2 << -1e-5, 2e-4, 8e-4, -1.5e-4, 1e-4, 5e-5, 1.2e-4;
  q << 1e-4, 8e-4, 2e-4, -1e-4, 1.5e-4, 5e-5, -6e-5;
  Eigen::VectorXd X(dofs * s);
  X << u1, q, u2, v;  // DOF 0: u_1, DOF 1: gap spring, DOF 2: u_2, DOF 3: normal
  const FrictionContact c = contact(2);
  const double gap = 3e-4;
  const Eigen::MatrixXd K = 1e4 * Eigen::MatrixXd::Identity(dofs, dofs);
  const HarmonicBalance hb(Eigen::MatrixXd::Identity(dofs, dofs),
                           1e-2 * Eigen::MatrixXd::Identity(dofs, dofs), K, b,
                           {friction_contact_force({3, 0, 2}, c), unilateral_spring(1, kn, gap)},
                           Eigen::VectorXd::Zero(dofs * s));
  const double omega = 50.0;
  Eigen::MatrixXd J;
  const Eigen::VectorXd R = hb.residual(X, omega, &J);
  Eigen::MatrixXd J_linear;
  const Eigen::VectorXd linear = HarmonicBalance(Eigen::MatrixXd::Identity(dofs, dofs),
                                                 1e-2 * Eigen::MatrixXd::Identity(dofs, dofs), K, b,
                                                 {}, Eigen::VectorXd::Zero(dofs * s))
                                     .residual(X, omega, &J_linear);
  const ContactResponse element = friction_contact_response(c, b, stack(v, u1, u2));
  const UnilateralResponse spring = unilateral_spring_response(kn, gap, b, q);
  Eigen::VectorXd expected(dofs * s);
  expected << element.coefficients.segment(s, s), spring.coefficients,
      element.coefficients.segment(2 * s, s), element.coefficients.head(s);
  EXPECT_LT(max_abs(R - linear - expected), 1e-12 * max_abs(expected));
  // The contact's Jacobian block (tangential u_1 row, normal column) lands on (DOF 0, DOF 3).
  EXPECT_LT(max_abs((J - J_linear).block(0, 3 * s, s, s) - element.jacobian.block(s, 0, s, s)),
            1e-12 * max_abs(element.jacobian));
  const Eigen::MatrixXd fd = central_differences(
      [&](const Eigen::VectorXd& x) { return hb.residual(x, omega); }, X, 1e-10);
  EXPECT_LT(max_abs(J - fd), 1e-6 * max_abs(J));
}

}  // namespace
}  // namespace geardyn::hbm
