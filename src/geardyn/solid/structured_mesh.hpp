#pragma once
// Structured meshes of simple solids, for tests and validation: a box and an annular sector.
//
// Supported element types: Hex8, Hex20, Tet4 (6 tets per hex cell, conforming: every hex is split
// along its main diagonal from its lowest to its highest corner, the same way in every cell),
// Tet10 (the same with mid-edge nodes), Wedge6 (2 wedges per hex cell, the cell's bottom face
// split along a diagonal, extruded along the third axis), Wedge15 (same with mid-edge nodes).
// The mesh has one material (index 0) and node ids 1..n, element ids 1..m.
#include <Eigen/Dense>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::solid {

/// Box [lo, hi] with nx x ny x nz cells. Node sets "xmin", "xmax", "ymin", "ymax", "zmin",
/// "zmax" (all nodes, corner and mid-edge, on each face). Wedges are extruded along z.
/// Throws InputError for n < 1 or hi <= lo in any direction.
Mesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny, int nz,
              ElementType type, const Material& material);

/// Annular sector about the z axis: r_inner <= r <= r_outer, 0 <= theta <= angle,
/// -thickness/2 <= z <= thickness/2, with n_radial x n_theta x n_thick cells (nodes equally
/// spaced in r, theta and z). Node sets "inner", "outer", "bottom" (z = -t/2), "top" (z = t/2),
/// and for angle < 2 pi "left" (theta = 0) and "right" (theta = angle). The right-face nodes are
/// exactly the left-face nodes rotated by `angle` (same r and z; they appear in the same order in
/// both sets, so right[k] pairs with left[k]). angle = 2 pi: closed annulus, the seam nodes merged,
/// no "left"/"right" sets. Wedges are extruded along z. Mid-edge nodes of quadratic elements are
/// placed by the exact (r, theta, z) map, so circumferential edges follow the arcs.
/// Throws InputError for r_inner <= 0, r_outer <= r_inner, thickness <= 0, angle outside
/// (0, 2 pi], counts < 1, or a closed annulus with n_theta < 3.
Mesh annular_sector_mesh(double r_inner, double r_outer, double thickness, double angle_rad,
                         int n_radial, int n_theta, int n_thick, ElementType type,
                         const Material& material);

}  // namespace geardyn::solid
