#pragma once
// Small rotor models for the transient tests (Jeffcott rotor with unbalance, a flexible rotor on
// bearings), built directly as model::Model.
#include <cmath>
#include <string>

#include "geardyn/model/model.hpp"

namespace geardyn::transient::testing {

inline model::Sensor sensor(const std::string& name, const std::string& node, model::Component c) {
  model::Sensor s;
  s.name = name;
  s.node = node;
  s.dof = c;
  return s;
}

inline model::Bearing::Matrix6 diagonal6(double xx, double yy) {
  model::Bearing::Matrix6 m{};
  m[0] = xx;
  m[7] = yy;
  return m;
}

/// Jeffcott rotor: a point mass m on an isotropic massless shaft of lateral stiffness k, viscous
/// damping c = 2 zeta sqrt(k m), unbalance m_e at phase 0; only ux, uy free. The node spins with
/// `speed_ratio` x the reference speed.
///
///        k, c               x, y: lateral motion of the disk centre
///   ///--/\/\/--( m )        unbalance m_e rotating with the disk
inline model::Model jeffcott(double m, double k, double zeta, double m_e,
                             double speed_ratio = 1.0) {
  model::Model model;
  model.title = "jeffcott";
  model::Node node;
  node.name = "disk";
  node.speed_ratio = speed_ratio;
  model.nodes.push_back(node);
  model::PointMass mass;
  mass.name = "disk_mass";
  mass.node = "disk";
  mass.mass = m;
  model.point_masses.push_back(mass);
  const double c = 2.0 * zeta * std::sqrt(k * m);
  model::Bearing b;
  b.name = "shaft";
  b.node = "disk";
  b.stiffness.push_back(diagonal6(k, k));
  b.damping.push_back(diagonal6(c, c));
  model.bearings.push_back(b);
  model::Constraint fixed;
  fixed.node = "disk";
  fixed.dofs = {model::Component::Uz, model::Component::Rx, model::Component::Ry,
                model::Component::Rz};
  model.constraints.push_back(fixed);
  model::Unbalance u;
  u.name = "u1";
  u.node = "disk";
  u.mass_eccentricity = m_e;
  model.unbalances.push_back(u);
  model.sensors.push_back(sensor("disk_x", "disk", model::Component::Ux));
  model.sensors.push_back(sensor("disk_y", "disk", model::Component::Uy));
  return model;
}

/// A steel shaft (4 Timoshenko elements, 0.8 m, d = 50 mm) with a gyroscopic disk in the middle
/// carrying an unbalance, on two anisotropic damped bearings; axial and torsional motion fixed at
/// the first station. Rayleigh damping so that every mode's free response dies out.
///
///   [kxx!=kyy]==========( disk )==========[kxx!=kyy]
///     s.0      s.1        s.2       s.3      s.4
inline model::Model flexible_rotor(double speed_ratio) {
  model::Model model;
  model.title = "flexible rotor";
  model::Material steel;
  steel.name = "steel";
  steel.youngs_modulus = 2.1e11;
  steel.shear_modulus = 2.1e11 / 2.6;
  steel.density = 7850.0;
  model.materials.push_back(steel);
  model::Shaft shaft;
  shaft.name = "s";
  shaft.material = "steel";
  shaft.speed_ratio = speed_ratio;
  model::ShaftElement e;
  e.length = 0.8;
  e.outer_diameter = 0.05;
  e.divisions = 4;
  shaft.elements.push_back(e);
  model.shafts.push_back(shaft);
  model::Disk disk;
  disk.name = "d";
  disk.node = "s.2";
  disk.mass = 15.0;
  disk.polar_inertia = 0.3;
  disk.diametral_inertia = 0.15;
  model.disks.push_back(disk);
  for (const char* node : {"s.0", "s.4"}) {
    model::Bearing b;
    b.name = std::string("b_") + node;
    b.node = node;
    b.stiffness.push_back(diagonal6(2e7, 5e7));
    b.damping.push_back(diagonal6(2e3, 3e3));
    model.bearings.push_back(b);
  }
  model::Constraint fixed;
  fixed.node = "s.0";
  fixed.dofs = {model::Component::Uz, model::Component::Rz};
  model.constraints.push_back(fixed);
  model.damping.rayleigh_alpha = 6.0;
  model.damping.rayleigh_beta = 2e-5;
  model::Unbalance u;
  u.name = "u_disk";
  u.node = "s.2";
  u.mass_eccentricity = 2e-4;
  u.phase = 0.7;
  model.unbalances.push_back(u);
  model.sensors.push_back(sensor("disk_x", "s.2", model::Component::Ux));
  model.sensors.push_back(sensor("disk_y", "s.2", model::Component::Uy));
  model.sensors.push_back(sensor("brg_x", "s.4", model::Component::Ux));
  model.sensors.push_back(sensor("tilt", "s.1", model::Component::Ry));
  return model;
}

}  // namespace geardyn::transient::testing
