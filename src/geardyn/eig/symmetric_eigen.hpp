#pragma once
// Real symmetric generalised eigenproblem  K phi = lambda M phi  (lambda = omega^2 [rad^2/s^2]),
// K symmetric positive semi-definite, M symmetric positive (semi-)definite.
//
//   dense  (n <= dense_limit): Eigen's GeneralizedSelfAdjointEigenSolver on (K, M); when M is
//          singular (massless DOFs) on (M, K - sigma M) instead, mu = 1 / (lambda - sigma).
//   sparse: shift-invert Lanczos on the operator (K - sigma M)^{-1} M, self-adjoint in the M inner
//          product, with one sparse factorisation of K - sigma M (CHOLMOD supernodal Cholesky,
//          or UMFPACK LU when K - sigma M is indefinite). The default sigma is slightly
//          negative, so K - sigma M stays positive definite and rigid-body modes (lambda = 0)
//          are found. Two Krylov engines:
//          - KrylovEngine::Block (default): the block thick-restart Lanczos of
//            hermitian_eigen.hpp (Wu & Simon 2000; Stewart 2001) in real arithmetic. Each step
//            applies the operator to a block of `block_size` vectors with one supernodal block
//            solve, so the factor -- gigabytes for a 3e5-DOF solid -- is streamed from memory
//            once per block instead of once per vector, and eigenvalues of multiplicity up to
//            block_size (rigid-body modes, double modes of axisymmetric parts) are found with
//            all their copies.
//          - KrylovEngine::Spectra: Spectra's SymGEigsShiftSolver (single-vector implicitly
//            restarted Lanczos), kept as an independent cross-check.
//
// Wanted eigenpairs: the n_modes eigenvalues nearest sigma (for sigma <= 0: the lowest), or every
// eigenvalue in a band [band_min, band_max]. Eigenvectors are mass-normalised (phi^T M phi = 1).
// Reference: Ericsson & Ruhe, "The spectral transformation Lanczos method", Math. Comp. 35
// (1980) 1251-1268; Spectra documentation (SymGEigsShiftSolver).
// Cost of the sparse path: one factorisation plus about (number of Lanczos vectors) / block_size
// block solves; docs/performance.md has measured figures.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/eig/eigen_options.hpp"

namespace geardyn::eig {

struct SymmetricEigenOptions {
  /// Number of eigenpairs wanted (nearest the shift). In band mode: the first guess of how many
  /// the band holds (the solver enlarges the request until the band is covered).
  int n_modes = 10;
  /// Band of eigenvalues [rad^2/s^2]. Both finite: every eigenvalue lambda with
  /// band_min <= lambda <= band_max is returned, n_modes is only a starting guess.
  double band_min = kNaN;
  double band_max = kNaN;
  /// Shift sigma [rad^2/s^2]: the eigenvalues nearest to it are wanted. NaN: automatic,
  /// sigma = -1e-6 * min_i (K_ii / M_ii) (slightly negative; finds rigid-body modes first).
  /// In band mode sigma = band_min when band_min > 0, else automatic.
  double shift = kNaN;
  Method method = Method::Auto;
  /// Auto uses the dense solver for n <= dense_limit.
  int dense_limit = 400;
  KrylovOptions krylov;
  KrylovEngine engine = KrylovEngine::Block;
  /// Lanczos block size p (1..64, block engine): vectors per operator application.
  int block_size = 4;
  /// Seed of the random start block (block engine; results are reproducible for a given seed).
  unsigned seed = 12345;
  /// A mode whose backward error (see SymmetricEigenResult::residuals) exceeds this sets
  /// Status::NotConverged.
  double residual_limit = 1e-8;

  /// Every problem with the options, one line each; empty when valid.
  std::vector<std::string> validate() const;
};

struct SymmetricEigenResult {
  Status status = Status::Failed;
  std::string message;  ///< empty when ok; otherwise what went wrong and what usually helps

  Eigen::VectorXd eigenvalues;   ///< lambda = omega^2, ascending [rad^2/s^2]
  Eigen::MatrixXd eigenvectors;  ///< columns phi, phi^T M phi = 1
  /// Normwise backward error of each pair (Tisseur 2000, LAA 309:339, Thm 1, for the linear
  /// pencil):  eta = ||K phi - lambda M phi|| / ((||K||_1 + |lambda| ||M||_1) ||phi||).
  /// Well defined for rigid-body modes too; the eigenvalue's relative error is at most about
  /// its condition number times eta.
  Eigen::VectorXd residuals;

  Method method_used = Method::Auto;
  double shift_used = kNaN;   ///< sigma actually used [rad^2/s^2]
  std::string factorization;  ///< "cholmod_cholesky", "umfpack_lu", "dense_cholesky", ...
  int requested = 0;          ///< n_modes (count mode) or final request (band mode)
  int converged = 0;          ///< eigenpairs returned
  int iterations = 0;         ///< Lanczos restarts (all rounds)
  int operations = 0;         ///< operator applications (solves with the factorisation)
  int factorizations = 0;
  double asymmetry = 0.0;  ///< ||K - K^T||_F / ||K||_F; the solver uses (K + K^T) / 2
  double max_residual() const;

  /// One line: method, modes found/asked, max residual, counters.
  std::string brief_report() const;
};

/// Solves K phi = lambda M phi. K and M: square, same size, symmetric (a non-symmetric K is
/// replaced by its symmetric part and `asymmetry` records by how much). Throws InputError for
/// invalid options or mismatched sizes; numerical trouble (singular shifted matrix, fewer modes
/// than asked, large residuals) is returned in `status` and `message`.
SymmetricEigenResult solve_symmetric(const Eigen::SparseMatrix<double>& K,
                                     const Eigen::SparseMatrix<double>& M,
                                     const SymmetricEigenOptions& options = {});

/// sigma used when SymmetricEigenOptions::shift is NaN: -1e-6 * min_i (K_ii / M_ii) over DOFs
/// with K_ii > 0 and M_ii > 0 (-1e-6 when there are none). By the Rayleigh quotient of a unit
/// vector, min_i K_ii / M_ii bounds the lowest eigenvalue from above, so |sigma| stays small
/// compared with the lowest elastic eigenvalue unless the model is very soft overall.
double automatic_shift(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M);

}  // namespace geardyn::eig
