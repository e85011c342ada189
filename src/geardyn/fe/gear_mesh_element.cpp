#include "geardyn/fe/gear_mesh_element.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::fe {

GearMeshGeometry gear_mesh_geometry(const model::GearMesh& mesh, const NodeInfo& gear1,
                                    const NodeInfo& gear2, const std::string& key) {
  if (!(mesh.base_radius1 > 0) || !std::isfinite(mesh.base_radius1)) {
    throw InputError(mesh.where, key + ".base_radius1", "a positive base radius [m]",
                     fmt::format("{}", mesh.base_radius1));
  }
  if (!(mesh.pressure_angle > 0 && mesh.pressure_angle < units::kPi / 2)) {
    throw InputError(mesh.where, key + ".pressure_angle", "an angle in (0, 90) deg",
                     fmt::format("{} rad", mesh.pressure_angle));
  }
  const bool spur = mesh.type == model::GearType::Spur;
  const bool straight = spur || mesh.type == model::GearType::StraightBevel;
  const double beta = straight ? 0.0 : mesh.helix_angle;
  if (!(std::abs(beta) < units::kPi / 2)) {
    throw InputError(mesh.where, key + ".helix_angle", "an angle with |angle| < 90 deg",
                     fmt::format("{} rad", mesh.helix_angle));
  }

  GearMeshGeometry g;
  const Eigen::Vector3d x1 = gear1.position, x2 = gear2.position;
  const Eigen::Vector3d e_a = gear1.frame.col(2);

  Eigen::Vector3d toward = x2 - x1;
  std::string toward_key = key + ".gear2";
  if (mesh.mesh_direction) {
    const auto& d = *mesh.mesh_direction;
    toward = Eigen::Vector3d(d[0], d[1], d[2]);
    toward_key = key + ".mesh_direction";
  }
  Eigen::Vector3d radial = toward - toward.dot(e_a) * e_a;
  const double scale = std::max({toward.norm(), mesh.base_radius1, 1e-300});
  if (radial.norm() <= 1e-9 * scale) {
    throw InputError(mesh.where, toward_key,
                     "a direction from gear 1 towards gear 2 with a part normal to gear 1's axis",
                     mesh.mesh_direction ? "a mesh_direction along the axis"
                                         : fmt::format("gear nodes '{}' and '{}' on one axis",
                                                       gear1.name, gear2.name),
                     "give mesh_direction or place the gear nodes at their centres");
  }
  g.radial = radial.normalized();
  g.tangential = e_a.cross(g.radial);
  g.axial = e_a;

  const double tan_alpha = std::tan(mesh.pressure_angle);
  g.transverse_pressure_angle = spur ? mesh.pressure_angle : std::atan(tan_alpha / std::cos(beta));
  g.pitch_radius1 = mesh.base_radius1 / std::cos(g.transverse_pressure_angle);
  g.pitch_point = x1 + g.pitch_radius1 * g.radial;

  const double rotation = gear1.speed_ratio < 0 ? -1.0 : 1.0;
  const double flank = mesh.flank == model::Flank::Coast ? -1.0 : 1.0;
  g.sigma = rotation * flank;
  const double hand = mesh.hand == model::Hand::Right ? 1.0 : -1.0;

  g.tangential_force = 1.0;
  if (spur) {
    g.radial_force = tan_alpha;
    g.axial_force = 0.0;
  } else if (mesh.type == model::GearType::Helical) {
    g.radial_force = tan_alpha / std::cos(beta);
    g.axial_force = g.sigma * hand * std::tan(beta);
  } else {
    const double delta = mesh.pitch_cone_angle1;
    if (!(delta > 0 && delta < units::kPi)) {
      throw InputError(mesh.where, key + ".pitch_cone_angle1", "an angle in (0, 180) deg",
                       fmt::format("{} rad", delta));
    }
    // Apex: point of gear 1's axis closest to gear 2's axis (their intersection for bevel gears).
    const Eigen::Vector3d a2 = gear2.frame.col(2);
    const double b = e_a.dot(a2);
    if (1.0 - b * b < 1e-12) {
      throw InputError(mesh.where, key, "bevel / hypoid gears with non-parallel axes",
                       fmt::format("parallel axes at nodes '{}' and '{}'", gear1.name, gear2.name));
    }
    const Eigen::Vector3d w = x1 - x2;
    const double t = (b * a2.dot(w) - e_a.dot(w)) / (1.0 - b * b);
    if (std::abs(t) <= 1e-9 * scale) {
      throw InputError(mesh.where, key + ".gear1", "a gear node away from the cone apex",
                       fmt::format("node '{}' at the apex", gear1.name),
                       "place the node at the mid-face plane on the axis");
    }
    // x1 - apex = -t e_a: u_a points from the apex towards the gear.
    const double apex_side = t < 0 ? 1.0 : -1.0;
    g.axial = apex_side * e_a;
    const double s = hand * g.sigma * apex_side;
    const double cb = std::cos(beta), sb = std::sin(beta);
    g.axial_force = (tan_alpha * std::sin(delta) + s * sb * std::cos(delta)) / cb;
    g.radial_force = (tan_alpha * std::cos(delta) - s * sb * std::sin(delta)) / cb;
  }

  const Eigen::Vector3d force1 =
      -g.sigma * g.tangential + g.axial_force * g.axial - g.radial_force * g.radial;
  g.line_of_action = -force1.normalized();
  return g;
}

Vector12d gear_mesh_vector(const GearMeshGeometry& g, const NodeInfo& gear1,
                           const NodeInfo& gear2) {
  const Eigen::Vector3d& n = g.line_of_action;
  Vector12d v;
  v.segment<3>(0) = n;
  v.segment<3>(3) = (g.pitch_point - gear1.position).cross(n);
  v.segment<3>(6) = -n;
  v.segment<3>(9) = -(g.pitch_point - gear2.position).cross(n);
  return two_node_rotation(gear1.frame, gear2.frame).transpose() * v;
}

}  // namespace geardyn::fe
