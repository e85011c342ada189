#include "geardyn/fe/bearing_element.hpp"

namespace geardyn::fe {

Matrix6d bearing_matrix(const model::Bearing::Matrix6& values) {
  Matrix6d m;
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) m(r, c) = values[static_cast<std::size_t>(6 * r + c)];
  return m;
}

Matrix12d bearing_between_nodes(const Matrix6d& B, const Eigen::Matrix3d& frame1,
                                const Eigen::Matrix3d& frame2) {
  const Matrix6d T = node_rotation(frame1.transpose() * frame2);
  Matrix12d e;
  e.block<6, 6>(0, 0) = B;
  e.block<6, 6>(0, 6) = -B * T;
  e.block<6, 6>(6, 0) = -T.transpose() * B;
  e.block<6, 6>(6, 6) = T.transpose() * B * T;
  return e;
}

}  // namespace geardyn::fe
