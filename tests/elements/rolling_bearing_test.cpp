// The rolling-element bearing element (elements/rolling_bearing.hpp, docs/theory.md §16.5)
// against closed forms:
//   * the static load-deflection of a radial ball bearing, F_r = Z K_n delta_max^n J_r(epsilon),
//     with Sjovall's radial integral J_r (T.A. Harris, "Rolling Bearing Analysis", 4th ed., 2001:
//     J_r(0.5) = 0.2288 for point contact) and Stribeck's Q_max = 4.37 F_r / Z (R. Stribeck,
//     "Kugellager fur beliebige Belastungen", Z. VDI 45, 1901);
//   * the discrete sum over Z elements vs that integral, bounded through the Poisson summation
//     formula with the Fourier coefficients of cos^nu in closed form (Gradshteyn & Ryzhik, "Table
//     of Integrals, Series, and Products", 7th ed. 2007, 3.631.9);
//   * the stiffness variation at the ball-pass frequency (period 2 pi / Z in the cage angle) and
//     its amplitude from the same Fourier coefficients;
//   * the kinematic frequencies of a 6205 ball bearing (Case Western Reserve University Bearing
//     Data Center, bearing specifications, 6205-2RS JEM SKF).
#include "geardyn/elements/rolling_bearing.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

namespace {

using namespace geardyn::elements;
using geardyn::InputError;
constexpr double kPi = std::numbers::pi;

RollingBearingParams ball_bearing(int z, double clearance = 0.0) {
  RollingBearingParams p;
  p.elements = z;
  p.stiffness_constant = 1.0e10;  // N/m^1.5, a 10 mm steel ball between grooves (Harris ch. 6)
  p.exponent = 1.5;
  p.radial_clearance = clearance;
  p.pitch_diameter = 0.05;
  p.element_diameter = 0.008;
  return p;
}

// Fourier coefficient c_m = (1/2 pi) int_{-pi/2}^{pi/2} cos^nu(psi) cos(m psi) d psi of the
// clipped cosine power cos_+^nu (Gradshteyn & Ryzhik 3.631.9):
//   c_m = Gamma(nu + 1) / (2^(nu + 1) Gamma(1 + (nu + m)/2) Gamma(1 + (nu - m)/2)).
double clipped_cos_coefficient(double nu, int m) {
  return std::tgamma(nu + 1.0) / (std::pow(2.0, nu + 1.0) * std::tgamma(1.0 + 0.5 * (nu + m)) *
                                  std::tgamma(1.0 + 0.5 * (nu - m)));
}

// |c_m| through log-Gamma, for the large m of the Poisson tails (Gamma overflows past 171).
double clipped_cos_magnitude(double nu, int m) {
  return std::exp(std::lgamma(nu + 1.0) - (nu + 1.0) * std::log(2.0) -
                  std::lgamma(1.0 + 0.5 * (nu + m)) - std::lgamma(1.0 + 0.5 * (nu - m)));
}

// 2 sum_{j>=1} |c_{jZ}|, the largest deviation of the Z-point mean (1/Z) sum_k cos_+^nu(psi_k)
// from its integral c_0 (Poisson summation); terms fall like (jZ)^(-nu-1): 2000 of them leave
// < 1e-8 of the sum for nu = 5/2.
double poisson_tail(double nu, int z) {
  double tail = 0.0;
  for (int j = 1; j <= 2000; ++j) tail += 2.0 * clipped_cos_magnitude(nu, j * z);
  return tail;
}

// Harris's radial integral J_r(eps) = (1/2 pi) int [1 - (1 - cos psi) / (2 eps)]_+^n cos psi dpsi
// by the composite Simpson rule on the loaded zone |psi| <= psi_l, cos psi_l = 1 - 2 eps. The
// integrand vanishes like s^n at the zone's ends: 20000 intervals leave < 1e-9.
double radial_integral(double eps, double n) {
  const double psi_l = std::acos(std::max(1.0 - 2.0 * eps, -1.0));
  const int intervals = 20000;
  const double h = 2.0 * psi_l / intervals;
  auto g = [&](double psi) {
    const double base = 1.0 - (1.0 - std::cos(psi)) / (2.0 * eps);
    return base > 0.0 ? std::pow(base, n) * std::cos(psi) : 0.0;
  };
  double sum = g(-psi_l) + g(psi_l);
  for (int i = 1; i < intervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * g(-psi_l + i * h);
  return sum * h / 3.0 / (2.0 * kPi);
}

// The static radial problem f(u) = (F, 0, 0) by Newton's method on x, y with the element's
// tangent (z is free and unloaded for alpha = 0). The start is the closed-form deflection.
// `x_only`: keep y = 0 (a load zone symmetric about x, which is then exact, with a single loaded
// ball that has no y stiffness).
Eigen::VectorXd solve_radial(const RollingBearing& b, double force, double start,
                             bool x_only = false) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3), v = Eigen::VectorXd::Zero(3);
  u(0) = start;
  ElementForce out;
  for (int it = 0; it < 50; ++it) {
    b.evaluate(u, v, 0.0, out);
    const Eigen::Vector2d r(out.force(0) - force, x_only ? 0.0 : out.force(1));
    if (r.norm() < 1e-12 * force) return u;
    if (x_only)
      u(0) -= r(0) / out.stiffness(0, 0);
    else
      u.head<2>() -= out.stiffness.topLeftCorner<2, 2>().lu().solve(r);
  }
  ADD_FAILURE() << "Newton did not converge";
  return u;
}

// Harris's tabulated J_r(0.5) = 0.2288 and Stribeck's 4.37 = 1 / J_r(0.5) are the closed form
// J_r(0.5) = (1/2 pi) int cos^(5/2) = c_0(5/2) rounded to their printed digits.
TEST(RollingBearing, RadialIntegralMatchesHarrisAndStribeck) {
  const double j_closed = clipped_cos_coefficient(2.5, 0);
  EXPECT_NEAR(j_closed, 0.2288, 5e-5);
  EXPECT_NEAR(radial_integral(0.5, 1.5), j_closed, 1e-9);
  EXPECT_NEAR(1.0 / j_closed, 4.37, 5e-3);
}

// Zero clearance, F_r = 5 kN on Z = 40 balls, the cage with a ball under the load (psi_0 = 0)
// and half a pitch on (psi_0 = pi / Z), both symmetric so y = 0. The discrete mean
// S = (1/Z) sum_k cos_+^(5/2)(psi_k) = sum_j c_{jZ} 2 cos(j Z psi_0) (Poisson) differs from
// J_r = c_0 by at most 2 sum_{j>=1} |c_{jZ}| (= 1.8e-5 J_r for Z = 40), so the deflection
// delta_r = (F_r / (Z K_n S))^(2/3) is within 2/3 of that of Harris's: the tolerance is that
// bound (computed; at psi_0 = 0 all harmonics add in phase and it is attained) plus 1e-9 for
// Newton's 1e-12 and rounding.
TEST(RollingBearing, StaticLoadDeflectionOfARadialBallBearingMatchesHarris) {
  const int z = 40;
  const double force = 5000.0, k_n = 1.0e10;
  const double j_r = clipped_cos_coefficient(2.5, 0);
  const double tail = poisson_tail(2.5, z);
  EXPECT_LT(tail / j_r, 2e-5);
  const double delta_r = std::pow(force / (z * k_n * j_r), 2.0 / 3.0);
  for (double psi0 : {0.0, kPi / z}) {
    RollingBearingParams p = ball_bearing(z);
    p.cage_angle = psi0;
    const RollingBearing b(p, "bearing");
    const Eigen::VectorXd u = solve_radial(b, force, delta_r);
    EXPECT_NEAR(u(1), 0.0, 1e-12 * delta_r);
    EXPECT_NEAR(u(0) / delta_r - 1.0, 0.0, 2.0 / 3.0 * tail / j_r + 1e-9) << "psi0 " << psi0;
    // Stribeck: the most loaded ball (at psi = 0 when psi0 = 0) carries 4.37 F_r / Z.
    if (psi0 == 0.0) {
      const double q_max = k_n * std::pow(b.deflection(u, 0.0, 0), 1.5);
      EXPECT_NEAR(q_max * z / force, 1.0 / j_r, 1.0 / j_r * tail / j_r + 1e-9);
      EXPECT_NEAR(q_max * z / force, 4.37, 5e-3);
    }
  }
}

// Few balls (Z = 9): one position is far from the integral (the bound 2 sum |c_jZ| is 4e-3 of
// J_r), but the mean over the cage angle of the force at a given deflection is exactly
// Z K_n delta^n J_r; M = 16 cage positions over one ball pitch form the (9 x 16)-point rule,
// within 2 sum_j |c_{144 j}| = 2.1e-7 of J_r (attained: the samples include psi_0 = 0).
TEST(RollingBearing, CageAveragedForceOfFewBallsIsHarrisIntegral) {
  const int z = 9, m = 16;
  const double delta = 2.0e-5, k_n = 1.0e10;
  const double j_r = clipped_cos_coefficient(2.5, 0);
  const double tail = poisson_tail(2.5, z * m);
  double spread_min = 1e300, spread_max = 0.0, mean = 0.0;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3), v = Eigen::VectorXd::Zero(3);
  u(0) = delta;
  ElementForce out;
  for (int i = 0; i < m; ++i) {
    RollingBearingParams p = ball_bearing(z);
    p.cage_angle = 2.0 * kPi * i / (z * m);
    RollingBearing(p, "bearing").evaluate(u, v, 0.0, out);
    const double s = out.force(0) / (z * k_n * std::pow(delta, 1.5));
    mean += s / m;
    spread_min = std::min(spread_min, s);
    spread_max = std::max(spread_max, s);
  }
  EXPECT_NEAR(mean / j_r, 1.0, tail / j_r + 1e-10);
  // One position alone misses by up to 2 |c_9| / J_r = 3.3e-3 (its Z-th harmonic). The half
  // spread of the 16 samples is that harmonic's amplitude 2 |c_9| within 5 %: the samples miss
  // its extremes by at most 1 - cos(pi / 16) = 2 % and the higher harmonics add ~ 2^(-7/2) of it.
  const double c_z = std::abs(clipped_cos_coefficient(2.5, z));
  EXPECT_NEAR((spread_max - spread_min) / 2.0, 2.0 * c_z, 0.05 * 2.0 * c_z);
}

// Diametral clearance c_r: element k deflects delta_r cos psi_k - c_r / 2, the loaded zone is
// |psi| < psi_l, cos psi_l = c_r / (2 delta_r), Harris's load-distribution factor
// eps = (1 - c_r / (2 delta_r)) / 2 < 0.5, and F_r = Z K_n (delta_r - c_r/2)^n J_r(eps).
//   (a) a table point: c_r chosen so that eps = 0.3 at 5 kN gives Harris's J_r(0.3) = 0.1892;
//       Z = 400 makes the discrete sum's error negligible against the table's 4 digits: the
//       integrand has kinks ~ s^(3/2) at +-psi_l, so |c_m| <= Gamma(5/2) A / (pi m^(5/2)) with
//       A = (sin psi_l / (2 eps))^(3/2) cos psi_l = 0.76, 2 |c_400| = 2e-7 = 1.1e-6 of J_r
//       in the force and 7e-7 in the deflection (tolerance 2e-6; eps = 1/2 - c_r / (4 delta_r)
//       moves by (1/2 - eps) times that);
//   (b) the one-ball limit (Harris's J_r -> 1/Z for eps -> 0): with a ball at psi = 0 and
//       delta_r < c_r / (2 cos(2 pi / Z)) only that ball touches and F_r = K_n (delta_r - c_r/2)^n
//       exactly (Newton's 1e-12 in force, rounding of the powers: 1e-10).
TEST(RollingBearing, ClearanceShrinksTheLoadedZoneAsHarrisTabulates) {
  const double k_n = 1.0e10, force = 5000.0, eps = 0.3;
  const double j_r = radial_integral(eps, 1.5);
  EXPECT_NEAR(j_r, 0.1892, 5e-5);
  EXPECT_LT(j_r, radial_integral(0.5, 1.5));  // the loaded zone shrinks: less of Z carries load
  {
    const int z = 400;
    // delta_max = (F / (Z K J))^(2/3); delta_r = delta_max / (2 eps); c_r = 2 (delta_r - delta_max)
    const double delta_max = std::pow(force / (z * k_n * j_r), 2.0 / 3.0);
    const double delta_r = delta_max / (2.0 * eps);
    const double clearance = 2.0 * (delta_r - delta_max);
    const RollingBearing b(ball_bearing(z, clearance), "bearing");
    const Eigen::VectorXd u = solve_radial(b, force, delta_r);
    EXPECT_NEAR(u(0) / delta_r, 1.0, 2e-6);
    const double eps_found = 0.5 * (1.0 - clearance / (2.0 * u(0)));
    EXPECT_NEAR(eps_found, eps, 0.2 * 2e-6);
    int loaded = 0;
    for (int k = 0; k < z; ++k) loaded += b.deflection(u, 0.0, k) > 0.0;
    // 2 psi_l / (2 pi) of the balls: cos psi_l = 1 - 2 eps = 0.4, psi_l = 66.4 deg.
    EXPECT_NEAR(loaded, z * std::acos(1.0 - 2.0 * eps) / kPi, 2.0);
  }
  {
    const int z = 9;
    const double clearance = 20e-6, force_small = 50.0;
    const RollingBearing b(ball_bearing(z, clearance), "bearing");
    const double delta_max = std::pow(force_small / k_n, 2.0 / 3.0);
    ASSERT_LT(clearance / 2.0 + delta_max, clearance / (2.0 * std::cos(2.0 * kPi / z)));
    const Eigen::VectorXd u = solve_radial(b, force_small, clearance / 2.0 + 1.2 * delta_max, true);
    EXPECT_NEAR(u(0) / (clearance / 2.0 + delta_max), 1.0, 1e-10);
    for (int k = 1; k < z; ++k) EXPECT_LT(b.deflection(u, 0.0, k), 0.0);
  }
}

// The stiffness at a fixed deflection as the cage turns: periodic in psi_0 with the ball pitch
// 2 pi / Z, i.e. in time with 1 / BPFO for a fixed outer ring. Its Z-th harmonic follows from
// Poisson's formula: K_yy / (n K_n delta^(n-1)) = sum_k cos_+^(1/2) psi_k sin^2 psi_k
// = Z sum_j h_{jZ} e^{i j Z psi_0} with h_m = (c_m - (c_{m-2} + c_{m+2}) / 2) / 2, c_m of
// cos_+^(1/2). The amplitude 2 Z |h_Z| relative to the mean Z h_0 decreases like Z^(-3/2)
// (the kinks at +-pi/2); a 1024-point DFT over one pitch aliases the harmonics 1023 Z and 1025 Z,
// each ~ 1023^(-3/2) = 3e-5 of the Z-th: 1e-4.
TEST(RollingBearing, StiffnessVariesAtTheBallPassFrequency) {
  const double delta = 2.0e-5, k_n = 1.0e10, omega_c = 40.0;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3), v = Eigen::VectorXd::Zero(3);
  u(0) = delta;
  auto h = [](int m) {
    return 0.5 * (clipped_cos_coefficient(0.5, m) - 0.5 * (clipped_cos_coefficient(0.5, m - 2) +
                                                           clipped_cos_coefficient(0.5, m + 2)));
  };
  double previous = 1e300;
  for (int z : {8, 16, 32}) {
    RollingBearingParams p = ball_bearing(z);
    p.cage_angle = 0.1;
    p.cage_speed = omega_c;
    const RollingBearing b(p, "bearing");
    const double period = 2.0 * kPi / (z * omega_c);  // 1 / BPFO [s]
    const double scale = 1.5 * k_n * std::sqrt(delta);
    ElementForce a, c;
    const int samples = 1024;
    std::complex<double> harmonic = 0.0;
    double mean = 0.0;
    for (int i = 0; i < samples; ++i) {
      const double t = period * i / samples;
      b.evaluate(u, v, t, a);
      b.evaluate(u, v, t + period, c);
      EXPECT_LT((a.stiffness - c.stiffness).cwiseAbs().maxCoeff(), 1e-12 * scale * z);
      const double kyy = a.stiffness(1, 1) / scale;
      mean += kyy / samples;
      harmonic += kyy * std::polar(2.0 / samples, -z * b.cage_angle(t));
    }
    EXPECT_NEAR(mean, z * h(0), 1e-3 * z * h(0)) << "Z " << z;
    const double amplitude = std::abs(harmonic);
    EXPECT_NEAR(amplitude, 2.0 * z * std::abs(h(z)), 1e-4 * amplitude) << "Z " << z;
    EXPECT_GT(amplitude / mean, 1e-3);
    EXPECT_LT(amplitude / mean, previous);
    previous = amplitude / mean;
  }
}

// Analytic tangents vs central differences at states where every element is at least 0.3 um
// from its contact kink (delta^n has an infinite higher derivative at 0): h = 1e-10 m leaves a
// truncation ~ (h / delta_min)^2 = 1e-7 of the largest entry and round-off ~ 1e-16 delta / h;
// the constant damping (150 N s/m) differenced with h_v = 1e-4 m/s on forces ~ 1e4 N has a
// round-off ~ 1e-16 1e4 / 1e-4 / 150 < 1e-9.
TEST(RollingBearing, TangentsMatchCentralDifferences) {
  for (double n : {1.5, 10.0 / 9.0}) {
    RollingBearingParams p = ball_bearing(9, 4e-6);
    p.exponent = n;
    p.contact_angle = 15.0 * kPi / 180.0;
    p.axial_clearance = 10e-6;
    p.cage_speed = 30.0;
    p.cage_angle = 0.2;
    p.radial_damping = 150.0;
    p.axial_damping = 80.0;
    const RollingBearing b(p, "bearing");
    Eigen::VectorXd u(3), v(3);
    u << 2.0e-5, -0.7e-5, 1.1e-5;
    v << 0.01, -0.02, 0.005;
    const double t = 0.013;
    int loaded = 0;
    for (int k = 0; k < p.elements; ++k) {
      const double d = b.deflection(u, t, k);
      ASSERT_GT(std::abs(d), 3e-7) << "element " << k << " too close to its kink";
      loaded += d > 0.0;
    }
    ASSERT_GE(loaded, 3);
    ASSERT_LT(loaded, p.elements);
    const TangentCheck check = check_tangents(b, u, v, t, 1e-10, 1e-4);
    EXPECT_LT(check.stiffness_error, 1e-7) << "n " << n;
    EXPECT_LT(check.damping_error, 1e-9) << "n " << n;
  }
}

// The kinematic frequencies of the 6205-2RS JEM SKF (Z = 9, D = 0.3126 in, d_m = 1.537 in,
// alpha = 0) as multiples of the shaft speed, fixed outer ring: CWRU Bearing Data Center lists
// BPFI 5.4152, BPFO 3.5848, FTF 0.39828 and the rolling element 4.7135 (= 2 BSF: a ball defect
// strikes both races). Their geometry is rounded to 4 digits: 1e-4 relative.
TEST(RollingBearing, KinematicFrequenciesOfA6205) {
  const BearingKinematics k{9, 1.537 * 0.0254, 0.3126 * 0.0254, 0.0};
  EXPECT_NEAR(k.cage(1.0), 0.39828, 1e-4 * 0.39828);
  EXPECT_NEAR(k.ball_pass_outer(1.0), 3.5848, 1e-4 * 3.5848);
  EXPECT_NEAR(k.ball_pass_inner(1.0), 5.4152, 1e-4 * 5.4152);
  EXPECT_NEAR(2.0 * k.ball_spin(1.0), 4.7135, 1e-4 * 4.7135);
  // A rotating outer ring and fixed inner ring swap the roles: f_c = f_o (1 + gamma) / 2.
  EXPECT_NEAR(k.cage(0.0, 1.0), 0.5 * (1.0 + k.gamma()), 1e-15);
  EXPECT_NEAR(k.ball_pass_outer(1.0, 1.0), 0.0, 1e-15);  // rings together: no rolling
}

TEST(RollingBearing, BadParametersNameTheirKey) {
  auto key_of = [](auto edit) {
    RollingBearingParams p = ball_bearing(9);
    edit(p);
    try {
      const RollingBearing b(p, "bearings[2]", {"model.toml", 12, 3});
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().line, 12);
      return e.key_path();
    }
    return std::string("no error");
  };
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.elements = 0; }), "bearings[2].elements");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.stiffness_constant = -1.0; }),
            "bearings[2].stiffness_constant");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.exponent = 3.0; }), "bearings[2].exponent");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.radial_clearance = NAN; }),
            "bearings[2].radial_clearance");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.contact_angle = 2.0; }),
            "bearings[2].contact_angle");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.element_diameter = 0.06; }),
            "bearings[2].element_diameter");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.radial_damping = -1.0; }),
            "bearings[2].radial_damping");
  EXPECT_EQ(key_of([](RollingBearingParams& p) { p.radial_clearance = -2e-6; }), "no error");
}

}  // namespace
