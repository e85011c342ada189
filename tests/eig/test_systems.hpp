#pragma once
// Small synthetic systems with known eigenvalues, shared by the eigen-solver tests.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "geardyn/eig/quadratic_eigen.hpp"

namespace geardyn::test {

/// Spring-mass chain of n equal masses m joined by springs k:
///
///   fixed_ends = true :  |--k--(m)--k--(m)-- ... --(m)--k--|     K = k tridiag(-1, 2, -1)
///   fixed_ends = false:      (m)--k--(m)-- ... --(m)             free-free (one rigid-body mode)
inline Eigen::SparseMatrix<double> chain_stiffness(int n, double k, bool fixed_ends) {
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    double diag = 2.0 * k;
    if (!fixed_ends && (i == 0 || i == n - 1)) diag = k;
    t.emplace_back(i, i, diag);
    if (i + 1 < n) {
      t.emplace_back(i, i + 1, -k);
      t.emplace_back(i + 1, i, -k);
    }
  }
  Eigen::SparseMatrix<double> K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  return K;
}

inline Eigen::SparseMatrix<double> diagonal_matrix(int n, double value) {
  Eigen::SparseMatrix<double> D(n, n);
  D.reserve(Eigen::VectorXi::Constant(n, 1));
  for (int i = 0; i < n; ++i) D.insert(i, i) = value;
  D.makeCompressed();
  return D;
}

/// Eigenvalues of the chains above, derived by substitution:
/// fixed ends,  m x_i'' = k (x_{i-1} - 2 x_i + x_{i+1}),  x_0 = x_{N+1} = 0: x_i = sin(i j pi /
/// (N+1)) gives m omega^2 = 2 k (1 - cos(j pi / (N + 1))), i.e.
///   lambda_j = omega_j^2 = 4 k/m sin^2(j pi / (2 (N + 1))),  j = 1..N;
/// free ends: x_i = cos((i - 1/2) j pi / N) gives lambda_j = 4 k/m sin^2(j pi / (2 N)),
/// j = 0..N-1 (j = 0: rigid-body translation). (Any text on lattice vibrations, e.g. Kittel,
/// Introduction to Solid State Physics, ch. 4; the substitution is the whole proof.)
inline double fixed_chain_lambda(int j, int N, double k, double m) {
  const double s = std::sin(j * std::numbers::pi / (2.0 * (N + 1)));
  return 4.0 * k / m * s * s;
}
inline double free_chain_lambda(int j, int N, double k, double m) {
  const double s = std::sin(j * std::numbers::pi / (2.0 * N));
  return 4.0 * k / m * s * s;
}

/// Sparse pencil from small dense matrices.
inline eig::QuadraticPencil pencil(const Eigen::MatrixXd& M, const Eigen::MatrixXd& C,
                                   const Eigen::MatrixXd& K) {
  eig::QuadraticPencil p;
  p.M = M.sparseView();
  p.C = C.sparseView();
  p.K = K.sparseView();
  return p;
}

/// Roots of m s^2 + c s + k = 0 (quadratic formula), the one with Im >= 0 first.
inline std::pair<std::complex<double>, std::complex<double>> sdof_roots(double m, double c,
                                                                        double k) {
  const std::complex<double> disc = std::sqrt(std::complex<double>(c * c - 4.0 * m * k, 0.0));
  return {(-c + disc) / (2.0 * m), (-c - disc) / (2.0 * m)};
}

/// |computed - exact| <= rel |exact|.
inline void expect_close(std::complex<double> computed, std::complex<double> exact, double rel,
                         const std::string& what) {
  EXPECT_LE(std::abs(computed - exact), rel * std::abs(exact))
      << what << ": computed " << computed << ", exact " << exact;
}

}  // namespace geardyn::test
