#pragma once
// The full 360 deg mesh of a cyclic structure from one sector mesh: N copies rotated by
// s alpha (alpha = 2 pi / N, s = 0..N-1) about an axis through the origin, coincident interface
// nodes merged. Used to check a cyclic-symmetry analysis against the full model on the same mesh.
#include <Eigen/Dense>
#include <vector>

#include "geardyn/eig/eigen_options.hpp"
#include "geardyn/solid/mesh.hpp"

namespace geardyn::cyclic {

struct ReplicatedMesh {
  solid::Mesh mesh;
  /// node_map[s][i]: index in `mesh` of node i of the sector in copy s (node_map[0][i] = i).
  std::vector<std::vector<int>> node_map;
  int merged_nodes = 0;        ///< nodes of copies s >= 1 merged with an earlier node
  double worst_merge_gap = 0;  ///< largest distance between two merged nodes [m]
};

/// Replicates `sector` N times about `axis` (through the origin, right-handed).
///   Nodes: copy s puts node i at R(s alpha) x_i; a node within `tolerance` of a node of an
///     earlier copy is merged with it (nodes of the same copy are never merged). Node ids:
///     id + s * stride with stride the smallest power of 10 above the largest sector id (merged
///     nodes keep the earlier id); element and mass ids likewise.
///   Elements, rigid elements, constraints: copied with remapped nodes.
///   Point masses: offset rotated, inertia R J R^T.
///   Springs: each end's direction rotated, n -> R(s alpha) n (solid::Spring::direction1/2), so
///     a sector's spring on ux acts along the copy's rotated x axis, as the cyclic-symmetry
///     constraints imply for the sector model; ends along the axis of symmetry stay scalar.
///     Spring ids: id + s * stride, like the element ids.
///   Node and element sets: the union of the copies under the same name.
///   Materials: shared.
/// tolerance NaN: 1e-6 times the largest distance of a sector node from the origin.
/// Throws InputError for N < 2, a zero axis, rigid elements or constraints whose component sets
/// change under the rotation (e.g. a constraint on ux only: it would fix a different direction
/// in each copy), or a copy whose node would merge with two earlier nodes.
ReplicatedMesh replicate(const solid::Mesh& sector, int n_sectors, double tolerance = eig::kNaN,
                         const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ());

}  // namespace geardyn::cyclic
