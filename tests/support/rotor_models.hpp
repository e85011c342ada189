#pragma once
// Small rotor models built in code for the modal and Campbell tests.
#include <cmath>
#include <string>

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

}  // namespace geardyn::test
