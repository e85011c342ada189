#pragma once
// Options and result shared by the generalised eigen-solvers K phi = lambda M phi:
// solve_symmetric (real symmetric, symmetric_eigen.hpp) and solve_hermitian (complex Hermitian,
// hermitian_eigen.hpp). Wanted pairs, shift and convergence mean the same in both.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "geardyn/core/status.hpp"
#include "geardyn/eig/eigen_options.hpp"

namespace geardyn::eig {

struct GeneralizedEigenOptions {
  /// Number of eigenpairs wanted (nearest the shift). In band mode: the first guess of how many
  /// the band holds (the solver enlarges the request until the band is covered).
  int n_modes = 10;
  /// Band of eigenvalues [rad^2/s^2]. Both finite: every eigenvalue lambda with
  /// band_min <= lambda <= band_max is returned, n_modes is only a starting guess.
  double band_min = kNaN;
  double band_max = kNaN;
  /// Shift sigma [rad^2/s^2]: the eigenvalues nearest to it are wanted. NaN: automatic,
  /// sigma = -1e-6 * min_i (Re K_ii / Re M_ii) (slightly negative; finds rigid-body modes
  /// first). In band mode sigma = band_min when band_min > 0, else automatic.
  double shift = kNaN;
  Method method = Method::Auto;
  /// Auto uses the dense solver for n <= dense_limit.
  int dense_limit = 400;
  /// tolerance: a Ritz value theta of the shift-inverted operator is converged when the M-norm
  /// of its residual is <= tolerance * |theta|. max_restarts: thick restarts. subspace_size:
  /// basis size before a restart (0: automatic, see KrylovOptions).
  KrylovOptions krylov;
  /// Lanczos block size p (1..64): vectors per operator application; eigenvalues of
  /// multiplicity <= p are found with all their copies.
  int block_size = 4;
  /// Seed of the random start block (results are reproducible for a given seed).
  unsigned seed = 12345;
  /// A mode whose backward error (GeneralizedEigenResult::residuals) exceeds this sets
  /// Status::NotConverged.
  double residual_limit = 1e-8;

  /// Every problem with the options, one line each; empty when valid.
  std::vector<std::string> validate() const;
};

/// Vectors: Eigen::MatrixXd (real symmetric) or Eigen::MatrixXcd (complex Hermitian).
template <class Vectors>
struct GeneralizedEigenResult {
  Status status = Status::Failed;
  std::string message;  ///< empty when ok; otherwise what went wrong and what usually helps

  Eigen::VectorXd eigenvalues;  ///< lambda = omega^2, ascending [rad^2/s^2]
  Vectors eigenvectors;         ///< columns phi, phi^H M phi = 1
  /// Normwise backward error of each pair (Tisseur 2000, LAA 309:339, Thm 1, for the linear
  /// pencil):  eta = ||K phi - lambda M phi|| / ((||K||_1 + |lambda| ||M||_1) ||phi||).
  /// Well defined for rigid-body modes too; the eigenvalue's relative error is at most about
  /// its condition number times eta.
  Eigen::VectorXd residuals;

  Method method_used = Method::Auto;
  double shift_used = kNaN;   ///< sigma actually used [rad^2/s^2]
  std::string factorization;  ///< "cholmod_cholesky", "umfpack_lu", "dense_cholesky_of_M", ...
  int requested = 0;          ///< n_modes (count mode) or final request (band mode)
  int converged = 0;          ///< eigenpairs returned
  int iterations = 0;         ///< Lanczos restarts (all rounds)
  int operations = 0;         ///< operator applications (solves with the factorisation)
  int factorizations = 0;
  double asymmetry = 0.0;  ///< ||K - K^H||_F / ||K||_F; the solver uses (K + K^H) / 2

  double max_residual() const { return residuals.size() > 0 ? residuals.maxCoeff() : 0.0; }
  /// One line: method, modes found/asked, max residual, counters.
  std::string brief_report() const;
};

extern template struct GeneralizedEigenResult<Eigen::MatrixXd>;
extern template struct GeneralizedEigenResult<Eigen::MatrixXcd>;

}  // namespace geardyn::eig
