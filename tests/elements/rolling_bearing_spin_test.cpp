// The rolling bearing's optional spin-angle coordinate (elements/rolling_bearing.hpp,
// docs/theory.md §16.5): the cage follows the inner ring's angle theta with the fixed-outer-ring
// cage ratio kappa = (1 - gamma) / 2 (T.A. Harris, "Rolling Bearing Analysis", 4th ed., 2001,
// bearing kinematics), so
//   * at theta = omega t / kappa the 4-coordinate bearing is the 3-coordinate one with cage speed
//     omega (the same arithmetic on the same cage angle: 1e-12);
//   * the stiffness repeats with the ball pitch of the cage, a period 2 pi / (Z kappa) in theta
//     (the ball-pass frequency BPFO = Z f_c of a fixed outer ring);
//   * the tangent's theta column is the exact derivative.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/elements/rolling_bearing.hpp"

namespace {

using namespace geardyn::elements;
constexpr double kPi = std::numbers::pi;

RollingBearingParams bearing(bool spin) {
  RollingBearingParams p;
  p.elements = 9;
  p.stiffness_constant = 1.0e10;  // N/m^1.5 (as tests/elements/rolling_bearing_test.cpp)
  p.exponent = 1.5;
  p.radial_clearance = 4e-6;
  p.axial_clearance = 10e-6;
  p.contact_angle = 15.0 * kPi / 180.0;
  p.pitch_diameter = 0.05;
  p.element_diameter = 0.008;
  p.cage_angle = 0.2;
  p.radial_damping = 150.0;
  p.axial_damping = 80.0;
  p.spin_angle = spin;
  return p;
}

Eigen::VectorXd displacement(double theta) {
  Eigen::VectorXd u(4);
  u << 2.0e-5, -0.7e-5, 1.1e-5, theta;
  return u;
}

Eigen::VectorXd velocity() {
  Eigen::VectorXd v(4);
  v << 0.01, -0.02, 0.005, 120.0;
  return v;
}

TEST(RollingBearingSpin, FollowsTheShaftAngleAsTheCageSpeedDoes) {
  const RollingBearing spin(bearing(true), "bearing");
  EXPECT_EQ(spin.size(), 4);
  const double kappa = spin.cage_ratio();
  EXPECT_NEAR(kappa, 0.5 * (1.0 - 0.008 * std::cos(15.0 * kPi / 180.0) / 0.05), 1e-15);
  const double omega = 35.0;  // cage speed [rad/s]
  RollingBearingParams p3 = bearing(false);
  p3.cage_speed = omega;
  const RollingBearing fixed(p3, "bearing");
  ElementForce a, b;
  for (double t : {0.0, 0.0137, 0.41, 3.3}) {
    const Eigen::VectorXd u = displacement(omega * t / kappa), v = velocity();
    spin.evaluate(u, v, 0.0, a);
    fixed.evaluate(u.head<3>(), v.head<3>(), t, b);
    const double scale = b.force.cwiseAbs().maxCoeff();
    EXPECT_LT((a.force.head<3>() - b.force).cwiseAbs().maxCoeff(), 1e-12 * scale) << t;
    EXPECT_EQ(a.force(3), 0.0);
    EXPECT_LT((a.stiffness.topLeftCorner<3, 3>() - b.stiffness).cwiseAbs().maxCoeff(),
              1e-12 * b.stiffness.cwiseAbs().maxCoeff())
        << t;
    EXPECT_EQ((a.damping.topLeftCorner<3, 3>() - b.damping).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(a.stiffness.row(3).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(a.damping.col(3).cwiseAbs().maxCoeff(), 0.0);
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(spin.deflection(u, 0.0, k), fixed.deflection(u.head<3>(), t, k), 1e-18);
  }
}

// The stiffness at a fixed deflection repeats after the shaft turns by 2 pi / (Z kappa) (one
// ball pitch of the cage), to rounding of the angles (~ 1e-16 x 7 rad in psi, a change
// ~ 1e-15 of the entries); half that turn does not repeat it (the ball-pass modulation of
// tests/elements/rolling_bearing_test.cpp is several 1e-3 of the mean for Z = 9).
TEST(RollingBearingSpin, BallPassPeriodInTheShaftAngle) {
  const RollingBearing spin(bearing(true), "bearing");
  const double period = 2.0 * kPi / (9 * spin.cage_ratio());
  ElementForce a, b, c;
  const Eigen::VectorXd v = velocity();
  for (double theta : {0.0, 0.3, 1.7}) {
    spin.evaluate(displacement(theta), v, 0.0, a);
    spin.evaluate(displacement(theta + period), v, 0.0, b);
    spin.evaluate(displacement(theta + 0.5 * period), v, 0.0, c);
    const double scale = a.stiffness.cwiseAbs().maxCoeff();
    EXPECT_LT((a.stiffness - b.stiffness).cwiseAbs().maxCoeff(), 1e-12 * scale);
    EXPECT_LT((a.force - b.force).cwiseAbs().maxCoeff(), 1e-12 * a.force.cwiseAbs().maxCoeff());
    EXPECT_GT((a.stiffness - c.stiffness).cwiseAbs().maxCoeff(), 1e-4 * scale);
  }
}

// Tangents vs central differences, at states where every element is >= 0.3 um from its kink
// (as in rolling_bearing_test.cpp: truncation (h / delta_min)^2 ~ 1e-7 with h = 1e-10). The theta
// column is checked on its own scale too (its terms partly cancel, down to ~ 20 N/rad against
// K ~ 1e8 N/m): h = 1e-6 rad turns the cage by kappa h = 4e-7 rad and moves every contact by
// ~ 1e-11 m, truncation ~ (1e-11 / 3e-7)^2 ~ 1e-9; round-off 1e-16 F / h with F ~ 3e3 N is
// 3e-7 N/rad, 1.5e-8 of 20 N/rad: tolerance 1e-6.
TEST(RollingBearingSpin, TangentsIncludingTheAngleColumn) {
  const RollingBearing spin(bearing(true), "bearing");
  const Eigen::VectorXd v = velocity();
  for (double theta : {0.05, 1.3, 4.0}) {
    const Eigen::VectorXd u = displacement(theta);
    int loaded = 0;
    for (int k = 0; k < 9; ++k) {
      const double d = spin.deflection(u, 0.0, k);
      ASSERT_GT(std::abs(d), 3e-7) << "element " << k << " too close to its kink";
      loaded += d > 0.0;
    }
    ASSERT_GE(loaded, 3);
    const TangentCheck check = check_tangents(spin, u, v, 0.0, 1e-10, 1e-4);
    EXPECT_LT(check.stiffness_error, 1e-7) << theta;
    EXPECT_LT(check.damping_error, 1e-9) << theta;
    ElementForce at, plus, minus;
    spin.evaluate(u, v, 0.0, at);
    Eigen::VectorXd up = u, um = u;
    up(3) += 1e-6;
    um(3) -= 1e-6;
    spin.evaluate(up, v, 0.0, plus);
    spin.evaluate(um, v, 0.0, minus);
    const Eigen::VectorXd fd = (plus.force - minus.force) / 2e-6;
    EXPECT_GT(fd.cwiseAbs().maxCoeff(), 1.0);
    EXPECT_LT((at.stiffness.col(3) - fd).cwiseAbs().maxCoeff(), 1e-6 * fd.cwiseAbs().maxCoeff())
        << theta;
  }
}

}  // namespace
