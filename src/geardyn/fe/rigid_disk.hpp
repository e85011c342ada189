#pragma once
// Rigid disk and point mass at one node, in the node frame (e3 = spin axis).
// Source: Friswell, Penny, Garvey, Lees, "Dynamics of Rotating Machines", CUP 2010, ch. 5 (rigid
// disk: translational mass m, diametral inertia Id about e1 and e2, polar inertia Ip about e3).
#include "geardyn/fe/element_types.hpp"

namespace geardyn::fe {

/// diag(m, m, m, Id, Id, Ip). Preconditions: m, Id, Ip >= 0.
Matrix6d rigid_disk_mass(double mass, double diametral_inertia, double polar_inertia);

/// Gyroscopic matrix of a disk spinning at unit speed about +e3, entering as
/// M q'' + Omega G q' + K q = f: G(rx, ry) = +Ip, G(ry, rx) = -Ip. From the angular momentum of the
/// tilted disk, H = (Id rx' + Ip Omega ry) e1 + (Id ry' - Ip Omega rx) e2 + Ip Omega e3, so forward
/// whirl frequencies rise with speed. Multiply by the node's speed ratio.
Matrix6d rigid_disk_gyroscopic(double polar_inertia);

/// diag(m, m, m, 0, 0, 0).
Matrix6d point_mass_matrix(double mass);

/// Mass, polar and diametral inertia of a uniform annular disk (outer radius r_o, bore r_i,
/// thickness h, density rho): m = rho pi (r_o^2 - r_i^2) h, Ip = m (r_o^2 + r_i^2) / 2,
/// Id = m (3 (r_o^2 + r_i^2) + h^2) / 12 (about a diameter through the centre of mass).
struct DiskInertia {
  double mass = 0, polar = 0, diametral = 0;
};
DiskInertia annular_disk_inertia(double density, double outer_radius, double inner_radius,
                                 double thickness);

}  // namespace geardyn::fe
