#pragma once
// Complex Hermitian generalised eigenproblem  K phi = lambda M phi  (lambda = omega^2 [rad^2/s^2]),
// K Hermitian positive semi-definite, M Hermitian positive (semi-)definite. Eigenvalues are real.
// This is the problem of one nodal diameter of a cyclic structure (K_h = T_h^H K T_h).
//
//   dense  (n <= dense_limit): Eigen's GeneralizedSelfAdjointEigenSolver on (K, M); when M is
//          singular on (M, K - sigma M) instead, mu = 1 / (lambda - sigma).
//   sparse: block shift-invert Lanczos with thick restart on the operator (K - sigma M)^{-1} M,
//          which is self-adjoint in the M inner product <x, y> = x^H M y. K - sigma M is factored
//          once: CHOLMOD supernodal Cholesky (complex LL^H) when it is positive definite,
//          UMFPACK complex LU otherwise. Every new block is M-orthogonalised twice against the
//          whole basis (full reorthogonalisation, classical Gram-Schmidt applied twice), and a
//          restart keeps the wanted Ritz vectors (thick restart): Wu & Simon, "Thick-restart
//          Lanczos method for large symmetric eigenvalue problems", SIAM J. Matrix Anal. Appl.
//          22 (2000) 602-616; Stewart, "A Krylov-Schur algorithm for large eigenproblems", SIAM
//          J. Matrix Anal. Appl. 23 (2001) 601-614 (the Hermitian case of which is the former).
//          Spectral transformation: Ericsson & Ruhe, Math. Comp. 35 (1980) 1251-1268.
//
// Multiple eigenvalues: a Krylov space grown from p start vectors holds p independent directions
// of every eigenspace, so eigenvalues of multiplicity <= block_size are found with all their
// copies (a single-vector Lanczos finds one copy in exact arithmetic). block_size defaults to 2;
// raise it when higher multiplicities are expected.
//
// Wanted eigenpairs and the shift are chosen exactly as for solve_symmetric (symmetric_eigen.hpp):
// n_modes nearest sigma (sigma <= 0: the lowest, rigid-body modes included) or every eigenvalue in
// [band_min, band_max]. Eigenvectors are M-orthonormal, phi_i^H M phi_j = delta_ij, and the phase
// of each is fixed so that its entry of largest magnitude (the first within 1e-3 of the largest)
// is real and positive.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/eig/eigen_options.hpp"

namespace geardyn::eig {

struct HermitianEigenOptions {
  /// Number of eigenpairs wanted (nearest the shift). In band mode: the first guess of how many
  /// the band holds (the solver enlarges the request until the band is covered).
  int n_modes = 10;
  /// Band of eigenvalues [rad^2/s^2]; both finite: every lambda in [band_min, band_max].
  double band_min = kNaN;
  double band_max = kNaN;
  /// Shift sigma [rad^2/s^2]. NaN: automatic, -1e-6 * min_i (Re K_ii / Re M_ii). In band mode
  /// sigma = band_min when band_min > 0, else automatic.
  double shift = kNaN;
  Method method = Method::Auto;
  /// Auto uses the dense solver for n <= dense_limit.
  int dense_limit = 400;
  /// tolerance: a Ritz value theta of the shift-inverted operator is converged when the M-norm
  /// of its residual is <= tolerance * |theta|. max_restarts: thick restarts. subspace_size:
  /// basis size m before a restart; 0: min(n - block_size, max(2 nev + 2 p, nev + 20 + p)).
  KrylovOptions krylov;
  /// Lanczos block size p >= 1 (see "Multiple eigenvalues" above).
  int block_size = 2;
  /// Seed of the random start block (results are reproducible for a given seed).
  unsigned seed = 12345;
  /// A mode whose backward error exceeds this sets Status::NotConverged.
  double residual_limit = 1e-8;

  /// Every problem with the options, one line each; empty when valid.
  std::vector<std::string> validate() const;
};

struct HermitianEigenResult {
  Status status = Status::Failed;
  std::string message;  ///< empty when ok; otherwise what went wrong and what usually helps

  Eigen::VectorXd eigenvalues;    ///< lambda = omega^2, ascending [rad^2/s^2]
  Eigen::MatrixXcd eigenvectors;  ///< columns phi, phi^H M phi = 1
  /// Normwise backward error of each pair (Tisseur 2000, LAA 309:339, Thm 1):
  ///   eta = ||K phi - lambda M phi|| / ((||K||_1 + |lambda| ||M||_1) ||phi||).
  Eigen::VectorXd residuals;

  Method method_used = Method::Auto;
  double shift_used = kNaN;   ///< sigma actually used [rad^2/s^2]
  std::string factorization;  ///< "cholmod_cholesky", "umfpack_lu", "dense_cholesky_of_M", ...
  int requested = 0;          ///< n_modes (count mode) or final request (band mode)
  int converged = 0;          ///< eigenpairs returned
  int iterations = 0;         ///< thick restarts (all rounds)
  int operations = 0;         ///< operator applications (solves with the factorisation)
  int factorizations = 0;
  double asymmetry = 0.0;  ///< ||K - K^H||_F / ||K||_F; the solver uses (K + K^H) / 2
  double max_residual() const;

  /// One line: method, modes found/asked, max residual, counters.
  std::string brief_report() const;
};

/// Solves K phi = lambda M phi for Hermitian K, M (a non-Hermitian input is replaced by its
/// Hermitian part and `asymmetry` records by how much). Throws InputError for invalid options or
/// mismatched sizes; numerical trouble (singular shifted matrix, no convergence within
/// max_restarts, large residuals) is returned in `status` and `message`.
HermitianEigenResult solve_hermitian(const Eigen::SparseMatrix<std::complex<double>>& K,
                                     const Eigen::SparseMatrix<std::complex<double>>& M,
                                     const HermitianEigenOptions& options = {});

/// The automatic shift of HermitianEigenOptions: -1e-6 * min_i (Re K_ii / Re M_ii) over DOFs
/// with both positive (-1e-6 when there are none); see automatic_shift in symmetric_eigen.hpp.
double automatic_shift(const Eigen::SparseMatrix<std::complex<double>>& K,
                       const Eigen::SparseMatrix<std::complex<double>>& M);

}  // namespace geardyn::eig
