#pragma once
// Internal to the eig module (not installed, not included outside src/geardyn/eig/): the parts of
// solve_symmetric (Scalar = double) and solve_hermitian (Scalar = std::complex<double>) that do
// not depend on the scalar type -- the block thick-restart Lanczos iteration, the dense path,
// pair selection, normalisation, residuals and the count/band driver. The public headers
// (symmetric_eigen.hpp, hermitian_eigen.hpp) document the methods and cite the references.
//
// Result is SymmetricEigenResult or HermitianEigenResult and Options the matching options struct;
// both pairs have the same member names, which is all these templates rely on.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/core/status.hpp"
#include "geardyn/eig/conditioning.hpp"
#include "geardyn/eig/eigen_options.hpp"

namespace geardyn::eig::detail {

template <class Scalar>
using DenseMatrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
template <class Scalar>
using DenseVector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
template <class Scalar>
using SparseMatrix = Eigen::SparseMatrix<Scalar>;

[[noreturn]] inline void throw_options(const char* where,
                                       const std::vector<std::string>& problems) {
  std::string found;
  for (const auto& p : problems) found += (found.empty() ? "" : "; ") + p;
  throw InputError({}, where, "valid eigen-solver options", found);
}

/// -1e-6 * min_i (Re K_ii / Re M_ii) over DOFs with both positive (-1e-6 when there are none).
template <class Scalar>
double automatic_shift(const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M) {
  const DenseVector<Scalar> kd = K.diagonal(), md = M.diagonal();
  double smallest = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < kd.size(); ++i)
    if (std::real(kd[i]) > 0.0 && std::real(md[i]) > 0.0)
      smallest = std::min(smallest, std::real(kd[i]) / std::real(md[i]));
  if (!std::isfinite(smallest)) smallest = 1.0;
  return -1e-6 * smallest;
}

/// 1-norm (largest absolute column sum).
template <class Scalar>
double norm1(const SparseMatrix<Scalar>& A) {
  double best = 0.0;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j) {
    double sum = 0.0;
    for (typename SparseMatrix<Scalar>::InnerIterator it(A, j); it; ++it)
      sum += std::abs(it.value());
    best = std::max(best, sum);
  }
  return best;
}

/// ||A - A^H||_F / ||A||_F (0 for a zero matrix).
template <class Scalar>
double self_adjoint_defect(const SparseMatrix<Scalar>& A) {
  const double norm = A.norm();
  if (norm == 0.0) return 0.0;
  const SparseMatrix<Scalar> Ah = A.adjoint();
  return (A - Ah).norm() / norm;
}

/// (A + A^H) / 2, or A itself when it is exactly self-adjoint.
template <class Scalar>
SparseMatrix<Scalar> self_adjoint_part(const SparseMatrix<Scalar>& A, double defect) {
  if (defect == 0.0) return A;
  const SparseMatrix<Scalar> Ah = A.adjoint();
  return Scalar(0.5) * (A + Ah);
}

/// Y = (K - sigma M)^{-1} M X for a block X, self-adjoint in the M inner product. Factorization
/// provides solve(DenseMatrix) (one supernodal block solve for all columns).
template <class Scalar, class Factorization>
class ShiftInvertOperator {
 public:
  ShiftInvertOperator(const SparseMatrix<Scalar>& M, const Factorization& factorization)
      : M_(M), factorization_(factorization) {}
  DenseMatrix<Scalar> apply(const DenseMatrix<Scalar>& X) const {
    const DenseMatrix<Scalar> MX = M_ * X;
    return solve(MX);
  }
  /// The same with M X already known (Lanczos keeps M V next to V): no product with M.
  DenseMatrix<Scalar> apply_to_product(const DenseMatrix<Scalar>& MX) const { return solve(MX); }
  /// Right-hand sides solved so far (a block of p counts p).
  int count() const { return count_; }

 private:
  DenseMatrix<Scalar> solve(const DenseMatrix<Scalar>& MX) const {
    count_ += static_cast<int>(MX.cols());
    return factorization_.solve(MX);
  }

  const SparseMatrix<Scalar>& M_;
  const Factorization& factorization_;
  mutable int count_ = 0;
};

template <class Scalar>
struct LanczosOutcome {
  Eigen::VectorXd theta;             // Ritz values of the operator, wanted first (largest |theta|)
  DenseMatrix<Scalar> vectors;       // M-orthonormal Ritz vectors
  int converged = 0;                 // how many of the first nev met the tolerance
  std::vector<bool> pair_converged;  // per wanted pair
  int restarts = 0;
  bool broke_down = false;  // no vector with non-zero M-norm could be made
};

// Block thick-restart Lanczos (a Hermitian Krylov-Schur iteration) with full reorthogonalisation.
// Invariant between steps, with V M-orthonormal and `known` columns whose images are expanded:
//   Op V(:, 0:known) = V(:, 0:known+p) H(0:known+p, 0:known).
// H(0:known, 0:known) = V^H M Op V is the Rayleigh quotient (self-adjoint because Op is M-self-
// adjoint), and the Ritz residual of y = V s is Op y - theta y = V_next E s with E =
// H(known:known+p, 0:known), so its M-norm is ||E s||_2 without forming y. The operator is
// applied to a whole block at once: one pass over the factor serves p right-hand sides. Products
// with M, the other large cost, are made once per basis vector: M V is kept next to V (so the
// operator's own M V and every M inner product with the basis are free), and the only fresh
// product is the one that normalises a new vector.
template <class Scalar, class Op, class Options>
class BlockLanczos {
 public:
  using Matrix = DenseMatrix<Scalar>;
  using Vector = DenseVector<Scalar>;

  BlockLanczos(const Op& op, const SparseMatrix<Scalar>& M, const Options& options,
               Eigen::Index nev)
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

  LanczosOutcome<Scalar> run() {
    LanczosOutcome<Scalar> out;
    V_.setZero(n_, m_ + p_);
    MV_.setZero(n_, m_ + p_);
    H_.setZero(m_ + p_, m_ + p_);
    Matrix W = random_in_range(p_);
    Matrix C, R;
    if (!orthonormalise(W, 0, C, R)) {
      out.broke_down = true;
      return out;
    }
    Eigen::Index known = 0;
    for (int restart = 0;; ++restart) {
      while (known + p_ <= m_) {
        const Eigen::Index cols = known + p_;
        W = op_.apply_to_product(MV_.middleCols(known, p_));
        if (!orthonormalise(W, cols, C, R)) {
          out.broke_down = true;
          return out;
        }
        H_.block(0, known, cols, p_) = C;
        H_.block(cols, known, p_, p_) = R;
        known += p_;
      }
      const Matrix Hm = H_.topLeftCorner(known, known);
      const Eigen::SelfAdjointEigenSolver<Matrix> es(Scalar(0.5) * (Hm + Hm.adjoint()));
      const Eigen::VectorXd theta = es.eigenvalues();
      const Matrix& S = es.eigenvectors();
      const Matrix E = H_.block(known, 0, p_, known);
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
        Matrix Sw(known, nev_);
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
      Matrix Sk(known, k);
      Eigen::VectorXd theta_k(k);
      for (Eigen::Index i = 0; i < k; ++i) {
        Sk.col(i) = S.col(order[static_cast<std::size_t>(i)]);
        theta_k[i] = theta[order[static_cast<std::size_t>(i)]];
      }
      const Matrix next = V_.middleCols(known, p_), next_m = MV_.middleCols(known, p_);
      const Matrix Vk = V_.leftCols(known) * Sk, MVk = MV_.leftCols(known) * Sk;
      V_.leftCols(k) = Vk;
      MV_.leftCols(k) = MVk;
      V_.middleCols(k, p_) = next;
      MV_.middleCols(k, p_) = next_m;
      const Matrix Ek = E * Sk;
      H_.setZero();
      H_.topLeftCorner(k, k) = theta_k.template cast<Scalar>().asDiagonal();
      H_.block(k, 0, p_, k) = Ek;
      known = k;
    }
  }

 private:
  Scalar random_scalar(std::normal_distribution<double>& normal) {
    if constexpr (std::is_same_v<Scalar, double>) {
      return normal(rng_);
    } else {
      const double re = normal(rng_);
      return Scalar(re, normal(rng_));
    }
  }

  // Random vectors in the range of Op: components along the infinite eigenvalues of a singular M
  // are removed (Ericsson & Ruhe 1980, section 3).
  Matrix random_in_range(Eigen::Index columns) {
    std::normal_distribution<double> normal;
    Matrix X(n_, columns);
    for (Eigen::Index c = 0; c < columns; ++c)
      for (Eigen::Index i = 0; i < n_; ++i) X(i, c) = random_scalar(normal);
    return op_.apply(X);
  }

  double m_norm(const Vector& w, Vector& Mw) const {
    Mw = M_ * w;
    return std::sqrt(std::max(0.0, std::real(w.dot(Mw))));
  }

  // M-orthonormalises the block W against V(:, 0:cols) and itself (classical Gram-Schmidt,
  // twice: "twice is enough", Giraud et al., Numer. Math. 101 (2005) 87-100), so that
  //   W = V(:, 0:cols) C + Q R,  Q stored in V(:, cols:cols+p), R upper triangular.
  // A column that vanishes after projection means the Krylov space is invariant in that
  // direction: it is replaced by a fresh random vector orthogonal to everything and R(c, c) = 0,
  // which keeps the Krylov relation exact. "Vanishes" is judged against the M-norm of the
  // column before projection, which by Pythagoras (the basis is M-orthonormal) is
  // sqrt(||C(:, c)||^2 + ||R(:, c)||^2) -- known without another product with M.
  bool orthonormalise(Matrix W, Eigen::Index cols, Matrix& C, Matrix& R) {
    C.setZero(cols, p_);
    R.setZero(p_, p_);
    Vector Mw;
    for (int pass = 0; pass < 2 && cols > 0; ++pass) {
      const Matrix coefficients = MV_.leftCols(cols).adjoint() * W;
      W.noalias() -= V_.leftCols(cols) * coefficients;
      C += coefficients;
    }
    for (Eigen::Index c = 0; c < p_; ++c) {
      Vector w = W.col(c);
      for (int pass = 0; pass < 2 && c > 0; ++pass) {
        const Vector r = MV_.middleCols(cols, c).adjoint() * w;
        w.noalias() -= V_.middleCols(cols, c) * r;
        R.col(c).head(c) += r;
      }
      double norm = m_norm(w, Mw);
      const double before =
          std::sqrt(C.col(c).squaredNorm() + R.col(c).head(c).squaredNorm() + norm * norm);
      if (!(norm > 1e-12 * before)) {
        R(c, c) = Scalar(0.0);
        w = random_in_range(1).col(0);
        const Eigen::Index span = cols + c;
        for (int pass = 0; pass < 2; ++pass)
          w -= V_.leftCols(span) * (MV_.leftCols(span).adjoint() * w);
        norm = m_norm(w, Mw);
        if (!(norm > 0.0)) return false;
      } else {
        R(c, c) = Scalar(norm);
      }
      V_.col(cols + c) = w / norm;
      MV_.col(cols + c) = Mw / norm;
    }
    return true;
  }

  const Op& op_;
  const SparseMatrix<Scalar>& M_;
  const Options& options_;
  Eigen::Index nev_, n_, p_, m_ = 0;
  std::mt19937 rng_;
  Matrix V_, MV_, H_;
};

/// Keeps the wanted pairs of a full (or partial) spectrum -- the n_modes nearest
/// `selection_shift`, or those inside the band -- and orders them ascending.
template <class Scalar, class Options, class Result>
void select_pairs(const Eigen::VectorXd& values, const DenseMatrix<Scalar>& vectors,
                  const Options& options, double selection_shift, bool band, Result& r) {
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

/// Every eigenpair by Eigen's dense generalised solver; when M is singular the pencil
/// (M, K - sigma M) with mu = 1 / (lambda - sigma), dropping the infinite eigenvalues (mu = 0) of
/// massless DOFs.
template <class Scalar, class Options, class Result>
void solve_dense(const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M,
                 const Options& options, bool band, Result& r) {
  using Matrix = DenseMatrix<Scalar>;
  const Matrix Kd(K), Md(M);
  r.method_used = Method::Dense;
  r.factorizations = 1;
  Eigen::VectorXd values;
  Matrix vectors;
  const Eigen::LLT<Matrix> mass_llt(Md);
  if (mass_llt.info() == Eigen::Success && mass_llt.rcond() > 1e-12) {
    r.factorization = "dense_cholesky_of_M";
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> ges(
        Kd, Md, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
    if (ges.info() != Eigen::Success) {
      r.status = Status::Failed;
      const std::string scaling = scaling_diagnosis(Kd, Md);
      r.message = "dense eigen-solver (QR iteration) did not converge" +
                  (scaling.empty() ? std::string() : ": " + scaling);
      return;
    }
    values = ges.eigenvalues();
    vectors = ges.eigenvectors();
  } else {
    const double sigma = automatic_shift(K, M);
    r.factorization = "dense_cholesky_of_K_minus_sigma_M";
    const Matrix A = Kd - Scalar(sigma) * Md;
    const Eigen::GeneralizedSelfAdjointEigenSolver<Matrix> ges(
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

/// The common start of every sparse path: the shift (options.shift, band_min when positive, or
/// automatic) and the factorisation of K - sigma M. Returns sigma, or NaN after recording a
/// singular factorisation in r (status and message).
template <class Scalar, class Factorization, class Options, class Result>
double factor_shifted(const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M,
                      const Options& options, bool band, Factorization& factorization, Result& r) {
  r.method_used = Method::Sparse;
  double sigma;
  if (band)
    sigma = options.band_min > 0.0 ? options.band_min : automatic_shift(K, M);
  else
    sigma = std::isnan(options.shift) ? automatic_shift(K, M) : options.shift;
  r.shift_used = sigma;
  const SparseMatrix<Scalar> A = K - Scalar(sigma) * M;
  r.factorizations = 1;
  const Status fs = factorization.compute(A);
  if (fs != Status::Ok) {
    r.status = fs;
    r.message = fmt::format(
        "K - sigma M is singular at sigma = {:.6g} rad^2/s^2 ({}); sigma is an eigenvalue or the "
        "model has an unsupported mechanism: move the shift or check supports",
        sigma, factorization.message());
    return std::numeric_limits<double>::quiet_NaN();
  }
  r.factorization = std::string(to_string(factorization.kind()));
  return sigma;
}

/// The sparse path: factor K - sigma M once, run block Lanczos for nev pairs; in band mode double
/// nev until the converged Ritz values reach past the band. Factorization: compute(A) -> Status,
/// solve(DenseMatrix), kind(), message().
template <class Scalar, class Factorization, class Options, class Result>
void solve_sparse(const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M,
                  const Options& options, bool band, Result& r) {
  const Eigen::Index n = K.rows();
  const Eigen::Index p = options.block_size;
  Factorization factorization;
  const double sigma = factor_shifted(K, M, options, band, factorization, r);
  if (std::isnan(sigma)) return;
  const ShiftInvertOperator<Scalar, Factorization> op(M, factorization);
  // The basis needs nev + p columns plus one block to expand into.
  const Eigen::Index largest_nev = n - 2 * p;
  Eigen::Index nev = std::clamp<Eigen::Index>(options.n_modes, 1, largest_nev);
  const double reach = band ? std::max(options.band_max - sigma, sigma - options.band_min) : 0.0;
  LanczosOutcome<Scalar> outcome;
  bool covered = !band;
  while (true) {
    BlockLanczos<Scalar, ShiftInvertOperator<Scalar, Factorization>, Options> lanczos(op, M,
                                                                                      options, nev);
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
  DenseMatrix<Scalar> vectors(n, static_cast<Eigen::Index>(kept.size()));
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

/// Sign/phase convention for reproducible output.
/// Real: the first entry of at least 1e-3 of the largest magnitude is positive (the largest entry
/// alone is ambiguous for antisymmetric shapes, whose extremes come in +- pairs).
/// Complex: the entry of largest magnitude (the first within 1e-3 of the largest) is real and
/// positive.
inline void fix_phase(Eigen::Ref<Eigen::VectorXd> v) {
  const double largest = v.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (std::abs(v[i]) >= 1e-3 * largest) {
      if (v[i] < 0.0) v *= -1.0;
      return;
    }
  }
}
inline void fix_phase(Eigen::Ref<Eigen::VectorXcd> v) {
  const double largest = v.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    const double magnitude = std::abs(v[i]);
    if (magnitude >= (1.0 - 1e-3) * largest && magnitude > 0.0) {
      v *= std::conj(v[i]) / magnitude;
      return;
    }
  }
}

/// M-normalises every column and fixes its sign or phase.
template <class Scalar>
void normalise(const SparseMatrix<Scalar>& M, DenseMatrix<Scalar>& vectors) {
  for (Eigen::Index j = 0; j < vectors.cols(); ++j) {
    const double mass = std::real(vectors.col(j).dot(M * vectors.col(j)));
    if (mass > 0.0) vectors.col(j) /= std::sqrt(mass);
    fix_phase(vectors.col(j));
  }
}

/// Normwise backward error of each pair (Tisseur 2000, LAA 309:339, Thm 1).
template <class Scalar, class Result>
void compute_residuals(const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M, Result& r) {
  const double norm_k = norm1(K), norm_m = norm1(M);
  const Eigen::Index m = r.eigenvalues.size();
  r.residuals.resize(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    const DenseVector<Scalar> phi = r.eigenvectors.col(j);
    const double lambda = r.eigenvalues[j];
    const DenseVector<Scalar> res = K * phi - Scalar(lambda) * (M * phi);
    const double scale = (norm_k + std::abs(lambda) * norm_m) * phi.norm();
    r.residuals[j] = scale > 0.0 ? res.norm() / scale : res.norm();
  }
}

/// The whole solve after validation: method choice, dense or sparse path, normalisation,
/// residuals. K and M are already self-adjoint. `sparse` runs the sparse path (the caller may
/// pick another Krylov engine for it).
template <class Scalar, class Options, class Result, class SparsePath>
void solve_generalized(const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M,
                       const Options& options, Result& r, SparsePath&& sparse) {
  const Eigen::Index n = K.rows();
  const bool band = !std::isnan(options.band_min);
  const Eigen::Index largest_sparse = n - 2 * options.block_size;
  Method method = options.method;
  // Auto: dense for small systems, and whenever Lanczos could not return the modes asked for.
  if (method == Method::Auto)
    method = n <= options.dense_limit ||
                     (!band && options.n_modes > largest_sparse && n <= kDenseHardLimit)
                 ? Method::Dense
                 : Method::Sparse;
  check_dense_size(method, n);
  // The block Krylov basis needs room for the wanted pairs plus two blocks.
  if (method == Method::Sparse && largest_sparse < 1) method = Method::Dense;

  if (method == Method::Dense)
    solve_dense(K, M, options, band, r);
  else
    sparse(band);
  if (r.eigenvalues.size() > 0) {
    normalise(M, r.eigenvectors);
    compute_residuals(K, M, r);
    if (r.status == Status::Ok && r.max_residual() > options.residual_limit) {
      r.status = Status::NotConverged;
      r.message = fmt::format(
          "largest backward error {:.3e} exceeds residual_limit {:.1e}: the model is badly "
          "conditioned: check for stiffness or mass values many orders of magnitude apart, and "
          "for nearly unsupported parts",
          r.max_residual(), options.residual_limit);
    }
  }
}

/// Checks sizes, the common front of solve_symmetric and solve_hermitian.
template <class Scalar>
void check_pencil(const char* where, const SparseMatrix<Scalar>& K, const SparseMatrix<Scalar>& M) {
  if (K.rows() != K.cols() || M.rows() != M.cols() || K.rows() != M.rows())
    throw InputError({}, where, "square K and M of the same size",
                     fmt::format("K {}x{}, M {}x{}", K.rows(), K.cols(), M.rows(), M.cols()));
  if (K.rows() == 0) throw InputError({}, where, "at least one DOF", "an empty system");
}

}  // namespace geardyn::eig::detail
