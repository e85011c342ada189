#include "geardyn/eig/symmetric_eigen.hpp"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "geardyn/core/error.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

void KrylovOptions::validate(std::vector<std::string>& problems) const {
  if (!(tolerance > 0.0 && tolerance < 1.0))
    problems.push_back(fmt::format("krylov.tolerance must be in (0, 1), found {}", tolerance));
  if (max_restarts < 1)
    problems.push_back(fmt::format("krylov.max_restarts must be >= 1, found {}", max_restarts));
  if (subspace_size < 0)
    problems.push_back(fmt::format("krylov.subspace_size must be >= 0, found {}", subspace_size));
}

std::vector<std::string> SymmetricEigenOptions::validate() const {
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
  if (!(residual_limit > 0.0))
    problems.push_back(fmt::format("residual_limit must be > 0, found {}", residual_limit));
  krylov.validate(problems);
  return problems;
}

double SymmetricEigenResult::max_residual() const {
  return residuals.size() > 0 ? residuals.maxCoeff() : 0.0;
}

std::string SymmetricEigenResult::brief_report() const {
  return fmt::format(
      "symmetric eigen: {} ({}), {}/{} modes, sigma={:.4g}, max residual {:.2e}, {} restarts, "
      "{} solves, status {}{}{}",
      to_string(method_used), factorization, converged, requested, shift_used, max_residual(),
      iterations, operations, to_string(status), message.empty() ? "" : ": ", message);
}

double automatic_shift(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M) {
  const Eigen::VectorXd kd = K.diagonal(), md = M.diagonal();
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < kd.size(); ++i)
    if (kd[i] > 0.0 && md[i] > 0.0) smallest = std::min(smallest, kd[i] / md[i]);
  if (!std::isfinite(smallest)) smallest = 1.0;
  return -1e-6 * smallest;
}

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

[[noreturn]] void throw_options(const std::vector<std::string>& problems) {
  std::string found;
  for (const auto& p : problems) found += (found.empty() ? "" : "; ") + p;
  throw InputError({}, "eig.SymmetricEigenOptions", "valid eigen-solver options", found);
}

SparseMatrix symmetric_part(const SparseMatrix& A, double asymmetry) {
  if (asymmetry == 0.0) return A;
  const SparseMatrix At = A.transpose();
  return 0.5 * (A + At);
}

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

void compute_residuals(const SparseMatrix& K, const SparseMatrix& M, SymmetricEigenResult& r) {
  const double norm_k = linalg::norm1(K), norm_m = linalg::norm1(M);
  const Eigen::Index m = r.eigenvalues.size();
  r.residuals.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::VectorXd phi = r.eigenvectors.col(j);
    const double lambda = r.eigenvalues[j];
    const Eigen::VectorXd res = K * phi - lambda * (M * phi);
    const double scale = (norm_k + std::abs(lambda) * norm_m) * phi.norm();
    r.residuals[j] = scale > 0.0 ? res.norm() / scale : res.norm();
  }
}

void mass_normalise(const SparseMatrix& M, Eigen::MatrixXd& vectors) {
  for (Eigen::Index j = 0; j < vectors.cols(); ++j) {
    const double mass = vectors.col(j).dot(M * vectors.col(j));
    if (mass > 0.0) vectors.col(j) /= std::sqrt(mass);
    // Sign convention for reproducible output: the first entry of at least 1e-3 of the
    // largest magnitude is positive (the largest entry alone is ambiguous for antisymmetric
    // shapes, whose extremes come in +- pairs).
    const double largest = vectors.col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < vectors.rows(); ++i) {
      if (std::abs(vectors(i, j)) >= 1e-3 * largest) {
        if (vectors(i, j) < 0.0) vectors.col(j) *= -1.0;
        break;
      }
    }
  }
}

// Keeps the wanted pairs of a full (or partial) spectrum and orders them ascending.
void select_pairs(const Eigen::VectorXd& values, const Eigen::MatrixXd& vectors,
                  const SymmetricEigenOptions& options, double selection_shift, bool band,
                  SymmetricEigenResult& r) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(values.size()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::vector<Eigen::Index> keep;
  if (band) {
    for (auto i : order)
      if (values[i] >= options.band_min && values[i] <= options.band_max) keep.push_back(i);
  } else {
    std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
      return std::abs(values[a] - selection_shift) < std::abs(values[b] - selection_shift);
    });
    const auto count =
        std::min<std::size_t>(order.size(), static_cast<std::size_t>(options.n_modes));
    keep.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count));
  }
  std::stable_sort(keep.begin(), keep.end(),
                   [&](Eigen::Index a, Eigen::Index b) { return values[a] < values[b]; });
  r.eigenvalues.resize(static_cast<Eigen::Index>(keep.size()));
  r.eigenvectors.resize(vectors.rows(), static_cast<Eigen::Index>(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) {
    r.eigenvalues[static_cast<Eigen::Index>(k)] = values[keep[k]];
    r.eigenvectors.col(static_cast<Eigen::Index>(k)) = vectors.col(keep[k]);
  }
}

void solve_dense(const SparseMatrix& K, const SparseMatrix& M, const SymmetricEigenOptions& options,
                 bool band, SymmetricEigenResult& r) {
  const Eigen::MatrixXd Kd(K), Md(M);
  r.method_used = Method::Dense;
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  const Eigen::LLT<Eigen::MatrixXd> mass_llt(Md);
  r.factorizations = 1;
  if (mass_llt.info() == Eigen::Success && mass_llt.rcond() > 1e-12) {
    r.factorization = "dense_cholesky_of_M";
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(
        Kd, Md, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (ges.info() != Eigen::Success) {
      r.status = Status::Failed;
      r.message = "dense symmetric eigen-solver (QR iteration) did not converge";
      return;
    }
    values = ges.eigenvalues();
    vectors = ges.eigenvectors();
  } else {
    // M is singular (massless DOFs): M phi = mu (K - sigma M) phi, mu = 1 / (lambda - sigma),
    // with sigma below the spectrum so K - sigma M is positive definite. mu = 0 are the
    // infinite eigenvalues of the massless DOFs and are dropped.
    const double sigma = automatic_shift(K, M);
    r.factorization = "dense_cholesky_of_K_minus_sigma_M";
    const Eigen::MatrixXd A = Kd - sigma * Md;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(
        Md, A, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (ges.info() != Eigen::Success) {
      r.status = Status::Singular;
      r.message = fmt::format(
          "mass matrix is singular and K - sigma M (sigma = {:.4g}) is not positive definite: "
          "the model has a mechanism without mass or negative stiffness; add mass or supports",
          sigma);
      return;
    }
    const Eigen::VectorXd mu = ges.eigenvalues();
    const double mu_max = mu.cwiseAbs().maxCoeff();
    std::vector<Eigen::Index> finite;
    for (Eigen::Index i = 0; i < mu.size(); ++i)
      if (mu[i] > 1e-13 * mu_max) finite.push_back(i);
    values.resize(static_cast<Eigen::Index>(finite.size()));
    vectors.resize(Kd.rows(), static_cast<Eigen::Index>(finite.size()));
    for (std::size_t k = 0; k < finite.size(); ++k) {
      values[static_cast<Eigen::Index>(k)] = sigma + 1.0 / mu[finite[k]];
      vectors.col(static_cast<Eigen::Index>(k)) = ges.eigenvectors().col(finite[k]);
    }
  }
  // The dense solver has every pair; without a shift the lowest ones are wanted, i.e. those
  // nearest any point below the spectrum.
  r.shift_used = options.shift;
  const double selection_shift = !std::isnan(options.shift)
                                     ? options.shift
                                     : (values.size() > 0 ? values.minCoeff() - 1.0 : 0.0);
  select_pairs(values, vectors, options, selection_shift, band, r);
  r.requested = band ? static_cast<int>(r.eigenvalues.size()) : options.n_modes;
  r.converged = static_cast<int>(r.eigenvalues.size());
  r.status = Status::Ok;
  if (!band && r.converged < r.requested) {
    r.status = Status::FewerModes;
    r.message = fmt::format("the system has only {} finite modes, {} were asked for", values.size(),
                            r.requested);
  }
}

void solve_sparse(const SparseMatrix& K, const SparseMatrix& M,
                  const SymmetricEigenOptions& options, bool band, SymmetricEigenResult& r) {
  const Eigen::Index n = K.rows();
  r.method_used = Method::Sparse;
  double sigma;
  if (band)
    sigma = options.band_min > 0.0 ? options.band_min : automatic_shift(K, M);
  else
    sigma = std::isnan(options.shift) ? automatic_shift(K, M) : options.shift;
  r.shift_used = sigma;

  const SparseMatrix A = K - sigma * M;
  linalg::SymmetricFactorization factorization;
  r.factorizations = 1;
  const Status fs = factorization.compute(A);
  if (fs != Status::Ok) {
    r.status = fs;
    r.message = fmt::format(
        "K - sigma M is singular at sigma = {:.6g} rad^2/s^2 ({}); sigma is an eigenvalue or the "
        "model has an unsupported mechanism: move the shift or check supports",
        sigma, factorization.message());
    return;
  }
  r.factorization = std::string(to_string(factorization.kind()));

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
  select_pairs(values, vectors, options, sigma, band, r);
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
  if (auto problems = options.validate(); !problems.empty()) throw_options(problems);
  if (K_in.rows() != K_in.cols() || M_in.rows() != M_in.cols() || K_in.rows() != M_in.rows())
    throw InputError(
        {}, "eig.solve_symmetric", "square K and M of the same size",
        fmt::format("K {}x{}, M {}x{}", K_in.rows(), K_in.cols(), M_in.rows(), M_in.cols()));
  const Eigen::Index n = K_in.rows();
  if (n == 0) throw InputError({}, "eig.solve_symmetric", "at least one DOF", "an empty system");

  SymmetricEigenResult r;
  r.asymmetry = linalg::relative_asymmetry(K_in);
  const SparseMatrix K = symmetric_part(K_in, r.asymmetry);
  const SparseMatrix M = symmetric_part(M_in, linalg::relative_asymmetry(M_in));
  const bool band = !std::isnan(options.band_min);

  Method method = options.method;
  // Auto: dense for small systems, and whenever Lanczos could not return the modes asked for
  // (at most n - 1).
  if (method == Method::Auto)
    method = n <= options.dense_limit || (!band && options.n_modes > n - 1 && n <= kDenseHardLimit)
                 ? Method::Dense
                 : Method::Sparse;
  if (method == Method::Dense && n > kDenseHardLimit)
    throw InputError({}, "eig.method", fmt::format("sparse for more than {} DOFs", kDenseHardLimit),
                     fmt::format("dense with {} DOFs", n),
                     "a dense solve of this size takes O(n^3) time and O(n^2) memory");
  if (method == Method::Sparse && n < 3) method = Method::Dense;  // Lanczos needs n >= 3

  if (method == Method::Dense)
    solve_dense(K, M, options, band, r);
  else
    solve_sparse(K, M, options, band, r);
  if (r.eigenvalues.size() > 0) {
    mass_normalise(M, r.eigenvectors);
    compute_residuals(K, M, r);
    if (r.status == Status::Ok && r.max_residual() > options.residual_limit) {
      r.status = Status::NotConverged;
      r.message = fmt::format(
          "largest backward error {:.3e} exceeds residual_limit {:.1e}; tighten "
          "krylov.tolerance or check the model's conditioning",
          r.max_residual(), options.residual_limit);
    }
  }
  return r;
}

}  // namespace geardyn::eig
