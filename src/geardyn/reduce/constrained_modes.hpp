#pragma once
// Sparse solvers for a structure under linear constraints A x = c (r rows, full row rank), the
// kernels of Craig-Bampton with interface constraints (craig_bampton.hpp, docs/theory.md §9):
//
//   saddle-point solve    [F  A^T] [x ]   [b]
//                         [A  0  ] [mu] = [c]      (F symmetric; F itself may be singular)
//   constrained pencil    K phi = lambda M phi + A^T mu,  A phi = 0,  phi^T M phi = 1
//
// Both keep A as sparse rows next to the sparse K and M: nothing is eliminated, so the few dense
// rows of an averaging (RBE3) constraint cause no fill in K (eliminating a pivot in terms of the
// rest of its node set couples the whole set: S^T K S is then about as dense as set x set).
// The saddle-point matrix is factored by UMFPACK LU, which needs the whole matrix regular (K
// positive definite on the null space of A), not F; its constraint rows are scaled by
// s = max_j |F_jj| / max |A_kj| so that both blocks are of one magnitude (the solution x does
// not depend on s, mu is returned for s = 1).
// The pencil is solved as the augmented pencil (K_a, M_a) = ([K sA^T; sA 0], [M 0; 0 0]) of
// size n + r, whose finite eigenvalues are exactly those of the constrained problem (the second
// row says A phi = 0, the first is the equilibrium with the constraint forces s A^T mu); shift-
// invert Lanczos on it applies y = [F sA^T; sA 0]^{-1} [M x; 0], F = K - sigma M, whose range
// lies in {A y = 0}, so the r infinite eigenvalues of the singular M_a never appear (Ericsson &
// Ruhe, "The spectral transformation Lanczos method for the numerical solution of large sparse
// generalized symmetric eigenvalue problems", Math. Comp. 35 (1980) 1251-1268, section 3).
// Small problems (n - r <= dense_limit) are solved densely on an orthonormal basis Z of the null
// space of A (from a QR factorisation of A^T): Z^T K Z y = lambda Z^T M Z y, phi = Z y.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <string>

#include "geardyn/core/status.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"

namespace geardyn::reduce {

/// Factor once, solve [F A^T; A 0] [x; mu] = [B; C] for blocks of right-hand sides.
class SaddlePointSolver {
 public:
  SaddlePointSolver();
  ~SaddlePointSolver();
  SaddlePointSolver(const SaddlePointSolver&) = delete;
  SaddlePointSolver& operator=(const SaddlePointSolver&) = delete;

  /// F: n x n symmetric, A: r x n. Returns Status::Ok or Status::Singular (message() says so).
  Status compute(const Eigen::SparseMatrix<double>& F, const Eigen::SparseMatrix<double>& A);
  /// x for F x + A^T mu = B, A x = C (B: n x k, C: r x k).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B, const Eigen::MatrixXd& C) const;
  const std::string& message() const { return message_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string message_;
};

/// The scale s of the constraint rows (see the file comment).
double constraint_scale(const Eigen::SparseMatrix<double>& F, const Eigen::SparseMatrix<double>& A);

/// The lowest eigenpairs of K phi = lambda M phi restricted to A phi = 0 (see the file comment),
/// with the options and result of eig::solve_symmetric (eigenvectors: n rows, M-orthonormal;
/// residuals: backward errors of the augmented pencil, or of the projected one when dense).
/// options.method Dense forces the null-space path (n <= eig::kDenseHardLimit).
eig::SymmetricEigenResult solve_constrained(const Eigen::SparseMatrix<double>& K,
                                            const Eigen::SparseMatrix<double>& M,
                                            const Eigen::SparseMatrix<double>& A,
                                            const eig::SymmetricEigenOptions& options);

}  // namespace geardyn::reduce
