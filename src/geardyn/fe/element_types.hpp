#pragma once
// Fixed-size matrix types shared by the element kernels. Element vectors are ordered per node as
// (ux, uy, uz, rx, ry, rz) in the node's frame (DofMap), node 1 first for two-node elements.
#include <Eigen/Dense>

namespace geardyn::fe {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

/// blockdiag(R1, R1, R2, R2): maps a two-node element vector from node frames to global
/// coordinates, u_global = T u_node (R = NodeInfo::frame).
inline Matrix12d two_node_rotation(const Eigen::Matrix3d& frame1, const Eigen::Matrix3d& frame2) {
  Matrix12d T = Matrix12d::Zero();
  T.block<3, 3>(0, 0) = frame1;
  T.block<3, 3>(3, 3) = frame1;
  T.block<3, 3>(6, 6) = frame2;
  T.block<3, 3>(9, 9) = frame2;
  return T;
}

/// blockdiag(R, R) for one node.
inline Matrix6d node_rotation(const Eigen::Matrix3d& frame) {
  Matrix6d T = Matrix6d::Zero();
  T.block<3, 3>(0, 0) = frame;
  T.block<3, 3>(3, 3) = frame;
  return T;
}

}  // namespace geardyn::fe
