// Tooth friction of the gear tooth-contact element (elements/gear_mesh_contact.hpp,
// docs/theory.md §16.6) on a standard external spur pair z1 = 20, z2 = 40, m = 4 mm,
// alpha = 20 deg, addendum 1 m (epsilon_alpha = 1.635):
//   * the friction power of a pair is mu F |v_s| with the sliding velocity
//     v_s = (omega1 + omega2) s (s: the contact's distance from the pitch point along the line of
//     action; G. Niemann, H. Winter, Maschinenelemente Band II, 2nd ed., Springer 1989, sec.
//     21.3, the sliding speed v_g);
//   * it vanishes at the pitch point and changes sign across it;
//   * the mean power loss over a mesh cycle is mu H_V P_in with Ohlendorf's tooth loss factor
//     H_V = pi (u + 1) / (z1 u) (1 - eps_alpha + eps_1^2 + eps_2^2) (H. Ohlendorf, "Verlust-
//     leistung und Erwärmung von Stirnrädern", Dissertation TH München, 1958; as quoted in
//     Niemann & Winter, Maschinenelemente Band II, sec. 21.3, and ISO/TR 14179-2:2001);
//   * its tangents are analytic (central differences).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "geardyn/elements/gear_mesh_contact.hpp"

namespace {

using namespace geardyn::elements;
constexpr double kPi = std::numbers::pi;

struct Pair {
  int z1 = 20, z2 = 40;
  double m = 4e-3, alpha = 20.0 * kPi / 180.0;
  double r1() const { return m * z1 / 2.0; }
  double r2() const { return m * z2 / 2.0; }
  double rb1() const { return r1() * std::cos(alpha); }
  double rb2() const { return r2() * std::cos(alpha); }
  double base_pitch() const { return kPi * m * std::cos(alpha); }
  // Addendum contact ratios (ISO 21771): pinion tip (recess) eps_1, wheel tip (approach) eps_2.
  double eps1() const {
    const double ra = r1() + m;
    return (std::sqrt(ra * ra - rb1() * rb1()) - r1() * std::sin(alpha)) / base_pitch();
  }
  double eps2() const {
    const double ra = r2() + m;
    return (std::sqrt(ra * ra - rb2() * rb2()) - r2() * std::sin(alpha)) / base_pitch();
  }
  double pitch_angle() const { return 2.0 * kPi / z1; }
};

constexpr double kStiffness = 4e8;  // N/m
constexpr double kMu = 0.05;

GearMeshContact element(const Pair& g, double v_eps, double damping = 0.0) {
  GearMeshContactOptions o;
  o.damping = damping;
  o.friction = spur_tooth_friction(kMu, v_eps, g.rb1(), g.rb2(), g.r1() + g.m, g.r2() + g.m,
                                   g.r1() + g.r2());
  auto map =
      std::make_shared<MeshForceMap>(MeshForceMap::constant_stiffness(kStiffness, g.pitch_angle()));
  return GearMeshContact("mesh", map, o);
}

Eigen::VectorXd vec4(double a, double b, double c, double d) {
  Eigen::VectorXd x(4);
  x << a, b, c, d;
  return x;
}

// Pinion angle at which the newest pair is a fraction `x` of a base pitch past the start of the
// active path (phase 0).
double angle_at(const Pair& g, double x) { return (x + 7.0) * g.pitch_angle(); }

// Friction power of the element: sum over theta1, theta2, y of force x rate.
double friction_power(const ElementForce& out, const Eigen::VectorXd& v) {
  return out.force.tail<3>().dot(v.tail<3>());
}

TEST(GearMeshFriction, PathOfContactIsTheStandardPair) {
  const Pair g;
  const ToothFriction f =
      spur_tooth_friction(kMu, 1e-3, g.rb1(), g.rb2(), g.r1() + g.m, g.r2() + g.m, g.r1() + g.r2());
  // Working = reference pressure angle at the standard centre distance: rho_p = r sin(alpha).
  EXPECT_NEAR(f.pitch_arm1, g.r1() * std::sin(g.alpha), 1e-15);
  EXPECT_NEAR(f.pitch_arm2, g.r2() * std::sin(g.alpha), 1e-15);
  EXPECT_NEAR(f.path_start, -g.eps2() * g.base_pitch(), 1e-15);
  EXPECT_NEAR(f.path_length / g.base_pitch(), g.eps1() + g.eps2(), 1e-12);
  // eps_alpha = (sqrt(r_a1^2 - r_b1^2) + sqrt(r_a2^2 - r_b2^2) - a sin(alpha_w)) / p_b
  // (ISO 21771:2007, eq. for the transverse contact ratio): 1.635 for this pair.
  const auto leg = [](double ra, double rb) { return std::sqrt(ra * ra - rb * rb); };
  const double eps = (leg(g.r1() + g.m, g.rb1()) + leg(g.r2() + g.m, g.rb2()) -
                      (g.r1() + g.r2()) * std::sin(g.alpha)) /
                     g.base_pitch();
  EXPECT_NEAR(f.path_length / g.base_pitch(), eps, 1e-12);
  EXPECT_NEAR(eps, 1.635, 1e-3);
}

// At the kinematic speeds omega2 = omega1 r_b1 / r_b2 the power of each pair is
// mu F_k |(omega1 + omega2) s|: the smoothed sign is 1 to double precision
// (|v_s| / v_eps > 1e6), so the identity holds to rounding (1e-10 asked).
TEST(GearMeshFriction, PowerLossIsMuFnTimesTheSlidingSpeed) {
  const Pair g;
  const GearMeshContact c = element(g, 1e-9);
  const double w1 = 150.0, w2 = w1 * g.rb1() / g.rb2();
  const double delta = 1e-5, normal = kStiffness * delta;
  const double start = -g.eps2() * g.base_pitch();
  for (double x : {0.05, 0.3, 0.52, 0.62, 0.75, 0.95}) {
    const double theta = angle_at(g, x);
    const Eigen::VectorXd u = vec4(delta, theta, 0.3, 1e-6), v = vec4(0.0, w1, w2, 0.0);
    ElementForce out;
    c.evaluate(u, v, 0.0, out);
    ASSERT_EQ(out.force.size(), 4);
    EXPECT_NEAR(out.force(0), normal, 1e-12 * normal);
    // The pairs on the path: s = s_A + x p_b, and s + p_b while it is before s_E.
    const double s = start + x * g.base_pitch();
    const bool two = s + g.base_pitch() < start + (g.eps1() + g.eps2()) * g.base_pitch();
    const auto pairs = c.pairs(theta);
    ASSERT_EQ(pairs.size(), two ? 2u : 1u) << x;
    EXPECT_NEAR(pairs[0].s, s, 1e-12 * g.base_pitch());
    double expected = kMu * normal / pairs.size() * (w1 + w2) * std::abs(s);
    if (two) expected += kMu * normal / 2.0 * (w1 + w2) * std::abs(s + g.base_pitch());
    EXPECT_NEAR(friction_power(out, v), expected, 1e-10 * expected) << x;
    if (!two) {
      // Single pair: moments mu F rho about each shaft, the force mu F on the centres.
      const double sign = s > 0.0 ? 1.0 : -1.0;
      EXPECT_NEAR(out.force(1), kMu * normal * (g.r1() * std::sin(g.alpha) + s) * sign,
                  1e-12 * normal);
      EXPECT_NEAR(out.force(2), -kMu * normal * (g.r2() * std::sin(g.alpha) - s) * sign,
                  1e-12 * normal);
      EXPECT_NEAR(out.force(3), -kMu * normal * sign, 1e-12 * normal);
    }
  }
}

// At the pitch point v_s = 0: no friction; across it the sliding and the friction reverse.
// v_eps = 1e-3 m/s: at the pitch point |v_s| <= (omega1 + omega2) x 1e-18 m (the rounding of
// s), so sigma < 1e-13; at +- 1 % of a base pitch |v_s| = 0.027 m/s = 27 v_eps, sigma = 1 - 1e-23.
TEST(GearMeshFriction, ZeroAtThePitchPointAndReversedAcrossIt) {
  const Pair g;
  const GearMeshContact c = element(g, 1e-3);
  const double w1 = 150.0, w2 = w1 * g.rb1() / g.rb2();
  const double delta = 1e-5, normal = kStiffness * delta;
  const double x_pitch = g.eps2();  // s = s_A + x p_b = 0
  const Eigen::VectorXd v = vec4(0.0, w1, w2, 0.0);
  ElementForce at, before, after;
  c.evaluate(vec4(delta, angle_at(g, x_pitch), 0.0, 0.0), v, 0.0, at);
  c.evaluate(vec4(delta, angle_at(g, x_pitch - 0.01), 0.0, 0.0), v, 0.0, before);
  c.evaluate(vec4(delta, angle_at(g, x_pitch + 0.01), 0.0, 0.0), v, 0.0, after);
  ASSERT_EQ(c.pairs(angle_at(g, x_pitch)).size(), 1u);  // the pitch point is in single contact
  EXPECT_LT(at.force.tail<3>().cwiseAbs().maxCoeff(), 1e-9 * kMu * normal);
  EXPECT_NEAR(before.force(3), kMu * normal, 1e-12 * normal);  // approach: s < 0
  EXPECT_NEAR(after.force(3), -kMu * normal, 1e-12 * normal);  // recess: s > 0
  EXPECT_LT(before.force(1), 0.0);
  EXPECT_GT(after.force(1), 0.0);
  EXPECT_GT(before.force(2), 0.0);
  EXPECT_LT(after.force(2), 0.0);
  // Both sides dissipate.
  EXPECT_GT(friction_power(before, v), 0.0);
  EXPECT_GT(friction_power(after, v), 0.0);
}

// Mean over a mesh cycle: P_loss / P_in = mu H_V with P_in = F r_b1 omega1 and the rigid-tooth
// load sharing (F / 2 per pair in double contact) that Ohlendorf's H_V assumes. Midpoint rule on
// N = 2e5 pinion angles: the integrand is linear in theta1 but for its two jumps (a pair
// entering / leaving) and the kink at the pitch point, each costing at most one cell's share of
// the jump, |error| <= 3 max / N ~ 3e-5 of the mean; the smoothing with v_eps = 1e-6 m/s removes
// ~ v_eps^2 / ((omega1 + omega2) p_b) ~ 1e-14 of it. Tolerance 1e-4 relative.
TEST(GearMeshFriction, MeanLossIsOhlendorfsToothLossFactor) {
  const Pair g;
  const GearMeshContact c = element(g, 1e-6);
  const double w1 = 150.0, w2 = w1 * g.rb1() / g.rb2();
  const double delta = 1e-5, normal = kStiffness * delta;
  const Eigen::VectorXd v = vec4(0.0, w1, w2, 0.0);
  const int n = 200000;
  double sum = 0.0;
  ElementForce out;
  for (int k = 0; k < n; ++k) {
    c.evaluate(vec4(delta, angle_at(g, (k + 0.5) / n), 0.0, 0.0), v, 0.0, out);
    sum += friction_power(out, v);
  }
  const double loss = sum / n / (normal * g.rb1() * w1);
  const double u = static_cast<double>(g.z2) / g.z1;
  const double eps = g.eps1() + g.eps2();
  const double h_v =
      kPi * (u + 1.0) / (g.z1 * u) * (1.0 - eps + g.eps1() * g.eps1() + g.eps2() * g.eps2());
  EXPECT_NEAR(loss / kMu, h_v, 1e-4 * h_v);
  EXPECT_NEAR(1.0 - loss, 1.0 - kMu * h_v, 1e-5);  // the efficiency, ~ 0.99
}

// Tangents of the friction rows (theta1, theta2, y) against central differences, on their own
// scale (the delta row's stiffness 4e8 N/m would hide them in check_tangents' global norm), at
// sliding speeds comparable to v_eps = 0.05 m/s so that the smoothed sign's slope matters, with
// a mesh damping (the normal force depends on the rates), in single and double contact, away
// from a pair entering or leaving. Steps 1e-12 m on delta and y, 1e-9 rad on the angles, 1e-6
// on the rates: the law is linear in delta and y_dot-smooth, and the truncation
// (h / scale)^2 (scale v_eps / ((omega1 + omega2) r_b1) ~ 0.09 rad) is < 1e-15; round-off
// 1e-16 x 4 N m / 1e-9 = 4e-7 against entries ~ 10: 1e-6 relative is met.
TEST(GearMeshFriction, TangentsMatchCentralDifferences) {
  const Pair g;
  const GearMeshContact c = element(g, 0.05, 1.5e3);
  for (double x : {0.1, 0.45, 0.53, 0.8}) {
    for (double w1 : {0.7, 3.0, -2.0}) {
      const Eigen::VectorXd u = vec4(1e-5, angle_at(g, x), -0.4, 2e-6);
      const Eigen::VectorXd v = vec4(0.013, w1, 0.45 * w1 + 0.2, 0.004);
      ElementForce at;
      c.evaluate(u, v, 0.0, at);
      ASSERT_GT(at.damping.bottomRows<3>().cwiseAbs().maxCoeff(), 0.0);
      // Each column on its own scale (d / d delta ~ mu k rho ~ 4e5 dwarfs d / d theta1 ~ 10).
      auto scale = [](const Eigen::MatrixXd& a, int j) {
        return std::max(a.col(j).tail<3>().cwiseAbs().maxCoeff(), 1e-12);
      };
      const double hu[4] = {1e-12, 1e-9, 1e-9, 1e-12};
      for (int j = 0; j < 4; ++j) {
        ElementForce plus, minus;
        Eigen::VectorXd up = u, um = u, vp = v, vm = v;
        up(j) += hu[j];
        um(j) -= hu[j];
        c.evaluate(up, v, 0.0, plus);
        c.evaluate(um, v, 0.0, minus);
        const Eigen::Vector3d dk = (plus.force - minus.force).tail<3>() / (2.0 * hu[j]);
        vp(j) += 1e-6;
        vm(j) -= 1e-6;
        c.evaluate(u, vp, 0.0, plus);
        c.evaluate(u, vm, 0.0, minus);
        const Eigen::Vector3d dc = (plus.force - minus.force).tail<3>() / 2e-6;
        for (int i = 0; i < 3; ++i) {
          EXPECT_NEAR(at.stiffness(i + 1, j), dk(i), 1e-6 * scale(at.stiffness, j))
              << "K(" << i + 1 << "," << j << ") x " << x << " w1 " << w1;
          EXPECT_NEAR(at.damping(i + 1, j), dc(i), 1e-6 * scale(at.damping, j))
              << "C(" << i + 1 << "," << j << ") x " << x << " w1 " << w1;
        }
      }
      const TangentCheck t = check_tangents(c, u, v, 0.0, 1e-12, 1e-6, 1.0);
      EXPECT_LT(t.stiffness_error, 1e-6);
      EXPECT_LT(t.damping_error, 1e-6);
    }
  }
}

// Without friction the element keeps its two coordinates; bad friction options name their key.
TEST(GearMeshFriction, OptionsAreChecked) {
  const Pair g;
  auto map =
      std::make_shared<MeshForceMap>(MeshForceMap::constant_stiffness(kStiffness, g.pitch_angle()));
  EXPECT_EQ(GearMeshContact("m", map, {}).size(), 2);
  EXPECT_EQ(element(g, 1e-3).size(), 4);
  GearMeshContactOptions o;
  o.friction =
      spur_tooth_friction(kMu, 0.0, g.rb1(), g.rb2(), g.r1() + g.m, g.r2() + g.m, g.r1() + g.r2());
  LawSource source;
  source.location.file = "f.toml";
  source.location.line = 3;
  source.key_path = "gear_meshes[0].contact";
  try {
    GearMeshContact("m", map, o, source);
    ADD_FAILURE() << "v_eps = 0 accepted";
  } catch (const geardyn::InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_meshes[0].contact.friction_velocity");
    EXPECT_EQ(e.where().line, 3);
  }
  o.friction.velocity = 1e-3;
  o.friction.coefficient = -0.1;
  EXPECT_THROW(GearMeshContact("m", map, o), geardyn::InputError);
}

}  // namespace
