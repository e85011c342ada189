#pragma once
// Small systems for the frequency-response tests: matrix-level single- and multi-DOF systems
// (LinearSystem without a DOF map) and plain-data models assembled by fe.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::harmonic_test {

using Complex = std::complex<double>;

inline fe::SparseMatrix sparse(const Eigen::MatrixXd& A) {
  fe::SparseMatrix S = A.sparseView();
  S.makeCompressed();
  return S;
}

/// m x'' + c x' + k (1 + i eta) x = f: one DOF, matrices 1 x 1, no DOF map.
inline fe::LinearSystem sdof(double m, double k, double c, double eta = 0.0) {
  fe::LinearSystem s;
  s.M = sparse(Eigen::MatrixXd::Constant(1, 1, m));
  s.K = sparse(Eigen::MatrixXd::Constant(1, 1, k));
  s.C = sparse(Eigen::MatrixXd::Constant(1, 1, c));
  s.G = fe::SparseMatrix(1, 1);
  s.K_loss = sparse(Eigen::MatrixXd::Constant(1, 1, eta * k));
  return s;
}

/// Fixed-free chain of n masses m joined by springs k (ground - m - m - ... - m).
inline Eigen::MatrixXd chain_stiffness(int n, double k, bool grounded = true) {
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i + 1 < n; ++i) {
    K(i, i) += k;
    K(i + 1, i + 1) += k;
    K(i, i + 1) -= k;
    K(i + 1, i) -= k;
  }
  if (grounded) K(0, 0) += k;
  return K;
}

/// Relative error with an absolute floor.
inline double relative_error(double value, double reference, double floor = 1e-300) {
  return std::abs(value - reference) / std::max(std::abs(reference), floor);
}

inline analyses::HarmonicSettings grid(double f_min, double f_max, int n_points, bool adaptive) {
  analyses::HarmonicSettings s;
  s.f_min = f_min;
  s.f_max = f_max;
  s.n_points = n_points;
  s.adaptive = adaptive;
  return s;
}

/// Jeffcott rotor: a point mass m on a node "disk" that spins with the reference speed, held by
/// a bearing to ground with stiffness kx, ky and damping c in both directions; axial and
/// rotational DOFs constrained. Unbalance "u1" (m e) at phase 0; sensors "dx" (ux), "dy" (uy).
inline model::Model jeffcott(double m, double kx, double ky, double c, double me) {
  model::Model model;
  model.title = "Jeffcott rotor";
  model::Node node;
  node.name = "disk";
  node.speed_ratio = 1.0;
  model.nodes.push_back(node);
  model::PointMass mass;
  mass.name = "m";
  mass.node = "disk";
  mass.mass = m;
  model.point_masses.push_back(mass);
  model::Bearing b;
  b.name = "b";
  b.node = "disk";
  model::Bearing::Matrix6 k{}, d{};
  k[0] = kx;
  k[7] = ky;
  d[0] = c;
  d[7] = c;
  b.stiffness.push_back(k);
  b.damping.push_back(d);
  model.bearings.push_back(b);
  model::Constraint fix;
  fix.node = "disk";
  fix.dofs = {model::Component::Uz, model::Component::Rx, model::Component::Ry,
              model::Component::Rz};
  model.constraints.push_back(fix);
  model::Unbalance u;
  u.name = "u1";
  u.node = "disk";
  u.mass_eccentricity = me;
  model.unbalances.push_back(u);
  model::Sensor dx, dy;
  dx.name = "dx";
  dx.node = "disk";
  dx.dof = model::Component::Ux;
  dy.name = "dy";
  dy.node = "disk";
  dy.dof = model::Component::Uy;
  model.sensors = {dx, dy};
  return model;
}

}  // namespace geardyn::harmonic_test
