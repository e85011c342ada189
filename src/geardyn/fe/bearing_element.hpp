#pragma once
// Bearing / bushing element: a 6x6 stiffness or damping matrix in node 1's frame acting on the
// relative motion d = u1 - u2 (u2 expressed in node 1's frame), or on u1 alone (to ground).
// Cross-coupled terms (kxy != kyx) are kept, so the element may be non-symmetric.
#include <vector>

#include "geardyn/fe/element_types.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::fe {

/// Row-major 36 numbers (ux, uy, uz, rx, ry, rz) to a matrix.
Matrix6d bearing_matrix(const model::Bearing::Matrix6& values);

/// Node-to-node element in the two node frames: with T = blockdiag(R1^T R2, R1^T R2) mapping
/// node 2's DOFs into node 1's frame, d = u1 - T u2 and the element matrix is
/// [B, -B T; -T^T B, T^T B T]. B is k (or c) in node 1's frame.
Matrix12d bearing_between_nodes(const Matrix6d& B, const Eigen::Matrix3d& frame1,
                                const Eigen::Matrix3d& frame2);

/// Linear interpolation of a table `values[i]` given at increasing `speeds[i]`, held constant
/// outside the table (Bearing in model.hpp). Precondition: sizes equal and >= 1.
template <class Matrix>
Matrix interpolate_by_speed(const std::vector<double>& speeds, const std::vector<Matrix>& values,
                            double speed) {
  if (speeds.size() == 1 || speed <= speeds.front()) return values.front();
  if (speed >= speeds.back()) return values.back();
  std::size_t i = 1;
  while (speeds[i] < speed) ++i;
  const double t = (speed - speeds[i - 1]) / (speeds[i] - speeds[i - 1]);
  return ((1.0 - t) * values[i - 1] + t * values[i]).eval();
}

/// d/d speed of interpolate_by_speed: the slope of the table's segment that holds `speed`, zero
/// outside the table (where it is held constant) and for a one-row table. At a breakpoint, the
/// slope of the segment to its right (the segment below the last one at the last breakpoint).
template <class Matrix>
Matrix slope_by_speed(const std::vector<double>& speeds, const std::vector<Matrix>& values,
                      double speed) {
  if (speeds.size() == 1 || speed < speeds.front() || speed >= speeds.back())
    return (0.0 * values.front()).eval();
  std::size_t i = 1;
  while (speeds[i] <= speed) ++i;
  return ((values[i] - values[i - 1]) / (speeds[i] - speeds[i - 1])).eval();
}

}  // namespace geardyn::fe
