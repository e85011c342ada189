// The bolted joint (elements/bolted_joint.hpp) against the joint diagram of VDI 2230 and the
// bushing (elements/bushing.hpp) against its linear law and its tables; analytic tangents of
// both against central differences (docs/theory.md §16.3, §16.4).
//
// References:
//   VDI 2230 Part 1, "Systematic calculation of highly stressed bolted joints - Joints with one
//   cylindrical bolt", Verein Deutscher Ingenieure, 2015: load factor Phi_n = n delta_P /
//   (delta_S + delta_P), additional bolt load F_SA = Phi_n F_A, clamp load relief
//   F_PA = (1 - Phi_n) F_A, residual clamp load F_KR = F_V - F_PA.
//   R. G. Budynas, J. K. Nisbett, "Shigley's Mechanical Engineering Design", 2011, section
//   "Tension joints - the external load": the same diagram with the joint constant
//   C = k_b / (k_b + k_m) (n = 1); after separation the bolt carries the whole load.
//   F. N. Fritsch, R. E. Carlson, "Monotone piecewise cubic interpolation", SIAM Journal on
//   Numerical Analysis 17 (1980) 238-246.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/elements/bolted_joint.hpp"
#include "geardyn/elements/bushing.hpp"

namespace {

using namespace geardyn::elements;
using geardyn::InputError;

// An M12 steel bolt in a steel flange: k_S = 4e8 N/m, k_P = 1.6e9 N/m, F_V = 20 kN, so
// Phi = 0.2 with n = 1 and the joint opens at F_A = 25 kN.
BoltedJointParams m12(double n = 1.0) {
  BoltedJointParams p;
  p.name = "B1";
  p.bolt_stiffness = 4e8;
  p.clamp_stiffness = 1.6e9;
  p.preload = 20e3;
  p.load_introduction = n;
  return p;
}

// The axial opening at which the joint carries the external load F_A at time t: Newton on
// f(u_a) = F_A with the element's own force and tangent, as the solver will do. The law is
// piecewise linear, so Newton ends in at most three steps; 50 only bounds the loop.
double opening_under(const BoltedJoint& bolt, double f_a, double t = 0.0) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(bolt.size()), v = u;
  ElementForce out;
  for (int it = 0; it < 50; ++it) {
    bolt.evaluate(u, v, t, out);
    const double r = out.force(0) - f_a;
    if (std::abs(r) <= 1e-12 * std::max(std::abs(f_a), 1.0)) break;
    u(0) -= r / out.stiffness(0, 0);
  }
  return u(0);
}

// VDI 2230 Part 1 (2015): below the opening load F_S = F_V + Phi_n F_A and
// F_K = F_V - (1 - Phi_n) F_A; the joint opens at F_A = F_V / (1 - Phi_n); beyond, F_S = F_A
// and F_K = 0. Phi_n is computed here from the compliances (not from the element). Tolerance
// 1e-6 relative, the issue's; the piecewise linear law gives rounding (~1e-15) in fact.
void check_joint_diagram(double n) {
  const BoltedJointParams p = m12(n);
  const BoltedJoint bolt(p, "bolts[0]");
  const double delta_s = 1.0 / p.bolt_stiffness, delta_p = 1.0 / p.clamp_stiffness;
  const double phi = n * delta_p / (delta_s + delta_p);
  const double f_open = p.preload / (1.0 - phi);
  EXPECT_NEAR(bolt.load_factor(), phi, 1e-12);
  EXPECT_NEAR(bolt.opening_load(), f_open, 1e-6 * f_open);
  const double tol = 1e-6 * p.preload;
  // Working range, including a compressive external load (F_A < 0).
  for (const double f_a : {-10e3, 0.0, 5e3, 12.5e3, 0.999 * f_open}) {
    const BoltForces b = bolt.forces(opening_under(bolt, f_a), 0.0);
    EXPECT_EQ(b.state, BoltState::closed) << "F_A = " << f_a;
    EXPECT_NEAR(b.bolt_force, p.preload + phi * f_a, tol) << "F_A = " << f_a;
    EXPECT_NEAR(b.clamp_force, p.preload - (1.0 - phi) * f_a, tol) << "F_A = " << f_a;
  }
  // The opening load: clamp force just above 0 below it, 0 (open) just above it.
  const BoltForces below = bolt.forces(opening_under(bolt, f_open * (1.0 - 1e-9)), 0.0);
  const BoltForces above = bolt.forces(opening_under(bolt, f_open * (1.0 + 1e-9)), 0.0);
  EXPECT_EQ(below.state, BoltState::closed);
  EXPECT_GT(below.clamp_force, 0.0);
  EXPECT_LT(below.clamp_force, 1e-6 * p.preload);
  EXPECT_EQ(above.state, BoltState::open);
  EXPECT_EQ(above.clamp_force, 0.0);
  // Beyond opening the bolt carries the whole load, with the bolt-branch stiffness
  // k_1 = 1 / (delta_S + (1 - n) delta_P) (k_S for n = 1).
  for (const double f_a : {1.2 * f_open, 2.0 * f_open}) {
    const double u_a = opening_under(bolt, f_a);
    const BoltForces b = bolt.forces(u_a, 0.0);
    EXPECT_EQ(b.state, BoltState::open);
    EXPECT_NEAR(b.bolt_force, f_a, 1e-6 * f_a);
    EXPECT_EQ(b.clamp_force, 0.0);
    const double u_open = n * delta_p * p.preload;  // clamp-branch compression at assembly
    EXPECT_NEAR(u_a - u_open, (f_a - f_open) * (delta_s + (1.0 - n) * delta_p), 1e-6 * u_a);
  }
}

TEST(BoltedJoint, Vdi2230JointDiagramLoadIntroducedUnderHeadAndNut) { check_joint_diagram(1.0); }

TEST(BoltedJoint, Vdi2230JointDiagramLoadIntroducedInsideTheClampedParts) {
  check_joint_diagram(0.5);
}

// Under a compressive load large enough to unload the bolt (F_S would be < 0) only the clamped
// parts carry: F_S = 0, F_K = -F_A (equilibrium of the clamped parts alone).
TEST(BoltedJoint, SlackBoltUnderLargeCompression) {
  const BoltedJoint bolt(m12(), "bolts[0]");
  const double f_a = -150e3;  // beyond -F_V / Phi = -100 kN
  const BoltForces b = bolt.forces(opening_under(bolt, f_a), 0.0);
  EXPECT_EQ(b.state, BoltState::slack);
  EXPECT_EQ(b.bolt_force, 0.0);
  EXPECT_NEAR(b.clamp_force, -f_a, 1e-9 * -f_a);
}

// Tightening sequence: nothing before t_a (or k_0 u with an inactive stiffness), the preload
// ramped linearly over t_r, full after; a fixed external load F_A = 10 kN (below opening at
// every preload >= 12.5 kN) gives F_S = F_V(t) + Phi F_A (VDI 2230, as above).
TEST(BoltedJoint, ActivationAndPreloadRamp) {
  BoltedJointParams p = m12();
  p.shear = true;
  p.shear_stiffness = 5e7;
  p.axial_damping = 100.0;
  p.activation_time = 0.5;
  p.preload_ramp = 0.1;
  const BoltedJoint bolt(p, "bolts[0]");
  Eigen::VectorXd u(3), v(3);
  u << 1e-5, 2e-6, -3e-6;
  v << 0.01, 0.02, 0.03;
  ElementForce out;
  bolt.evaluate(u, v, 0.4999, out);
  EXPECT_EQ(out.force.norm(), 0.0);
  EXPECT_EQ(out.stiffness.norm(), 0.0);
  EXPECT_EQ(out.damping.norm(), 0.0);
  EXPECT_EQ(bolt.forces(u(0), 0.4999).state, BoltState::inactive);

  p.inactive_stiffness = 1e3;
  const BoltedJoint held(p, "bolts[0]");
  held.evaluate(u, v, 0.0, out);
  EXPECT_EQ(out.force, Eigen::VectorXd(1e3 * u));

  const double phi = 0.2, f_a = 10e3;
  EXPECT_EQ(bolt.preload_at(0.5), 0.0);
  EXPECT_NEAR(bolt.preload_at(0.525), 0.25 * p.preload, 1e-9 * p.preload);
  EXPECT_NEAR(bolt.preload_at(0.575), 0.75 * p.preload, 1e-9 * p.preload);
  EXPECT_EQ(bolt.preload_at(0.6), p.preload);
  EXPECT_EQ(bolt.preload_at(50.0), p.preload);
  for (const double t : {0.575, 0.6, 1.0}) {
    const BoltForces b = bolt.forces(opening_under(bolt, f_a, t), t);
    EXPECT_EQ(b.state, BoltState::closed);
    EXPECT_NEAR(b.bolt_force, bolt.preload_at(t) + phi * f_a, 1e-6 * p.preload) << "t = " << t;
  }
  // Early in the ramp (F_V(t) = 5 kN < (1 - Phi) F_A) the same load opens the joint.
  const BoltForces early = bolt.forces(opening_under(bolt, f_a, 0.525), 0.525);
  EXPECT_EQ(early.state, BoltState::open);
  EXPECT_NEAR(early.bolt_force, f_a, 1e-6 * f_a);
  // Shear sticks: k_q u_q + c_q v_q once active.
  bolt.evaluate(u, v, 1.0, out);
  EXPECT_DOUBLE_EQ(out.force(1), 5e7 * u(1));
  EXPECT_DOUBLE_EQ(out.force(2), 5e7 * u(2));
}

// Analytic tangents vs central differences in each branch (closed, open, slack, during the
// ramp), away from the kinks. The law is piecewise linear in u and linear in v, so the
// differences are exact up to rounding, eps |f| / h with |f| <= 3e5 N: in u (h = 1e-10 m)
// 7e-1 N/m against tangents of 1e8...2e9 N/m, < 1e-9; in v (h = 1e-2 m/s, large because the
// law is linear in v) 7e-9 N s/m against c = 200 N s/m, < 1e-10. 1e-7 bounds both.
TEST(BoltedJoint, TangentsMatchCentralDifferences) {
  BoltedJointParams p = m12(0.7);
  p.shear = true;
  p.shear_stiffness = 5e7;
  p.shear_damping = 30.0;
  p.axial_damping = 200.0;
  p.activation_time = 0.0;
  p.preload_ramp = 0.2;
  const BoltedJoint bolt(p, "bolts[0]");
  Eigen::VectorXd v(3);
  v << 0.01, -0.02, 0.03;
  for (const double u_a : {-1e-4, -1e-5, 1e-6, 1e-4}) {  // slack, closed, closed, open
    for (const double t : {0.1, 1.0}) {
      Eigen::VectorXd u(3);
      u << u_a, 3e-6, -1e-6;
      const TangentCheck c = check_tangents(bolt, u, v, t, 1e-10, 1e-2);
      EXPECT_LT(c.stiffness_error, 1e-7) << "u_a = " << u_a << ", t = " << t;
      EXPECT_LT(c.damping_error, 1e-7) << "u_a = " << u_a << ", t = " << t;
    }
  }
}

TEST(BoltedJoint, BadParametersNameTheKey) {
  auto key_of = [](BoltedJointParams p) {
    try {
      BoltedJoint bolt(std::move(p), "bolts[3]");
    } catch (const InputError& e) {
      return e.key_path();
    }
    return std::string("accepted");
  };
  BoltedJointParams p = m12();
  p.bolt_stiffness = -1.0;
  EXPECT_EQ(key_of(p), "bolts[3].bolt_stiffness");
  p = m12(1.2);
  EXPECT_EQ(key_of(p), "bolts[3].load_introduction");
  p = m12();
  p.preload = std::nan("");
  EXPECT_EQ(key_of(p), "bolts[3].preload");
  p = m12();
  p.shear = true;
  EXPECT_EQ(key_of(p), "bolts[3].shear_stiffness");
  p = m12();
  p.preload_ramp = -0.1;
  EXPECT_EQ(key_of(p), "bolts[3].preload_ramp");
  EXPECT_EQ(key_of(m12()), "accepted");
}

// ---------------------------------------------------------------------------------------------
// Bushing

using Mat6 = Eigen::Matrix<double, 6, 6>;

// A rubber bushing: translational 1e6...2e6 N/m, rotational 1e3...2e3 N m/rad, coupled
// x <-> ry (2e4 N/rad) and y <-> rx; positive definite. C = 1e-4 s K (stiffness-proportional).
BushingParams rubber() {
  BushingParams p;
  p.name = "seat";
  p.stiffness.diagonal() << 1e6, 1.2e6, 2e6, 1e3, 1.1e3, 2e3;
  p.stiffness(0, 4) = p.stiffness(4, 0) = 2e4;
  p.stiffness(1, 3) = p.stiffness(3, 1) = -1.5e4;
  p.damping = 1e-4 * p.stiffness;
  return p;
}

// A progressive (end-stop) curve in z: soft within +-1 mm, then stiffening. The averaged-secant
// slopes alone (without the Fritsch-Carlson limit) give a cubic that decreases near -0.6 mm,
// next to the steep end segment: the monotonicity test below fails without the limit.
ForceDeflectionTable end_stop(ForceDeflectionTable::Interpolation kind) {
  return ForceDeflectionTable({-2e-3, -1e-3, 0.0, 1e-3, 1.5e-3, 2e-3},
                              {-20e3, -1e3, 0.0, 1e3, 1.2e3, 20e3}, kind, "bushings[0].tables.z");
}

Eigen::VectorXd state(double scale) {
  Eigen::VectorXd x(6);
  x << 3e-4, -2e-4, 4e-4, 2e-3, -1e-3, 3e-3;
  return scale * x;
}

// Without tables the bushing is K u + C v + f_0 (here f_0 = 0) to rounding (1e-15 relative:
// the same products, possibly summed in another order).
TEST(Bushing, LinearLimitIsKuPlusCv) {
  const BushingParams p = rubber();
  const Bushing b(p, "bushings[0]");
  const Eigen::VectorXd u = state(1.0), v = state(50.0);
  ElementForce out;
  b.evaluate(u, v, 0.0, out);
  const Eigen::VectorXd expected = p.stiffness * u + p.damping * v;
  EXPECT_LT((out.force - expected).cwiseAbs().maxCoeff(), 1e-15 * expected.cwiseAbs().maxCoeff());
  EXPECT_EQ(out.stiffness, Eigen::MatrixXd(p.stiffness));
  EXPECT_EQ(out.damping, Eigen::MatrixXd(p.damping));
}

// A table of a straight line k x is that line everywhere with either interpolation (the
// Fritsch-Carlson slopes of equal secants are the secant), so the bushing equals the linear one
// with K(2, 2) = k; 1e-12 relative bounds the rounding of the cubic basis.
TEST(Bushing, StraightTableEqualsLinearStiffness) {
  for (const auto kind : {ForceDeflectionTable::Interpolation::cubic_hermite,
                          ForceDeflectionTable::Interpolation::linear}) {
    BushingParams p = rubber();
    p.tables[2] = ForceDeflectionTable({-1e-3, 0.0, 0.5e-3, 2e-3}, {-2e3, 0.0, 1e3, 4e3}, kind,
                                       "bushings[0].tables.z");
    const Bushing tabulated(p, "bushings[0]"), linear(rubber(), "bushings[0]");
    for (const double s : {-10.0, -1.0, 0.7, 3.0}) {  // inside and outside the table
      ElementForce a, b;
      tabulated.evaluate(state(s), state(s), 0.0, a);
      linear.evaluate(state(s), state(s), 0.0, b);
      EXPECT_LT((a.force - b.force).norm(), 1e-12 * b.force.norm()) << "scale " << s;
      EXPECT_LT((a.stiffness - b.stiffness).norm(), 1e-12 * b.stiffness.norm());
    }
  }
}

// The table is reproduced at its nodes (exactly: the Hermite basis is 1 and 0 there) and is
// monotone between them (Fritsch & Carlson 1980): 20001 samples of the force never decrease and
// the analytic slope is never negative (-1e-9 N/m allows the rounding of a zero slope).
TEST(Bushing, TableThroughNodesAndMonotone) {
  for (const auto kind : {ForceDeflectionTable::Interpolation::cubic_hermite,
                          ForceDeflectionTable::Interpolation::linear}) {
    const ForceDeflectionTable t = end_stop(kind);
    for (std::size_t k = 0; k < t.deflection().size(); ++k)
      EXPECT_EQ(t.value(t.deflection()[k]), t.force()[k]);
    double last = -std::numeric_limits<double>::infinity();
    for (int s = 0; s <= 20000; ++s) {
      const double x = -2.5e-3 + 5e-3 * s / 20000.0;
      double slope = 0.0;
      const double f = t.value(x, &slope);
      EXPECT_GE(f, last) << "x = " << x;
      EXPECT_GE(slope, -1e-9) << "x = " << x;
      last = f;
    }
  }
  // Through the bushing, the z force at a node is the tabulated force (no coupling in z).
  BushingParams p = rubber();
  p.tables[2] = end_stop(ForceDeflectionTable::Interpolation::cubic_hermite);
  const Bushing b(p, "bushings[0]");
  ElementForce out;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(6), v = u;
  u(2) = 1.5e-3;
  b.evaluate(u, v, 0.0, out);
  EXPECT_EQ(out.force(2), 1.2e3);
}

// At u = v = 0 the force is the preload, with and without tables (a table passes through (0, 0)).
TEST(Bushing, PreloadAtZeroDeflection) {
  BushingParams p = rubber();
  p.preload << 100.0, -50.0, 2e3, 1.0, -2.0, 0.5;
  p.tables[2] = end_stop(ForceDeflectionTable::Interpolation::cubic_hermite);
  p.tables[5] = ForceDeflectionTable({0.0, 0.1}, {0.0, 300.0},
                                     ForceDeflectionTable::Interpolation::linear, "t");
  const Bushing b(p, "bushings[0]");
  ElementForce out;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(6);
  b.evaluate(zero, zero, 0.0, out);
  EXPECT_EQ(out.force, Eigen::VectorXd(p.preload));
}

// Tangents vs central differences away from the table nodes (and so from the linear table's
// kinks). Hermite cubics: truncation h^2 f''' / 6 ~ (1e-10 / 5e-4)^2 ~ 4e-14 relative, round-off
// eps |f| / h ~ 1e-16 * 2e4 N / 1e-10 m = 2e-2 N/m vs entries ~1e6 N/m; linear in v, so
// h_v = 1e-3 m/s: round-off 2e-9 against damping entries ~200 N s/m. 1e-6 bounds both.
TEST(Bushing, TangentsMatchCentralDifferences) {
  for (const auto kind : {ForceDeflectionTable::Interpolation::cubic_hermite,
                          ForceDeflectionTable::Interpolation::linear}) {
    BushingParams p = rubber();
    p.preload(2) = 500.0;
    p.tables[2] = end_stop(kind);
    p.tables[4] = ForceDeflectionTable({-0.01, 0.0, 0.005, 0.01}, {-30.0, 0.0, 3.0, 40.0}, kind,
                                       "bushings[0].tables.ry");
    const Bushing b(p, "bushings[0]");
    for (const double s : {-4.0, 1.0, 4.0}) {  // z = -1.6, 0.4, 1.6 mm; ry = 4, -1, -4 mrad
      const TangentCheck c = check_tangents(b, state(s), state(30.0), 0.0, 1e-10, 1e-3);
      EXPECT_LT(c.stiffness_error, 1e-6) << "scale " << s;
      EXPECT_LT(c.damping_error, 1e-6) << "scale " << s;
    }
  }
}

TEST(Bushing, BadInputNamesTheKey) {
  auto key_of = [](auto make) {
    try {
      make();
    } catch (const InputError& e) {
      return e.key_path();
    }
    return std::string("accepted");
  };
  const auto hermite = ForceDeflectionTable::Interpolation::cubic_hermite;
  EXPECT_EQ(key_of([] {
              BushingParams p = rubber();
              p.stiffness(0, 4) = 3e4;  // asymmetric
              Bushing b(p, "bushings[1]");
            }),
            "bushings[1].stiffness");
  EXPECT_EQ(key_of([] {
              BushingParams p = rubber();
              p.stiffness(0, 4) = p.stiffness(4, 0) = 5e4;  // 1e6 * 1.1e3 < (5e4)^2: indefinite
              Bushing b(p, "bushings[1]");
            }),
            "bushings[1].stiffness");
  EXPECT_EQ(key_of([] {
              BushingParams p = rubber();
              p.damping(2, 2) = -1.0;
              Bushing b(p, "bushings[1]");
            }),
            "bushings[1].damping");
  EXPECT_EQ(key_of([hermite] {
              ForceDeflectionTable t({-1.0, 0.0, 1.0}, {-1.0, 0.0, -0.5}, hermite, "tb");
            }),
            "tb.force");
  EXPECT_EQ(key_of([hermite] {
              ForceDeflectionTable t({-1.0, 0.5, 1.0}, {-1.0, 0.0, 1.0}, hermite, "tb");
            }),
            "tb.deflection");
  EXPECT_EQ(key_of([hermite] {
              ForceDeflectionTable t({0.0, 0.0}, {0.0, 1.0}, hermite, "tb");
            }),
            "tb.deflection");
  EXPECT_EQ(key_of([] { Bushing b(rubber(), "bushings[1]"); }), "accepted");
}

}  // namespace
