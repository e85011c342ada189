// GCC's -Wnull-dereference reports a false positive inside Eigen's
// SparseCompressedBase::nonZeros() once it is inlined into the SparseRef that the CHOLMOD /
// UMFPACK wrappers build: GCC assumes outerIndexPtr() may be null on the compressed path, which
// Eigen never allows for a matrix with storage. The pragma must precede the first Eigen include,
// because GCC attributes the warning to Eigen's own lines.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <Eigen/UmfPackSupport>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <utility>

#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::linalg {

// ---------------------------------------------------------------------------------------------
// SparseLU

template <class Scalar>
struct SparseLU<Scalar>::Impl {
  // umfpack_*_solve reads the original matrix again, and Eigen's UmfPackLU keeps only a
  // reference to it, so the factorisation owns a compressed copy.
  Matrix matrix;
  Eigen::UmfPackLU<Matrix> lu;
};

template <class Scalar>
SparseLU<Scalar>::SparseLU() = default;
template <class Scalar>
SparseLU<Scalar>::~SparseLU() = default;
template <class Scalar>
SparseLU<Scalar>::SparseLU(SparseLU&&) noexcept = default;
template <class Scalar>
SparseLU<Scalar>& SparseLU<Scalar>::operator=(SparseLU&&) noexcept = default;

template <class Scalar>
Status SparseLU<Scalar>::compute(const Matrix& A, bool refine) {
  impl_ = std::make_unique<Impl>();
  n_ = A.rows();
  ok_ = false;
  message_.clear();
  if (A.rows() != A.cols()) {
    message_ = "matrix is not square";
    return Status::Failed;
  }
  impl_->matrix = A;
  impl_->matrix.makeCompressed();
  if (!refine) impl_->lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
  impl_->lu.compute(impl_->matrix);
  if (impl_->lu.info() != Eigen::Success) {
    message_ = "UMFPACK LU found the matrix singular (return code " +
               std::to_string(impl_->lu.umfpackFactorizeReturncode()) + ")";
    return Status::Singular;
  }
  ok_ = true;
  return Status::Ok;
}

template <class Scalar>
typename SparseLU<Scalar>::Vector SparseLU<Scalar>::solve(const Vector& b) const {
  return impl_->lu.solve(b);
}

template <class Scalar>
typename SparseLU<Scalar>::DenseMatrix SparseLU<Scalar>::solve(const DenseMatrix& B) const {
  return impl_->lu.solve(B);
}

template class SparseLU<double>;
template class SparseLU<std::complex<double>>;

// ---------------------------------------------------------------------------------------------
// SymmetricFactorization

struct SymmetricFactorization::Impl {
  Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> cholesky;
  SparseLU<double> lu;
};

SymmetricFactorization::SymmetricFactorization() = default;
SymmetricFactorization::~SymmetricFactorization() = default;
SymmetricFactorization::SymmetricFactorization(SymmetricFactorization&&) noexcept = default;
SymmetricFactorization& SymmetricFactorization::operator=(SymmetricFactorization&&) noexcept =
    default;

Status SymmetricFactorization::compute(const Eigen::SparseMatrix<double>& A) {
  impl_ = std::make_unique<Impl>();
  n_ = A.rows();
  kind_ = FactorizationKind::None;
  message_.clear();
  // CHOLMOD reports "not positive definite" through its error handler, which prints by
  // default; the library must stay silent, and the condition is handled here.
  impl_->cholesky.cholmod().print = 0;
  impl_->cholesky.cholmod().error_handler = nullptr;
  impl_->cholesky.compute(A);
  if (impl_->cholesky.info() == Eigen::Success) {
    kind_ = FactorizationKind::Cholesky;
    return Status::Ok;
  }
  const Status s = impl_->lu.compute(A);
  if (s != Status::Ok) {
    message_ = impl_->lu.message();
    return s;
  }
  kind_ = FactorizationKind::LU;
  return Status::Ok;
}

Eigen::VectorXd SymmetricFactorization::solve(const Eigen::VectorXd& b) const {
  if (kind_ == FactorizationKind::Cholesky) return impl_->cholesky.solve(b);
  return impl_->lu.solve(b);
}

Eigen::MatrixXd SymmetricFactorization::solve(const Eigen::MatrixXd& B) const {
  if (kind_ == FactorizationKind::Cholesky) return impl_->cholesky.solve(B);
  return impl_->lu.solve(B);
}

void SymmetricFactorization::solve(const double* x, double* y) const {
  Eigen::Map<const Eigen::VectorXd> xin(x, n_);
  Eigen::Map<Eigen::VectorXd> yout(y, n_);
  if (kind_ == FactorizationKind::Cholesky)
    yout = impl_->cholesky.solve(xin);
  else
    yout = impl_->lu.solve(Eigen::VectorXd(xin));
}

// ---------------------------------------------------------------------------------------------

double norm1(const Eigen::SparseMatrix<double>& A) {
  double best = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, j); it; ++it) sum += std::abs(it.value());
    best = std::max(best, sum);
  }
  return best;
}

double relative_asymmetry(const Eigen::SparseMatrix<double>& A) {
  const double norm = A.norm();
  if (norm == 0.0) return 0.0;
  const Eigen::SparseMatrix<double> At = A.transpose();
  return (A - At).norm() / norm;
}

Eigen::VectorXcd multiply(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x) {
  const Eigen::VectorXd re = A * x.real();
  const Eigen::VectorXd im = A * x.imag();
  Eigen::VectorXcd y(re.size());
  y.real() = re;
  y.imag() = im;
  return y;
}

}  // namespace geardyn::linalg
