#pragma once
// A body described by matrices (a superelement), joined to a rotor model: typically a solid
// component reduced by Craig-Bampton onto the reference points of its spiders (docs/theory.md §9).
//
// The body's coordinates q are, in order:
//   for each point p, its listed components c (ascending, 0..5 = ux, uy, uz, rx, ry, rz) in
//   GLOBAL axes, then n_generalized generalised coordinates (e.g. fixed-interface modal
//   coordinates eta).
// A point is either a node of the model (a shaft station or a [[nodes]] node), whose DOFs are in
// the node frame F (u_global = F u_node, for translations and rotations alike), or a new node
// the body adds to the DofMap (frame = global axes; unlisted components get no equation).
// With q = T u (T: the listed rows of blockdiag(F, F) per model-node point, identity for new
// nodes and generalised coordinates) the body adds T^T K T, T^T M T, T^T G T and T^T C T to the
// system (C: e.g. the component's own modal damping, added to the system's viscous C).
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

namespace geardyn::fe {

struct SuperelementPoint {
  std::string node;       ///< name of the model node it joins, or of the new node
  bool new_node = false;  ///< true: the body adds this node to the DofMap
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< new node: position [m]
  double speed_ratio = 0;                              ///< new node: spin speed / reference speed
  std::array<bool, 6> components{true, true, true, true, true, true};  ///< listed, global axes
};

struct Superelement {
  std::string name;  ///< unique; names the range of generalised coordinates in the DofMap
  std::vector<SuperelementPoint> points;
  int n_generalized = 0;
  Eigen::MatrixXd K;  ///< stiffness over q, symmetric
  Eigen::MatrixXd M;  ///< mass over q, symmetric
  Eigen::MatrixXd G;  ///< gyroscopic per unit reference speed over q (skew), or empty (0 x 0)
  Eigen::MatrixXd C;  ///< viscous damping over q (symmetric), or empty (0 x 0)

  /// Number of physical coordinates (listed components of all points).
  int n_physical() const {
    int n = 0;
    for (const SuperelementPoint& p : points)
      for (bool c : p.components) n += c ? 1 : 0;
    return n;
  }
  int size() const { return n_physical() + n_generalized; }
};

}  // namespace geardyn::fe
