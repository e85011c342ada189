// Gear meshes use both base radii: the gear ratio of a geared torsional system is r_b1 / r_b2
// whatever rounding the node coordinates carry, and node positions that disagree with the base
// radii and the pressure angle are refused with a located message.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>

#include "geardyn/analyses/model_file.hpp"
#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"
#include "geardyn/fe/linear_system.hpp"

namespace geardyn {
namespace {

constexpr double kDeg = units::kRadPerDegree;

// Branched torsional system: pinion g1 (J1, r_b1) drives an external helical gear g2 (J2, r_b2)
// and an internal spur ring g3 (J3, r_b3). Only the rotations about z are free.
//
//            g3 centre (ring, internal mesh along +y from g1)
//               |
//     g1 o------+-------o g2        external mesh along +x
//
// The node coordinates are deliberately off the exact centre distances by 8e-4 and -6e-4
// (inside the 1e-3 tolerance): the old element took gear 2's lever arm from the node positions
// and gave a gear ratio off by about 1e-3.
struct Branched {
  double J1 = 2e-3, J2 = 3e-2, J3 = 8e-2;
  double rb1 = 0.030, rb2 = 0.048, rb3 = 0.110;
  double alpha_n = 20 * kDeg, beta = 15 * kDeg, alpha_spur = 22.5 * kDeg;
  double k_a = 4e8, k_b = 6e8;  // mesh stiffnesses [N/m]

  double alpha_t() const { return std::atan(std::tan(alpha_n) / std::cos(beta)); }
  double cos_beta_b() const { return std::cos(std::atan(std::tan(beta) * std::cos(alpha_t()))); }

  std::string toml() const {
    const double a12 = (rb1 + rb2) / std::cos(alpha_t()) * (1 + 8e-4);
    const double a13 = (rb3 - rb1) / std::cos(alpha_spur) * (1 - 6e-4);
    return fmt::format(R"(version = 1
title = "branched torsional gear train"

[[nodes]]
name = "g1"
position = [0.0, 0.0, 0.0]

[[nodes]]
name = "g2"
position = [{:.17g}, 0.0, 0.0]

[[nodes]]
name = "g3"
position = [0.0, {:.17g}, 0.0]

[[disks]]
node = "g1"
mass = 1.0
diametral_inertia = 1.0
polar_inertia = {}

[[disks]]
node = "g2"
mass = 1.0
diametral_inertia = 1.0
polar_inertia = {}

[[disks]]
node = "g3"
mass = 1.0
diametral_inertia = 1.0
polar_inertia = {}

[[constraints]]
node = "g1"
dofs = ["ux", "uy", "uz", "rx", "ry"]

[[constraints]]
node = "g2"
dofs = ["ux", "uy", "uz", "rx", "ry"]

[[constraints]]
node = "g3"
dofs = ["ux", "uy", "uz", "rx", "ry"]

[[gear_meshes]]
name = "external"
gear1 = "g1"
gear2 = "g2"
type = "helical"
base_radius1 = {}
base_radius2 = {}
pressure_angle_deg = 20
helix_angle_deg = 15
stiffness = {}

[[gear_meshes]]
name = "ring"
gear1 = "g1"
gear2 = "g3"
type = "spur"
base_radius1 = {}
base_radius2 = {}
pressure_angle_deg = 22.5
mesh_direction = [0.0, 1.0, 0.0]
stiffness = {}
)",
                       a12, -a13, J1, J2, J3, rb1, rb2, k_a, rb1, rb3, k_b);
  }
};

// Undamped frequencies and modes of the 3x3 torsional system (dense, generalised symmetric).
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solve(const fe::LinearSystem& s) {
  const Eigen::MatrixXd K(s.K), M(s.M);
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(K, M);
}

// Reference: equations of motion of geared torsional systems with flexible meshes, the mesh
// compression along the line of action being delta = r_b1 theta1 +- r_b2 theta2 (W. T. Thomson
// and M. D. Dahleh, Theory of Vibration with Applications, 5th ed., 1998, geared systems: the
// gear ratio is the ratio of the base radii, inertias reflect with its square). For a helical
// mesh the torsional lever arm is r_b cos(beta_b) (the line of action lies in the plane of
// action, inclined by the base helix angle; ISO 21771:2007). With p = k_a cos^2(beta_b),
// q = k_b: K = p w_a w_a^T + q w_b w_b^T, w_a = (r1, r2, 0), w_b = (r1, 0, -r3); one rigid
// mode theta = (1, -r1/r2, r1/r3) and omega^4 - T omega^2 + S = 0 with
//   T = (p + q) r1^2 / J1 + p r2^2 / J2 + q r3^2 / J3,
//   S = p q (r1^2 r2^2 / (J1 J2) + r1^2 r3^2 / (J1 J3) + r2^2 r3^2 / (J2 J3)).
TEST(GearMeshRatio, BranchedTorsionalSystemFollowsTheBaseRadii) {
  const Branched b;
  const model::Model m = analyses::parse_model(b.toml(), "branched.toml");
  const fe::LinearSystem s = fe::assemble(m);
  ASSERT_EQ(s.size(), 3);
  const auto eig = solve(s);
  const Eigen::Vector3d w2 = eig.eigenvalues().head<3>();

  const double p = b.k_a * b.cos_beta_b() * b.cos_beta_b(), q = b.k_b;
  const double r1 = b.rb1, r2 = b.rb2, r3 = b.rb3;
  const double T = (p + q) * r1 * r1 / b.J1 + p * r2 * r2 / b.J2 + q * r3 * r3 / b.J3;
  const double S = p * q *
                   (r1 * r1 * r2 * r2 / (b.J1 * b.J2) + r1 * r1 * r3 * r3 / (b.J1 * b.J3) +
                    r2 * r2 * r3 * r3 / (b.J2 * b.J3));
  const double root = std::sqrt(T * T - 4 * S);
  const double lo = (T - root) / 2, hi = (T + root) / 2;
  // Tolerances: round-off of a 3x3 eigenproblem whose entries span 1e5 .. 1e9 (condition of
  // the stiffness scale): 1e-10 relative on omega^2; the rigid root to 1e-10 of the largest.
  EXPECT_LT(std::abs(w2(0)), 1e-10 * hi);
  EXPECT_NEAR(w2(1), lo, 1e-10 * lo);
  EXPECT_NEAR(w2(2), hi, 1e-10 * hi);

  // The rigid mode is the gear train turning: theta2 / theta1 = -r_b1 / r_b2 (external mesh,
  // opposite sense), theta3 / theta1 = +r_b1 / r_b3 (internal, same sense). Node positions
  // 8e-4 off would change the old position-based ratio by ~1e-3; round-off only here: 1e-10.
  const auto& dofs = s.dofs;
  auto rz = [&](const char* node) { return dofs.dof(dofs.node_index(node), model::Component::Rz); };
  const Eigen::VectorXd rigid = eig.eigenvectors().col(0);
  const double t1 = rigid(rz("g1")), t2 = rigid(rz("g2")), t3 = rigid(rz("g3"));
  EXPECT_NEAR(t2 / t1, -r1 / r2, 1e-10);
  EXPECT_NEAR(t3 / t1, r1 / r3, 1e-10);
}

// Torsional lever arms in the element vector itself: r_b cos(beta_b) at both gears.
TEST(GearMeshRatio, LeverArmsAreTheBaseRadii) {
  const Branched b;
  const model::Model m = analyses::parse_model(b.toml(), "branched.toml");
  const fe::LinearSystem s = fe::assemble(m);
  const auto& dofs = s.dofs;
  for (int mesh = 0; mesh < 2; ++mesh) {
    const model::GearMesh& g = m.gear_meshes[static_cast<std::size_t>(mesh)];
    const fe::NodeInfo& n1 = dofs.node(dofs.node_index(g.gear1));
    const fe::NodeInfo& n2 = dofs.node(dofs.node_index(g.gear2));
    const fe::GearMeshGeometry geo = fe::gear_mesh_geometry(g, n1, n2, "m");
    const fe::Vector12d v = fe::gear_mesh_vector(geo, n1, n2);
    const double c = mesh == 0 ? b.cos_beta_b() : 1.0;
    // Round-off of the geometry (acos of a ratio near 1): 1e-12 relative.
    EXPECT_NEAR(std::abs(v(5)), g.base_radius1 * c, 1e-12 * g.base_radius1);
    EXPECT_NEAR(std::abs(v(11)), g.base_radius2 * c, 1e-12 * g.base_radius2);
    // The pitch point divides the centre distance in the ratio of the base radii.
    const double a = (n2.position - n1.position).norm();
    const double expected_rp1 =
        a * g.base_radius1 /
        (mesh == 0 ? g.base_radius1 + g.base_radius2 : g.base_radius2 - g.base_radius1);
    EXPECT_NEAR(geo.pitch_radius1, expected_rp1, 1e-12 * expected_rp1);
  }
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

InputError assemble_error(const std::string& text) {
  const model::Model m = analyses::parse_model(text, "bad.toml");
  try {
    (void)fe::assemble(m);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError({}, "", "", "");
}

int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

// The issue's case: a centre distance that does not match the base radii (here base_radius2
// 0.054 instead of 0.048, 1.2 % of the centre distance) used to give a wrong gear ratio
// silently; it is refused at the mesh's table, naming the expected and the found distance.
TEST(GearMeshRatio, InconsistentCentreDistanceIsRefused) {
  const Branched b;
  const std::string text = replace(b.toml(), "base_radius2 = 0.048", "base_radius2 = 0.054");
  const InputError e = assemble_error(text);
  EXPECT_EQ(e.key_path(), "gear_meshes[0].base_radius2");
  EXPECT_EQ(e.where().file, "bad.toml");
  EXPECT_EQ(e.where().line, line_of(text, "name = \"external\"") - 1);
  const double expected = (b.rb1 + 0.054) / std::cos(b.alpha_t());
  const double found = (b.rb1 + b.rb2) / std::cos(b.alpha_t()) * (1 + 8e-4);
  EXPECT_NE(e.expected().find(fmt::format("{:.6g} m", expected)), std::string::npos)
      << e.expected();
  EXPECT_NE(e.found().find(fmt::format("{:.6g} m", found)), std::string::npos) << e.found();
  EXPECT_NE(e.found().find("'g1' and 'g2'"), std::string::npos) << e.found();
  EXPECT_NE(e.hint().find("pressure_angle_deg"), std::string::npos);

  // Beyond the tolerance by a pressure angle: 22.7 instead of 22.5 deg at the ring moves the
  // expected centre distance by tan(alpha) d(alpha) = +1.4e-3, the nodes are at -6e-4.
  const InputError ring =
      assemble_error(replace(b.toml(), "pressure_angle_deg = 22.5", "pressure_angle_deg = 22.7"));
  EXPECT_EQ(ring.key_path(), "gear_meshes[1].base_radius2");
  EXPECT_NE(ring.expected().find("base_radius2 - base_radius1"), std::string::npos)
      << ring.expected();
}

// Gear 2's centre off the line of centres given by mesh_direction, and an "internal" gear 2
// smaller than gear 1, are refused too.
TEST(GearMeshRatio, GearTwoOffTheLineOfCentresIsRefused) {
  const Branched b;
  const InputError off = assemble_error(
      replace(b.toml(), "mesh_direction = [0.0, 1.0, 0.0]", "mesh_direction = [0.1, 1.0, 0.0]"));
  EXPECT_EQ(off.key_path(), "gear_meshes[1].base_radius2");
  EXPECT_NE(off.found().find("off that line"), std::string::npos) << off.found();

  const InputError small =
      assemble_error(replace(b.toml(), "base_radius2 = 0.11", "base_radius2 = 0.02"));
  EXPECT_EQ(small.key_path(), "gear_meshes[1].base_radius2");
  EXPECT_NE(small.expected().find("internal"), std::string::npos) << small.expected();
}

// The speed ratios of spinning gear nodes and the tooth counts must follow r_b1 / r_b2 too:
// here gear 1 spins at 1 and gear 2 at -0.7 instead of -r_b1 / r_b2 = -0.625, and then 20 / 30
// teeth instead of 20 / 32.
TEST(GearMeshRatio, SpeedRatiosAndToothCountsFollowTheBaseRadii) {
  const Branched b;
  model::Model m = analyses::parse_model(b.toml(), "branched.toml");
  m.nodes[0].speed_ratio = 1.0;
  m.nodes[1].speed_ratio = -0.7;
  try {
    (void)fe::assemble(m);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key_path(), "gear_meshes[0].base_radius2");
    EXPECT_NE(e.expected().find("0.625"), std::string::npos) << e.expected();
    EXPECT_NE(e.found().find("= 0.7"), std::string::npos) << e.found();
  }
  m.nodes[1].speed_ratio = -b.rb1 / b.rb2;
  m.nodes[2].speed_ratio = b.rb1 / b.rb3;
  EXPECT_NO_THROW((void)fe::assemble(m));
  m.gear_meshes[0].teeth1 = 20;
  m.gear_meshes[0].teeth2 = 32;  // 20 / 32 = 0.625 = r_b1 / r_b2
  EXPECT_NO_THROW((void)fe::assemble(m));
  m.gear_meshes[0].teeth2 = 30;
  try {
    (void)fe::assemble(m);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(e.expected().find("teeth1 / teeth2 = 20 / 30"), std::string::npos) << e.expected();
  }
}

}  // namespace
}  // namespace geardyn
