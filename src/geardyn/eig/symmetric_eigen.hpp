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
#include "geardyn/eig/generalized_eigen.hpp"

namespace geardyn::eig {

struct SymmetricEigenOptions : GeneralizedEigenOptions {
  KrylovEngine engine = KrylovEngine::Block;
};

using SymmetricEigenResult = GeneralizedEigenResult<Eigen::MatrixXd>;

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
