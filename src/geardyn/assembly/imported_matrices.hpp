#pragma once
// Definiteness of a component's imported stiffness and mass matrices (Matrix Market files).
// The reader already refuses asymmetric matrices and a wrong-signed diagonal, with the line of
// the entry (meshio::read_matrix_market_component). What the diagonal cannot show is checked
// here by sparse Cholesky factorisations (CHOLMOD, through linalg::SymmetricFactorization):
//   M positive definite:      Cholesky of M succeeds;
//   K positive semi-definite: Cholesky of K + s M succeeds with the shift
//        s = 1e-8 max_i (K_ii / M_ii). A free component's rigid-body modes have K-eigenvalues
//        of round-off size (n eps max K_ii / M_ii, far below s), so K + s M stays positive
//        definite for a valid K; an eigenvalue omega^2 < -s (|omega| above 1e-4 of the highest
//        natural frequency scale) makes it fail. Smaller negative eigenvalues are round-off
//        scale and are left to the eigen-solver.
// Each factorisation costs about one factorisation of the component (the eigen-solve does
// several), so it is done for every import.
#include <Eigen/Sparse>
#include <string>

#include "geardyn/core/error.hpp"

namespace geardyn::assembly {

/// Throws InputError at `where` (the solid's table) with key `key_m` or `key_k` (the model keys
/// of the mass and stiffness files) naming the file when M is not positive definite or K not
/// positive semi-definite (above). Precondition: K, M square, symmetric, of one size.
void check_imported_matrices(const Eigen::SparseMatrix<double>& K,
                             const Eigen::SparseMatrix<double>& M, const SourceLocation& where,
                             const std::string& key_k, const std::string& file_k,
                             const std::string& key_m, const std::string& file_m);

}  // namespace geardyn::assembly
