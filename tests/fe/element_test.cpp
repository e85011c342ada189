// Unit tests of the element kernels: symmetry, rigid-body null spaces, closed forms, signs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fe_test_support.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/fe/bearing_element.hpp"
#include "geardyn/fe/coupling_element.hpp"
#include "geardyn/fe/dof_map.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/fe/rigid_disk.hpp"
#include "geardyn/fe/timoshenko_beam.hpp"

namespace geardyn::fe {
namespace {

BeamProperties steel_tube(double length) {
  BeamProperties p;
  p.length = length;
  p.outer_diameter = 0.06;
  p.inner_diameter = 0.02;
  p.youngs_modulus = 2.1e11;
  p.shear_modulus = 8.1e10;
  p.density = 7800;
  return p;
}

// Rigid-body motions of a two-node element along e3 with node 2 at z = L (node frame):
// translations, and small rotations a about e1 (uy = -a z), e2 (ux = +a z), e3.
Eigen::Matrix<double, 12, 6> element_rigid_modes(double L) {
  Eigen::Matrix<double, 12, 6> r = Eigen::Matrix<double, 12, 6>::Zero();
  for (int t = 0; t < 3; ++t) r(t, t) = r(6 + t, t) = 1.0;
  r(3, 3) = r(9, 3) = 1.0;
  r(7, 3) = -L;
  r(4, 4) = r(10, 4) = 1.0;
  r(6, 4) = L;
  r(5, 5) = r(11, 5) = 1.0;
  return r;
}

TEST(TimoshenkoBeam, SymmetryAndRigidBodyNullSpace) {
  for (const auto theory : {model::BeamTheory::Timoshenko, model::BeamTheory::EulerBernoulli}) {
    BeamProperties p = steel_tube(0.2);
    p.theory = theory;
    const BeamMatrices b = timoshenko_beam(p);
    EXPECT_NEAR((b.stiffness - b.stiffness.transpose()).norm(), 0.0, 1e-12 * b.stiffness.norm());
    EXPECT_NEAR((b.mass - b.mass.transpose()).norm(), 0.0, 1e-14 * b.mass.norm());
    EXPECT_NEAR((b.gyroscopic + b.gyroscopic.transpose()).norm(), 0.0, 1e-14 * b.gyroscopic.norm());
    EXPECT_GT(b.gyroscopic.norm(), 0.0);
    // K annihilates the six rigid motions; K has exactly six zero eigenvalues; M is positive.
    EXPECT_LT((b.stiffness * element_rigid_modes(p.length)).norm(), 1e-9 * b.stiffness.norm());
    Eigen::SelfAdjointEigenSolver<Matrix12d> ks(b.stiffness);
    const double kmax = ks.eigenvalues().maxCoeff();
    int zero = 0;
    for (int i = 0; i < 12; ++i) zero += std::abs(ks.eigenvalues()(i)) < 1e-10 * kmax ? 1 : 0;
    EXPECT_EQ(zero, 6);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Matrix12d>(b.mass).eigenvalues().minCoeff(), 0.0);
  }
}

TEST(TimoshenkoBeam, MassOfRigidMotions) {
  // r^T M r for a rigid translation is the element mass rho A L; for a rigid spin about e3 it is
  // the polar inertia rho J L (consistent mass reproduces rigid kinetic energy exactly).
  const BeamProperties p = steel_tube(0.3);
  const BeamMatrices b = timoshenko_beam(p);
  const double pi = std::numbers::pi;
  const double A = pi * (0.06 * 0.06 - 0.02 * 0.02) / 4;
  const double J = pi * (std::pow(0.06, 4) - std::pow(0.02, 4)) / 32;
  const auto r = element_rigid_modes(p.length);
  for (int t = 0; t < 3; ++t) {
    EXPECT_NEAR(r.col(t).dot(b.mass * r.col(t)), 7800 * A * 0.3, 1e-12 * 7800 * A * 0.3);
  }
  EXPECT_NEAR(r.col(5).dot(b.mass * r.col(5)), 7800 * J * 0.3, 1e-12 * 7800 * J * 0.3);
}

// Friswell et al. (2010), ch. 5 closed forms for the Timoshenko element in one bending plane,
// DOFs (w1, theta1, w2, theta2), theta = dw/dz: translational mass rho A L / (1 + Phi)^2 [...]
// and rotary mass rho I / (L (1 + Phi)^2) [...]. The element integrates shape functions by
// quadrature instead; both must agree to round-off.
TEST(TimoshenkoBeam, MatchesPublishedClosedForms) {
  BeamProperties p = steel_tube(0.25);
  const BeamMatrices b = timoshenko_beam(p);
  const double L = p.length, phi = b.shear_parameter, f2 = (1 + phi) * (1 + phi);
  const double pi = std::numbers::pi;
  const double A = pi * (0.06 * 0.06 - 0.02 * 0.02) / 4;
  const double I = pi * (std::pow(0.06, 4) - std::pow(0.02, 4)) / 64;
  ASSERT_GT(phi, 0.01);
  const double m1 = 13.0 / 35 + 7 * phi / 10 + phi * phi / 3;
  const double m2 = (11.0 / 210 + 11 * phi / 120 + phi * phi / 24) * L;
  const double m3 = 9.0 / 70 + 3 * phi / 10 + phi * phi / 6;
  const double m4 = -(13.0 / 420 + 3 * phi / 40 + phi * phi / 24) * L;
  const double m5 = (1.0 / 105 + phi / 60 + phi * phi / 120) * L * L;
  const double m6 = -(1.0 / 140 + phi / 60 + phi * phi / 120) * L * L;
  Eigen::Matrix4d mt;
  mt << m1, m2, m3, m4, m2, m5, -m4, m6, m3, -m4, m1, -m2, m4, m6, -m2, m5;
  mt *= 7800 * A * L / f2;
  const double m7 = 6.0 / 5, m8 = (1.0 / 10 - phi / 2) * L;
  const double m9 = (2.0 / 15 + phi / 6 + phi * phi / 3) * L * L;
  const double m10 = (-1.0 / 30 - phi / 6 + phi * phi / 6) * L * L;
  Eigen::Matrix4d mr;
  mr << m7, m8, -m7, m8, m8, m9, -m8, m10, -m7, -m8, m7, -m8, m8, m10, -m8, m9;
  mr *= 7800 * I / (L * f2);
  // e1-e3 plane: (ux1, ry1, ux2, ry2).
  const std::array<int, 4> xz = {0, 4, 6, 10};
  Eigen::Matrix4d m_xz;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      m_xz(i, j) = b.mass(xz[static_cast<std::size_t>(i)], xz[static_cast<std::size_t>(j)]);
  EXPECT_NEAR((m_xz - (mt + mr)).norm(), 0.0, 1e-13 * m_xz.norm());
  // e2-e3 plane: (uy1, rx1, uy2, rx2) with theta = -rx: same matrix with signs flipped.
  const std::array<int, 4> yz = {1, 3, 7, 9};
  const Eigen::Vector4d s(1, -1, 1, -1);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(b.mass(yz[static_cast<std::size_t>(i)], yz[static_cast<std::size_t>(j)]),
                  s(i) * s(j) * (mt + mr)(i, j), 1e-13 * m_xz.norm());
  // The gyroscopic matrix is the rotary mass with rho I -> rho J = 2 rho I, coupling the planes:
  // G(rx_i, ry_j) = 2 M_R^{yz,xz} with the sign pattern of the e2-e3 plane (Friswell ch. 5).
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double expected = -2.0 * s(i) * mr(i, j);
      EXPECT_NEAR(b.gyroscopic(yz[static_cast<std::size_t>(i)], xz[static_cast<std::size_t>(j)]),
                  expected, 1e-13 * mr.norm());
    }
}

TEST(TimoshenkoBeam, EulerBernoulliLimitAndFlags) {
  BeamProperties p = steel_tube(0.4);
  p.theory = model::BeamTheory::EulerBernoulli;
  const BeamMatrices b = timoshenko_beam(p);
  EXPECT_EQ(b.shear_parameter, 0.0);
  const double L = p.length;
  const double EI = 2.1e11 * std::numbers::pi * (std::pow(0.06, 4) - std::pow(0.02, 4)) / 64;
  EXPECT_NEAR(b.stiffness(0, 0), 12 * EI / (L * L * L), 1e-12 * b.stiffness(0, 0));
  EXPECT_NEAR(b.stiffness(4, 4), 4 * EI / L, 1e-12 * b.stiffness(4, 4));
  EXPECT_NEAR(b.stiffness(4, 10), 2 * EI / L, 1e-12 * b.stiffness(4, 4));
  EXPECT_NEAR(b.stiffness(3, 7), 6 * EI / (L * L), 1e-12 * b.stiffness(3, 7));  // -(-6EI/L^2)
  p.rotary_inertia = false;
  p.gyroscopic = false;
  const BeamMatrices c = timoshenko_beam(p);
  EXPECT_EQ(c.gyroscopic.norm(), 0.0);
  EXPECT_NEAR(c.mass(4, 4),
              7800 * std::numbers::pi * (0.06 * 0.06 - 0.02 * 0.02) / 4 * L * L * L / 105,
              1e-12 * c.mass(4, 4));
}

TEST(TimoshenkoBeam, InvalidPropertiesThrow) {
  BeamProperties p = steel_tube(0.2);
  p.inner_diameter = 0.07;
  EXPECT_THROW((void)timoshenko_beam(p), std::invalid_argument);
  p = steel_tube(-1.0);
  EXPECT_THROW((void)timoshenko_beam(p), std::invalid_argument);
}

TEST(CowperShearCoefficient, SolidAndHollowValues) {
  // Cowper (1966): solid circle 6 (1 + nu) / (7 + 6 nu).
  EXPECT_NEAR(cowper_shear_coefficient(0.3, 0.0), 7.8 / 8.8, 1e-15);
  // Friswell et al. Example 5.9.1 quote 0.8863 for E = 211 GPa, G = 81.2 GPa.
  EXPECT_NEAR(cowper_shear_coefficient(211.0 / (2 * 81.2) - 1, 0.0), 0.8863, 5e-5);
  // Thin-walled tube limit m -> 1: 2 (1 + nu) / (4 + 3 nu) (Cowper, Table 1).
  EXPECT_NEAR(cowper_shear_coefficient(0.3, 1.0 - 1e-9), 2 * 1.3 / 4.9, 1e-8);
}

TEST(RigidDisk, MassGyroscopicAndAnnularInertia) {
  const Matrix6d m = rigid_disk_mass(10, 0.2, 0.35);
  EXPECT_EQ(m(0, 0), 10);
  EXPECT_EQ(m(3, 3), 0.2);
  EXPECT_EQ(m(5, 5), 0.35);
  const Matrix6d g = rigid_disk_gyroscopic(0.35);
  EXPECT_EQ(g(3, 4), 0.35);
  EXPECT_EQ(g(4, 3), -0.35);
  EXPECT_EQ((g + g.transpose()).norm(), 0.0);
  EXPECT_EQ(point_mass_matrix(3)(2, 2), 3);
  EXPECT_EQ(point_mass_matrix(3)(3, 3), 0);
  const DiskInertia d = annular_disk_inertia(7810, 0.14, 0.025, 0.07);
  const double mass = 7810 * std::numbers::pi * (0.14 * 0.14 - 0.025 * 0.025) * 0.07;
  EXPECT_NEAR(d.mass, mass, 1e-12 * mass);
  EXPECT_NEAR(d.polar, mass * (0.14 * 0.14 + 0.025 * 0.025) / 2, 1e-12 * d.polar);
  EXPECT_NEAR(d.diametral, mass * (3 * (0.14 * 0.14 + 0.025 * 0.025) + 0.07 * 0.07) / 12,
              1e-12 * d.diametral);
}

TEST(BearingElement, RelativeMotionBetweenRotatedFrames) {
  Matrix6d k = Matrix6d::Zero();
  k.diagonal() << 1e7, 2e7, 3e7, 1e4, 2e4, 3e4;
  k(0, 1) = 5e6;  // cross-coupled, non-symmetric
  const Eigen::Matrix3d R1 = frame_from_axis({0, 0, 1});
  const Eigen::Matrix3d R2 = frame_from_axis({1, 1, 0});
  const Matrix12d e = bearing_between_nodes(k, R1, R2);
  // A common global translation or rotation of both nodes (expressed in each node's frame)
  // produces no force.
  for (int i = 0; i < 6; ++i) {
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g(i % 3) = 1.0;
    Vector12d q = Vector12d::Zero();
    const int block = i < 3 ? 0 : 3;
    q.segment<3>(block) = R1.transpose() * g;
    q.segment<3>(6 + block) = R2.transpose() * g;
    EXPECT_LT((e * q).norm(), 1e-8 * k.norm()) << "motion " << i;
  }
  // Node 2 fixed: the element reduces to k on node 1.
  EXPECT_NEAR((e.topLeftCorner<6, 6>() - k).norm(), 0.0, 0.0);
}

TEST(BearingElement, SpeedInterpolationHeldOutsideTable) {
  const std::vector<double> speeds = {100, 200, 400};
  const std::vector<Matrix6d> values = {Matrix6d::Constant(1), Matrix6d::Constant(3),
                                        Matrix6d::Constant(7)};
  EXPECT_DOUBLE_EQ(interpolate_by_speed(speeds, values, 0.0)(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(interpolate_by_speed(speeds, values, 150.0)(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(interpolate_by_speed(speeds, values, 300.0)(2, 3), 5.0);
  EXPECT_DOUBLE_EQ(interpolate_by_speed(speeds, values, 1e4)(5, 5), 7.0);
}

TEST(CouplingElement, GlobalToNodeFrames) {
  // A global x-spring between two nodes whose frames have e3 = global x: in the node frames it
  // acts on uz (e3 = x).
  std::vector<double> k(144, 0.0);
  k[0] = 1e6;
  k[6] = -1e6;
  k[12 * 6] = -1e6;
  k[12 * 6 + 6] = 1e6;
  const Eigen::Matrix3d R = frame_from_axis({1, 0, 0});
  const Matrix12d a = coupling_between_nodes(k, R, R);
  EXPECT_NEAR(a(2, 2), 1e6, 1e-9);
  EXPECT_NEAR(a(2, 8), -1e6, 1e-9);
  EXPECT_NEAR(a(0, 0), 0.0, 1e-9);
  std::vector<double> g(36, 0.0);
  g[6 * 4 + 4] = 5.0;                                       // global ry
  EXPECT_NEAR(coupling_to_ground(g, R)(3, 3), 5.0, 1e-14);  // e1 = global y
  EXPECT_THROW((void)coupling_to_ground(k, R), std::invalid_argument);
}

// Gear nodes of a spur pair: gear 1 at the origin, gear 2 at (a, 0, 0), both axes along z.
struct SpurPair {
  model::GearMesh mesh;
  NodeInfo gear1, gear2;
  SpurPair() {
    mesh.type = model::GearType::Spur;
    mesh.base_radius1 = 0.05 * std::cos(0.35);
    mesh.base_radius2 = 0.10 * std::cos(0.35);
    mesh.pressure_angle = 0.35;
    mesh.stiffness = 1e8;
    gear1.name = "g1";
    gear1.position = Eigen::Vector3d::Zero();
    gear1.frame = Eigen::Matrix3d::Identity();
    gear1.speed_ratio = 1.0;
    gear2 = gear1;
    gear2.name = "g2";
    gear2.position = Eigen::Vector3d(0.15, 0, 0);
    gear2.speed_ratio = -0.5;
  }
};

TEST(GearMeshElement, SpurGeometryAndLeverArms) {
  const SpurPair pair;
  const GearMeshGeometry g = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  EXPECT_NEAR((g.pitch_point - Eigen::Vector3d(0.05, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((g.tangential - Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-15);
  // Force on gear 2 points along +e_t (driven forward) and +e_r (pushed away).
  EXPECT_NEAR(g.line_of_action.norm(), 1.0, 1e-15);
  EXPECT_NEAR(g.line_of_action.y(), std::cos(0.35), 1e-15);
  EXPECT_NEAR(g.line_of_action.x(), std::sin(0.35), 1e-15);
  const Vector12d v = gear_mesh_vector(g, pair.gear1, pair.gear2);
  EXPECT_NEAR(v(5), pair.mesh.base_radius1, 1e-15);   // rz of gear 1: +r_b1
  EXPECT_NEAR(v(11), pair.mesh.base_radius2, 1e-15);  // rz of gear 2: +r_b2 (opposite rotation)
  // Rigid motion of the pair as one body gives no mesh compression.
  Vector12d rigid = Vector12d::Zero();
  rigid(0) = rigid(6) = 1.0;
  EXPECT_NEAR(v.dot(rigid), 0.0, 1e-15);
  // Kinematic rolling theta2 = -(r_b1 / r_b2) theta1 gives no compression.
  Vector12d rolling = Vector12d::Zero();
  rolling(5) = 1.0;
  rolling(11) = -pair.mesh.base_radius1 / pair.mesh.base_radius2;
  EXPECT_NEAR(v.dot(rolling), 0.0, 1e-15);
}

TEST(GearMeshElement, CoastFlankAndReverseRotationMirrorTheLineOfAction) {
  SpurPair pair;
  const GearMeshGeometry drive = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  pair.mesh.flank = model::Flank::Coast;
  const GearMeshGeometry coast = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  EXPECT_NEAR(coast.line_of_action.y(), -drive.line_of_action.y(), 1e-15);
  EXPECT_NEAR(coast.line_of_action.x(), drive.line_of_action.x(), 1e-15);
  pair.mesh.flank = model::Flank::Drive;
  pair.gear1.speed_ratio = -1.0;
  const GearMeshGeometry reverse = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  EXPECT_NEAR((reverse.line_of_action - coast.line_of_action).norm(), 0.0, 1e-15);
}

TEST(GearMeshElement, HelicalThrustFollowsHandAndFlank) {
  SpurPair pair;
  pair.mesh.type = model::GearType::Helical;
  pair.mesh.helix_angle = 0.3;
  // Base radii of the helical pair at the same pitch radii (transverse pressure angle).
  const double alpha_t = std::atan(std::tan(0.35) / std::cos(0.3));
  pair.mesh.base_radius1 = 0.05 * std::cos(alpha_t);
  pair.mesh.base_radius2 = 0.10 * std::cos(alpha_t);
  const GearMeshGeometry right = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  // Right-hand driver turning positively: thrust on gear 1 along +e_a (screw analogy), so the
  // force on gear 2 has a negative z component; ratio to the tangential part is tan(beta).
  EXPECT_NEAR(-right.line_of_action.z() / right.line_of_action.y(), std::tan(0.3), 1e-14);
  EXPECT_NEAR(right.line_of_action.x() / right.line_of_action.y(), std::tan(0.35) / std::cos(0.3),
              1e-14);
  EXPECT_NEAR(right.transverse_pressure_angle, std::atan(std::tan(0.35) / std::cos(0.3)), 1e-15);
  pair.mesh.hand = model::Hand::Left;
  const GearMeshGeometry left = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  EXPECT_NEAR(left.line_of_action.z(), -right.line_of_action.z(), 1e-15);
  pair.mesh.flank = model::Flank::Coast;
  const GearMeshGeometry left_coast = gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m");
  EXPECT_NEAR(left_coast.line_of_action.z(), right.line_of_action.z(), 1e-15);
  EXPECT_NEAR(left_coast.line_of_action.y(), -right.line_of_action.y(), 1e-15);
}

TEST(GearMeshElement, InvalidGeometryIsInputError) {
  SpurPair pair;
  pair.gear2.position = Eigen::Vector3d(0, 0, 0.3);  // coaxial
  EXPECT_THROW((void)gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m"), InputError);
  // A mesh direction does not make coaxial gears mesh: the centre distance (0) disagrees with
  // the base radii.
  pair.mesh.mesh_direction = model::Vec3{1.0, 0.0, 0.0};
  EXPECT_THROW((void)gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m"), InputError);
  pair.gear2.position = Eigen::Vector3d(0.15, 0, 0.3);  // axially offset: fine
  EXPECT_NO_THROW((void)gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m"));
  pair.mesh.mesh_direction = model::Vec3{0.0, 0.0, 2.0};
  EXPECT_THROW((void)gear_mesh_geometry(pair.mesh, pair.gear1, pair.gear2, "m"), InputError);
  SpurPair bevel;
  bevel.mesh.type = model::GearType::StraightBevel;
  bevel.mesh.pitch_cone_angle1 = 0.4;
  EXPECT_THROW((void)gear_mesh_geometry(bevel.mesh, bevel.gear1, bevel.gear2, "m"), InputError);
  SpurPair bad_angle;
  bad_angle.mesh.pressure_angle = 2.0;
  EXPECT_THROW((void)gear_mesh_geometry(bad_angle.mesh, bad_angle.gear1, bad_angle.gear2, "m"),
               InputError);
}

}  // namespace
}  // namespace geardyn::fe
