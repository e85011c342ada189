#pragma once
// Sparse direct factorisations behind one small interface: factor once, solve many.
//   SparseLU<Scalar>          general square matrix, UMFPACK (real or complex)
//   SymmetricFactorization    real symmetric matrix: CHOLMOD supernodal Cholesky when the matrix
//                             is positive definite, UMFPACK LU otherwise (kind() says which)
// The SuiteSparse headers stay in the .cpp (pImpl), so users only see Eigen types.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <memory>
#include <string>
#include <string_view>

#include "geardyn/core/status.hpp"

namespace geardyn::linalg {

/// LU factorisation P A Q = L U of a square sparse matrix by UMFPACK. Scalar is double or
/// std::complex<double>.
template <class Scalar>
class SparseLU {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using DenseMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  SparseLU();
  ~SparseLU();
  SparseLU(SparseLU&&) noexcept;
  SparseLU& operator=(SparseLU&&) noexcept;
  SparseLU(const SparseLU&) = delete;
  SparseLU& operator=(const SparseLU&) = delete;

  /// Factors `A` (square, compressed or not). Returns Status::Ok, or Status::Singular when
  /// UMFPACK finds a zero pivot (message() then says so); the matrix is not kept.
  /// `refine`: UMFPACK's iterative refinement of every solution (up to 2 steps, its default).
  /// Off, a solve costs about half (the residual flexibility of bench/data/damper_ring_100.toml,
  /// 210 right-hand sides on each of 6 nodal diameters: the whole analysis 11.4 s -> 6.5 s); the
  /// pivoted LU alone is backward stable, so turn it off for many solves with a well-conditioned
  /// matrix.
  Status compute(const Matrix& A, bool refine = true);
  /// x = A^{-1} b. Precondition: compute() returned Ok.
  Vector solve(const Vector& b) const;
  DenseMatrix solve(const DenseMatrix& B) const;

  Eigen::Index rows() const { return n_; }
  bool ok() const { return ok_; }
  const std::string& message() const { return message_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Eigen::Index n_ = 0;
  bool ok_ = false;
  std::string message_;
};

extern template class SparseLU<double>;
extern template class SparseLU<std::complex<double>>;

enum class FactorizationKind { None, Cholesky, LU };
constexpr std::string_view to_string(FactorizationKind k) {
  switch (k) {
    case FactorizationKind::None:
      return "none";
    case FactorizationKind::Cholesky:
      return "cholmod_cholesky";
    case FactorizationKind::LU:
      return "umfpack_lu";
  }
  return "none";
}

/// Factorisation of a real symmetric sparse matrix (both triangles stored). Cholesky is tried
/// first because it is about twice as fast and needs half the memory; when the matrix is not
/// positive definite (a shift inside the spectrum) UMFPACK's pivoting LU is used instead. This
/// is a choice by matrix property, not a fallback that changes results: both solve A x = b to
/// working precision, and kind() records which one ran.
class SymmetricFactorization {
 public:
  SymmetricFactorization();
  ~SymmetricFactorization();
  SymmetricFactorization(SymmetricFactorization&&) noexcept;
  SymmetricFactorization& operator=(SymmetricFactorization&&) noexcept;

  /// Returns Status::Ok or Status::Singular (message() says why).
  Status compute(const Eigen::SparseMatrix<double>& A);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  /// y = A^{-1} x on raw arrays of length rows() (the form Spectra's operators use).
  void solve(const double* x, double* y) const;
  /// X = A^{-1} B for a block of right-hand sides at once (CHOLMOD's supernodal solve works on
  /// the whole block, which is much faster than column by column).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;

  Eigen::Index rows() const { return n_; }
  FactorizationKind kind() const { return kind_; }
  const std::string& message() const { return message_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Eigen::Index n_ = 0;
  FactorizationKind kind_ = FactorizationKind::None;
  std::string message_;
};

/// 1-norm (largest absolute column sum) of a sparse matrix; used to scale residuals.
double norm1(const Eigen::SparseMatrix<double>& A);

/// ||A - A^T||_F / ||A||_F (0 for a zero matrix).
double relative_asymmetry(const Eigen::SparseMatrix<double>& A);

/// y = A x for a real sparse A and a complex x, without forming a complex copy of A.
Eigen::VectorXcd multiply(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXcd& x);

}  // namespace geardyn::linalg
