#include "geardyn/eig/projected_quadratic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/core/error.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

using Complex = std::complex<double>;
using SparseMatrix = Eigen::SparseMatrix<double>;

std::vector<std::string> ProjectedQuadraticOptions::validate() const {
  std::vector<std::string> problems;
  if (extra_modes < 0)
    problems.push_back(fmt::format("extra_modes must be >= 0, found {}", extra_modes));
  if (max_rounds < 0)
    problems.push_back(fmt::format("max_rounds must be >= 0, found {}", max_rounds));
  if (max_basis < 0) problems.push_back(fmt::format("max_basis must be >= 0, found {}", max_basis));
  if (!(tolerance > 0.0))
    problems.push_back(fmt::format("tolerance must be > 0, found {}", tolerance));
  return problems;
}

namespace {

// Columns of the pencil residuals r_k = (lambda_k^2 M + lambda_k D + K) x_k, with one sparse
// product per matrix over the real and imaginary parts of all columns at once.
Eigen::MatrixXcd residual_vectors(const QuadraticPencil& p, const Eigen::VectorXcd& lambda,
                                  const Eigen::MatrixXd& Xri) {
  const Eigen::Index k = lambda.size();
  const Eigen::MatrixXd MX = p.M * Xri, KX = p.K * Xri;
  Eigen::MatrixXd DX = p.C * Xri;
  if (p.low_rank_coefficients.size() > 0)
    DX += p.low_rank_basis *
          (p.low_rank_coefficients.asDiagonal() * (p.low_rank_basis.transpose() * Xri));
  auto cplx = [k](const Eigen::MatrixXd& A, Eigen::Index j) {
    return Eigen::VectorXcd(A.col(j).cast<Complex>() + Complex(0.0, 1.0) * A.col(k + j));
  };
  Eigen::MatrixXcd R(Xri.rows(), k);
  for (Eigen::Index j = 0; j < k; ++j)
    R.col(j) = lambda[j] * lambda[j] * cplx(MX, j) + lambda[j] * cplx(DX, j) + cplx(KX, j);
  return R;
}

// Scales each column so that its largest entry is exactly 1 (QuadraticEigenResult's convention).
void normalise_columns(Eigen::MatrixXcd& X) {
  for (Eigen::Index k = 0; k < X.cols(); ++k) {
    Eigen::Index imax = 0;
    X.col(k).cwiseAbs().maxCoeff(&imax);
    const Complex top = X(imax, k);
    if (std::abs(top) > 0.0) X.col(k) /= top;
  }
}

SparseMatrix square_or_zero(const SparseMatrix& A, Eigen::Index n) {
  if (A.rows() == n && A.cols() == n) return A;
  SparseMatrix Z(n, n);
  return Z;
}

}  // namespace

struct ProjectedQuadratic::Impl {
  SpeedPencilParts parts;
  ProjectedQuadraticOptions options;
  bool built = false;
  Status build_status = Status::Ok;
  std::string build_message;
  linalg::SymmetricFactorization factor;  // K0_sym - sigma_b M
  Eigen::MatrixXd V;                      // M-orthonormal basis
  Eigen::MatrixXd Mr, Kr, Cr, Gr, Br;     // V^T (.) V and V^T B
  int enrichments = 0;
  Eigen::Index max_basis = 0;

  void build(int n_modes);
  int add_columns(const Eigen::MatrixXd& W);
  void project();
  QuadraticPencil reduced(double speed, const SparseMatrix& dK, const SparseMatrix& dC) const;
};

void ProjectedQuadratic::Impl::build(int n_modes) {
  built = true;
  const Eigen::Index n = parts.M.rows();
  max_basis = options.max_basis > 0
                  ? std::min<Eigen::Index>(n, options.max_basis)
                  : std::min<Eigen::Index>(n, std::max<Eigen::Index>(8 * n_modes, 80));
  const SparseMatrix K_sym = 0.5 * (parts.K0 + SparseMatrix(parts.K0.transpose()));
  SymmetricEigenOptions so;
  so.n_modes = static_cast<int>(std::min<Eigen::Index>(n, n_modes + options.extra_modes));
  const SymmetricEigenResult modes = solve_symmetric(K_sym, parts.M, so);
  if (modes.eigenvectors.cols() == 0) {
    build_status = Status::Failed;
    build_message = "the undamped modes of the basis failed: " + modes.brief_report();
    return;
  }
  const double sigma_b = automatic_shift(K_sym, parts.M);
  const SparseMatrix F = K_sym - sigma_b * parts.M;
  if (factor.compute(F) != Status::Ok) {
    build_status = Status::Singular;
    build_message = "K0 - sigma M of the basis is singular: " + factor.message();
    return;
  }
  V.resize(n, 0);
  add_columns(modes.eigenvectors);
}

// Appends the parts of W M-orthogonal to V (classical Gram-Schmidt applied twice, which is
// orthogonal to working precision: Giraud et al., Numer. Math. 101 (2005) 87-100); drops
// columns that V already spans. Returns the number added and re-projects.
int ProjectedQuadratic::Impl::add_columns(const Eigen::MatrixXd& W) {
  int added = 0;
  for (Eigen::Index j = 0; j < W.cols() && V.cols() < max_basis; ++j) {
    Eigen::VectorXd w = W.col(j);
    const double norm0 = std::sqrt(std::max(0.0, w.dot(parts.M * w)));
    if (!(norm0 > 0.0)) continue;
    for (int pass = 0; pass < 2; ++pass) w -= V * (V.transpose() * (parts.M * w));
    const double norm = std::sqrt(std::max(0.0, w.dot(parts.M * w)));
    if (!(norm > 1e-10 * norm0)) continue;
    V.conservativeResize(Eigen::NoChange, V.cols() + 1);
    V.col(V.cols() - 1) = w / norm;
    ++added;
  }
  if (added > 0) project();
  return added;
}

void ProjectedQuadratic::Impl::project() {
  Mr = V.transpose() * (parts.M * V);
  Kr = V.transpose() * (parts.K0 * V);
  Cr = V.transpose() * (parts.C0 * V);
  Gr = V.transpose() * (parts.G * V);
  // No low-rank term: B stays 0 x 0, as in a pencil without one.
  Br = parts.low_rank_coefficients.size() > 0
           ? Eigen::MatrixXd(V.transpose() * parts.low_rank_basis)
           : Eigen::MatrixXd();
}

QuadraticPencil ProjectedQuadratic::Impl::reduced(double speed, const SparseMatrix& dK,
                                                  const SparseMatrix& dC) const {
  Eigen::MatrixXd K = Kr, C = Cr + speed * Gr;
  if (dK.nonZeros() > 0) K += V.transpose() * (dK * V);
  if (dC.nonZeros() > 0) C += V.transpose() * (dC * V);
  QuadraticPencil p;
  p.M = Mr.sparseView();
  p.K = K.sparseView();
  p.C = C.sparseView();
  p.low_rank_basis = Br;
  p.low_rank_coefficients = parts.low_rank_coefficients;
  return p;
}

ProjectedQuadratic::ProjectedQuadratic(SpeedPencilParts parts,
                                       const ProjectedQuadraticOptions& options)
    : impl_(std::make_unique<Impl>()) {
  if (auto problems = options.validate(); !problems.empty()) {
    std::string found;
    for (const auto& pr : problems) found += (found.empty() ? "" : "; ") + pr;
    throw InputError({}, "eig.ProjectedQuadraticOptions", "valid options", found);
  }
  const Eigen::Index n = parts.M.rows();
  if (n == 0 || parts.M.cols() != n || parts.K0.rows() != n || parts.K0.cols() != n ||
      parts.low_rank_basis.cols() != parts.low_rank_coefficients.size() ||
      (parts.low_rank_coefficients.size() > 0 && parts.low_rank_basis.rows() != n))
    throw InputError({}, "eig.ProjectedQuadratic", "square M, K0 of one size and B (n x r)",
                     fmt::format("M {}x{}, K0 {}x{}, B {}x{}, c {}", parts.M.rows(), parts.M.cols(),
                                 parts.K0.rows(), parts.K0.cols(), parts.low_rank_basis.rows(),
                                 parts.low_rank_basis.cols(), parts.low_rank_coefficients.size()));
  parts.C0 = square_or_zero(parts.C0, n);
  parts.G = square_or_zero(parts.G, n);
  impl_->parts = std::move(parts);
  impl_->options = options;
}

ProjectedQuadratic::~ProjectedQuadratic() = default;
ProjectedQuadratic::ProjectedQuadratic(ProjectedQuadratic&&) noexcept = default;
ProjectedQuadratic& ProjectedQuadratic::operator=(ProjectedQuadratic&&) noexcept = default;

Eigen::Index ProjectedQuadratic::basis_size() const { return impl_->V.cols(); }
int ProjectedQuadratic::enrichments() const { return impl_->enrichments; }

QuadraticEigenResult ProjectedQuadratic::solve(const QuadraticPencil& full, double speed,
                                               const SparseMatrix& dK, const SparseMatrix& dC,
                                               const QuadraticEigenOptions& options) {
  Impl& s = *impl_;
  QuadraticEigenResult r;
  r.requested = options.n_modes;
  r.method_used = Method::Dense;
  if (!s.built) {
    s.build(options.n_modes);
    r.factorizations = 1;
  }
  if (s.build_status != Status::Ok) {
    r.status = s.build_status;
    r.message = s.build_message;
    return r;
  }
  QuadraticEigenOptions qo;
  qo.n_modes = options.n_modes;
  qo.method = Method::Dense;
  qo.target =
      std::isnan(options.target.real()) ? Complex(automatic_target(full), 0.0) : options.target;
  qo.dense_shift = -std::sqrt(-1e6 * automatic_shift(full.K, full.M));
  qo.residual_limit = 1.0;  // the reduced residuals are not the ones that count
  for (int round = 0;; ++round) {
    const QuadraticEigenResult red = solve_quadratic(s.reduced(speed, dK, dC), qo);
    r.iterations = round;
    r.shift_used = red.shift_used;
    r.factorization = fmt::format("projected({})", s.V.cols());
    if (red.status != Status::Ok && red.status != Status::FewerModes) {
      r.status = red.status;
      r.message = "projected solve: " + red.message;
      return r;
    }
    // x = V y as two real products (V is real), then the largest entry scaled to 1.
    const Eigen::MatrixXd Yr = red.eigenvectors.real(), Yi = red.eigenvectors.imag();
    Eigen::MatrixXcd X(s.V.rows(), Yr.cols());
    X.real() = s.V * Yr;
    X.imag() = s.V * Yi;
    normalise_columns(X);
    const Eigen::Index k_modes = X.cols();
    Eigen::MatrixXd Xri(X.rows(), 2 * k_modes);
    Xri << X.real(), X.imag();
    const Eigen::MatrixXcd R = residual_vectors(full, red.eigenvalues, Xri);
    r.eigenvalues = red.eigenvalues;
    r.residuals = backward_errors_from_residuals(full, red.eigenvalues, X, R);
    r.eigenvectors = std::move(X);
    r.converged = static_cast<int>(red.eigenvalues.size());
    const bool complete = r.converged == options.n_modes || s.V.cols() == full.size();
    if (!complete) {
      r.status = Status::FewerModes;
      r.message = fmt::format("the projection basis ({} vectors) holds {} of {} modes asked",
                              s.V.cols(), r.converged, options.n_modes);
      return r;
    }
    // Preconditioned residuals W = F^{-1} R (real and imaginary parts side by side): their
    // M-norm relative to x is the size of x's error (the accuracy test) and they are the
    // enrichment directions.
    Eigen::MatrixXd RW(R.rows(), 2 * k_modes);
    RW << R.real(), R.imag();
    const Eigen::MatrixXd W = s.factor.solve(RW);
    r.operations += static_cast<int>(RW.cols());
    const Eigen::MatrixXd MW = s.parts.M * W, MX = s.parts.M * Xri;
    std::vector<Eigen::Index> bad;
    double worst = 0.0;
    for (Eigen::Index k = 0; k < k_modes; ++k) {
      const Eigen::Index k2 = k_modes + k;
      const double wm = W.col(k).dot(MW.col(k)) + W.col(k2).dot(MW.col(k2));
      const double xm = Xri.col(k).dot(MX.col(k)) + Xri.col(k2).dot(MX.col(k2));
      const double rho = xm > 0.0 ? std::sqrt(std::max(0.0, wm) / xm) : 0.0;
      worst = std::max(worst, rho);
      if (!(rho <= s.options.tolerance) || !(r.residuals[k] <= options.residual_limit))
        bad.push_back(k);
    }
    if (bad.empty()) {
      r.status = r.converged < options.n_modes ? Status::FewerModes : Status::Ok;
      return r;
    }
    Eigen::MatrixXd enrich(W.rows(), 2 * static_cast<Eigen::Index>(bad.size()));
    for (std::size_t b = 0; b < bad.size(); ++b) {
      enrich.col(static_cast<Eigen::Index>(2 * b)) = W.col(bad[b]);
      enrich.col(static_cast<Eigen::Index>(2 * b + 1)) = W.col(k_modes + bad[b]);
    }
    const int added = round < s.options.max_rounds ? s.add_columns(enrich) : 0;
    s.enrichments += added;
    if (added == 0) {
      r.status = Status::NotConverged;
      r.message = fmt::format(
          "projection: {} of {} modes not converged after {} enrichment rounds (basis {} "
          "vectors, limit {}): largest relative correction {:.2e} (tolerance {:.1e}), largest "
          "backward error {:.2e} (limit {:.1e})",
          bad.size(), r.converged, round, s.V.cols(), s.max_basis, worst, s.options.tolerance,
          r.max_residual(), options.residual_limit);
      return r;
    }
  }
}

}  // namespace geardyn::eig
