#include "geardyn/assembly/imported_matrices.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::assembly {

namespace {

bool positive_definite(const Eigen::SparseMatrix<double>& A) {
  linalg::SymmetricFactorization f;
  return f.compute(A) == Status::Ok && f.kind() == linalg::FactorizationKind::Cholesky;
}

}  // namespace

void check_imported_matrices(const Eigen::SparseMatrix<double>& K,
                             const Eigen::SparseMatrix<double>& M, const SourceLocation& where,
                             const std::string& key_k, const std::string& file_k,
                             const std::string& key_m, const std::string& file_m) {
  if (M.rows() == 0) return;
  if (!positive_definite(M))
    throw InputError(where, key_m, "a positive definite mass matrix (a Cholesky factorisation)",
                     fmt::format("'{}': M is not positive definite although its diagonal is "
                                 "positive (some combination of DOFs has zero or negative "
                                 "kinetic energy)",
                                 file_m),
                     "check the export of the mass matrix (units, lumping, coupling terms)");
  const Eigen::VectorXd k = K.diagonal(), m = M.diagonal();
  double scale = 0.0;
  for (Eigen::Index i = 0; i < k.size(); ++i) scale = std::max(scale, k(i) / m(i));
  if (!(scale > 0.0)) return;  // K = 0 on the diagonal: zero (PSD) by the reader's checks
  const double shift = 1e-8 * scale;
  const Eigen::SparseMatrix<double> shifted = K + shift * M;
  if (!positive_definite(shifted))
    throw InputError(
        where, key_k, "a positive semi-definite stiffness matrix",
        fmt::format("'{}': K has a negative eigenvalue, omega^2 < -{:.3g} (rad/s)^2 (K + s M with "
                    "s = 1e-8 max K_ii/M_ii has no Cholesky factorisation)",
                    file_k, shift),
        "check the export of the stiffness matrix (a pre-stressed or follower-load stiffness "
        "is not a structural stiffness)");
}

}  // namespace geardyn::assembly
