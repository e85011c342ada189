#pragma once
// Sparse global stiffness and mass of a solid Mesh, with constraints and multipoint constraints
// eliminated.
//
// DOFs per node ("all" DOF vector, node-major, node by node in mesh order):
//   6 (ux uy uz rx ry rz) for a node that needs rotations: the independent node of a Rigid
//     element, the reference node of an Averaging element, a node with a PointMass that has an
//     inertia or an offset, a node with a Spring on component 3..5, and any node referenced
//     by something but by no solid element;
//   3 (ux uy uz) for the other nodes of solid elements;
//   0 for nodes referenced by nothing (no element, rigid element, mass, spring or constraint).
// Components 3..5 named on a 3-DOF node (a Constraint "123456" on a solid node, a Rigid element's
// dependent solid node) refer to DOFs that do not exist and are ignored.
//
// Multipoint constraints, all linear, u_dependent = sum c_j u_j:
//   Rigid (RBE2), independent node r (6 DOFs), dependent node d at x_d, listed components:
//       u_d = u_r + theta_r x (x_d - x_r),     theta_d = theta_r   (if d has rotations).
//   Averaging (RBE3), reference node r, independent nodes i at x_i with weights w_i (their
//   translations only): the rigid motion (u_c, theta) at the weighted centroid
//   c = sum w_i x_i / W, W = sum w_i, that fits the independent translations best in the
//   weighted least-squares sense, minimise sum w_i |u_c + theta x (x_i - c) - u_i|^2:
//       u_c   = sum w_i u_i / W,
//       theta = J^-1 sum w_i (x_i - c) x u_i,   J = sum w_i (|x_i - c|^2 I - (x_i - c)(x_i - c)^T)
//       u_r   = u_c + theta x (x_r - c),        theta_r = theta.
//   The reference node's listed components are dependent; its other components stay free.
//   (MSC Nastran Reference Manual, RBE3 "weighted average"; the interpolation used by
//   Abaqus *DISTRIBUTING COUPLING with uniform weighting is the same fit.) If the independent
//   nodes are collinear (J singular) the rotation about their line is undetermined: the
//   pseudo-inverse is used when no rotation is listed and x_r is on the line, otherwise
//   InputError.
// Chains (a dependent DOF whose masters are themselves dependent) are resolved by substitution;
// a DOF dependent in two rigid elements, or both dependent and constrained, is an InputError.
//
// With T the resulting sparse map  u_all = T u_reduced  (constrained DOFs -> 0 rows), the
// reduced matrices are  K = T^T K_all T,  M = T^T M_all T  (formed element by element, never as a
// product of global matrices). SolidSystem::recovery is T.
//
// Point masses (CONM2): with offset e (CG = node + e), mass m and inertia J about the CG, the
// node's 6x6 mass is  [m I, -m S(e); m S(e), J + m (|e|^2 I - e e^T)]  (S(e) v = e x v), i.e. the
// parallel-axis theorem; on a 3-DOF node (J = 0, e = 0) it is m I.
// Springs (CELAS): k (u_1 - u_2)^2 / 2 between two DOFs, or k u_1^2 / 2 grounded; an end with a
// direction n (Spring::direction1/2) contributes n . u over its node's triple instead of one DOF,
// so a grounded spring along n adds k n n^T to the node's 3x3 block.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::solid {

struct AssemblyOptions {
  /// Worker threads for element integration and scatter; 0: std::thread::hardware_concurrency.
  int threads = 1;
  /// Assemble the mass matrix (false: M is empty, 0 x 0).
  bool mass = true;
  /// Remove DOFs whose reduced stiffness and mass columns are both exactly zero (e.g. the
  /// rotations of a free-standing node that nothing resists); they are listed in
  /// SolidSystem::removed_dofs and recover to zero. false: keep them (K and M singular).
  bool remove_unconnected_dofs = true;
  /// Progress of the element loop (nullptr: silent).
  Progress* progress = nullptr;
};

struct SolidSystem {
  /// The reduced (kept) DOFs, in the order of the rows of K and M: node by node in mesh order,
  /// components ascending.
  std::vector<DofInfo> dofs;
  /// Reduced stiffness [N/m, N/rad, N m/rad] and mass [kg, kg m, kg m^2], symmetric, both
  /// triangles stored, compressed column-major.
  Eigen::SparseMatrix<double> K, M;
  /// u_all = recovery * u_reduced: all node DOFs (node-major, node_dofs[n] per node starting at
  /// node_offset[n]) from the reduced ones. num_all_dofs() x dofs.size().
  Eigen::SparseMatrix<double> recovery;

  std::vector<int> node_dofs;    ///< per node: 0, 3 or 6
  std::vector<int> node_offset;  ///< per node: index of its first DOF in the all-DOF vector
  /// per all-DOF: its index among the reduced DOFs, or -1 (constrained, dependent or removed).
  std::vector<int> reduced_index;
  /// DOFs removed by AssemblyOptions::remove_unconnected_dofs.
  std::vector<DofInfo> removed_dofs;

  int num_dofs() const { return static_cast<int>(dofs.size()); }
  int num_all_dofs() const { return static_cast<int>(reduced_index.size()); }
  /// Index of (node, component 0..5) in the all-DOF vector, -1 if the node has no such DOF.
  int all_dof(int node, int component) const;
  /// Index of (node, component 0..5) among the reduced DOFs (row of K), -1 if the DOF is
  /// absent, constrained, dependent (eliminated by a rigid element) or removed.
  int node_dof(int node, int component) const;

  double volume = 0;      ///< total solid-element volume [m^3]
  double solid_mass = 0;  ///< sum rho V over solid elements [kg]
  int num_elements = 0;
  double seconds = 0;  ///< wall time of assemble()
};

/// Assembles K and M of `mesh` (see the file comment). Throws InputError for invalid input:
/// node indices out of range, bad elements (see element_matrices), bad materials, rigid-element
/// conflicts, springs/masses with non-finite or negative values, components outside 0..5.
SolidSystem assemble(const Mesh& mesh, const AssemblyOptions& options = {});

/// The node indices of node set `name`. Throws InputError at `where` (key path `name`) listing
/// the available set names when there is no such set.
std::vector<int> nodes_of_set(const Mesh& mesh, const std::string& name, SourceLocation where);

/// Number of DOFs of each node according to the rules in the file comment (0, 3 or 6).
std::vector<int> node_dof_counts(const Mesh& mesh);

}  // namespace geardyn::solid
