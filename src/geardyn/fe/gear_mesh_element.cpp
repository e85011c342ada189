#include "geardyn/fe/gear_mesh_element.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/core/units.hpp"

namespace geardyn::fe {

namespace {

void check_inputs(const model::GearMesh& mesh, double beta, const std::string& key) {
  if (!(mesh.base_radius1 > 0) || !std::isfinite(mesh.base_radius1)) {
    throw InputError(mesh.where, key + ".base_radius1", "a positive base radius [m]",
                     fmt::format("{}", mesh.base_radius1));
  }
  if (!(mesh.base_radius2 > 0) || !std::isfinite(mesh.base_radius2)) {
    throw InputError(mesh.where, key + ".base_radius2", "a positive base radius [m]",
                     fmt::format("{}", mesh.base_radius2));
  }
  if (!(mesh.pressure_angle > 0 && mesh.pressure_angle < units::kPi / 2)) {
    throw InputError(mesh.where, key + ".pressure_angle", "an angle in (0, 90) deg",
                     fmt::format("{} rad", mesh.pressure_angle));
  }
  if (!(std::abs(beta) < units::kPi / 2)) {
    throw InputError(mesh.where, key + ".helix_angle", "an angle with |angle| < 90 deg",
                     fmt::format("{} rad", mesh.helix_angle));
  }
}

constexpr const char* kGeometryHint =
    "move the gear nodes, or correct base_radius1, base_radius2 or pressure_angle_deg (and "
    "helix_angle_deg: the transverse pressure angle depends on it)";
constexpr const char* kRatioHint =
    "correct base_radius1 or base_radius2, teeth1 or teeth2, or the shafts' speed_ratio / "
    "gear_ratio";

[[noreturn]] void inconsistent(const model::GearMesh& mesh, const std::string& key,
                               const std::string& expected, const std::string& found,
                               const char* hint = kGeometryHint) {
  throw InputError(mesh.where, key + ".base_radius2", expected, found, hint);
}

// Spur and helical gears (parallel axes): the line of action is the common tangent of the base
// circles at the centre distance of the nodes (see the header), checked against the keys.
void parallel_axes(const model::GearMesh& mesh, const NodeInfo& gear1, const NodeInfo& gear2,
                   const std::string& key, double beta, GearMeshGeometry& g) {
  const double rb1 = mesh.base_radius1, rb2 = mesh.base_radius2;
  const double alpha_t = g.transverse_pressure_angle;
  const Eigen::Vector3d delta = gear2.position - gear1.position;
  const Eigen::Vector3d normal = delta - delta.dot(g.axial) * g.axial;
  const double along = normal.dot(g.radial);  // signed centre distance along e_r
  const bool internal = along < 0;
  if (internal && !(rb2 > rb1)) {
    inconsistent(mesh, key,
                 "an internal gear 2 (its centre behind gear 1's, seen along mesh_direction) "
                 "with base_radius2 > base_radius1",
                 fmt::format("base_radius1 = {} m, base_radius2 = {} m", rb1, rb2));
  }
  const double rb_sum = internal ? rb2 - rb1 : rb2 + rb1;
  const double expected = rb_sum / std::cos(alpha_t);
  const double found = std::abs(along);
  const double offset = (normal - along * g.radial).norm();
  const double tolerance = kConsistencyTolerance * expected;
  if (!(std::abs(found - expected) <= tolerance) || !(offset <= tolerance)) {
    inconsistent(
        mesh, key,
        fmt::format("a centre distance ({}) / cos(alpha_t) = "
                    "{:.6g} m (transverse pressure angle alpha_t = {:.6g} deg) within {:g} %, "
                    "gear 2's centre on the line through gear 1's centre along the mesh "
                    "direction",
                    internal ? "base_radius2 - base_radius1" : "base_radius1 + base_radius2",
                    expected, alpha_t / units::kRadPerDegree, 100 * kConsistencyTolerance),
        fmt::format(
            "{:.6g} m between the axes of nodes '{}' and '{}'{}", found, gear1.name, gear2.name,
            offset > tolerance ? fmt::format(", gear 2's centre {:.3g} m off that line", offset)
                               : std::string()));
  }
  // Working transverse pressure angle and pitch point: exact lever arms r_b1, r_b2.
  const double alpha_w = std::acos(std::min(1.0, rb_sum / found));
  g.transverse_pressure_angle = alpha_w;
  g.pitch_radius1 = rb1 / std::cos(alpha_w);
  g.pitch_point = gear1.position + g.pitch_radius1 * g.radial;
  g.lever2 = g.pitch_point - (gear1.position + delta.dot(g.axial) * g.axial + along * g.radial);
  const double tan_beta_b = std::tan(beta) * std::cos(alpha_t);
  g.radial_force = std::tan(alpha_w);
  g.axial_force = mesh.type == model::GearType::Spur
                      ? 0.0
                      : g.sigma * (mesh.hand == model::Hand::Right ? 1.0 : -1.0) * tan_beta_b /
                            std::cos(alpha_w);
}

// Straight / spiral bevel and hypoid: force components of docs/theory.md §11.2 at the mid-face
// pitch point of gear 1, gear 2's lever arm scaled to its mean pitch radius (checked for bevel
// gears).
void crossed_axes(const model::GearMesh& mesh, const NodeInfo& gear1, const NodeInfo& gear2,
                  const std::string& key, double beta, double scale, GearMeshGeometry& g) {
  const double tan_alpha = std::tan(mesh.pressure_angle);
  const double hand = mesh.hand == model::Hand::Right ? 1.0 : -1.0;
  const double delta = mesh.pitch_cone_angle1;
  if (!(delta > 0 && delta < units::kPi)) {
    throw InputError(mesh.where, key + ".pitch_cone_angle1", "an angle in (0, 180) deg",
                     fmt::format("{} rad", delta));
  }
  const Eigen::Vector3d e_a = gear1.frame.col(2);
  const Eigen::Vector3d x1 = gear1.position, x2 = gear2.position;
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

  const Eigen::Vector3d arm = g.pitch_point - x2;
  const Eigen::Vector3d normal = arm - arm.dot(a2) * a2;
  const double r_p2 = mesh.base_radius2 / std::cos(g.transverse_pressure_angle);
  const double found = normal.norm();
  if (mesh.type != model::GearType::Hypoid &&
      !(std::abs(found - r_p2) <= kConsistencyTolerance * r_p2)) {
    inconsistent(mesh, key,
                 fmt::format("the mid-face pitch point at the mean pitch radius of gear 2, "
                             "base_radius2 / cos(alpha_t) = {:.6g} m (alpha_t = {:.6g} deg), "
                             "from gear 2's axis within {:g} %",
                             r_p2, g.transverse_pressure_angle / units::kRadPerDegree,
                             100 * kConsistencyTolerance),
                 fmt::format("{:.6g} m from the axis of node '{}' (pitch point at base_radius1 "
                             "/ cos(alpha_t) = {:.6g} m from node '{}')",
                             found, gear2.name, g.pitch_radius1, gear1.name));
  }
  if (!(found > 1e-9 * scale)) {
    throw InputError(mesh.where, key + ".gear2", "a pitch point away from gear 2's axis",
                     fmt::format("the pitch point on the axis of node '{}'", gear2.name));
  }
  g.lever2 = arm.dot(a2) * a2 + (r_p2 / found) * normal;
}

// Kinematics the base radii imply: the gear ratio |omega2 / omega1| = r_b1 / r_b2 must be the
// ratio of the nodes' speed ratios (when both spin) and, except for hypoid gears (pinion
// enlargement), z1 / z2 (conjugate gears share one base pitch 2 pi r_b / z; ISO 21771).
void check_ratios(const model::GearMesh& mesh, const NodeInfo& gear1, const NodeInfo& gear2,
                  const std::string& key) {
  const double ratio = mesh.base_radius1 / mesh.base_radius2;
  const auto off = [&](double value) {
    return !(std::abs(value - ratio) <= kConsistencyTolerance * ratio);
  };
  if (gear1.speed_ratio != 0.0 && gear2.speed_ratio != 0.0 &&
      off(std::abs(gear2.speed_ratio / gear1.speed_ratio)))
    inconsistent(mesh, key,
                 fmt::format("a gear ratio base_radius1 / base_radius2 = {:.6g} within {:g} % of "
                             "the speed ratios of the gear nodes",
                             ratio, 100 * kConsistencyTolerance),
                 fmt::format("|speed ratio| {:.6g} of node '{}' / {:.6g} of node '{}' = {:.6g}",
                             std::abs(gear2.speed_ratio), gear2.name, std::abs(gear1.speed_ratio),
                             gear1.name, std::abs(gear2.speed_ratio / gear1.speed_ratio)),
                 kRatioHint);
  if (mesh.type != model::GearType::Hypoid && mesh.teeth1 > 0 && mesh.teeth2 > 0 &&
      off(static_cast<double>(mesh.teeth1) / mesh.teeth2))
    inconsistent(
        mesh, key,
        fmt::format("base radii in the ratio of the tooth counts (one base pitch): "
                    "teeth1 / teeth2 = {} / {} = {:.6g} within {:g} %",
                    mesh.teeth1, mesh.teeth2, static_cast<double>(mesh.teeth1) / mesh.teeth2,
                    100 * kConsistencyTolerance),
        fmt::format("base_radius1 / base_radius2 = {} / {} = {:.6g}", mesh.base_radius1,
                    mesh.base_radius2, ratio),
        kRatioHint);
}

}  // namespace

GearMeshGeometry gear_mesh_geometry(const model::GearMesh& mesh, const NodeInfo& gear1,
                                    const NodeInfo& gear2, const std::string& key) {
  const bool spur = mesh.type == model::GearType::Spur;
  const bool straight = spur || mesh.type == model::GearType::StraightBevel;
  const double beta = straight ? 0.0 : mesh.helix_angle;
  check_inputs(mesh, beta, key);
  check_ratios(mesh, gear1, gear2, key);

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

  g.tangential_force = 1.0;
  if (spur || mesh.type == model::GearType::Helical) {
    parallel_axes(mesh, gear1, gear2, key, beta, g);
  } else {
    crossed_axes(mesh, gear1, gear2, key, beta, scale, g);
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
  v.segment<3>(9) = -g.lever2.cross(n);
  return two_node_rotation(gear1.frame, gear2.frame).transpose() * v;
}

}  // namespace geardyn::fe
