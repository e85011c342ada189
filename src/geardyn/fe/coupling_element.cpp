#include "geardyn/fe/coupling_element.hpp"

#include <stdexcept>

namespace geardyn::fe {

Matrix12d coupling_between_nodes(const std::vector<double>& global_row_major,
                                 const Eigen::Matrix3d& frame1, const Eigen::Matrix3d& frame2) {
  if (global_row_major.size() != 144)
    throw std::invalid_argument("coupling_between_nodes: expected 144 values");
  Matrix12d a;
  for (int r = 0; r < 12; ++r)
    for (int c = 0; c < 12; ++c) a(r, c) = global_row_major[static_cast<std::size_t>(12 * r + c)];
  const Matrix12d T = two_node_rotation(frame1, frame2);
  return T.transpose() * a * T;
}

Matrix6d coupling_to_ground(const std::vector<double>& global_row_major,
                            const Eigen::Matrix3d& frame) {
  if (global_row_major.size() != 36)
    throw std::invalid_argument("coupling_to_ground: expected 36 values");
  Matrix6d a;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) a(r, c) = global_row_major[static_cast<std::size_t>(6 * r + c)];
  const Matrix6d T = node_rotation(frame);
  return T.transpose() * a * T;
}

}  // namespace geardyn::fe
