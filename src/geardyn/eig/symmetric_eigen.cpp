// GCC's -Wnull-dereference false positive inside Eigen's sparse wrappers (see
// linalg/sparse_factorization.cpp): the pragma must precede the first Eigen include.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Sparse>
#pragma GCC diagnostic pop

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <type_traits>

#include "geardyn/core/error.hpp"
#include "geardyn/eig/generalized_eigen_impl.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

void check_dense_size(Method method, long n) {
  if (method == Method::Dense && n > kDenseHardLimit)
    throw InputError({}, "eig.method", fmt::format("sparse for more than {} DOFs", kDenseHardLimit),
                     fmt::format("dense with {} DOFs", n),
                     "a dense solve of this size takes O(n^3) time and O(n^2) memory");
}

void KrylovOptions::validate(std::vector<std::string>& problems) const {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    problems.push_back(fmt::format("krylov.tolerance must be in (0, 1), found {}", tolerance));
  if (max_restarts < 1)
    problems.push_back(fmt::format("krylov.max_restarts must be >= 1, found {}", max_restarts));
  if (subspace_size < 0)
    problems.push_back(fmt::format("krylov.subspace_size must be >= 0, found {}", subspace_size));
}

std::vector<std::string> GeneralizedEigenOptions::validate() const {
  std::vector<std::string> problems;
  if (n_modes < 1) problems.push_back(fmt::format("n_modes must be >= 1, found {}", n_modes));
  const bool has_min = !std::isnan(band_min), has_max = !std::isnan(band_max);
  if (has_min != has_max) problems.push_back("band_min and band_max must be given together");
  if (has_min && has_max) {
    if (!std::isfinite(band_min) || !std::isfinite(band_max) || !(band_max > band_min))
      problems.push_back(fmt::format("band must be finite with band_max > band_min, found [{}, {}]",
                                     band_min, band_max));
    if (!std::isnan(shift))
      problems.push_back("shift and band are exclusive (the band sets the shift)");
  }
  if (!std::isnan(shift) && !std::isfinite(shift))
    problems.push_back(fmt::format("shift must be finite or NaN (automatic), found {}", shift));
  if (dense_limit < 0)
    problems.push_back(fmt::format("dense_limit must be >= 0, found {}", dense_limit));
  if (block_size < 1 || block_size > 64)
    problems.push_back(fmt::format("block_size must be in 1..64, found {}", block_size));
  if (!(residual_limit > 0.0))
    problems.push_back(fmt::format("residual_limit must be > 0, found {}", residual_limit));
  krylov.validate(problems);
  return problems;
}

template <class Vectors>
std::string GeneralizedEigenResult<Vectors>::brief_report() const {
  constexpr bool real = std::is_same_v<typename Vectors::Scalar, double>;
  return fmt::format(
      "{} eigen: {} ({}), {}/{} modes, sigma={:.4g}, max residual {:.2e}, {} restarts, "
      "{} solves, status {}{}{}",
      real ? "symmetric" : "hermitian", to_string(method_used), factorization, converged, requested,
      shift_used, max_residual(), iterations, operations, to_string(status),
      message.empty() ? "" : ": ", message);
}

template struct GeneralizedEigenResult<Eigen::MatrixXd>;
template struct GeneralizedEigenResult<Eigen::MatrixXcd>;

double automatic_shift(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M) {
  return detail::automatic_shift(K, M);
}

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Spectra operator: y = (K - sigma M)^{-1} x with the factorisation made once by the caller.
// set_shift is a no-op because the shift is baked into the factorisation.
class ShiftInvertOperator {
 public:
  using Scalar = double;
  explicit ShiftInvertOperator(const linalg::SymmetricFactorization& factorization)
      : factorization_(factorization) {}
  Eigen::Index rows() const { return factorization_.rows(); }
  Eigen::Index cols() const { return factorization_.rows(); }
  void set_shift(double) {}
  void perform_op(const double* x, double* y) const {
    factorization_.solve(x, y);
    ++count_;
  }
  int count() const { return count_; }

 private:
  const linalg::SymmetricFactorization& factorization_;
  mutable int count_ = 0;
};

// The Spectra engine (single-vector implicitly restarted Lanczos, Spectra's SymGEigsShiftSolver),
// kept to cross-check the block Lanczos engine.
void solve_sparse_spectra(const SparseMatrix& K, const SparseMatrix& M,
                          const SymmetricEigenOptions& options, bool band,
                          SymmetricEigenResult& r) {
  const Eigen::Index n = K.rows();
  linalg::SymmetricFactorization factorization;
  const double sigma = detail::factor_shifted(K, M, options, band, factorization, r);
  if (std::isnan(sigma)) return;

  ShiftInvertOperator op(factorization);
  Spectra::SparseSymMatProd<double> mass_op(M);
  Eigen::Index nev = std::clamp<Eigen::Index>(options.n_modes, 1, n - 1);
  const double reach = band ? std::max(options.band_max - sigma, sigma - options.band_min) : 0.0;
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  bool enough = false;
  while (true) {
    const Eigen::Index ncv =
        options.krylov.subspace_size > 0
            ? std::min<Eigen::Index>(n,
                                     std::max<Eigen::Index>(options.krylov.subspace_size, nev + 1))
            : std::min<Eigen::Index>(n, std::max<Eigen::Index>(2 * nev + 1, nev + 20));
    Spectra::SymGEigsShiftSolver<ShiftInvertOperator, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(op, mass_op, nev, ncv, sigma);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, options.krylov.max_restarts,
                   options.krylov.tolerance, Spectra::SortRule::SmallestAlge);
    r.iterations += static_cast<int>(solver.num_iterations());
    values = solver.eigenvalues();
    vectors = solver.eigenvectors();
    if (values.size() < nev) break;  // not converged: reported below
    if (!band) {
      enough = true;
      break;
    }
    const double farthest = (values.array() - sigma).abs().maxCoeff();
    if (farthest > reach) {
      enough = true;
      break;
    }
    if (nev >= n - 1) {
      enough = false;
      break;
    }
    nev = std::min<Eigen::Index>(2 * nev, n - 1);
  }
  r.operations = op.count();
  detail::select_pairs(values, vectors, options, sigma, band, r);
  r.requested = band ? static_cast<int>(nev) : options.n_modes;
  r.converged = static_cast<int>(r.eigenvalues.size());
  r.status = Status::Ok;
  if (values.size() < nev) {
    r.status = Status::FewerModes;
    r.message = fmt::format(
        "shift-invert Lanczos converged {} of {} eigenpairs in {} restarts; increase "
        "krylov.max_restarts or krylov.subspace_size",
        values.size(), nev, options.krylov.max_restarts);
  } else if (band && !enough) {
    r.status = Status::FewerModes;
    r.message = fmt::format(
        "the band [{:.6g}, {:.6g}] was not covered: the sparse solver can return at most n - 1 = "
        "{} modes; use the dense method for this size",
        options.band_min, options.band_max, n - 1);
  } else if (!band && options.n_modes > n - 1) {
    r.status = Status::FewerModes;
    r.message = fmt::format(
        "{} modes asked, the sparse solver returns at most n - 1 = {}; use the dense method",
        options.n_modes, n - 1);
  }
}

}  // namespace

SymmetricEigenResult solve_symmetric(const SparseMatrix& K_in, const SparseMatrix& M_in,
                                     const SymmetricEigenOptions& options) {
  if (auto problems = options.validate(); !problems.empty())
    detail::throw_options("eig.SymmetricEigenOptions", problems);
  detail::check_pencil("eig.solve_symmetric", K_in, M_in);
  SymmetricEigenResult r;
  r.asymmetry = detail::self_adjoint_defect(K_in);
  const SparseMatrix K = detail::self_adjoint_part(K_in, r.asymmetry);
  const SparseMatrix M = detail::self_adjoint_part(M_in, detail::self_adjoint_defect(M_in));
  detail::solve_generalized(K, M, options, r, [&](bool band) {
    if (options.engine == KrylovEngine::Spectra)
      solve_sparse_spectra(K, M, options, band, r);
    else
      detail::solve_sparse<double, linalg::SymmetricFactorization>(K, M, options, band, r);
  });
  return r;
}

}  // namespace geardyn::eig
