#include "geardyn/elements/force_element.hpp"

#include <algorithm>

namespace geardyn::elements {

namespace {

// Central-difference Jacobian of the element's force in u (wrt_velocity false) or v.
Eigen::MatrixXd differences(const ForceElement& element, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v, double t, double h, bool wrt_velocity) {
  const Eigen::Index n = element.size();
  Eigen::MatrixXd j(n, n);
  ElementForce plus, minus;
  for (Eigen::Index k = 0; k < n; ++k) {
    Eigen::VectorXd up = u, um = u, vp = v, vm = v;
    (wrt_velocity ? vp : up)(k) += h;
    (wrt_velocity ? vm : um)(k) -= h;
    element.evaluate(up, vp, t, plus);
    element.evaluate(um, vm, t, minus);
    j.col(k) = (plus.force - minus.force) / (2.0 * h);
  }
  return j;
}

double relative_error(const Eigen::MatrixXd& analytic, const Eigen::MatrixXd& fd, double floor) {
  const double scale = std::max(fd.cwiseAbs().maxCoeff(), floor);
  return (analytic - fd).cwiseAbs().maxCoeff() / scale;
}

}  // namespace

TangentCheck check_tangents(const ForceElement& element, const Eigen::VectorXd& u,
                            const Eigen::VectorXd& v, double t, double h_u, double h_v,
                            double floor) {
  ElementForce at;
  element.evaluate(u, v, t, at);
  TangentCheck c;
  c.stiffness_error =
      relative_error(at.stiffness, differences(element, u, v, t, h_u, false), floor);
  c.damping_error = relative_error(at.damping, differences(element, u, v, t, h_v, true), floor);
  return c;
}

}  // namespace geardyn::elements
