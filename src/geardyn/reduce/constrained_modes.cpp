#include "geardyn/reduce/constrained_modes.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <vector>

#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::reduce {

using SparseMatrix = Eigen::SparseMatrix<double>;

namespace {

// [F sA^T; sA 0] (both triangles stored).
SparseMatrix saddle_matrix(const SparseMatrix& F, const SparseMatrix& A, double s) {
  const Eigen::Index n = F.rows(), r = A.rows();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(F.nonZeros() + 2 * A.nonZeros()));
  for (Eigen::Index c = 0; c < F.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(F, c); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      const auto row = static_cast<int>(n + it.row()), col = static_cast<int>(it.col());
      t.emplace_back(row, col, s * it.value());
      t.emplace_back(col, row, s * it.value());
    }
  SparseMatrix out(n + r, n + r);
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

// The dense path: an orthonormal basis Z of {A x = 0} (the last n - r columns of Q in the QR
// factorisation of A^T), the projected pencil by the dense solver, phi = Z y.
eig::SymmetricEigenResult solve_on_null_space(const SparseMatrix& K, const SparseMatrix& M,
                                              const SparseMatrix& A,
                                              eig::SymmetricEigenOptions options) {
  const Eigen::Index n = K.rows(), r = A.rows();
  const Eigen::MatrixXd At = Eigen::MatrixXd(A.transpose());
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(At);
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd Z = Q.rightCols(n - r);
  Eigen::MatrixXd Kz = Z.transpose() * (K * Z), Mz = Z.transpose() * (M * Z);
  Kz = 0.5 * (Kz + Kz.transpose()).eval();
  Mz = 0.5 * (Mz + Mz.transpose()).eval();
  options.method = eig::Method::Dense;
  eig::SymmetricEigenResult result =
      eig::solve_symmetric(SparseMatrix(Kz.sparseView()), SparseMatrix(Mz.sparseView()), options);
  result.eigenvectors = Z * result.eigenvectors;
  return result;
}

}  // namespace

struct SaddlePointSolver::Impl {
  linalg::SparseLU<double> lu;
  Eigen::Index n = 0, r = 0;
  double scale = 1.0;
};

SaddlePointSolver::SaddlePointSolver() : impl_(std::make_unique<Impl>()) {}
SaddlePointSolver::~SaddlePointSolver() = default;

double constraint_scale(const SparseMatrix& F, const SparseMatrix& A) {
  const double f = F.diagonal().cwiseAbs().maxCoeff();
  double a = 0.0;
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) a = std::max(a, std::abs(it.value()));
  return f > 0.0 && a > 0.0 ? f / a : 1.0;
}

Status SaddlePointSolver::compute(const SparseMatrix& F, const SparseMatrix& A) {
  impl_->n = F.rows();
  impl_->r = A.rows();
  impl_->scale = constraint_scale(F, A);
  const Status s = impl_->lu.compute(saddle_matrix(F, A, impl_->scale));
  message_ = s == Status::Ok ? std::string() : impl_->lu.message();
  return s;
}

Eigen::MatrixXd SaddlePointSolver::solve(const Eigen::MatrixXd& B, const Eigen::MatrixXd& C) const {
  Eigen::MatrixXd rhs(impl_->n + impl_->r, B.cols());
  rhs.topRows(impl_->n) = B;
  rhs.bottomRows(impl_->r) = impl_->scale * C;
  return impl_->lu.solve(rhs).topRows(impl_->n);
}

eig::SymmetricEigenResult solve_constrained(const SparseMatrix& K, const SparseMatrix& M,
                                            const SparseMatrix& A,
                                            const eig::SymmetricEigenOptions& options) {
  const Eigen::Index n = K.rows(), r = A.rows();
  if (r == 0) return eig::solve_symmetric(K, M, options);
  const Eigen::Index n_free = n - r;
  const bool band = !std::isnan(options.band_min);
  const Eigen::Index p = options.block_size;
  // The Krylov basis lives in the n - r dimensional space {A x = 0}: it must hold the wanted
  // pairs and two blocks (see eig::BlockLanczos), else the dense path.
  const Eigen::Index nev = std::max(options.n_modes, 1);
  const Eigen::Index basis = std::max(2 * nev + 2 * p, nev + 20 + p);
  const bool dense = options.method == eig::Method::Dense ||
                     (options.method == eig::Method::Auto && n_free <= options.dense_limit) ||
                     (!band && nev + 2 * p + 20 > n_free);
  if (dense && n <= eig::kDenseHardLimit) return solve_on_null_space(K, M, A, options);

  const double s = constraint_scale(K, A);
  const SparseMatrix Ka = saddle_matrix(K, A, s);
  SparseMatrix Ma = M;
  Ma.conservativeResize(n + r, n + r);
  eig::SymmetricEigenOptions o = options;
  o.method = eig::Method::Sparse;
  if (o.krylov.subspace_size == 0)
    o.krylov.subspace_size = static_cast<int>(std::min(basis, n_free - p));
  eig::SymmetricEigenResult result = eig::solve_symmetric(Ka, Ma, o);
  result.eigenvectors = result.eigenvectors.topRows(n).eval();
  return result;
}

}  // namespace geardyn::reduce
