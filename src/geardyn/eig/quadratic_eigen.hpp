#pragma once
// Quadratic eigenproblem of a damped gyroscopic system (docs/theory.md §3):
//     (lambda^2 M + lambda D + K) x = 0,   D = C + Omega G + B diag(c) B^T,
// solved through its first-order (state) form  A z = lambda B z  with z = [x; lambda x],
//     A = [0 I; -K -D],   B = [I 0; 0 M].
// The shift-invert operator (A - sigma B)^{-1} B never forms the 2n state matrix: with
// P(sigma) = K + sigma D + sigma^2 M, the state solve reduces to
//     y1 = -P(sigma)^{-1} (M x2 + (D + sigma M) x1),   y2 = x1 + sigma y1,
// i.e. one sparse LU of the n x n matrix P(sigma) (the Schur complement of the state matrix's
// first block), which is exactly equivalent, half the size and without the identity blocks'
// fill. The low-rank modal damping term enters through the Sherman-Morrison-Woodbury formula,
// so P stays sparse.
//
//   dense  (n <= dense_limit): the same operator as a dense 2n x 2n matrix, all eigenvalues by
//          Eigen's real EigenSolver; lambda = sigma + 1/nu.
//   sparse, real target sigma: Spectra GenEigsSolver (implicitly restarted Arnoldi) on the real
//          operator above; eigenvalues nu = 1/(lambda - sigma) of largest magnitude.
//   sparse, complex target sigma (a frequency of interest i*omega): the real operator
//          Re[(A - sigma B)^{-1} B] of Parlett & Saad (LAA 88/89 (1987) 575-595) with a complex LU;
//          its eigenvectors are those of the pencil and lambda is their Rayleigh quotient.
//
// Every eigenvalue with Im lambda != 0 has its conjugate; each pair is returned once (the one
// with Im lambda > 0). Real (overdamped) roots are returned one by one.
#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <complex>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/eig/eigen_options.hpp"

namespace geardyn::eig {

/// The matrices of (lambda^2 M + lambda D + K) x = 0. D = C + B diag(c) B^T, where C holds every
/// sparse viscous and gyroscopic term (C_at(speed) + speed G) and B, c an optional low-rank
/// (modal) damping term. K and C may be non-symmetric.
struct QuadraticPencil {
  Eigen::SparseMatrix<double> M, C, K;
  Eigen::MatrixXd low_rank_basis;         ///< B, n x m (m = 0: none)
  Eigen::VectorXd low_rank_coefficients;  ///< c, m

  Eigen::Index size() const { return K.rows(); }
  /// D x.
  Eigen::VectorXcd apply_damping(const Eigen::VectorXcd& x) const;
  /// D as a dense matrix (small systems only).
  Eigen::MatrixXd damping_dense() const;
};

struct QuadraticEigenOptions {
  /// Number of modes wanted, nearest the target: a conjugate pair counts once, each real root
  /// once.
  int n_modes = 10;
  /// Target lambda [rad/s] around which modes are wanted, e.g. {0, omega} for modes near the
  /// frequency omega. NaN real part: automatic, a small negative real value
  /// sigma = -1e-3 sqrt(min_i K_ii / M_ii), which selects the modes of smallest |lambda| (the
  /// lowest natural frequencies, rigid-body modes included).
  std::complex<double> target{kNaN, 0.0};
  Method method = Method::Auto;
  /// Auto: dense for n <= dense_limit (or when Arnoldi cannot return n_modes). The dense
  /// state-space solve costs O((2n)^3) with eigenvectors, about 0.05 s at n = 100 and 4 s at
  /// n = 400, which a Campbell sweep pays per speed; the sparse solve is far cheaper above that.
  int dense_limit = 100;
  /// Real shift sigma of the dense state-space solve (all eigenvalues are computed, sigma only
  /// keeps T = (A - sigma B)^{-1} B well scaled). NaN: automatic, -sqrt(min_i K_ii / M_ii).
  /// A projected (reduced) pencil passes the full model's value, since min K_ii / M_ii of a
  /// modal basis is 0 for rigid-body modes.
  double dense_shift = kNaN;
  KrylovOptions krylov;
  /// A mode whose backward error exceeds this sets Status::NotConverged.
  double residual_limit = 1e-8;
  /// Optional start vector of the Arnoldi iteration in state space (length 2n), e.g. from
  /// start_vector() of a neighbouring speed's modes; empty: Spectra's fixed-seed random vector.
  Eigen::VectorXd start;

  std::vector<std::string> validate() const;
};

struct QuadraticEigenResult {
  Status status = Status::Failed;
  std::string message;  ///< empty when ok; otherwise what went wrong and what usually helps

  /// lambda [rad/s], Im lambda >= 0, ordered by |lambda| (undamped natural frequency).
  Eigen::VectorXcd eigenvalues;
  /// Displacement part x of each mode, scaled so that its largest entry is exactly 1.
  Eigen::MatrixXcd eigenvectors;
  /// Normwise backward error (Tisseur, LAA 309 (2000) 339-361, Thm 1):
  ///   eta = ||(lambda^2 M + lambda D + K) x|| / ((|lambda|^2 ||M||_1 + |lambda| ||D||_1
  ///         + ||K||_1) ||x||).
  /// Defined for rigid-body modes (lambda = 0) too, where ||K x|| / ... would be 0/0.
  Eigen::VectorXd residuals;

  Method method_used = Method::Auto;
  std::complex<double> shift_used{kNaN, 0.0};  ///< sigma of the operator
  std::string factorization;                   ///< "umfpack_lu", "umfpack_lu_complex", "dense_lu"
  int requested = 0;
  int converged = 0;   ///< modes returned
  int iterations = 0;  ///< Arnoldi restarts
  int operations = 0;  ///< operator applications
  int factorizations = 0;
  double max_residual() const;
  std::string brief_report() const;
};

/// Solves the quadratic eigenproblem. Throws InputError for invalid options or inconsistent
/// matrix sizes; numerical trouble is returned in `status` / `message`.
QuadraticEigenResult solve_quadratic(const QuadraticPencil& pencil,
                                     const QuadraticEigenOptions& options = {});

/// The backward errors (QuadraticEigenResult::residuals) of the pairs (eigenvalues[k],
/// vectors.col(k)) for `pencil`: the norms are computed once, the residuals with one pencil
/// application per pair.
Eigen::VectorXd backward_errors(const QuadraticPencil& pencil, const Eigen::VectorXcd& eigenvalues,
                                const Eigen::MatrixXcd& vectors);

/// The backward errors from residual vectors already computed: eta_k = ||R.col(k)|| /
/// ((|lambda_k|^2 ||M||_1 + |lambda_k| ||D||_1 + ||K||_1) ||vectors.col(k)||), the norms of
/// `pencil` as backward_errors() uses them.
Eigen::VectorXd backward_errors_from_residuals(const QuadraticPencil& pencil,
                                               const Eigen::VectorXcd& eigenvalues,
                                               const Eigen::MatrixXcd& vectors,
                                               const Eigen::MatrixXcd& residuals);

/// The automatic target of QuadraticEigenOptions (NaN target): -1e-3 sqrt(min_i K_ii / M_ii).
double automatic_target(const QuadraticPencil& pencil);

/// A start vector for the Arnoldi iteration from known modes (e.g. the previous speed of a
/// Campbell sweep): sum over modes of the normalised real and imaginary parts of
/// z = [x; lambda x]. Empty when `modes` has none.
Eigen::VectorXd start_vector(const QuadraticEigenResult& modes);

/// Undamped natural frequency |lambda| [rad/s].
inline double natural_frequency(std::complex<double> lambda) { return std::abs(lambda); }
/// Damping ratio -Re(lambda) / |lambda| (0 for lambda = 0); 1 or more for real roots.
inline double damping_ratio(std::complex<double> lambda) {
  const double a = std::abs(lambda);
  return a > 0.0 ? -lambda.real() / a : 0.0;
}

}  // namespace geardyn::eig
