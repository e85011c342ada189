// GCC's -Wnull-dereference false positive inside Eigen's sparse wrappers (see
// linalg/sparse_factorization.cpp): the pragma must precede the first Eigen include.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <random>

#include "geardyn/core/error.hpp"
#include "geardyn/eig/hermitian_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

using Complex = std::complex<double>;
using ComplexSparse = Eigen::SparseMatrix<Complex>;

std::vector<std::string> HermitianEigenOptions::validate() const {
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

double HermitianEigenResult::max_residual() const {
  return residuals.size() > 0 ? residuals.maxCoeff() : 0.0;
}

std::string HermitianEigenResult::brief_report() const {
  return fmt::format(
      "hermitian eigen: {} ({}), {}/{} modes, sigma={:.4g}, max residual {:.2e}, {} restarts, "
      "{} solves, status {}{}{}",
      to_string(method_used), factorization, converged, requested, shift_used, max_residual(),
      iterations, operations, to_string(status), message.empty() ? "" : ": ", message);
}

double automatic_shift(const ComplexSparse& K, const ComplexSparse& M) {
  const Eigen::VectorXcd kd = K.diagonal(), md = M.diagonal();
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < kd.size(); ++i)
    if (kd[i].real() > 0.0 && md[i].real() > 0.0)
      smallest = std::min(smallest, kd[i].real() / md[i].real());
  if (!std::isfinite(smallest)) smallest = 1.0;
  return -1e-6 * smallest;
}

namespace {

[[noreturn]] void throw_options(const std::vector<std::string>& problems) {
  std::string found;
  for (const auto& p : problems) found += (found.empty() ? "" : "; ") + p;
  throw InputError({}, "eig.HermitianEigenOptions", "valid eigen-solver options", found);
}

double norm1(const ComplexSparse& A) {
  double best = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    double sum = 0.0;
    for (ComplexSparse::InnerIterator it(A, j); it; ++it) sum += std::abs(it.value());
    best = std::max(best, sum);
  }
  return best;
}

double hermitian_asymmetry(const ComplexSparse& A) {
  const double norm = A.norm();
  if (norm == 0.0) return 0.0;
  const ComplexSparse Ah = A.adjoint();
  return (A - Ah).norm() / norm;
}

ComplexSparse hermitian_part(const ComplexSparse& A, double asymmetry) {
  if (asymmetry == 0.0) return A;
  const ComplexSparse Ah = A.adjoint();
  return 0.5 * (A + Ah);
}

// Factorisation of the Hermitian matrix K - sigma M: complex Cholesky LL^H when it is positive
// definite (sigma below the spectrum, the usual case), UMFPACK's pivoting LU otherwise. Both
// solve to working precision; kind() records which one ran.
class HermitianFactorization {
 public:
  Status compute(const ComplexSparse& A) {
    // CHOLMOD reports "not positive definite" through its error handler, which prints by
    // default; the library stays silent and handles the condition here.
    cholesky_.cholmod().print = 0;
    cholesky_.cholmod().error_handler = nullptr;
    cholesky_.compute(A);
    if (cholesky_.info() == Eigen::Success) {
      kind_ = linalg::FactorizationKind::Cholesky;
      return Status::Ok;
    }
    const Status s = lu_.compute(A);
    if (s != Status::Ok) {
      message_ = lu_.message();
      return s;
    }
    kind_ = linalg::FactorizationKind::LU;
    return Status::Ok;
  }
  Eigen::VectorXcd solve(const Eigen::VectorXcd& b) const {
    if (kind_ == linalg::FactorizationKind::Cholesky) return cholesky_.solve(b);
    return lu_.solve(b);
  }
  linalg::FactorizationKind kind() const { return kind_; }
  const std::string& message() const { return message_; }

 private:
  Eigen::CholmodSupernodalLLT<ComplexSparse, Eigen::Lower> cholesky_;
  linalg::SparseLU<Complex> lu_;
  linalg::FactorizationKind kind_ = linalg::FactorizationKind::None;
  std::string message_;
};

// y = (K - sigma M)^{-1} M x, self-adjoint in the M inner product.
class ShiftInvertOperator {
 public:
  ShiftInvertOperator(const ComplexSparse& M, const HermitianFactorization& factorization)
      : M_(M), factorization_(factorization) {}
  Eigen::VectorXcd apply(const Eigen::VectorXcd& x) const {
    ++count_;
    return factorization_.solve(M_ * x);
  }
  int count() const { return count_; }

 private:
  const ComplexSparse& M_;
  const HermitianFactorization& factorization_;
  mutable int count_ = 0;
};

struct LanczosOutcome {
  Eigen::VectorXd theta;             // Ritz values of the operator, wanted first (largest |theta|)
  Eigen::MatrixXcd vectors;          // M-orthonormal Ritz vectors
  int converged = 0;                 // how many of the first nev met the tolerance
  std::vector<bool> pair_converged;  // per wanted pair
  int restarts = 0;
  bool broke_down = false;  // no vector with non-zero M-norm could be made
};

// Block thick-restart Lanczos (a Hermitian Krylov-Schur iteration) with full reorthogonalisation.
// Invariant between steps, with V M-orthonormal and `known` columns whose images are expanded:
//   Op V(:, 0:known) = V(:, 0:known+p) H(0:known+p, 0:known).
// H(0:known, 0:known) = V^H M Op V is the Rayleigh quotient (Hermitian because Op is M-self-
// adjoint), and the Ritz residual of y = V s is Op y - theta y = V_next E s with E =
// H(known:known+p, 0:known), so its M-norm is ||E s||_2 without forming y.
class BlockLanczos {
 public:
  BlockLanczos(const ShiftInvertOperator& op, const ComplexSparse& M,
               const HermitianEigenOptions& options, Eigen::Index nev)
      : op_(op),
        M_(M),
        options_(options),
        nev_(nev),
        n_(M.rows()),
        p_(options.block_size),
        rng_(options.seed) {
    const Eigen::Index automatic = std::max(2 * nev + 2 * p_, nev + 20 + p_);
    m_ = options.krylov.subspace_size > 0 ? options.krylov.subspace_size : automatic;
    m_ = std::min(std::max(m_, nev + p_), n_ - p_);
  }

  LanczosOutcome run() {
    LanczosOutcome out;
    V_.setZero(n_, m_ + p_);
    MV_.setZero(n_, m_ + p_);
    H_.setZero(m_ + p_, m_ + p_);
    Eigen::MatrixXcd W(n_, p_);
    for (Eigen::Index c = 0; c < p_; ++c) W.col(c) = random_in_range();
    Eigen::MatrixXcd C, R;
    if (!orthonormalise(W, 0, C, R)) {
      out.broke_down = true;
      return out;
    }
    Eigen::Index known = 0;
    for (int restart = 0;; ++restart) {
      while (known + p_ <= m_) {
        const Eigen::Index cols = known + p_;
        for (Eigen::Index c = 0; c < p_; ++c) W.col(c) = op_.apply(V_.col(known + c));
        if (!orthonormalise(W, cols, C, R)) {
          out.broke_down = true;
          return out;
        }
        H_.block(0, known, cols, p_) = C;
        H_.block(cols, known, p_, p_) = R;
        known += p_;
      }
      const Eigen::MatrixXcd Hm = H_.topLeftCorner(known, known);
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXcd> es(0.5 * (Hm + Hm.adjoint()));
      const Eigen::VectorXd theta = es.eigenvalues();
      const Eigen::MatrixXcd& S = es.eigenvectors();
      const Eigen::MatrixXcd E = H_.block(known, 0, p_, known);
      std::vector<Eigen::Index> order(static_cast<std::size_t>(known));
      std::iota(order.begin(), order.end(), Eigen::Index{0});
      std::stable_sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
        return std::abs(theta[a]) > std::abs(theta[b]);
      });
      int converged = 0;
      std::vector<bool> pair_converged(static_cast<std::size_t>(nev_));
      for (Eigen::Index i = 0; i < nev_; ++i) {
        const Eigen::Index k = order[static_cast<std::size_t>(i)];
        pair_converged[static_cast<std::size_t>(i)] =
            (E * S.col(k)).norm() <= options_.krylov.tolerance * std::abs(theta[k]);
        converged += pair_converged[static_cast<std::size_t>(i)] ? 1 : 0;
      }
      if (converged == nev_ || restart >= options_.krylov.max_restarts) {
        out.converged = converged;
        out.pair_converged = pair_converged;
        out.restarts = restart;
        out.theta.resize(nev_);
        Eigen::MatrixXcd Sw(known, nev_);
        for (Eigen::Index i = 0; i < nev_; ++i) {
          out.theta[i] = theta[order[static_cast<std::size_t>(i)]];
          Sw.col(i) = S.col(order[static_cast<std::size_t>(i)]);
        }
        out.vectors = V_.leftCols(known) * Sw;
        return out;
      }
      // Thick restart: keep the k best Ritz vectors, about halfway between nev and m (Wu & Simon
      // 2000, section 4, keep roughly that many for a good convergence rate per solve).
      const Eigen::Index k = std::min(known - p_, std::max(nev_ + p_, (known + nev_) / 2));
      Eigen::MatrixXcd Sk(known, k);
      Eigen::VectorXd theta_k(k);
      for (Eigen::Index i = 0; i < k; ++i) {
        Sk.col(i) = S.col(order[static_cast<std::size_t>(i)]);
        theta_k[i] = theta[order[static_cast<std::size_t>(i)]];
      }
      const Eigen::MatrixXcd next = V_.middleCols(known, p_), next_m = MV_.middleCols(known, p_);
      const Eigen::MatrixXcd Vk = V_.leftCols(known) * Sk, MVk = MV_.leftCols(known) * Sk;
      V_.leftCols(k) = Vk;
      MV_.leftCols(k) = MVk;
      V_.middleCols(k, p_) = next;
      MV_.middleCols(k, p_) = next_m;
      const Eigen::MatrixXcd Ek = E * Sk;
      H_.setZero();
      H_.topLeftCorner(k, k) = theta_k.cast<Complex>().asDiagonal();
      H_.block(k, 0, p_, k) = Ek;
      known = k;
    }
  }

 private:
  // A random vector in the range of Op: components along the infinite eigenvalues of a
  // singular M are removed (Ericsson & Ruhe 1980, section 3).
  Eigen::VectorXcd random_in_range() {
    std::normal_distribution<double> normal;
    Eigen::VectorXcd x(n_);
    for (Eigen::Index i = 0; i < n_; ++i) x[i] = Complex(normal(rng_), normal(rng_));
    return op_.apply(x);
  }

  double m_norm(const Eigen::VectorXcd& w, Eigen::VectorXcd& Mw) const {
    Mw = M_ * w;
    return std::sqrt(std::max(0.0, w.dot(Mw).real()));
  }

  // M-orthonormalises the block W against V(:, 0:cols) and itself (classical Gram-Schmidt,
  // twice: "twice is enough", Giraud et al., Numer. Math. 101 (2005) 87-100), so that
  //   W = V(:, 0:cols) C + Q R,  Q stored in V(:, cols:cols+p), R upper triangular.
  // A column that vanishes after projection means the Krylov space is invariant in that
  // direction: it is replaced by a fresh random vector orthogonal to everything and R(c, c) = 0,
  // which keeps the Krylov relation exact.
  bool orthonormalise(Eigen::MatrixXcd W, Eigen::Index cols, Eigen::MatrixXcd& C,
                      Eigen::MatrixXcd& R) {
    C.setZero(cols, p_);
    R.setZero(p_, p_);
    Eigen::VectorXcd Mw;
    Eigen::VectorXd reference(p_);
    for (Eigen::Index c = 0; c < p_; ++c) reference[c] = m_norm(W.col(c), Mw);
    for (int pass = 0; pass < 2 && cols > 0; ++pass) {
      const Eigen::MatrixXcd coefficients = MV_.leftCols(cols).adjoint() * W;
      W.noalias() -= V_.leftCols(cols) * coefficients;
      C += coefficients;
    }
    for (Eigen::Index c = 0; c < p_; ++c) {
      Eigen::VectorXcd w = W.col(c);
      for (int pass = 0; pass < 2 && c > 0; ++pass) {
        const Eigen::VectorXcd r = MV_.middleCols(cols, c).adjoint() * w;
        w.noalias() -= V_.middleCols(cols, c) * r;
        R.col(c).head(c) += r;
      }
      double norm = m_norm(w, Mw);
      if (!(norm > 1e-12 * reference[c])) {
        R(c, c) = 0.0;
        w = random_in_range();
        const Eigen::Index span = cols + c;
        for (int pass = 0; pass < 2; ++pass)
          w -= V_.leftCols(span) * (MV_.leftCols(span).adjoint() * w);
        norm = m_norm(w, Mw);
        if (!(norm > 0.0)) return false;
      } else {
        R(c, c) = norm;
      }
      V_.col(cols + c) = w / norm;
      MV_.col(cols + c) = Mw / norm;
    }
    return true;
  }

  const ShiftInvertOperator& op_;
  const ComplexSparse& M_;
  const HermitianEigenOptions& options_;
  Eigen::Index nev_, n_, p_, m_ = 0;
  std::mt19937 rng_;
  Eigen::MatrixXcd V_, MV_, H_;
};

void select_pairs(const Eigen::VectorXd& values, const Eigen::MatrixXcd& vectors,
                  const HermitianEigenOptions& options, double selection_shift, bool band,
                  HermitianEigenResult& r) {
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

void solve_dense(const ComplexSparse& K, const ComplexSparse& M,
                 const HermitianEigenOptions& options, bool band, HermitianEigenResult& r) {
  const Eigen::MatrixXcd Kd(K), Md(M);
  r.method_used = Method::Dense;
  r.factorizations = 1;
  Eigen::VectorXd values;
  Eigen::MatrixXcd vectors;
  const Eigen::LLT<Eigen::MatrixXcd> mass_llt(Md);
  if (mass_llt.info() == Eigen::Success && mass_llt.rcond() > 1e-12) {
    r.factorization = "dense_cholesky_of_M";
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> ges(
        Kd, Md, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (ges.info() != Eigen::Success) {
      r.status = Status::Failed;
      r.message = "dense Hermitian eigen-solver (QR iteration) did not converge";
      return;
    }
    values = ges.eigenvalues();
    vectors = ges.eigenvectors();
  } else {
    // Singular M: M phi = mu (K - sigma M) phi, mu = 1 / (lambda - sigma); mu = 0 are the
    // infinite eigenvalues of massless DOFs and are dropped.
    const double sigma = automatic_shift(K, M);
    r.factorization = "dense_cholesky_of_K_minus_sigma_M";
    const Eigen::MatrixXcd A = Kd - sigma * Md;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXcd> ges(
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

void solve_sparse(const ComplexSparse& K, const ComplexSparse& M,
                  const HermitianEigenOptions& options, bool band, HermitianEigenResult& r) {
  const Eigen::Index n = K.rows();
  const Eigen::Index p = options.block_size;
  r.method_used = Method::Sparse;
  double sigma;
  if (band)
    sigma = options.band_min > 0.0 ? options.band_min : automatic_shift(K, M);
  else
    sigma = std::isnan(options.shift) ? automatic_shift(K, M) : options.shift;
  r.shift_used = sigma;

  const ComplexSparse A = K - Complex(sigma) * M;
  HermitianFactorization factorization;
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
  r.factorization = std::string(linalg::to_string(factorization.kind()));

  const ShiftInvertOperator op(M, factorization);
  // The basis needs nev + p columns plus one block to expand into.
  const Eigen::Index largest_nev = n - 2 * p;
  Eigen::Index nev = std::clamp<Eigen::Index>(options.n_modes, 1, largest_nev);
  const double reach = band ? std::max(options.band_max - sigma, sigma - options.band_min) : 0.0;
  LanczosOutcome outcome;
  bool covered = !band;
  while (true) {
    BlockLanczos lanczos(op, M, options, nev);
    outcome = lanczos.run();
    r.iterations += outcome.restarts;
    if (outcome.broke_down || outcome.converged < nev || !band) break;
    const Eigen::VectorXd lambda = sigma + outcome.theta.array().inverse();
    if ((lambda.array() - sigma).abs().maxCoeff() > reach) {
      covered = true;
      break;
    }
    if (nev >= largest_nev) break;
    nev = std::min<Eigen::Index>(2 * nev, largest_nev);
  }
  r.operations = op.count();
  r.requested = band ? static_cast<int>(nev) : options.n_modes;
  if (outcome.broke_down) {
    r.status = Status::Failed;
    r.message =
        "Lanczos could not build a vector of non-zero M-norm: the mass matrix is zero on the "
        "range of (K - sigma M)^{-1} M; check the mass matrix";
    return;
  }
  // Only the converged Ritz pairs are returned: those with the largest |theta| converge first,
  // and a pair is kept when its own residual estimate meets the tolerance.
  std::vector<Eigen::Index> kept;
  for (std::size_t i = 0; i < outcome.pair_converged.size(); ++i)
    if (outcome.pair_converged[i]) kept.push_back(static_cast<Eigen::Index>(i));
  Eigen::VectorXd values(static_cast<Eigen::Index>(kept.size()));
  Eigen::MatrixXcd vectors(n, static_cast<Eigen::Index>(kept.size()));
  for (std::size_t i = 0; i < kept.size(); ++i) {
    values[static_cast<Eigen::Index>(i)] = sigma + 1.0 / outcome.theta[kept[i]];
    vectors.col(static_cast<Eigen::Index>(i)) = outcome.vectors.col(kept[i]);
  }
  select_pairs(values, vectors, options, sigma, band, r);
  r.converged = static_cast<int>(r.eigenvalues.size());
  r.status = Status::Ok;
  if (outcome.converged < nev) {
    r.status = Status::NotConverged;
    r.message = fmt::format(
        "block Lanczos converged {} of {} eigenpairs in {} restarts; increase "
        "krylov.max_restarts or krylov.subspace_size",
        outcome.converged, nev, options.krylov.max_restarts);
  } else if (!covered) {
    r.status = Status::FewerModes;
    r.message = fmt::format(
        "the band [{:.6g}, {:.6g}] was not covered: the sparse solver returns at most n - 2 p = "
        "{} modes; use the dense method for this size",
        options.band_min, options.band_max, largest_nev);
  } else if (!band && options.n_modes > largest_nev) {
    r.status = Status::FewerModes;
    r.message = fmt::format(
        "{} modes asked, the sparse solver returns at most n - 2 block_size = {}; use the dense "
        "method",
        options.n_modes, largest_nev);
  }
}

void normalise(const ComplexSparse& M, Eigen::MatrixXcd& vectors) {
  for (Eigen::Index j = 0; j < vectors.cols(); ++j) {
    const double mass = vectors.col(j).dot(M * vectors.col(j)).real();
    if (mass > 0.0) vectors.col(j) /= std::sqrt(mass);
    const double largest = vectors.col(j).cwiseAbs().maxCoeff();
    for (Eigen::Index i = 0; i < vectors.rows(); ++i) {
      const double magnitude = std::abs(vectors(i, j));
      if (magnitude >= (1.0 - 1e-3) * largest && magnitude > 0.0) {
        vectors.col(j) *= std::conj(vectors(i, j)) / magnitude;
        break;
      }
    }
  }
}

void compute_residuals(const ComplexSparse& K, const ComplexSparse& M, HermitianEigenResult& r) {
  const double norm_k = norm1(K), norm_m = norm1(M);
  const Eigen::Index m = r.eigenvalues.size();
  r.residuals.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::VectorXcd phi = r.eigenvectors.col(j);
    const double lambda = r.eigenvalues[j];
    const Eigen::VectorXcd res = K * phi - lambda * (M * phi);
    const double scale = (norm_k + std::abs(lambda) * norm_m) * phi.norm();
    r.residuals[j] = scale > 0.0 ? res.norm() / scale : res.norm();
  }
}

}  // namespace

HermitianEigenResult solve_hermitian(const ComplexSparse& K_in, const ComplexSparse& M_in,
                                     const HermitianEigenOptions& options) {
  if (auto problems = options.validate(); !problems.empty()) throw_options(problems);
  if (K_in.rows() != K_in.cols() || M_in.rows() != M_in.cols() || K_in.rows() != M_in.rows())
    throw InputError(
        {}, "eig.solve_hermitian", "square K and M of the same size",
        fmt::format("K {}x{}, M {}x{}", K_in.rows(), K_in.cols(), M_in.rows(), M_in.cols()));
  const Eigen::Index n = K_in.rows();
  if (n == 0) throw InputError({}, "eig.solve_hermitian", "at least one DOF", "an empty system");

  HermitianEigenResult r;
  r.asymmetry = hermitian_asymmetry(K_in);
  const ComplexSparse K = hermitian_part(K_in, r.asymmetry);
  const ComplexSparse M = hermitian_part(M_in, hermitian_asymmetry(M_in));
  const bool band = !std::isnan(options.band_min);
  const Eigen::Index largest_sparse = n - 2 * options.block_size;

  Method method = options.method;
  if (method == Method::Auto)
    method = n <= options.dense_limit ||
                     (!band && options.n_modes > largest_sparse && n <= kDenseHardLimit)
                 ? Method::Dense
                 : Method::Sparse;
  if (method == Method::Dense && n > kDenseHardLimit)
    throw InputError({}, "eig.method", fmt::format("sparse for more than {} DOFs", kDenseHardLimit),
                     fmt::format("dense with {} DOFs", n),
                     "a dense solve of this size takes O(n^3) time and O(n^2) memory");
  // The block Krylov basis needs room for the wanted pairs plus two blocks.
  if (method == Method::Sparse && largest_sparse < 1) method = Method::Dense;

  if (method == Method::Dense)
    solve_dense(K, M, options, band, r);
  else
    solve_sparse(K, M, options, band, r);
  if (r.eigenvalues.size() > 0) {
    normalise(M, r.eigenvectors);
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
