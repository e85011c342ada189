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
#include "geardyn/eig/generalized_eigen.hpp"

namespace geardyn::eig {

/// Block size 2 by default: enough for the double modes of 0 < h < N/2 (see above).
struct HermitianEigenOptions : GeneralizedEigenOptions {
  HermitianEigenOptions() { block_size = 2; }
};

using HermitianEigenResult = GeneralizedEigenResult<Eigen::MatrixXcd>;

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
