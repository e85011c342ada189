#include "geardyn/fe/rigid_disk.hpp"

#include "geardyn/core/units.hpp"

namespace geardyn::fe {

Matrix6d rigid_disk_mass(double mass, double diametral_inertia, double polar_inertia) {
  Matrix6d m = Matrix6d::Zero();
  m.diagonal() << mass, mass, mass, diametral_inertia, diametral_inertia, polar_inertia;
  return m;
}

Matrix6d rigid_disk_gyroscopic(double polar_inertia) {
  Matrix6d g = Matrix6d::Zero();
  g(3, 4) = polar_inertia;
  g(4, 3) = -polar_inertia;
  return g;
}

Matrix6d point_mass_matrix(double mass) {
  Matrix6d m = Matrix6d::Zero();
  m.diagonal().head<3>().setConstant(mass);
  return m;
}

DiskInertia annular_disk_inertia(double density, double outer_radius, double inner_radius,
                                 double thickness) {
  const double r2 = outer_radius * outer_radius + inner_radius * inner_radius;
  DiskInertia d;
  d.mass = density * units::kPi * (outer_radius * outer_radius - inner_radius * inner_radius) *
           thickness;
  d.polar = d.mass * r2 / 2;
  d.diametral = d.mass * (3 * r2 + thickness * thickness) / 12;
  return d;
}

}  // namespace geardyn::fe
