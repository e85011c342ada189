#pragma once
// The exterior surface of a solid mesh, as the radiating surface of a housing (issue #17, item 3):
// its faces with area, outward normal and centroid, and per surface node a lumped area and an
// outward normal, so that a sum over nodes sum_i A_i f_i approximates the surface integral of f.
//
// Faces per element type (local corner numbers in solid/mesh.hpp's Gmsh ordering):
//   tet4/tet10      4 triangles  (0,1,2) (0,1,3) (1,2,3) (0,2,3)
//   hex8/hex20      6 quads      (0,1,2,3) (4,5,6,7) (0,1,5,4) (1,2,6,5) (2,3,7,6) (3,0,4,7)
//   wedge6/wedge15  2 triangles  (0,1,2) (3,4,5) and 3 quads (0,1,4,3) (1,2,5,4) (2,0,3,5)
// with the mid-edge nodes of the quadratic types. A face is exterior when no other element has a
// face on the same corner nodes. Each face's nodes are stored counter-clockwise seen from outside
// (outward normal by the right-hand rule), in VTK's order for the face's cell type: corners, then
// the mid-edge nodes of edges (0,1) (1,2) (2,0) [triangle] or (0,1) (1,2) (2,3) (3,0) [quad]
// (VTK_TRIANGLE, VTK_QUADRATIC_TRIANGLE, VTK_QUAD, VTK_QUADRATIC_QUAD). "Outward" is decided per
// face against its element's corner centroid, which is right for every element that is convex
// enough to be valid.
//
// Geometry by Gauss quadrature of the face's own shape functions (3-, 6-node triangles; 4-, 8-node
// serendipity quads), so quadratic faces are curved: 7-point degree-5 rule on triangles (Dunavant,
// "High degree efficient symmetrical Gaussian quadrature rules for the triangle", 1985), 3 x 3
// Gauss-Legendre on quads.
//
// Lumped nodal areas: for linear faces the consistent row sum A_i = int N_i dA (all positive). For
// quadratic faces the row sum is useless (zero at the corners of a flat 6-node triangle, negative,
// -A/12, at the corners of a flat 8-node quad), so they are lumped by diagonal scaling (Hinton,
// Rock and Zienkiewicz, "A note on mass lumping and related processes in the finite element
// method", 1976): A_i = A int N_i^2 dA / sum_j int N_j^2 dA, positive and summing to the face
// area. The node normal is the same weighting of the face normal, normalised:
// n_i ~ sum_faces int w_i n dA with w_i = N_i (linear) or the scaled N_i^2 (quadratic).
#include <Eigen/Dense>
#include <vector>

#include "geardyn/solid/mesh.hpp"

namespace geardyn::acoustics {

/// One exterior element face.
struct SurfaceFace {
  std::vector<int>
      nodes;         ///< indices into Surface::nodes (corners, then mid-side nodes; VTK order)
  int element = -1;  ///< index into mesh.elements
  double area = 0;   ///< [m^2]
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();    ///< unit, outward (area-weighted mean)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< area centroid [m]
  /// This face's share of each of its nodes' lumped area [m^2] (same order as `nodes`; sums to
  /// `area`). Surface::node_area is the sum of these over the faces.
  std::vector<double> node_weight;
};

struct Surface {
  std::vector<int> nodes;        ///< mesh node indices (positions in mesh.coords), ascending
  Eigen::VectorXd node_area;     ///< lumped area per surface node [m^2] (see the file comment)
  Eigen::Matrix3Xd node_normal;  ///< unit outward normal per surface node (weighted as the area)
  std::vector<SurfaceFace> faces;
  double area() const;  ///< sum of the face areas [m^2]
  int num_nodes() const { return static_cast<int>(nodes.size()); }
};

/// Exterior faces of `mesh` (faces belonging to one element only): all of them (node_set empty)
/// or those whose nodes (corner and mid-side) all lie in `node_set` (mesh node indices, as in
/// mesh.node_sets). Throws std::invalid_argument when the set gives no face (the message says how
/// many set nodes there are and how many lie on the exterior), when a set index is outside the
/// mesh, or when the mesh has no exterior face; the caller turns it into a located InputError.
Surface exterior_surface(const solid::Mesh& mesh, const std::vector<int>& node_set = {});

/// Row indices into `dofs` (e.g. reduce::ReducedComponent::full_dofs, or an assembled solid's DOF
/// list) of each surface node's ux, uy, uz: 3 per node, surface-node order, so that the rows
/// rows[3 i + c] of a recovery matrix x = T q form the `recovery` of ErpOperator. A node's DOFs
/// are matched by its external id (mesh.node_ids[i], or the index i when the mesh has no ids, as
/// solid assembly numbers them) and component 0..2. Throws std::invalid_argument naming the first
/// surface node without one of its translations in `dofs` (e.g. a constrained node).
std::vector<int> surface_dof_rows(const solid::Mesh& mesh, const Surface& s,
                                  const std::vector<solid::DofInfo>& dofs);

}  // namespace geardyn::acoustics
