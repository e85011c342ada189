// The tooth-friction coordinates of a gear mesh placed by the drivetrain builder
// (drivetrain/builder.hpp MeshRows, elements/gear_mesh_contact.hpp): theta2 is the wheel's
// rotation in its working sense and y the wheel centre's motion along the profile direction t.
// Spur pair z1 = 20, z2 = 40 (r_b1 = 37.6 mm, r_b2 = 75.2 mm), pinion at the origin, wheel on +x.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "geardyn/assembly/system_builder.hpp"
#include "geardyn/drivetrain/builder.hpp"
#include "support/rotor_models.hpp"

namespace geardyn {
namespace {

using C = model::Component;

model::Model gear_pair(double pinion_ratio) {
  const double alpha = 20.0 * std::numbers::pi / 180.0;
  const double rb1 = 0.04 * std::cos(alpha), rb2 = 0.08 * std::cos(alpha);
  model::Model m;
  model::Node p = test::spinning_node("p", pinion_ratio);
  model::Node w = test::spinning_node("w", -pinion_ratio * rb1 / rb2);
  w.position = model::Vec3{0.12, 0.0, 0.0};
  m.nodes = {p, w};
  for (const char* n : {"p", "w"}) {
    model::Disk d;
    d.name = std::string("d") + n;
    d.node = n;
    d.mass = 1.0;
    d.polar_inertia = 1e-3;
    d.diametral_inertia = 5e-4;
    m.disks.push_back(d);
    model::Bearing b;
    b.node = n;
    b.stiffness = {test::diagonal6(1e8, 1e8, 0, 0, 0, 0)};
    m.bearings.push_back(b);
    m.constraints.push_back(test::fix(n, {C::Uz, C::Rx, C::Ry}));
  }
  model::GearMesh g;
  g.name = "mesh";
  g.gear1 = "p";
  g.gear2 = "w";
  g.teeth1 = 20;
  g.teeth2 = 40;
  g.base_radius1 = rb1;
  g.base_radius2 = rb2;
  g.pressure_angle = alpha;
  g.stiffness = 4e8;
  m.gear_meshes.push_back(g);
  return m;
}

double row(const drivetrain::MeshRows& r, const Eigen::VectorXd& q, bool profile) {
  const auto& eq = profile ? r.profile_equations : r.equations;
  const auto& c = profile ? r.profile_coefficients : r.coefficients;
  double sum = 0.0;
  for (std::size_t k = 0; k < eq.size(); ++k) sum += c[k] * q[eq[k]];
  return sum;
}

// At the kinematic spin (either sense of the pinion) the approach rate is zero and both angles
// advance: theta1_dot = |omega1|, theta2_dot = |omega1| r_b1 / r_b2 (exact up to rounding).
// The profile direction t is perpendicular to the line of action and to the axis, and points
// where the pinion's pitch point moves: a wheel translation along t gives y = 1.
TEST(DrivetrainMeshRows, FrictionCoordinatesFollowTheWorkingSense) {
  for (double sense : {1.0, -1.0}) {
    const model::Model m = gear_pair(sense);
    const fe::LinearSystem sys = assembly::build_system(m);
    const drivetrain::MeshRows r = drivetrain::mesh_rows(m, sys, 0);
    const Eigen::VectorXd spin = drivetrain::rigid_spin(sys, 100.0);
    const double rb1 = m.gear_meshes[0].base_radius1, rb2 = m.gear_meshes[0].base_radius2;
    EXPECT_NEAR(row(r, spin, false), 0.0, 1e-12 * 100.0 * rb1) << sense;
    EXPECT_NEAR(r.pinion_sign * spin[r.pinion_spin], 100.0, 1e-12) << sense;
    EXPECT_NEAR(r.wheel_sign * spin[r.wheel_spin], 100.0 * rb1 / rb2, 1e-12) << sense;
    // y: the wheel centre's translation along t (x, y of the wheel node) minus the pinion's.
    const int wx = sys.dofs.dof(sys.dofs.node_index("w"), C::Ux);
    const int wy = sys.dofs.dof(sys.dofs.node_index("w"), C::Uy);
    const int px = sys.dofs.dof(sys.dofs.node_index("p"), C::Ux);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(sys.size());
    q[wx] = 1.0;
    const double tx = row(r, q, true);
    q[wx] = 0.0;
    q[wy] = 1.0;
    const double ty = row(r, q, true);
    EXPECT_NEAR(tx * tx + ty * ty, 1.0, 1e-12);
    // The pitch point (0.04, 0, 0) of the pinion moves along sense x (0, 1, 0).
    EXPECT_GT(sense * ty, 0.0);
    // t is perpendicular to the line of action: a wheel motion along t does not change delta.
    q.setZero();
    q[wx] = tx;
    q[wy] = ty;
    EXPECT_NEAR(row(r, q, false), 0.0, 1e-12);
    q.setZero();
    q[px] = 1.0;
    EXPECT_NEAR(row(r, q, true), -tx, 1e-15);
  }
}

}  // namespace
}  // namespace geardyn
