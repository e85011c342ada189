#include "geardyn/drivetrain/builder.hpp"

#include <fmt/format.h>

#include <cmath>

#include "geardyn/core/units.hpp"
#include "geardyn/elements/bolted_joint.hpp"
#include "geardyn/elements/bushing.hpp"
#include "geardyn/elements/contact_law.hpp"
#include "geardyn/elements/gap_contact.hpp"
#include "geardyn/elements/rolling_bearing.hpp"
#include "geardyn/fe/gear_mesh_element.hpp"

namespace geardyn::drivetrain {
namespace {

using elements::LawSource;
using model::Component;

Eigen::Vector3d vec(const model::DrivetrainVec3& v) { return {v[0], v[1], v[2]}; }

int node_of(const fe::DofMap& dofs, const std::string& name, const SourceLocation& where,
            const std::string& key) {
  if (name.empty()) return -1;
  const int k = dofs.find_node(name);
  if (k < 0) throw InputError(where, key, "a node of the model", "'" + name + "'");
  return k;
}

}  // namespace

std::shared_ptr<const elements::ContactLaw> make_contact_law(const model::ContactLawSpec& s,
                                                             const elements::LawSource& src) {
  const auto tension = s.clip_tension ? elements::Tension::clipped : elements::Tension::allowed;
  switch (s.type) {
    case model::ContactLawKind::Linear:
      return std::make_shared<elements::LinearContactLaw>(
          elements::LinearLawParameters{s.stiffness, s.damping, tension}, src);
    case model::ContactLawKind::Hertz:
      return std::make_shared<elements::HertzContactLaw>(
          elements::HertzLawParameters{s.stiffness, s.exponent, s.damping, tension}, src);
    case model::ContactLawKind::Impact:
      return std::make_shared<elements::ImpactContactLaw>(
          elements::ImpactLawParameters{s.stiffness, s.exponent, s.max_damping, s.penetration_depth,
                                        tension},
          src);
    case model::ContactLawKind::Penalty:
      return std::make_shared<elements::PenaltyContactLaw>(
          elements::PenaltyLawParameters{
              s.stiffness, s.stiffness_exponent, s.damping, s.rate_exponent, s.damping_exponent,
              s.penetration_regularisation, s.rate_regularisation, tension},
          src);
  }
  throw std::logic_error("make_contact_law: unknown law");
}

namespace {

/// The element must see at least one free equation (a coordinate whose ends are both fixed, e.g.
/// a bushing's translations on a torsional model, stays zero), and every DOF it acts on must
/// belong to a body: carry mass or be held by the linear model's stiffness.
void check_placed(const PlacementBuilder& b, int rows, const PlacedElement& p,
                  const fe::LinearSystem& system, const SourceLocation& where,
                  const std::string& key) {
  bool any = false;
  for (int r = 0; r < rows; ++r) any = any || !b.row_empty(r);
  if (!any)
    throw InputError(
        where, key, "ends that can move along the element's coordinates (a node on a body)",
        fmt::format("{} has both ends fixed along every coordinate", p.element->describe()),
        "check node1 / node2, the [[constraints]] of those nodes and the model's dofs");
  for (int e : p.equations)
    if (!(system.M.coeff(e, e) > 0.0) && system.K.coeff(e, e) == 0.0) {
      const int node = system.dofs.dof_node(e);
      throw InputError(
          where, key, "ends on bodies (a shaft station, a disk, a reduced body's node)",
          fmt::format("{} acts on node '{}', which has neither mass nor stiffness: it belongs to "
                      "no body (the element joins unconnected bodies)",
                      p.element->describe(),
                      node >= 0 ? system.dofs.node(node).name : std::string("?")),
          "attach the node to a body (a shaft, a [[solids.spiders]] point, a point mass)");
    }
}

void place_contacts(const model::Model& m, const fe::LinearSystem& s, DrivetrainParts& parts) {
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    const model::ContactSpec& c = m.contacts[i];
    const std::string key = fmt::format("contacts[{}]", i);
    const LawSource src{c.law.where.line > 0 ? c.law.where : c.where, key + ".law"};
    auto law = make_contact_law(c.law, src);
    auto element = std::make_shared<elements::GapContact>(
        c.kind == model::ContactKind::Stop
            ? elements::GapContact::stop(c.name, c.gap, law, {c.where, key})
            : elements::GapContact::end_play(c.name, c.backlash, law, law, {c.where, key}));
    PlacementBuilder b(s.dofs, 1);
    const bool rot = c.motion == model::ContactMotion::Rotation;
    const Eigen::Vector3d d = vec(c.direction).normalized();
    b.add_projection(0, node_of(s.dofs, c.node1, c.where, key + ".node1"), rot, d, -1.0);
    b.add_projection(0, node_of(s.dofs, c.node2, c.where, key + ".node2"), rot, d, 1.0);
    PlacedElement p = b.finish(element, "contact", c.name);
    check_placed(b, 1, p, s, c.where, key);
    parts.elements.push_back(std::move(p));
  }
}

void place_bolts(const model::Model& m, const fe::LinearSystem& s, DrivetrainParts& parts) {
  for (std::size_t i = 0; i < m.bolts.size(); ++i) {
    const model::BoltSpec& c = m.bolts[i];
    const std::string key = fmt::format("bolts[{}]", i);
    elements::BoltedJointParams bp;
    bp.name = c.name;
    bp.bolt_stiffness = c.bolt_stiffness;
    bp.clamp_stiffness = c.clamp_stiffness;
    bp.preload = c.preload;
    bp.load_introduction = c.load_introduction;
    bp.axial_damping = c.axial_damping;
    bp.shear = c.shear_stiffness > 0.0;
    bp.shear_stiffness = c.shear_stiffness;
    bp.shear_damping = c.shear_damping;
    bp.activation_time = c.activation_time;
    bp.preload_ramp = c.preload_ramp;
    bp.inactive_stiffness = c.inactive_stiffness;
    auto element = std::make_shared<elements::BoltedJoint>(bp, key, c.where);
    const int rows = static_cast<int>(element->size());
    const Eigen::Matrix3d f = frame_with_axis(vec(c.axis), Eigen::Vector3d::UnitX());
    const int n1 = node_of(s.dofs, c.node1, c.where, key + ".node1");
    const int n2 = node_of(s.dofs, c.node2, c.where, key + ".node2");
    PlacementBuilder b(s.dofs, rows);
    const int axes[3] = {2, 0, 1};  // u(0) axial, u(1), u(2) shear
    for (int r = 0; r < rows; ++r) {
      b.add_projection(r, n1, false, f.col(axes[r]), -1.0);
      b.add_projection(r, n2, false, f.col(axes[r]), 1.0);
    }
    PlacedElement p = b.finish(element, "bolt", c.name);
    check_placed(b, rows, p, s, c.where, key);
    parts.elements.push_back(std::move(p));
  }
}

void place_bushings(const model::Model& m, const fe::LinearSystem& s, DrivetrainParts& parts) {
  for (std::size_t i = 0; i < m.bushings.size(); ++i) {
    const model::BushingSpec& c = m.bushings[i];
    const std::string key = fmt::format("bushings[{}]", i);
    elements::BushingParams bp;
    bp.name = c.name;
    for (int r = 0; r < 6; ++r) {
      for (int k = 0; k < 6; ++k) {
        bp.stiffness(r, k) = c.stiffness[static_cast<std::size_t>(6 * r + k)];
        bp.damping(r, k) = c.damping[static_cast<std::size_t>(6 * r + k)];
      }
      bp.preload[r] = c.preload[static_cast<std::size_t>(r)];
    }
    for (std::size_t t = 0; t < c.tables.size(); ++t) {
      const model::BushingTableSpec& ts = c.tables[t];
      bp.tables[static_cast<std::size_t>(ts.direction)].emplace(
          ts.deflection, ts.force,
          ts.linear ? elements::ForceDeflectionTable::Interpolation::linear
                    : elements::ForceDeflectionTable::Interpolation::cubic_hermite,
          fmt::format("{}.tables[{}]", key, t), ts.where.line > 0 ? ts.where : c.where);
    }
    auto element = std::make_shared<elements::Bushing>(bp, key, c.where);
    const Eigen::Matrix3d f = frame_with_axis(vec(c.z_axis), vec(c.x_axis));
    const int n1 = node_of(s.dofs, c.node1, c.where, key + ".node1");
    const int n2 = node_of(s.dofs, c.node2, c.where, key + ".node2");
    PlacementBuilder b(s.dofs, 6);
    for (int r = 0; r < 6; ++r) {
      b.add_projection(r, n1, r >= 3, f.col(r % 3), -1.0);
      b.add_projection(r, n2, r >= 3, f.col(r % 3), 1.0);
    }
    PlacedElement p = b.finish(element, "bushing", c.name);
    check_placed(b, 6, p, s, c.where, key);
    parts.elements.push_back(std::move(p));
  }
}

void place_rolling_bearings(const model::Model& m, const fe::LinearSystem& s, const BuildOptions& o,
                            DrivetrainParts& parts) {
  for (std::size_t i = 0; i < m.rolling_bearings.size(); ++i) {
    const model::RollingBearingSpec& c = m.rolling_bearings[i];
    const std::string key = fmt::format("rolling_bearings[{}]", i);
    const int inner = node_of(s.dofs, c.node, c.where, key + ".node");
    const int outer = node_of(s.dofs, c.housing, c.where, key + ".housing");
    elements::RollingBearingParams bp;
    bp.name = c.name;
    bp.elements = c.elements;
    bp.stiffness_constant = c.stiffness_constant;
    bp.exponent = c.exponent;
    bp.radial_clearance = c.radial_clearance;
    bp.axial_clearance = c.axial_clearance;
    bp.contact_angle = c.contact_angle;
    bp.pitch_diameter = c.pitch_diameter;
    bp.element_diameter = c.element_diameter;
    bp.cage_angle = c.cage_angle;
    bp.radial_damping = c.radial_damping;
    bp.axial_damping = c.axial_damping;
    const double inner_speed = o.initial_reference_speed * s.dofs.node(inner).speed_ratio;
    const double outer_speed =
        outer >= 0 ? o.initial_reference_speed * s.dofs.node(outer).speed_ratio : 0.0;
    // With the inner ring's spin a DOF the cage follows the actual spin angle (4 coordinates);
    // otherwise it turns at the kinematic cage speed of the starting speed.
    const int inner_spin = s.dofs.dof(inner, Component::Rz);
    bp.spin_angle = inner_spin >= 0;
    if (!bp.spin_angle)
      bp.cage_speed = elements::BearingKinematics{c.elements, c.pitch_diameter, c.element_diameter,
                                                  c.contact_angle}
                          .cage(inner_speed, outer_speed);
    auto element = std::make_shared<elements::RollingBearing>(bp, key, c.where);
    const Eigen::Matrix3d& f = s.dofs.node(inner).frame;
    const int rows = bp.spin_angle ? 4 : 3;
    PlacementBuilder b(s.dofs, rows);
    for (int r = 0; r < 3; ++r) {
      b.add_projection(r, outer, false, f.col(r), -1.0);
      b.add_projection(r, inner, false, f.col(r), 1.0);
    }
    if (bp.spin_angle) {
      b.add(3, inner_spin, 1.0);
      if (outer >= 0) b.add(3, s.dofs.dof(outer, Component::Rz), -1.0);
    }
    PlacedElement p = b.finish(element, "rolling_bearing", c.name);
    check_placed(b, rows, p, s, c.where, key);
    parts.elements.push_back(std::move(p));
  }
}

int spin_equation(const fe::LinearSystem& s, const std::string& node, const SourceLocation& where,
                  const std::string& key, const std::string& what) {
  const int k = node_of(s.dofs, node, where, key + ".node");
  const int e = s.dofs.dof(k, Component::Rz);
  if (e < 0)
    throw InputError(
        where, key + ".node", "a node whose spin (rz) is free",
        fmt::format("{} on node '{}', whose rz is constrained or not a DOF", what, node),
        "remove rz from the node's [[constraints]] or give its shaft torsion (dofs)");
  return e;
}

void place_drivers_and_loads(const model::Model& m, const fe::LinearSystem& s,
                             DrivetrainParts& parts) {
  for (std::size_t i = 0; i < m.drivers.size(); ++i) {
    const model::DriverSpec& d = m.drivers[i];
    const std::string key = fmt::format("drivers[{}]", i);
    const int e = spin_equation(s, d.node, d.where, key, "driver '" + d.name + "'");
    if (d.kind == model::DriverKind::Speed) {
      SpeedDriver sd;
      sd.name = d.name;
      sd.equation = e;
      sd.speed = PiecewiseLinear(d.times, d.speeds);
      parts.speed_drivers.push_back(std::move(sd));
    } else {
      Motor mo;
      mo.name = d.name;
      mo.equation = e;
      mo.torque = PiecewiseLinear(d.motor_speeds, d.motor_torques);
      mo.inertia = d.inertia;
      parts.motors.push_back(std::move(mo));
    }
    if (parts.speed_equation < 0) {
      const double ratio = s.dofs.node(s.dofs.dof_node(e)).speed_ratio;
      if (ratio != 0.0) {
        parts.speed_equation = e;
        parts.speed_ratio = ratio;
      }
    }
  }
  for (std::size_t i = 0; i < m.loads.size(); ++i) {
    const model::LoadTorqueSpec& l = m.loads[i];
    const std::string key = fmt::format("loads[{}]", i);
    LoadTorque lt;
    lt.name = l.name;
    lt.equation = spin_equation(s, l.node, l.where, key, "load '" + l.name + "'");
    lt.torque = l.torque;
    lt.drag = l.drag;
    if (l.table_over != model::LoadTableOver::None) {
      lt.table = PiecewiseLinear(l.table_x, l.table_torque);
      lt.table_over_time = l.table_over == model::LoadTableOver::Time;
    }
    parts.loads.push_back(std::move(lt));
  }
  for (std::size_t i = 0; i < m.unbalances.size(); ++i) {
    const model::Unbalance& u = m.unbalances[i];
    const std::string key = fmt::format("unbalances[{}]", i);
    const int k = node_of(s.dofs, u.node, u.where, key + ".node");
    SpinUnbalance su;
    su.name = u.name;
    su.e1 = s.dofs.dof(k, Component::Ux);
    su.e2 = s.dofs.dof(k, Component::Uy);
    su.spin = spin_equation(s, u.node, u.where, key, "unbalance '" + u.name + "'");
    su.mass_eccentricity = u.mass_eccentricity;
    // LinearRotorSystem's phase convention: psi = theta + sign(r) phi; here theta is the
    // geometric angle about e3, so phi turns with the spin's sense.
    su.phase = s.dofs.node(k).speed_ratio < 0.0 ? -u.phase : u.phase;
    parts.unbalances.push_back(std::move(su));
  }
  for (std::size_t i = 0; i < m.clutches.size(); ++i) {
    const model::ClutchSpec& c = m.clutches[i];
    const std::string key = fmt::format("clutches[{}]", i);
    auto element =
        std::make_shared<ClutchElement>(c.name, c.max_torque, c.slip_speed, c.engage_time);
    PlacementBuilder b(s.dofs, 1);
    if (!c.node1.empty()) b.add(0, spin_equation(s, c.node1, c.where, key, "clutch"), -1.0);
    b.add(0, spin_equation(s, c.node2, c.where, key, "clutch"), 1.0);
    PlacedElement p = b.finish(element, "clutch", c.name);
    check_placed(b, 1, p, s, c.where, key);
    parts.elements.push_back(std::move(p));
  }
}

void place_meshes(const model::Model& m, const fe::LinearSystem& s, const BuildOptions& o,
                  DrivetrainParts& parts) {
  for (std::size_t i = 0; i < m.gear_meshes.size(); ++i) {
    const model::GearMesh& g = m.gear_meshes[i];
    const std::string key = fmt::format("gear_meshes[{}]", i);
    const MeshRows rows = mesh_rows(m, s, i);
    std::shared_ptr<const elements::ForceElement> element =
        i < o.mesh_elements.size() ? o.mesh_elements[i] : nullptr;
    int n_rows = 2;
    if (element == nullptr) {
      // Constant stiffness and damping on the drive flank; the back flank at -backlash.
      n_rows = 1;
      auto law = std::make_shared<elements::LinearContactLaw>(
          elements::LinearLawParameters{g.stiffness, g.damping, elements::Tension::allowed},
          LawSource{g.where, key});
      std::optional<elements::GapContact::Side> back;
      if (g.contact && std::isfinite(g.contact->backlash))
        back = elements::GapContact::Side{-g.contact->backlash, law};
      element = std::make_shared<elements::GapContact>(
          "mesh " + g.name, elements::GapContact::Side{0.0, law}, back, LawSource{g.where, key});
    }
    if (element->size() == 4) n_rows = 4;  // tooth friction: theta2 and the profile motion y
    if (g.contact && g.contact->friction > 0.0 && n_rows != 4)
      throw InputError(g.contact->where.line > 0 ? g.contact->where : g.where,
                       key + ".contact.friction",
                       "a mesh whose tooth contact carries friction (a force map from a "
                       "[[gear_pairs]] entry, whose geometry gives the path of contact)",
                       fmt::format("{} without tooth friction", element->describe()),
                       "name the pair in [gear_meshes.contact] gear_pair, or set friction = 0");
    PlacementBuilder b(s.dofs, n_rows);
    for (std::size_t k = 0; k < rows.equations.size(); ++k)
      b.add(0, rows.equations[k], rows.coefficients[k]);
    if (n_rows >= 2) b.add(1, rows.pinion_spin, rows.pinion_sign);
    if (n_rows == 4) {
      b.add(2, rows.wheel_spin, rows.wheel_sign);
      for (std::size_t k = 0; k < rows.profile_equations.size(); ++k)
        b.add(3, rows.profile_equations[k], rows.profile_coefficients[k]);
    }
    PlacedElement p = b.finish(element, "gear_mesh", g.name);
    check_placed(b, n_rows, p, s, g.where, key);
    parts.elements.push_back(std::move(p));
  }
}

}  // namespace

model::Model without_mesh_springs(const model::Model& model) {
  model::Model m = model;
  for (model::GearMesh& g : m.gear_meshes) {
    g.stiffness = 0.0;
    g.damping = 0.0;
  }
  return m;
}

namespace {

// A crossed-axis mesh (bevel, hypoid: the equivalent spiral bevel at mid face, the hypoid offset
// in the pair's LTCA) is located at its mid-face pitch point, r_p1 = r_b1 / cos(alpha_t) from
// gear 1's node along the mesh direction. That point must lie on gear 2 too: in gear 2's
// transverse plane through its node, at r_p2 = r_b2 / cos(alpha_t) from its axis, within
// kConsistencyTolerance of r_p2 (as the parallel-axis centre distance, fe/gear_mesh_element.cpp):
// otherwise the lever arms of the two gears are not those of one contact point.
void check_crossed_axes_pitch_point(const model::GearMesh& g, const fe::NodeInfo& a,
                                    const fe::NodeInfo& b, const fe::GearMeshGeometry& geo,
                                    const std::string& key) {
  if (g.type != model::GearType::StraightBevel && g.type != model::GearType::SpiralBevel &&
      g.type != model::GearType::Hypoid)
    return;
  const double r_p2 = g.base_radius2 / std::cos(geo.transverse_pressure_angle);
  const Eigen::Vector3d a2 = b.frame.col(2);
  const Eigen::Vector3d arm = geo.pitch_point - b.position;
  const double axial = arm.dot(a2);
  const double radial = (arm - axial * a2).norm();
  const double distance = std::hypot(radial - r_p2, axial);
  const double tolerance = fe::kConsistencyTolerance * r_p2;
  if (distance <= tolerance) return;
  throw InputError(
      g.where, key + ".gear2",
      fmt::format("the mesh's mid-face pitch point, {:.6g} m from node '{}' along the mesh "
                  "direction (r_b1 / cos(alpha_t), alpha_t = {:.6g} deg), in the transverse "
                  "plane of node '{}' at r_b2 / cos(alpha_t) = {:.6g} m from its axis, within "
                  "{:.3g} m",
                  geo.pitch_radius1, a.name, geo.transverse_pressure_angle / units::kRadPerDegree,
                  b.name, r_p2, tolerance),
      fmt::format("the pitch point at ({:.6g}, {:.6g}, {:.6g}) m, {:.6g} m from that point "
                  "({:.6g} m from the axis, {:.6g} m off the plane) in mesh '{}'",
                  geo.pitch_point.x(), geo.pitch_point.y(), geo.pitch_point.z(), distance, radial,
                  axial, g.name),
      "move the gear nodes (shafts[].origin, the element lengths) or correct base_radius1, "
      "base_radius2, helix_angle_deg or mesh_direction");
}

}  // namespace

MeshRows mesh_rows(const model::Model& model, const fe::LinearSystem& system, std::size_t index) {
  model::GearMesh g = model.gear_meshes.at(index);
  g.flank = model::Flank::Drive;
  const std::string key = fmt::format("gear_meshes[{}]", index);
  const int n1 = node_of(system.dofs, g.gear1, g.where, key + ".gear1");
  const int n2 = node_of(system.dofs, g.gear2, g.where, key + ".gear2");
  const fe::NodeInfo& a = system.dofs.node(n1);
  const fe::NodeInfo& b = system.dofs.node(n2);
  const fe::GearMeshGeometry geo = fe::gear_mesh_geometry(g, a, b, key);
  check_crossed_axes_pitch_point(g, a, b, geo, key);
  const fe::Vector12d v = fe::gear_mesh_vector(geo, a, b);
  MeshRows rows;
  for (int k = 0; k < 12; ++k) {
    const int e = system.dofs.dof(k < 6 ? n1 : n2, static_cast<Component>(k % 6));
    if (e >= 0 && v[k] != 0.0) {
      rows.equations.push_back(e);
      rows.coefficients.push_back(v[k]);
    }
  }
  rows.pinion_spin = system.dofs.dof(n1, Component::Rz);
  // theta1 advances with gear 1's working rotation: the sense of its lever arm on delta.
  rows.pinion_sign = v[5] >= 0.0 ? 1.0 : -1.0;
  rows.base_radius1 = g.base_radius1;
  // The wheel turns in its working sense when it cancels the pinion's approach: v_11 theta2 has
  // the opposite sign of v_5 theta1 at the kinematic speeds.
  rows.wheel_spin = system.dofs.dof(n2, Component::Rz);
  rows.wheel_sign = v[11] >= 0.0 ? -1.0 : 1.0;
  // t: the pinion's contact-point velocity for theta1_dot > 0, without its components along the
  // line of action and the axis.
  const Eigen::Vector3d spin = rows.pinion_sign * a.frame.col(2);
  Eigen::Vector3d t = spin.cross(geo.pitch_point - a.position);
  t -= t.dot(geo.line_of_action) * geo.line_of_action + t.dot(geo.axial) * geo.axial;
  t.normalize();
  for (int k = 0; k < 3; ++k) {
    const double c1 = -t.dot(a.frame.col(k)), c2 = t.dot(b.frame.col(k));
    const int e1 = system.dofs.dof(n1, static_cast<Component>(k));
    const int e2 = system.dofs.dof(n2, static_cast<Component>(k));
    if (e1 >= 0 && c1 != 0.0) {
      rows.profile_equations.push_back(e1);
      rows.profile_coefficients.push_back(c1);
    }
    if (e2 >= 0 && c2 != 0.0) {
      rows.profile_equations.push_back(e2);
      rows.profile_coefficients.push_back(c2);
    }
  }
  return rows;
}

DrivetrainParts build_drivetrain(const model::Model& model, const fe::LinearSystem& system,
                                 const BuildOptions& options) {
  DrivetrainParts parts;
  parts.M = system.M;
  parts.G = system.G;
  parts.modal_basis = system.modal_basis;
  parts.modal_coefficients = system.modal_coefficients;
  place_contacts(model, system, parts);
  place_bolts(model, system, parts);
  place_bushings(model, system, parts);
  place_rolling_bearings(model, system, options, parts);
  place_drivers_and_loads(model, system, parts);
  place_meshes(model, system, options, parts);
  // Speed-dependent bearings follow the actual reference speed (a driver's spin); without one
  // they stay at the initial speed.
  if (parts.speed_equation >= 0) {
    parts.K = system.K;
    parts.C = system.C;
    parts.speed_bearings = system.speed_bearings;
  } else {
    parts.K = system.K_at(options.initial_reference_speed);
    parts.C = system.C_at(options.initial_reference_speed);
  }
  return parts;
}

Eigen::VectorXd rigid_spin(const fe::LinearSystem& system, double speed) {
  Eigen::VectorXd v = Eigen::VectorXd::Zero(system.size());
  for (int k = 0; k < system.dofs.num_nodes(); ++k) {
    const int e = system.dofs.dof(k, Component::Rz);
    if (e >= 0) v[e] = speed * system.dofs.node(k).speed_ratio;
  }
  return v;
}

}  // namespace geardyn::drivetrain
