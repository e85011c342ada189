#include "geardyn/drivetrain/placement.hpp"

#include <algorithm>
#include <cmath>

namespace geardyn::drivetrain {

void PlacedElement::gather(const Eigen::VectorXd& q, Eigen::VectorXd& u) const {
  u.setZero(B.rows());
  for (std::size_t k = 0; k < equations.size(); ++k)
    u += B.col(static_cast<Eigen::Index>(k)) * q[equations[k]];
}

void PlacedElement::scatter(const Eigen::VectorXd& f, double scale, Eigen::VectorXd& r) const {
  for (std::size_t k = 0; k < equations.size(); ++k)
    r[equations[k]] += scale * B.col(static_cast<Eigen::Index>(k)).dot(f);
}

Eigen::MatrixXd PlacedElement::project(const Eigen::MatrixXd& A) const {
  return B.transpose() * A * B;
}

void PlacementBuilder::add_projection(int row, int node, bool rotation,
                                      const Eigen::Vector3d& direction, double scale) {
  if (node < 0) return;
  // Global motion = frame * node components, so the projection on d has the coefficients
  // frame^T d on the node's three components.
  const Eigen::Vector3d c = dofs_.node(node).frame.transpose() * direction;
  const int first = rotation ? 3 : 0;
  for (int i = 0; i < 3; ++i)
    add(row, dofs_.dof(node, static_cast<model::Component>(first + i)), scale * c[i]);
}

void PlacementBuilder::add(int row, int equation, double coefficient) {
  if (equation < 0 || coefficient == 0.0) return;
  entries_.push_back({row, equation, coefficient});
}

bool PlacementBuilder::row_empty(int row) const {
  return std::none_of(entries_.begin(), entries_.end(),
                      [row](const Entry& e) { return e.row == row && e.value != 0.0; });
}

PlacedElement PlacementBuilder::finish(std::shared_ptr<const elements::ForceElement> element,
                                       std::string kind, std::string name) const {
  PlacedElement p;
  for (const Entry& e : entries_) p.equations.push_back(e.equation);
  std::sort(p.equations.begin(), p.equations.end());
  p.equations.erase(std::unique(p.equations.begin(), p.equations.end()), p.equations.end());
  p.B.setZero(rows_, static_cast<Eigen::Index>(p.equations.size()));
  for (const Entry& e : entries_) {
    const auto col =
        std::lower_bound(p.equations.begin(), p.equations.end(), e.equation) - p.equations.begin();
    p.B(e.row, col) += e.value;
  }
  p.element = std::move(element);
  p.kind = std::move(kind);
  p.name = std::move(name);
  return p;
}

Eigen::Matrix3d frame_with_axis(const Eigen::Vector3d& axis, const Eigen::Vector3d& x_hint) {
  const Eigen::Vector3d z = axis.normalized();
  Eigen::Vector3d x = x_hint - x_hint.dot(z) * z;
  if (x.norm() < 1e-6 * std::max(1.0, x_hint.norm())) {
    const Eigen::Vector3d other =
        std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    x = other - other.dot(z) * z;
  }
  x.normalize();
  Eigen::Matrix3d f;
  f.col(0) = x;
  f.col(1) = z.cross(x);
  f.col(2) = z;
  return f;
}

}  // namespace geardyn::drivetrain
