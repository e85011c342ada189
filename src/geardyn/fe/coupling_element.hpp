#pragma once
// General linear coupling (model::Coupling): 12x12 (node to node) or 6x6 (node to ground)
// stiffness, damping or mass given in global coordinates, transformed to the node frames:
// with u_global = T u_node (T = blockdiag of the node frames), A_node = T^T A_global T.
#include <vector>

#include "geardyn/fe/element_types.hpp"

namespace geardyn::fe {

/// Row-major 144 numbers to the 12x12 element in the node frames.
Matrix12d coupling_between_nodes(const std::vector<double>& global_row_major,
                                 const Eigen::Matrix3d& frame1, const Eigen::Matrix3d& frame2);

/// Row-major 36 numbers to the 6x6 node-to-ground element in the node frame.
Matrix6d coupling_to_ground(const std::vector<double>& global_row_major,
                            const Eigen::Matrix3d& frame);

}  // namespace geardyn::fe
