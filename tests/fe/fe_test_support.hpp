#pragma once
// Shared helpers for the fe tests: model builders and small dense reference eigensolvers.
#include <Eigen/Dense>
#include <algorithm>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "geardyn/fe/linear_system.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::fe::test {

inline model::Material material(const std::string& name, double E, double G, double rho) {
  model::Material m;
  m.name = name;
  m.youngs_modulus = E;
  m.shear_modulus = G;
  m.density = rho;
  return m;
}

/// A uniform shaft of `n` equal elements (one section with `divisions` = n).
inline model::Shaft uniform_shaft(const std::string& name, const std::string& material_name,
                                  double length, double outer_diameter, int n,
                                  double inner_diameter = 0.0) {
  model::Shaft s;
  s.name = name;
  s.material = material_name;
  model::ShaftElement e;
  e.length = length;
  e.outer_diameter = outer_diameter;
  e.inner_diameter = inner_diameter;
  e.divisions = n;
  s.elements.push_back(e);
  return s;
}

inline model::Constraint constrain(const std::string& node, std::vector<model::Component> dofs) {
  model::Constraint c;
  c.node = node;
  c.dofs = std::move(dofs);
  return c;
}

/// Isotropic lateral bearing to ground (kxx = kyy = k).
inline model::Bearing lateral_bearing(const std::string& node, double k) {
  model::Bearing b;
  b.name = "b_" + node;
  b.node = node;
  model::Bearing::Matrix6 stiffness{};
  stiffness[0] = k;
  stiffness[7] = k;
  b.stiffness.push_back(stiffness);
  return b;
}

/// Undamped natural frequencies [rad/s] of K x = w^2 M x, ascending (negative round-off -> 0).
inline Eigen::VectorXd undamped_frequencies(const LinearSystem& s) {
  const Eigen::MatrixXd K = Eigen::MatrixXd(s.K), M = Eigen::MatrixXd(s.M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M);
  return solver.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

/// Undamped frequency [rad/s] of the lowest mode (above `omega_min`) whose mass-weighted energy
/// is mostly in the torsional DOFs (mode_families), from the dense symmetric solver.
inline double first_torsional_undamped(const LinearSystem& s, double omega_min) {
  const Eigen::MatrixXd K = Eigen::MatrixXd(s.K), M = Eigen::MatrixXd(s.M);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M);
  for (int i = 0; i < s.size(); ++i) {
    const double w = std::sqrt(std::max(solver.eigenvalues()(i), 0.0));
    if (w <= omega_min) continue;
    const Eigen::VectorXcd shape = solver.eigenvectors().col(i).cast<std::complex<double>>();
    if (mode_families(s, shape).torsional > 0.5) return w;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

struct ComplexMode {
  std::complex<double> lambda;
  Eigen::VectorXcd shape;  ///< displacement part of the state vector
};

/// Eigenvalues with Im >= 0 of M q'' + D q' + K q = 0 in first-order form
/// z = [q; q'], z' = A z, A = [0 I; -M^-1 K, -M^-1 D], sorted by |lambda|.
inline std::vector<ComplexMode> complex_modes(const LinearSystem& s, double speed) {
  const int n = s.size();
  const Eigen::MatrixXd M = Eigen::MatrixXd(s.M);
  const Eigen::MatrixXd K = Eigen::MatrixXd(s.K_at(speed));
  const Eigen::MatrixXd D = s.damping_dense(speed);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(M);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  A.topRightCorner(n, n).setIdentity();
  A.bottomLeftCorner(n, n) = -lu.solve(K);
  A.bottomRightCorner(n, n) = -lu.solve(D);
  Eigen::EigenSolver<Eigen::MatrixXd> solver(A);
  std::vector<ComplexMode> modes;
  for (int i = 0; i < 2 * n; ++i) {
    const std::complex<double> lambda = solver.eigenvalues()(i);
    if (lambda.imag() < 0) continue;
    modes.push_back({lambda, solver.eigenvectors().col(i).head(n)});
  }
  std::sort(modes.begin(), modes.end(), [](const ComplexMode& a, const ComplexMode& b) {
    return std::abs(a.lambda) < std::abs(b.lambda);
  });
  return modes;
}

/// Relative error with an absolute floor.
inline double relative_error(double value, double reference, double floor = 1e-300) {
  return std::abs(value - reference) / std::max(std::abs(reference), floor);
}

}  // namespace geardyn::fe::test
