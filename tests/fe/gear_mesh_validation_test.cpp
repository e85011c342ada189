// Validation of the gear-mesh element: torsional frequency of a spur pair against the reduced
// inertia closed form, and the bevel / spiral bevel line of action against the tooth-force
// formulas of docs/theory.md §11.2 and the tooth-surface geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "fe_test_support.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn::fe {
namespace {

using model::Component;
constexpr double kPi = std::numbers::pi;

model::GearMesh spur_mesh(std::string gear1, std::string gear2, double base_radius1,
                          double base_radius2, double pressure_angle, double stiffness) {
  model::GearMesh mesh;
  mesh.gear1 = std::move(gear1);
  mesh.gear2 = std::move(gear2);
  mesh.base_radius1 = base_radius1;
  mesh.base_radius2 = base_radius2;
  mesh.pressure_angle = pressure_angle;
  mesh.stiffness = stiffness;
  return mesh;
}

// Two gear inertias on fixed axles, coupled by a spur mesh of stiffness k:
//
//      J1 (r_b1)  )( J2 (r_b2)      only rz free at both nodes
//        o--------||--------o       centre distance r_p1 + r_p2 along x
//
// Mesh compression delta = r_b1 theta1 + r_b2 theta2, so J1 theta1'' + k r_b1 delta = 0,
// J2 theta2'' + k r_b2 delta = 0: one rigid mode and omega^2 = k (r_b1^2 / J1 + r_b2^2 / J2),
// i.e. k / m_e with the reduced mesh mass m_e = J1 J2 / (J1 r_b2^2 + J2 r_b1^2) of docs/theory.md
// (13.3).
TEST(GearMeshValidation, SpurPairTorsionalFrequency) {
  const double alpha = 20.0 * kPi / 180, r_p1 = 0.04, r_p2 = 0.1, k = 3e8;
  const double J1 = 2e-3, J2 = 5e-2;
  for (double ratio : {1.0, -1.0}) {
    model::Model m;
    for (const char* name : {"g1", "g2"}) {
      model::Node n;
      n.name = name;
      m.nodes.push_back(n);
      m.constraints.push_back(test::constrain(
          name, {Component::Ux, Component::Uy, Component::Uz, Component::Rx, Component::Ry}));
    }
    m.nodes[0].speed_ratio = ratio;
    m.nodes[1].speed_ratio = -ratio * r_p1 / r_p2;
    m.nodes[1].position = {r_p1 + r_p2, 0.0, 0.0};
    for (int i = 0; i < 2; ++i) {
      model::Disk d;
      d.node = m.nodes[static_cast<std::size_t>(i)].name;
      d.mass = 1.0;
      d.diametral_inertia = 1.0;
      d.polar_inertia = i == 0 ? J1 : J2;
      m.disks.push_back(d);
    }
    m.gear_meshes.push_back(
        spur_mesh("g1", "g2", r_p1 * std::cos(alpha), r_p2 * std::cos(alpha), alpha, k));
    const model::GearMesh& mesh = m.gear_meshes.back();
    const LinearSystem s = assemble(m);
    ASSERT_EQ(s.size(), 2);
    const Eigen::VectorXd w = test::undamped_frequencies(s);
    const double rb1 = mesh.base_radius1, rb2 = mesh.base_radius2;
    const double exact = std::sqrt(k * (rb1 * rb1 / J1 + rb2 * rb2 / J2));
    EXPECT_LT(w(0), 1e-6 * exact);
    // Tolerance: round-off of a 2x2 eigenproblem.
    EXPECT_LT(test::relative_error(w(1), exact), 1e-12) << w(1) << " vs " << exact;
  }
}

// Straight bevel pair, shaft angle 90 deg, apex at the origin:
//
//           z ^ pinion axis (e_a = +z), pinion node at (0, 0, -r_m2)
//             |
//   apex  ----o------------> x   gear axis along x, gear node at (r_m1, 0, 0)
//             |      P = (r_m1, 0, -r_m2), mean pitch point
//
// z1 = 20, z2 = 40 (pitch cone delta1 = atan(20/40)), alpha = 20 deg, F_t = 5000 N:
// F_a = F_t tan(alpha) sin(delta1) = 813.862186 N (pinion pushed away from the apex, -z),
// F_r = F_t tan(alpha) cos(delta1) = 1627.724371 N (towards the pinion axis) (docs/theory.md
// (11.3); e.g. Budynas & Nisbett, Shigley's Mechanical Engineering Design, ch. 13, bevel-gear force
// analysis).
struct BevelPair {
  model::GearMesh mesh;
  NodeInfo pinion, gear;
  static constexpr double r_m1 = 0.05, r_m2 = 0.10;
  explicit BevelPair(model::GearType type) {
    mesh.type = type;
    mesh.teeth1 = 20;
    mesh.teeth2 = 40;
    mesh.pressure_angle = 20.0 * kPi / 180;
    mesh.pitch_cone_angle1 = std::atan(20.0 / 40.0);
    mesh.pitch_cone_angle2 = std::atan(40.0 / 20.0);
    mesh.stiffness = 1e8;
    pinion.name = "pinion";
    pinion.position = Eigen::Vector3d(0, 0, -r_m2);
    pinion.frame = frame_from_axis({0, 0, 1});
    pinion.speed_ratio = 1.0;
    gear.name = "gear";
    gear.position = Eigen::Vector3d(r_m1, 0, 0);
    gear.frame = frame_from_axis({1, 0, 0});
    gear.speed_ratio = -0.5;
  }
  void set_base_radius(double transverse_pressure_angle) {
    mesh.base_radius1 = r_m1 * std::cos(transverse_pressure_angle);
    mesh.base_radius2 = r_m2 * std::cos(transverse_pressure_angle);
  }
};

TEST(GearMeshValidation, StraightBevelLineOfActionMatchesToothForces) {
  BevelPair pair(model::GearType::StraightBevel);
  pair.set_base_radius(pair.mesh.pressure_angle);
  const GearMeshGeometry g = gear_mesh_geometry(pair.mesh, pair.pinion, pair.gear, "m");
  EXPECT_NEAR((g.pitch_point - Eigen::Vector3d(BevelPair::r_m1, 0, -BevelPair::r_m2)).norm(), 0.0,
              1e-15);
  EXPECT_NEAR((g.axial - Eigen::Vector3d(0, 0, -1)).norm(), 0.0, 1e-15);  // apex -> pinion
  const double Ft = 5000.0, Fa = 813.862186, Fr = 1627.724371;
  const double F = std::sqrt(Ft * Ft + Fa * Fa + Fr * Fr);
  // Force on the pinion: -e_t F_t + F_a u_a - F_r e_r; n is the force on the gear.
  const Eigen::Vector3d& n = g.line_of_action;
  EXPECT_NEAR(n.dot(g.tangential), Ft / F, 1e-9);
  EXPECT_NEAR(n.dot(g.axial), -Fa / F, 1e-9);
  EXPECT_NEAR(n.dot(g.radial), Fr / F, 1e-9);
  // Tolerance 1e-9: the reference forces are given to 1e-6 N on 5000 N.
  EXPECT_NEAR(g.axial_force * Ft, Fa, 1e-5);
  EXPECT_NEAR(g.radial_force * Ft, Fr, 1e-5);
  // The same pair seen from the gear's side: the axial thrust on the gear is the radial force
  // on the pinion (Shigley: W_a(gear) = W_r(pinion) for a 90 deg shaft angle).
  model::GearMesh reversed = pair.mesh;
  reversed.pitch_cone_angle1 = pair.mesh.pitch_cone_angle2;
  reversed.base_radius1 = BevelPair::r_m2 * std::cos(pair.mesh.pressure_angle);
  reversed.base_radius2 = BevelPair::r_m1 * std::cos(pair.mesh.pressure_angle);
  std::swap(reversed.teeth1, reversed.teeth2);
  const GearMeshGeometry h = gear_mesh_geometry(reversed, pair.gear, pair.pinion, "m");
  EXPECT_NEAR(h.axial_force * Ft, Fr, 1e-5);
  EXPECT_NEAR(h.radial_force * Ft, Fa, 1e-5);
  EXPECT_NEAR((h.pitch_point - g.pitch_point).norm(), 0.0, 1e-15);
}

// Spiral bevel: the line of action must be normal to the tooth surface at P. At mid face the
// tooth line lies in the pitch-cone tangent plane at the spiral angle beta from the cone
// generator g (pointing away from the apex); right hand (AGMA): the tooth advances in the sense
// of positive rotation about u_a when moving outward, h = cos(beta) g + sin(beta) e_t(u_a).
// The normal makes the normal pressure angle alpha_n with the tangent plane. docs/theory.md
// (11.3)'s formulas with the upper signs must hold for a right-hand driver turning positively about
// u_a.
TEST(GearMeshValidation, SpiralBevelLineOfActionIsNormalToTheTooth) {
  const double beta = 35.0 * kPi / 180, alpha = 20.0 * kPi / 180;
  for (const model::Hand hand : {model::Hand::Right, model::Hand::Left}) {
    for (const double rotation : {1.0, -1.0}) {
      BevelPair pair(model::GearType::SpiralBevel);
      pair.mesh.helix_angle = beta;
      pair.mesh.hand = hand;
      pair.pinion.speed_ratio = rotation;
      pair.set_base_radius(std::atan(std::tan(alpha) / std::cos(beta)));
      const GearMeshGeometry g = gear_mesh_geometry(pair.mesh, pair.pinion, pair.gear, "m");
      EXPECT_NEAR((g.pitch_point - Eigen::Vector3d(BevelPair::r_m1, 0, -BevelPair::r_m2)).norm(),
                  0.0, 1e-14);
      const double delta = pair.mesh.pitch_cone_angle1;
      const Eigen::Vector3d u_a = g.axial, e_r = g.radial;
      const Eigen::Vector3d e_t_ua = u_a.cross(e_r);
      const Eigen::Vector3d generator = std::cos(delta) * u_a + std::sin(delta) * e_r;
      const Eigen::Vector3d cone_normal = std::cos(delta) * e_r - std::sin(delta) * u_a;
      const double h = hand == model::Hand::Right ? 1.0 : -1.0;
      const Eigen::Vector3d tooth_line = std::cos(beta) * generator + h * std::sin(beta) * e_t_ua;
      const Eigen::Vector3d& n = g.line_of_action;
      EXPECT_NEAR(n.dot(tooth_line), 0.0, 1e-14);
      EXPECT_NEAR(std::abs(n.dot(cone_normal)), std::sin(alpha), 1e-14);
      // The force on the pinion presses it towards its axis (separating), i.e. n . m > 0.
      EXPECT_GT(n.dot(cone_normal), 0.0);
      // The pinion turns positively about u_a iff rotation * (u_a . e_a) > 0; with the hand
      // this selects the sign in docs/theory.md (11.3).
      const double s = h * rotation * u_a.dot(pair.pinion.frame.col(2));
      EXPECT_NEAR(g.axial_force,
                  (std::tan(alpha) * std::sin(delta) + s * std::sin(beta) * std::cos(delta)) /
                      std::cos(beta),
                  1e-14);
      EXPECT_NEAR(g.radial_force,
                  (std::tan(alpha) * std::cos(delta) - s * std::sin(beta) * std::sin(delta)) /
                      std::cos(beta),
                  1e-14);
      // Tangential part opposes the pinion's rotation.
      EXPECT_NEAR(n.dot(g.tangential) * rotation, std::cos(alpha) * std::cos(beta), 1e-14);
    }
  }
}

}  // namespace
}  // namespace geardyn::fe
