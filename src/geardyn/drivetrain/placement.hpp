#pragma once
// A force element placed in the assembled system (docs/theory.md §16.9): its relative coordinates
// are a linear map of the system's unknowns,
//   u = B q_e,   q_e = q[equations],
// with B (n x m) built from the node frames of the DofMap and the element's frame (a direction,
// a bolt axis, a bushing's axes, a bearing's axis, a mesh's line of action). The element's
// internal force f and tangents K_t, C_t enter the system as
//   r[equations] += B^T f,   S[equations, equations] += B^T (c_k K_t + c_c C_t) B.
// Constrained DOFs (no equation) and ground are left out of `equations`: their motion is zero.
#include <Eigen/Dense>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/elements/force_element.hpp"
#include "geardyn/fe/dof_map.hpp"

namespace geardyn::drivetrain {

struct PlacedElement {
  std::shared_ptr<const elements::ForceElement> element;
  std::string kind;  ///< "contact", "bolt", "bushing", "rolling_bearing", "gear_mesh", "clutch"
  std::string name;
  std::vector<int> equations;  ///< m distinct system equations
  Eigen::MatrixXd B;           ///< n x m

  /// u = B q[equations].
  void gather(const Eigen::VectorXd& q, Eigen::VectorXd& u) const;
  /// r[equations] += scale B^T f.
  void scatter(const Eigen::VectorXd& f, double scale, Eigen::VectorXd& r) const;
  /// The m x m block B^T A B (A n x n).
  Eigen::MatrixXd project(const Eigen::MatrixXd& A) const;
};

/// Builds the B of one element row by row: each row a sum of node DOF projections. Coefficients
/// on the same equation add up; constrained DOFs are dropped.
class PlacementBuilder {
 public:
  PlacementBuilder(const fe::DofMap& dofs, int rows) : dofs_(dofs), rows_(rows) {}

  /// Row `row` += scale x (the node's translation (rotation = false) or rotation vector, in
  /// global axes) . direction. node < 0: ground (nothing added).
  void add_projection(int row, int node, bool rotation, const Eigen::Vector3d& direction,
                      double scale);
  /// Row `row` += coefficient x q[equation] (equation < 0: nothing).
  void add(int row, int equation, double coefficient);
  /// True when row `row` has no coefficient on any equation (both ends fixed).
  bool row_empty(int row) const;

  /// The placed element; equations in ascending order.
  PlacedElement finish(std::shared_ptr<const elements::ForceElement> element, std::string kind,
                       std::string name) const;

 private:
  struct Entry {
    int row, equation;
    double value;
  };
  const fe::DofMap& dofs_;
  int rows_;
  std::vector<Entry> entries_;
};

/// A right-handed orthonormal frame (columns x, y, z) with z along `axis` and x the part of
/// `x_hint` normal to it (x_hint nearly parallel to the axis: any normal).
Eigen::Matrix3d frame_with_axis(const Eigen::Vector3d& axis, const Eigen::Vector3d& x_hint);

}  // namespace geardyn::drivetrain
