// Unit tests of global assembly: null space and mass of free rotors in arbitrary orientation,
// damping models, speed-dependent bearings, loads and input errors.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "fe_test_support.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::fe {
namespace {

using model::Component;
constexpr double kPi = std::numbers::pi;

// A free hollow shaft along `axis` (4 elements, 5 nodes) with a disk at s.2 and a point mass at
// s.4; no supports.
model::Model free_rotor(const model::Vec3& axis) {
  model::Model m;
  m.materials.push_back(test::material("steel", 2.1e11, 8.1e10, 7800));
  model::Shaft s = test::uniform_shaft("s", "steel", 0.8, 0.05, 4, 0.01);
  s.axis = axis;
  s.origin = {0.1, -0.2, 0.3};
  s.speed_ratio = 1.5;
  m.shafts.push_back(s);
  model::Disk d;
  d.node = "s.2";
  d.mass = 4.0;
  d.polar_inertia = 0.02;
  d.diametral_inertia = 0.011;
  m.disks.push_back(d);
  model::PointMass pm;
  pm.node = "s.4";
  pm.mass = 0.5;
  m.point_masses.push_back(pm);
  return m;
}

double shaft_mass() { return 7800 * kPi * (0.05 * 0.05 - 0.01 * 0.01) / 4 * 0.8; }
double shaft_polar() { return 7800 * kPi * (std::pow(0.05, 4) - std::pow(0.01, 4)) / 32 * 0.8; }

// Global rigid motion i (0..2 translation along global axis i, 3..5 small rotation about global
// axis i through the origin) expressed in the node frames and equation numbering.
Eigen::VectorXd rigid_motion(const LinearSystem& s, int i) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(s.size());
  for (int n = 0; n < s.dofs.num_nodes(); ++n) {
    const NodeInfo& node = s.dofs.node(n);
    Eigen::Vector3d u = Eigen::Vector3d::Zero(), theta = Eigen::Vector3d::Zero();
    if (i < 3) {
      u(i) = 1.0;
    } else {
      theta(i - 3) = 1.0;
      u = theta.cross(node.position);
    }
    const Eigen::Vector3d un = node.frame.transpose() * u, tn = node.frame.transpose() * theta;
    for (int c = 0; c < 6; ++c) {
      const int e = s.dofs.dof(n, static_cast<Component>(c));
      if (e >= 0) q(e) = c < 3 ? un(c) : tn(c - 3);
    }
  }
  return q;
}

TEST(Assembly, FreeRotorHasSixRigidBodyModesInAnyOrientation) {
  for (const model::Vec3& axis :
       {model::Vec3{0, 0, 1}, model::Vec3{1, 0, 0}, model::Vec3{0.3, -0.5, 0.8}}) {
    const LinearSystem s = assemble(free_rotor(axis));
    ASSERT_EQ(s.size(), 5 * 6);
    const Eigen::MatrixXd K = Eigen::MatrixXd(s.K);
    EXPECT_NEAR((K - K.transpose()).norm(), 0.0, 1e-12 * K.norm());
    for (int i = 0; i < 6; ++i) {
      EXPECT_LT((K * rigid_motion(s, i)).norm(), 1e-9 * K.norm()) << "rigid motion " << i;
    }
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(K);
    int zero = 0;
    for (int i = 0; i < K.rows(); ++i)
      zero += std::abs(eig.eigenvalues()(i)) < 1e-10 * K.norm() ? 1 : 0;
    EXPECT_EQ(zero, 6);
    // Total mass seen by every global translation.
    const double total = shaft_mass() + 4.0 + 0.5;
    for (int i = 0; i < 3; ++i) {
      const Eigen::VectorXd r = rigid_motion(s, i);
      EXPECT_NEAR(r.dot(s.M * r), total, 1e-12 * total);
    }
    // Spin inertia about the shaft axis through the shaft's origin-line: shaft + disk polar.
    Eigen::VectorXd spin = Eigen::VectorXd::Zero(s.size());
    for (int n = 0; n < 5; ++n) spin(s.dofs.dof(n, Component::Rz)) = 1.0;
    EXPECT_NEAR(spin.dot(s.M * spin), shaft_polar() + 0.02, 1e-12);
    // G is skew and carries the speed ratio: disk term 1.5 x Ip.
    const Eigen::MatrixXd G = Eigen::MatrixXd(s.G);
    EXPECT_NEAR((G + G.transpose()).norm(), 0.0, 1e-15);
    const int rx = s.dofs.dof(2, Component::Rx), ry = s.dofs.dof(2, Component::Ry);
    const Eigen::MatrixXd G_shaft_only = Eigen::MatrixXd(assemble([&] {
                                                           model::Model m = free_rotor(axis);
                                                           m.disks.clear();
                                                           return m;
                                                         }())
                                                             .G);
    EXPECT_NEAR(G(rx, ry) - G_shaft_only(rx, ry), 1.5 * 0.02, 1e-15);
  }
}

TEST(Assembly, ConstraintsRemoveRowsAndColumns) {
  model::Model m = free_rotor({0, 0, 1});
  const LinearSystem full = assemble(m);
  m.constraints.push_back(test::constrain("s.0", {Component::Ux, Component::Uy}));
  const LinearSystem reduced = assemble(m);
  ASSERT_EQ(reduced.size(), full.size() - 2);
  const Eigen::MatrixXd Kf = Eigen::MatrixXd(full.K), Kr = Eigen::MatrixXd(reduced.K);
  for (int i = 0; i < reduced.size(); ++i)
    for (int j = 0; j < reduced.size(); ++j) EXPECT_EQ(Kr(i, j), Kf(i + 2, j + 2));
}

TEST(Assembly, RayleighAndStructuralDamping) {
  model::Model m = free_rotor({0, 0, 1});
  m.bearings.push_back(test::lateral_bearing("s.0", 1e6));
  m.shafts[0].elements[0].loss_factor = 0.01;
  m.damping.rayleigh_alpha = 2.0;
  m.damping.rayleigh_beta = 1e-5;
  m.damping.loss_factor = 0.002;
  const LinearSystem s = assemble(m);
  const Eigen::MatrixXd C = Eigen::MatrixXd(s.C), M = Eigen::MatrixXd(s.M),
                        K = Eigen::MatrixXd(s.K);
  EXPECT_NEAR((C - 2.0 * M - 1e-5 * K).norm(), 0.0, 1e-12 * C.norm());
  // K_loss = 0.002 K + 0.01 K_shaft; the bearing only gets the global part.
  m.shafts[0].elements[0].loss_factor = 0.0;
  m.bearings.clear();
  m.disks.clear();
  m.point_masses.clear();
  const Eigen::MatrixXd K_shaft = Eigen::MatrixXd(assemble(m).K);
  const Eigen::MatrixXd K_loss = Eigen::MatrixXd(s.K_loss);
  EXPECT_NEAR((K_loss - 0.002 * K - 0.01 * K_shaft).norm(), 0.0, 1e-12 * K_loss.norm());
}

TEST(Assembly, SpeedDependentBearingInterpolates) {
  model::Model m = free_rotor({0, 0, 1});
  model::Bearing b;
  b.node = "s.0";
  b.speeds = {100.0, 300.0};
  model::Bearing::Matrix6 k1{}, k2{}, c1{}, c2{};
  k1[0] = 1e6;
  k2[0] = 3e6;
  k1[1] = 1e5;  // kxy, cross-coupled
  c1[7] = 100;
  c2[7] = 300;
  b.stiffness = {k1, k2};
  b.damping = {c1, c2};
  m.bearings.push_back(b);
  const LinearSystem s = assemble(m);
  ASSERT_EQ(s.speed_bearings.size(), 1u);
  const int ux = s.dofs.dof(0, Component::Ux), uy = s.dofs.dof(0, Component::Uy);
  const double base = s.K.coeff(ux, ux);
  EXPECT_NEAR(s.K_at(200.0).coeff(ux, ux) - base, 2e6, 1e-6);
  EXPECT_NEAR(s.K_at(200.0).coeff(ux, uy) - s.K.coeff(ux, uy), 0.5e5, 1e-6);
  EXPECT_NEAR(s.K_at(0.0).coeff(ux, ux) - base, 1e6, 1e-6);
  EXPECT_NEAR(s.K_at(1e4).coeff(ux, ux) - base, 3e6, 1e-6);
  EXPECT_NEAR(s.C_at(150.0).coeff(uy, uy), 150.0, 1e-9);
  // damping_dense adds speed x G.
  const Eigen::MatrixXd D = s.damping_dense(250.0);
  EXPECT_NEAR((D - Eigen::MatrixXd(s.C_at(250.0)) - 250.0 * Eigen::MatrixXd(s.G)).norm(), 0.0,
              1e-9);
}

TEST(Assembly, NodeToNodeBearingActsOnRelativeMotion) {
  model::Model m;
  for (const char* name : {"a", "b"}) {
    model::Node n;
    n.name = name;
    m.nodes.push_back(n);
  }
  m.nodes[1].position = {0, 0, 1};
  model::Bearing b;
  b.node = "a";
  b.node2 = "b";
  model::Bearing::Matrix6 k{};
  k[35] = 5e3;  // ktzz
  b.stiffness = {k};
  m.bearings.push_back(b);
  const LinearSystem s = assemble(m);
  const int a = s.dofs.dof(0, Component::Rz), c = s.dofs.dof(1, Component::Rz);
  EXPECT_EQ(s.K.coeff(a, a), 5e3);
  EXPECT_EQ(s.K.coeff(a, c), -5e3);
  EXPECT_EQ(s.K.coeff(c, c), 5e3);
  EXPECT_EQ(s.K.nonZeros(), 4);
}

TEST(Assembly, ModalDampingTermInDenseDamping) {
  LinearSystem s = assemble(free_rotor({0, 0, 1}));
  s.modal_basis = Eigen::MatrixXd::Random(s.size(), 2);
  s.modal_coefficients = Eigen::Vector2d(3.0, 4.0);
  const Eigen::MatrixXd extra = s.damping_dense(0.0) - Eigen::MatrixXd(s.C);
  EXPECT_NEAR(
      (extra - s.modal_basis * Eigen::Vector2d(3, 4).asDiagonal() * s.modal_basis.transpose())
          .norm(),
      0.0, 1e-12);
}

TEST(Loads, UnitLoadAndConstrainedDof) {
  model::Model m = free_rotor({0, 0, 1});
  m.constraints.push_back(test::constrain("s.1", {Component::Uz}));
  const LinearSystem s = assemble(m);
  const Eigen::VectorXd f = s.unit_load(1, Component::Ry);
  EXPECT_EQ(f.sum(), 1.0);
  EXPECT_EQ(f(s.dofs.dof(1, Component::Ry)), 1.0);
  EXPECT_THROW((void)s.unit_load(1, Component::Uz), InputError);
}

TEST(Loads, UnbalanceRotatesWithSpinSense) {
  model::Model m = free_rotor({0, 0, 1});
  model::Shaft second = test::uniform_shaft("t", "steel", 0.2, 0.03, 1);
  second.origin = {0.5, 0, 0};
  second.speed_ratio = -2.0;
  m.shafts.push_back(second);
  model::Unbalance u1;
  u1.name = "u1";
  u1.node = "s.2";
  u1.mass_eccentricity = 1e-4;
  u1.phase = 0.3;
  model::Unbalance u2 = u1;
  u2.name = "u2";
  u2.node = "t.1";
  m.unbalances = {u1, u2};
  const LinearSystem s = assemble(m);
  const double speed = 100.0;

  const std::vector<double> orders = unbalance_orders(m, s);
  ASSERT_EQ(orders.size(), 2u);
  EXPECT_DOUBLE_EQ(orders[0], 1.5);
  EXPECT_DOUBLE_EQ(orders[1], 2.0);
  EXPECT_EQ(unbalance_orders(m, s, {"u2"}), std::vector<double>{2.0});

  // Shaft s spins positively at 1.5 x speed: F_x = m e w^2 e^{i phi}, F_y = -i F_x, i.e.
  // F(t) = m e w^2 (cos(w t + phi), sin(w t + phi)) turning counter-clockwise about e3.
  const Eigen::VectorXcd f1 = unbalance_load(m, s, speed, 1.5);
  const double w1 = 1.5 * speed;
  const std::complex<double> fx = f1(s.dofs.dof(2, Component::Ux));
  const std::complex<double> fy = f1(s.dofs.dof(2, Component::Uy));
  EXPECT_NEAR(std::abs(fx - 1e-4 * w1 * w1 * std::polar(1.0, 0.3)), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(fy - std::complex<double>(0, -1) * fx), 0.0, 1e-12);
  EXPECT_NEAR(f1.norm(), std::sqrt(2.0) * 1e-4 * w1 * w1, 1e-12);  // u2 not at order 1.5
  // Shaft t spins negatively at 2 x speed: mirrored, F_y = +i F_x.
  const Eigen::VectorXcd f2 = unbalance_load(m, s, speed, 2.0);
  const int t1 = s.dofs.node_index("t.1");
  const std::complex<double> gx = f2(s.dofs.dof(t1, Component::Ux));
  const std::complex<double> gy = f2(s.dofs.dof(t1, Component::Uy));
  EXPECT_NEAR(std::abs(gx), 1e-4 * 4 * speed * speed, 1e-12);
  EXPECT_NEAR(std::abs(gy - std::complex<double>(0, 1) * gx), 0.0, 1e-12);
  EXPECT_EQ(unbalance_load(m, s, speed, 2.0, {"u1"}).norm(), 0.0);
  EXPECT_THROW((void)unbalance_load(m, s, speed, 1.5, {"nope"}), InputError);
}

TEST(ModeFamilies, FractionsSumToOne) {
  const LinearSystem s = assemble(free_rotor({0, 0, 1}));
  Eigen::VectorXcd torsion = Eigen::VectorXcd::Zero(s.size());
  for (int n = 0; n < 5; ++n) torsion(s.dofs.dof(n, Component::Rz)) = 1.0;
  const ModeFamilies t = mode_families(s, torsion);
  EXPECT_DOUBLE_EQ(t.torsional, 1.0);
  EXPECT_DOUBLE_EQ(t.lateral + t.axial, 0.0);
  const Eigen::VectorXcd mixed = Eigen::VectorXcd::Random(s.size());
  const ModeFamilies f = mode_families(s, mixed);
  EXPECT_NEAR(f.lateral + f.axial + f.torsional, 1.0, 1e-15);
  EXPECT_GT(f.lateral, f.axial);
}

TEST(AssemblyErrors, BadReferencesAreInputErrors) {
  {
    model::Model m = free_rotor({0, 0, 1});
    m.shafts[0].material = "unobtainium";
    EXPECT_THROW((void)assemble(m), InputError);
  }
  {
    model::Model m = free_rotor({0, 0, 1});
    m.disks[0].node = "s.9";
    EXPECT_THROW((void)assemble(m), InputError);
  }
  {
    model::Model m = free_rotor({0, 0, 1});
    model::Bearing b = test::lateral_bearing("s.0", 1e6);
    b.speeds = {1.0, 2.0};  // one stiffness matrix for two speeds
    m.bearings.push_back(b);
    EXPECT_THROW((void)assemble(m), InputError);
  }
  {
    model::Model m = free_rotor({0, 0, 1});
    model::Coupling c;
    c.node1 = "s.0";
    c.node2 = "s.1";
    c.stiffness.assign(36, 0.0);  // node-to-node needs 144
    m.couplings.push_back(c);
    EXPECT_THROW((void)assemble(m), InputError);
  }
  {
    model::Model m = free_rotor({0, 0, 1});
    m.shafts[0].elements[0].inner_diameter = 0.06;
    EXPECT_THROW((void)assemble(m), InputError);
  }
}

}  // namespace
}  // namespace geardyn::fe
