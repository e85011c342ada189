#pragma once
// Small rotor models built in code for the modal and Campbell tests.
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "geardyn/model/model.hpp"

namespace geardyn::test {

/// Diagonal 6x6 matrix (row-major over ux, uy, uz, rx, ry, rz).
inline model::Bearing::Matrix6 diagonal6(double ux, double uy, double uz, double rx, double ry,
                                         double rz) {
  model::Bearing::Matrix6 m{};
  const double d[6] = {ux, uy, uz, rx, ry, rz};
  for (int i = 0; i < 6; ++i) m[static_cast<std::size_t>(i * 6 + i)] = d[i];
  return m;
}

/// A free node spinning at `speed_ratio` x the reference speed.
inline model::Node spinning_node(const std::string& name, double speed_ratio) {
  model::Node n;
  n.name = name;
  n.speed_ratio = speed_ratio;
  return n;
}

inline model::Constraint fix(const std::string& node, std::vector<model::Component> dofs) {
  model::Constraint c;
  c.node = node;
  c.dofs = std::move(dofs);
  return c;
}

/// Jeffcott rotor: a point mass m on an isotropic spring k with a damper c (x and y only).
///
///        k, c            y
///   ///--/\/\--( m )     |__ x      spin about z (speed ratio 1)
inline model::Model jeffcott(double m, double k, double c) {
  using C = model::Component;
  model::Model model;
  model.nodes.push_back(spinning_node("disk", 1.0));
  model::PointMass pm;
  pm.node = "disk";
  pm.mass = m;
  model.point_masses.push_back(pm);
  model::Bearing b;
  b.name = "support";
  b.node = "disk";
  b.stiffness = {diagonal6(k, k, 0, 0, 0, 0)};
  b.damping = {diagonal6(c, c, 0, 0, 0, 0)};
  model.bearings.push_back(b);
  model.constraints.push_back(fix("disk", {C::Uz, C::Rx, C::Ry, C::Rz}));
  return model;
}

/// The steel of Friswell et al. 2010, Example 5.9.1: E = 211 GPa, G = 81.2 GPa, rho = 7810 kg/m^3.
inline model::Material friswell_steel() {
  model::Material steel;
  steel.name = "steel";
  steel.youngs_modulus = 211e9;
  steel.shear_modulus = 81.2e9;
  steel.density = 7810;
  return steel;
}

// Friswell, Penny, Garvey, Lees, "Dynamics of Rotating Machines", Cambridge University Press
// 2010, Example 5.9.1: a 1.5 m steel shaft (diameter 50 mm) with two disks on 1 MN/m isotropic
// bearings, nothing holding it axially or in torsion. `elements` equal Timoshenko elements; the
// disks stay at 0.5 m and 1.0 m (elements must be a multiple of 3). The six pieces of 0.25 m keep
// each piece within the schema's 1000 divisions.
inline model::Model friswell_591(int elements) {
  model::Model model;
  model.materials.push_back(friswell_steel());
  model::Shaft s;
  s.name = "shaft";
  s.material = "steel";
  s.shear_coefficient = 0.8863;
  for (int piece = 0; piece < 6; ++piece) {
    model::ShaftElement e;
    e.length = 0.25;
    e.outer_diameter = 0.05;
    e.divisions = elements / 6;
    s.elements.push_back(e);
  }
  model.shafts.push_back(s);
  const int third = elements / 3;
  for (const auto& [station, diameter] : {std::pair{third, 0.28}, std::pair{2 * third, 0.35}}) {
    const double ro = diameter / 2, ri = 0.025, h = 0.07;
    const double mass = 7810 * std::numbers::pi * (ro * ro - ri * ri) * h;
    model::Disk d;
    d.node = "shaft." + std::to_string(station);
    d.mass = mass;
    d.polar_inertia = mass * (ro * ro + ri * ri) / 2;
    d.diametral_inertia = mass * (3 * (ro * ro + ri * ri) + h * h) / 12;
    model.disks.push_back(d);
  }
  for (int station : {0, elements}) {
    model::Bearing b;
    b.node = "shaft." + std::to_string(station);
    b.stiffness = {test::diagonal6(1e6, 1e6, 0, 0, 0, 0)};
    model.bearings.push_back(b);
  }
  return model;
}

}  // namespace geardyn::test
