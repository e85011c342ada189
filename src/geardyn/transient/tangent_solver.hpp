#pragma once
// Sparse direct factorisation of an iteration matrix S + U diag(d) U^T, factor once, solve many.
// Symmetric S: sparse Cholesky (Eigen SimplicialLLT, AMD ordering); unsymmetric S (gyroscopic
// and cross-coupled bearing terms) or a symmetric S that is not positive definite: sparse LU
// (UMFPACK). Both are deterministic (no threaded BLAS in the factors' numbers). The low-rank
// part is applied with the Woodbury identity
//   (S + U D U^T)^{-1} b = y - W D (I + U^T W D)^{-1} U^T y,   y = S^{-1} b,  W = S^{-1} U,
// which needs no inverse of D (modal damping coefficients may be zero).
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <memory>
#include <string>

namespace geardyn::transient {

class TangentSolver {
 public:
  enum class Method { None, Cholesky, LU };

  TangentSolver();
  ~TangentSolver();
  TangentSolver(TangentSolver&&) noexcept;
  TangentSolver& operator=(TangentSolver&&) noexcept;

  /// Factorises S (+ U diag(d) U^T when U has columns). Returns false when S is singular (then
  /// `failure()` says so); the previous factor is discarded either way. The sparsity pattern's
  /// analysis is reused while the pattern of S does not change.
  bool factorize(const Eigen::SparseMatrix<double>& S, const Eigen::MatrixXd& U = {},
                 const Eigen::VectorXd& d = {});
  /// x = (S + U diag(d) U^T)^{-1} b for the last successful factorisation.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const;

  bool ok() const { return method_ != Method::None; }
  Method method() const { return method_; }
  /// "cholesky", "lu (umfpack)", with " + woodbury(m)" when a low-rank part is present.
  std::string description() const;
  const std::string& failure() const { return failure_; }
  int size() const { return n_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Method method_ = Method::None;
  int n_ = 0;
  std::string failure_;
};

}  // namespace geardyn::transient
