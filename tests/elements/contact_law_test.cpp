// Contact laws and the gap contact (elements/contact_law.hpp, elements/gap_contact.hpp;
// docs/theory.md §16.2): analytic tangents against central differences, single-DOF impacts
// against closed forms, the ADAMS IMPACT function's damping and STEP, the dead zone and
// symmetry of end play, and bad parameters.
#include "geardyn/elements/contact_law.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "geardyn/elements/gap_contact.hpp"

namespace {

using namespace geardyn::elements;
using geardyn::InputError;

// ---- tangents -------------------------------------------------------------------------------

struct Point {
  double delta, rate;
};

// Central differences with steps 1e-6 of the penetration and 1e-4 of max(|rate|, 1e-3 m/s): the
// truncation error (h^2/6) F'''/F' is < 1e-8 relative for these smooth laws and round-off
// ~1e-16 F / (h F') < 1e-7 even where the spring force dwarfs the damping tangent, so 1e-6 bounds
// both while a wrong tangent (an error above 1e-6 of the entry) fails. Points stay away from the
// kinks (delta = 0, delta = d of IMPACT, the regularisation scales, the clipping F = 0).
void expect_tangents(const std::shared_ptr<const ContactLaw>& law,
                     const std::vector<Point>& points) {
  const double gap = 2e-4;
  const GapContact stop = GapContact::stop("t", gap, law);
  const GapContact lower = GapContact(std::string("t"), std::nullopt, GapContact::Side{-gap, law});
  for (const Point& p : points) {
    Eigen::VectorXd u(1), v(1);
    const double h_u = 1e-6 * p.delta, h_v = 1e-4 * std::max(std::abs(p.rate), 1e-3);
    u << gap + p.delta;
    v << p.rate;
    const TangentCheck upper = check_tangents(stop, u, v, 0.0, h_u, h_v);
    EXPECT_LT(upper.stiffness_error, 1e-6) << law->describe() << " at " << p.delta;
    EXPECT_LT(upper.damping_error, 1e-6) << law->describe() << " at " << p.delta;
    const TangentCheck low = check_tangents(lower, -u, -v, 0.0, h_u, h_v);
    EXPECT_LT(low.stiffness_error, 1e-6) << law->describe() << " lower side";
    EXPECT_LT(low.damping_error, 1e-6) << law->describe() << " lower side";
  }
}

// Points on both sides of the approach/separation, including separation rates large enough to
// make the damped laws tensile (clipped variants: zero force and tangents there).
const std::vector<Point> kPoints = {{1e-6, 0.3},   {3e-5, -0.15}, {2e-4, 1.5},
                                    {5e-4, -0.05}, {1e-3, -3.0},  {2e-5, -4.0}};

TEST(ContactLaw, TangentsOfEveryLawMatchCentralDifferences) {
  for (Tension t : {Tension::allowed, Tension::clipped}) {
    expect_tangents(std::make_shared<LinearContactLaw>(LinearLawParameters{2e7, 3e3, t}), kPoints);
    expect_tangents(std::make_shared<HertzContactLaw>(HertzLawParameters{5e9, 1.5, 0.8, t}),
                    kPoints);
    expect_tangents(std::make_shared<HertzContactLaw>(HertzLawParameters{5e9, 10.0 / 9.0, 0.0, t}),
                    kPoints);
    expect_tangents(std::make_shared<ImpactContactLaw>(ImpactLawParameters{1e9, 2.2, 4e3, 1e-4, t}),
                    kPoints);
    expect_tangents(std::make_shared<ImpactContactLaw>(ImpactLawParameters{1e7, 1.0, 4e3, 1e-4, t}),
                    kPoints);
    // Penalty law with sub-linear exponents; the regularisation scales (1e-7 m, 1e-2 m/s) are
    // between the test points.
    expect_tangents(std::make_shared<PenaltyContactLaw>(
                        PenaltyLawParameters{1e8, 1.3, 2e4, 0.7, 0.5, 1e-7, 1e-2, t}),
                    kPoints);
    expect_tangents(std::make_shared<PenaltyContactLaw>(
                        PenaltyLawParameters{1e8, 0.8, 2e6, 1.6, 1.2, 1e-7, 1e-2, t}),
                    kPoints);
    // Inside the regularisation zones (delta < delta_r, |rate| < v_r): the secant branch.
    expect_tangents(std::make_shared<PenaltyContactLaw>(
                        PenaltyLawParameters{1e8, 0.5, 2e4, 0.0, 0.3, 1e-5, 1e-2, t}),
                    {{3e-6, 4e-3}, {6e-6, -5e-3}, {5e-4, 2e-3}, {3e-6, 0.5}});
  }
}

TEST(ContactLaw, OpenContactGivesNothingAndClippingRemovesTension) {
  const LinearContactLaw law({1e6, 1e3, Tension::allowed});
  const LinearContactLaw clipped({1e6, 1e3, Tension::clipped});
  for (double delta : {0.0, -1e-3}) {
    const ContactForce f = law.evaluate(delta, 1.0);
    EXPECT_EQ(f.force, 0.0);
    EXPECT_EQ(f.d_penetration, 0.0);
    EXPECT_EQ(f.d_rate, 0.0);
  }
  // k delta + c rate = 1e6 * 1e-4 - 1e3 * 1.0 = -900 N: tensile unless clipped.
  EXPECT_NEAR(law.evaluate(1e-4, -1.0).force, -900.0, 1e-9);
  const ContactForce c = clipped.evaluate(1e-4, -1.0);
  EXPECT_EQ(c.force, 0.0);
  EXPECT_EQ(c.d_penetration, 0.0);
  EXPECT_EQ(c.d_rate, 0.0);
  EXPECT_NEAR(clipped.evaluate(1e-4, 0.05).force, 150.0, 1e-9);
}

// ---- single-DOF impacts ---------------------------------------------------------------------

// A mass m on the stop (end i ground, end j the mass, u = x): m x'' + f(x, x') = 0, starting
// at contact closure x = 0 with x' = v0 > 0. The contact phase is integrated with the classical
// fourth-order Runge-Kutta method at a fixed step; the ends of the phase (x' = 0: maximum
// penetration; x = 0: separation) are located by regula falsi (Illinois) on the length of the
// last step. The closed branch of the law is continued across x = 0 by its first-order Taylor
// expansion from the closed side, using the element's own tangent, so the stages of the first
// and last steps see a smooth right-hand side: exact for the linear law, and equal to the open
// branch (zero) for the Hertz and IMPACT laws, whose force and stiffness vanish at x = 0.
struct State {
  double x, v;
};

struct Impact {
  double max_penetration = 0.0, peak_force = 0.0, contact_time = 0.0, exit_velocity = 0.0;
};

class Sdof {
 public:
  Sdof(const ForceElement& element, double mass) : element_(element), mass_(mass) {}

  double force(double x, double v) const {
    const double eps = std::numeric_limits<double>::min();
    Eigen::VectorXd u(1), w(1);
    u << std::max(x, eps);
    w << v;
    ElementForce out;
    element_.evaluate(u, w, 0.0, out);
    return out.force(0) + (x < eps ? out.stiffness(0, 0) * (x - eps) : 0.0);
  }

  State step(State s, double h) const {
    auto a = [&](double x, double v) { return -force(x, v) / mass_; };
    const double k1x = s.v, k1v = a(s.x, s.v);
    const double k2x = s.v + 0.5 * h * k1v, k2v = a(s.x + 0.5 * h * k1x, s.v + 0.5 * h * k1v);
    const double k3x = s.v + 0.5 * h * k2v, k3v = a(s.x + 0.5 * h * k2x, s.v + 0.5 * h * k2v);
    const double k4x = s.v + h * k3v, k4v = a(s.x + h * k3x, s.v + h * k3v);
    return {s.x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
            s.v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)};
  }

  // Steps from s until the component (x if `on_x`, else v) turns <= 0; returns the time to
  // that event and the state there.
  double advance(State& s, double h, bool on_x) const {
    auto g = [&](const State& z) { return on_x ? z.x : z.v; };
    double t = 0.0;
    for (int i = 0; i < 10000000; ++i) {
      const State next = step(s, h);
      if (g(next) > 0.0) {
        s = next;
        t += h;
        continue;
      }
      double a = 0.0, b = h, ga = g(s), gb = g(next);
      int side = 0;
      for (int k = 0; k < 200 && b - a > 1e-15 * h; ++k) {
        const double c = (a * gb - b * ga) / (gb - ga);
        const double gc = g(step(s, c));
        if (gc > 0.0) {
          a = c;
          ga = gc;
          if (side == 1) gb *= 0.5;
          side = 1;
        } else {
          b = c;
          gb = gc;
          if (side == -1) ga *= 0.5;
          side = -1;
        }
        if (gc == 0.0) a = b = c;
      }
      const double tau = 0.5 * (a + b);
      s = step(s, tau);
      return t + tau;
    }
    ADD_FAILURE() << "no event";
    return t;
  }

  Impact impact(double v0, double h) const {
    State s{0.0, v0};
    Impact r;
    const double t1 = advance(s, h, false);
    r.max_penetration = s.x;
    r.peak_force = force(s.x, 0.0);
    r.contact_time = t1 + advance(s, h, true);
    r.exit_velocity = s.v;
    return r;
  }

 private:
  const ForceElement& element_;
  double mass_;
};

// Kelvin-Voigt contact, unclipped (the tension at the end of the contact is part of the closed
// form): m d'' + c d' + k d = 0 from d = 0, d' = v0 gives d = v0/omega_d e^(-zeta omega t)
// sin(omega_d t), back at d = 0 after t_c = pi / omega_d with velocity -e v0,
// e = exp(-zeta pi / sqrt(1 - zeta^2)) (W. Goldsmith, Impact, 1960; any vibration text).
// Step h = t_c / 500: RK4's global error ~ (omega h)^4 ~ 2e-10 relative; the check below that
// the result with h/2 differs by < 1e-9 confirms it, and the tolerance 1e-8 bounds it.
TEST(ContactImpact, KelvinVoigtRestitutionAndContactTimeEqualClosedForm) {
  const double m = 2.0, k = 5e6, v0 = 0.7;
  for (double zeta : {0.0, 0.05, 0.2, 0.5}) {
    const double omega = std::sqrt(k / m), c = 2.0 * zeta * std::sqrt(k * m);
    const double omega_d = omega * std::sqrt(1.0 - zeta * zeta);
    const double t_c = std::numbers::pi / omega_d;
    const double e = std::exp(-zeta * std::numbers::pi / std::sqrt(1.0 - zeta * zeta));
    const GapContact stop = GapContact::stop(
        "stop", 0.0, std::make_shared<LinearContactLaw>(LinearLawParameters{k, c}));
    const Sdof sdof(stop, m);
    const Impact r = sdof.impact(v0, t_c / 500.0);
    const Impact r2 = sdof.impact(v0, t_c / 1000.0);
    EXPECT_LT(std::abs(r.exit_velocity - r2.exit_velocity), 1e-9 * v0);
    EXPECT_LT(std::abs(r.contact_time - r2.contact_time), 1e-9 * t_c);
    EXPECT_NEAR(-r.exit_velocity / v0, e, 1e-8) << "zeta " << zeta;
    EXPECT_NEAR(r.contact_time / t_c, 1.0, 1e-8) << "zeta " << zeta;
  }
}

// The integral t_c = 2 (delta_m / v0) int_0^1 dx / sqrt(1 - x^(5/2)) of the Hertz impact; the
// integral is (2/5) B(2/5, 1/2) = (2/5) Gamma(2/5) Gamma(1/2) / Gamma(9/10) (substitute
// y = x^(5/2)), so the constant is (4/5) sqrt(pi) Gamma(2/5) / Gamma(9/10) = 2.9432...
double hertz_duration_constant() {
  return 0.8 * std::sqrt(std::numbers::pi) * std::tgamma(0.4) / std::tgamma(0.9);
}

// Hertz sphere on a half-space (K.L. Johnson, Contact Mechanics, 1985, §11.4): energy
// (1/2) m v0^2 = (2/5) K delta_m^(5/2), K = (4/3) E* sqrt(R), gives
// delta_m = (15 m v0^2 / (16 E* sqrt(R)))^(2/5), peak force K delta_m^(3/2), and duration
// 2.94 delta_m / v0 (the constant derived above; Johnson prints 2.94). Steel ball R = 10 mm on a
// steel block (E = 210 GPa, nu = 0.3), v0 = 1 m/s. Step t_c / 2000: RK4's global error, with
// the first step's t^(7/2) term, is ~3e-10 relative (the h/2 run differs by < 1e-9); tolerance
// 1e-8.
TEST(ContactImpact, HertzSphereOnPlaneMatchesJohnson) {
  const double radius = 0.01, e_mod = 210e9, nu = 0.3, rho = 7850.0, v0 = 1.0;
  const double e_star = e_mod / (2.0 * (1.0 - nu * nu));
  const double mass = rho * 4.0 / 3.0 * std::numbers::pi * std::pow(radius, 3);
  const double k = 4.0 / 3.0 * e_star * std::sqrt(radius);
  const double delta_m = std::pow(15.0 * mass * v0 * v0 / (16.0 * e_star * std::sqrt(radius)), 0.4);
  const double f_max = k * std::pow(delta_m, 1.5);
  const double t_c = hertz_duration_constant() * delta_m / v0;
  EXPECT_NEAR(hertz_duration_constant(), 2.94, 0.005);  // Johnson's printed 3 digits

  const GapContact stop =
      GapContact::stop("ball", 0.0, std::make_shared<HertzContactLaw>(HertzLawParameters{k, 1.5}));
  const Sdof sdof(stop, mass);
  const Impact r = sdof.impact(v0, t_c / 2000.0);
  const Impact r2 = sdof.impact(v0, t_c / 4000.0);
  EXPECT_LT(std::abs(r.contact_time - r2.contact_time), 1e-9 * t_c);
  EXPECT_NEAR(r.max_penetration / delta_m, 1.0, 1e-8);
  EXPECT_NEAR(r.peak_force / f_max, 1.0, 1e-8);
  EXPECT_NEAR(r.contact_time / t_c, 1.0, 1e-8);
  EXPECT_NEAR(-r.exit_velocity / v0, 1.0, 1e-8);  // undamped: elastic rebound
}

// Hunt-Crossley damping (K.H. Hunt, F.R.E. Crossley, "Coefficient of restitution interpreted as
// damping in vibroimpact", 1975): the energy lost on the undamped path,
// 2 int_0^delta_m chi k delta^n delta_dot d delta with delta_dot = v0 sqrt(1 -
// (delta/delta_m)^(n+1)), is (4/3) chi v0 of the kinetic energy for any n, so 1 - e = (2/3) chi v0
// + O((chi v0)^2) -- the chi ~ 3 (1 - e) / (2 v_i) of docs/theory.md §16.2. Checked as an
// asymptotic statement: the relative deviation r = (1 - e) / ((2/3) chi v0) - 1 is below chi v0 and
// halves (0.4 ... 0.6) when chi halves. The RK4 error (step t_c / 2000, ~1e-10 on e) is 1e-6 of the
// smallest 1 - e.
TEST(ContactImpact, HuntCrossleyRestitutionToFirstOrder) {
  const double m = 0.05, v0 = 1.0;
  for (double n : {1.5, 10.0 / 9.0}) {
    std::vector<double> deviation;
    for (double chi_v : {4e-3, 2e-3, 1e-3}) {
      const double k = 1e9;
      const GapContact stop = GapContact::stop(
          "hc", 0.0, std::make_shared<HertzContactLaw>(HertzLawParameters{k, n, chi_v / v0}));
      const double delta_m = std::pow((n + 1.0) * 0.5 * m * v0 * v0 / k, 1.0 / (n + 1.0));
      const Impact r = Sdof(stop, m).impact(v0, 3.0 * delta_m / v0 / 2000.0);
      const double e = -r.exit_velocity / v0;
      deviation.push_back((1.0 - e) / (2.0 / 3.0 * chi_v) - 1.0);
      EXPECT_LT(std::abs(deviation.back()), chi_v) << "n " << n;
    }
    for (std::size_t i = 1; i < deviation.size(); ++i) {
      EXPECT_GT(deviation[i] / deviation[i - 1], 0.4) << "n " << n;
      EXPECT_LT(deviation[i] / deviation[i - 1], 0.6) << "n " << n;
    }
  }
}

// ADAMS IMPACT (MSC ADAMS/Solver function reference: IMPACT, STEP), k = 1e8 N/m^1.5, e = 1.5,
// d = 1e-4 m (below the undamped maximum penetration, 4e-4 m), m = 1 kg, v0 = 0.5 m/s. Without
// damping the rebound is elastic (restitution 1: the energy is conserved), within the RK4 error
// (step t_c / 2000: 1e-10 observed; tolerance 1e-8). With damping the restitution decreases
// strictly as c_max grows (each step of c_max changes it by far more than the 1e-8 error).
TEST(ContactImpact, ImpactLawConservesEnergyWithoutDampingAndLosesMoreWithMore) {
  const double m = 1.0, v0 = 0.5;
  std::vector<double> restitution;
  for (double c_max : {0.0, 20.0, 100.0, 500.0, 2000.0}) {
    const GapContact stop = GapContact::stop(
        "tooth", 0.0,
        std::make_shared<ImpactContactLaw>(ImpactLawParameters{1e8, 1.5, c_max, 1e-4}));
    const Sdof sdof(stop, m);
    // Undamped duration 2.94 delta_m / v0 with delta_m = 4.0e-4 m: ~2.4e-3 s.
    const Impact r = sdof.impact(v0, 2.4e-3 / 2000.0);
    restitution.push_back(-r.exit_velocity / v0);
  }
  EXPECT_NEAR(restitution[0], 1.0, 1e-8);
  for (std::size_t i = 1; i < restitution.size(); ++i)
    EXPECT_LT(restitution[i], restitution[i - 1] - 1e-4) << "c_max step " << i;
  EXPECT_GT(restitution.back(), 0.0);
}

// The cubic STEP is C1: values h0, h1 at x0, x1 and zero slope there from both sides (the
// one-sided difference quotients vanish like eps: |STEP(x0 + eps) - h0| <= 3 |h1 - h0|
// (eps / (x1 - x0))^2 at x0 + eps); IMPACT's stiffness tangent is therefore continuous at delta =
// d.
TEST(ContactLaw, CubicStepIsC1AtBothEnds) {
  const double x0 = 0.0, x1 = 1e-4, h0 = 0.0, h1 = 4e3;
  EXPECT_EQ(cubic_step(x0, x0, h0, x1, h1), h0);
  EXPECT_EQ(cubic_step(x1, x0, h0, x1, h1), h1);
  EXPECT_NEAR(cubic_step(0.5 * x1, x0, h0, x1, h1), 0.5 * (h0 + h1), 1e-9);
  for (double eps : {1e-3, 1e-4}) {
    const double e = eps * (x1 - x0);
    const double bound = 3.0 * h1 * eps / x1 * 1.01 + 1e-15 * h1 / e;  // + round-off of h1
    EXPECT_LT(std::abs(cubic_step(x0 + e, x0, h0, x1, h1) - h0) / e, bound);
    EXPECT_LT(std::abs(cubic_step(x1 - e, x0, h0, x1, h1) - h1) / e, bound);
    EXPECT_LT(std::abs(cubic_step_derivative(x0 + e, x0, h0, x1, h1)), 2.0 * bound);
    EXPECT_LT(std::abs(cubic_step_derivative(x1 - e, x0, h0, x1, h1)), 2.0 * bound);
    EXPECT_GT(std::abs(cubic_step(x0 + e, x0, h0, x1, h1) - h0) / e, 0.0);
  }
  EXPECT_NEAR(cubic_step_derivative(0.5 * x1, x0, h0, x1, h1), 1.5 * h1 / x1, 1e-6 * h1 / x1);
  const ImpactContactLaw law({1e8, 1.5, h1, x1});
  const double below = law.evaluate(x1 * (1.0 - 1e-9), 0.3).d_penetration;
  const double above = law.evaluate(x1 * (1.0 + 1e-9), 0.3).d_penetration;
  EXPECT_NEAR(below, above, 1e-6 * std::abs(above));
}

// ---- the gap element ------------------------------------------------------------------------

TEST(GapContact, DeadZoneIsForceFreeAndSidesAreSymmetric) {
  auto law = std::make_shared<ImpactContactLaw>(ImpactLawParameters{1e9, 1.5, 300.0, 5e-5});
  const double b = 1e-4;
  const GapContact play = GapContact::end_play("rattle", b, law, law);
  ElementForce f, g;
  Eigen::VectorXd u(1), v(1);
  for (double x : {-b, -0.5 * b, 0.0, 0.999 * b, b}) {
    u << x;
    v << 0.4;
    play.evaluate(u, v, 0.0, f);
    EXPECT_EQ(f.force(0), 0.0) << x;
    EXPECT_EQ(f.stiffness(0, 0), 0.0) << x;
    EXPECT_EQ(f.damping(0, 0), 0.0) << x;
  }
  for (double x : {1.3e-4, 1.6e-4, 3e-4}) {
    for (double w : {-0.5, 0.0, 0.8}) {
      u << x;
      v << w;
      play.evaluate(u, v, 0.0, f);
      play.evaluate(-u, -v, 0.0, g);
      EXPECT_GT(std::abs(f.force(0)), 0.0);
      EXPECT_EQ(f.force(0), -g.force(0));
      EXPECT_EQ(f.stiffness(0, 0), g.stiffness(0, 0));
      EXPECT_EQ(f.damping(0, 0), g.damping(0, 0));
    }
  }
  // A one-sided stop is force-free on the open side however far it goes.
  const GapContact stop = GapContact::stop("stop", b, law);
  u << -1.0;
  v << -3.0;
  stop.evaluate(u, v, 0.0, f);
  EXPECT_EQ(f.force(0), 0.0);
  EXPECT_NE(play.describe().find("contact 'rattle' (two-sided"), std::string::npos);
  EXPECT_NE(stop.describe().find("contact 'stop' (stop at u > 0.0001 m: IMPACT"),
            std::string::npos);
}

// ---- bad parameters -------------------------------------------------------------------------

template <class F>
void expect_input_error(F make, const std::string& key) {
  try {
    make();
    ADD_FAILURE() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), key);
    EXPECT_EQ(e.where().line, 12);
  }
}

LawSource source(const std::string& key_path) {
  LawSource s;
  s.location.file = "model.toml";
  s.location.line = 12;
  s.key_path = key_path;
  return s;
}

TEST(ContactLaw, BadParametersNameTheirKey) {
  const LawSource src = source("contacts[1].law");
  expect_input_error([&] { LinearContactLaw({0.0, 1.0}, src); }, "contacts[1].law.stiffness");
  expect_input_error([&] { LinearContactLaw({1e6, -1.0}, src); }, "contacts[1].law.damping");
  expect_input_error([&] { HertzContactLaw({1e9, 0.9}, src); }, "contacts[1].law.exponent");
  expect_input_error([&] { HertzContactLaw({1e9, 1.5, -0.1}, src); }, "contacts[1].law.damping");
  expect_input_error(
      [&] {
        ImpactContactLaw({1e9, 1.5, 10.0, 0.0}, src);
      },
      "contacts[1].law.penetration_depth");
  expect_input_error(
      [&] {
        ImpactContactLaw({-1e9, 1.5, 10.0, 1e-4}, src);
      },
      "contacts[1].law.stiffness");
  expect_input_error(
      [&] {
        ImpactContactLaw({1e9, std::numeric_limits<double>::quiet_NaN(), 10.0, 1e-4}, src);
      },
      "contacts[1].law.exponent");
  expect_input_error(
      [&] {
        PenaltyContactLaw({1e9, 1.5, 1.0, -0.5, 1.0}, src);
      },
      "contacts[1].law.rate_exponent");
  expect_input_error(
      [&] {
        PenaltyContactLaw({1e9, 1.5, 1.0, 1.0, 1.0, 0.0}, src);
      },
      "contacts[1].law.penetration_regularisation");
  const LawSource gap_src = source("contacts[1]");
  auto law = std::make_shared<LinearContactLaw>(LinearLawParameters{1e6, 0.0});
  expect_input_error([&] { GapContact::end_play("p", -1e-4, law, law, gap_src); },
                     "contacts[1].backlash");
  expect_input_error([&] { GapContact::stop("s", 1e-4, nullptr, gap_src); }, "contacts[1].law");
  expect_input_error(
      [&] {
        GapContact("p", GapContact::Side{-1e-4, law}, GapContact::Side{1e-4, law}, gap_src);
      },
      "contacts[1].gap");
}

}  // namespace
