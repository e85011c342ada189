// GCC 12 reports -Wuse-after-free inside Eigen's aligned_free when it inlines Spectra's
// UpperHessenbergEigen::doComputeEigenvectors (a known false positive of the realloc path). GCC
// attributes the warning to Eigen's lines, so the pragma must precede the first Eigen include.
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuse-after-free"
#endif
#include <Spectra/GenEigsSolver.h>

#include <Eigen/Dense>
#if defined(__GNUC__) && !defined(__clang__) && __GNUC__ >= 12
#pragma GCC diagnostic pop
#endif

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <type_traits>

#include "geardyn/core/error.hpp"
#include "geardyn/eig/conditioning.hpp"
#include "geardyn/eig/massless_condensation.hpp"
#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::eig {

using Complex = std::complex<double>;
using SparseMatrix = Eigen::SparseMatrix<double>;

Eigen::VectorXcd QuadraticPencil::apply_damping(const Eigen::VectorXcd& x) const {
  Eigen::VectorXcd y = linalg::multiply(C, x);
  if (low_rank_coefficients.size() > 0) {
    const Eigen::VectorXcd t = low_rank_basis.transpose().cast<Complex>() * x;
    y += low_rank_basis.cast<Complex>() *
         (low_rank_coefficients.cast<Complex>().array() * t.array()).matrix();
  }
  return y;
}

Eigen::MatrixXd QuadraticPencil::damping_dense() const {
  Eigen::MatrixXd D(C);
  if (low_rank_coefficients.size() > 0)
    D += low_rank_basis * low_rank_coefficients.asDiagonal() * low_rank_basis.transpose();
  return D;
}

std::vector<std::string> QuadraticEigenOptions::validate() const {
  std::vector<std::string> problems;
  if (n_modes < 1) problems.push_back(fmt::format("n_modes must be >= 1, found {}", n_modes));
  if (!std::isnan(target.real()) &&
      (!std::isfinite(target.real()) || !std::isfinite(target.imag())))
    problems.push_back("target must be finite (or NaN for automatic)");
  if (!std::isnan(dense_shift) && !std::isfinite(dense_shift))
    problems.push_back("dense_shift must be finite (or NaN for automatic)");
  if (dense_limit < 0)
    problems.push_back(fmt::format("dense_limit must be >= 0, found {}", dense_limit));
  if (!(residual_limit > 0.0))
    problems.push_back(fmt::format("residual_limit must be > 0, found {}", residual_limit));
  krylov.validate(problems);
  return problems;
}

double QuadraticEigenResult::max_residual() const {
  return residuals.size() > 0 ? residuals.maxCoeff() : 0.0;
}

std::string QuadraticEigenResult::brief_report() const {
  return fmt::format(
      "quadratic eigen: {} ({}), {}/{} modes, sigma=({:.4g}, {:.4g}), max residual {:.2e}, "
      "{} restarts, {} solves, status {}{}{}",
      to_string(method_used), factorization, converged, requested, shift_used.real(),
      shift_used.imag(), max_residual(), iterations, operations, to_string(status),
      message.empty() ? "" : ": ", message);
}

Eigen::VectorXd start_vector(const QuadraticEigenResult& modes) {
  const Eigen::Index n = modes.eigenvectors.rows();
  if (modes.eigenvalues.size() == 0 || n == 0) return {};
  Eigen::VectorXd v = Eigen::VectorXd::Zero(2 * n);
  for (Eigen::Index k = 0; k < modes.eigenvalues.size(); ++k) {
    Eigen::VectorXcd z(2 * n);
    z.head(n) = modes.eigenvectors.col(k);
    z.tail(n) = modes.eigenvalues[k] * modes.eigenvectors.col(k);
    const double norm = z.norm();
    if (norm == 0.0) continue;
    z /= norm;
    v += z.real() + z.imag();
  }
  return v;
}

namespace {

// What to look at when the modes are not accurate: the model's scaling if it is off, else the
// general advice (in terms of the model, not of solver settings a model file cannot reach).
std::string conditioning_advice(const SparseMatrix& K, const SparseMatrix& M) {
  const std::string scaling = scaling_diagnosis(K, M);
  return scaling.empty() ? "the model is badly conditioned: check for stiffness or mass values "
                           "many orders of magnitude apart, and for nearly unsupported parts"
                         : scaling;
}

// Scale of the problem: min_i K_ii / M_ii bounds omega_1^2 from above (see automatic_shift).
double lowest_ratio(const SparseMatrix& K, const SparseMatrix& M) {
  return -automatic_shift(K, M) * 1e6;
}

struct Norms {
  double M = 0, D = 0, K = 0;
};

// Velocity scale of the state vector, z = [x; lambda x / s] with s = sqrt(||K|| / ||M||)
// (the eigenvalue scaling of Fan, Lin & Van Dooren, SIAM J. Matrix Anal. Appl. 26 (2004)
// 252-256). Without it the two blocks of T = (A - sigma B)^{-1} B differ in size by about |lambda|,
// and Eigen's unbalanced Hessenberg QR (and the Arnoldi Ritz values) lose that many digits.
double velocity_scale(const Norms& norms) {
  const double s = std::sqrt(norms.K / norms.M);
  return std::isfinite(s) && s > 0.0 ? s : 1.0;
}

Norms pencil_norms(const QuadraticPencil& p) {
  Norms n;
  n.M = linalg::norm1(p.M);
  n.K = linalg::norm1(p.K);
  n.D = linalg::norm1(p.C);
  if (p.low_rank_coefficients.size() > 0) {
    // Upper bound of ||B diag(c) B^T||_1: max row of |B| diag(|c|) |B|^T 1.
    const Eigen::MatrixXd absB = p.low_rank_basis.cwiseAbs();
    const Eigen::VectorXd colsum = absB.transpose() * Eigen::VectorXd::Ones(absB.rows());
    const Eigen::VectorXd bound =
        absB * (p.low_rank_coefficients.cwiseAbs().array() * colsum.array()).matrix();
    n.D += bound.size() > 0 ? bound.maxCoeff() : 0.0;
  }
  return n;
}

double backward_error(const QuadraticPencil& p, const Norms& norms, Complex lambda,
                      const Eigen::VectorXcd& x) {
  const Eigen::VectorXcd r = lambda * lambda * linalg::multiply(p.M, x) +
                             lambda * p.apply_damping(x) + linalg::multiply(p.K, x);
  const double a = std::abs(lambda);
  const double scale = (a * a * norms.M + a * norms.D + norms.K) * x.norm();
  return scale > 0.0 ? r.norm() / scale : r.norm();
}

// One Ritz pair of the shift-inverted operator before it becomes a mode.
struct RitzPair {
  Complex value;       // nu (or theta for the complex target)
  Eigen::VectorXcd z;  // state vector
};

struct Mode {
  Complex lambda;
  Eigen::VectorXcd x;
  double residual = 0;
  double distance = 0;  // |lambda - target| in the upper half plane
};

// Keeps one member of each conjugate pair of Ritz values (one-to-one matching, so double
// eigenvalues such as the two whirl directions of an isotropic rotor at rest both survive).
std::vector<RitzPair> one_of_each_pair(std::vector<RitzPair> pairs) {
  std::vector<bool> used(pairs.size(), false), drop(pairs.size(), false);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    if (pairs[i].value.imag() >= 0.0) continue;
    const Complex partner = std::conj(pairs[i].value);
    for (std::size_t j = 0; j < pairs.size(); ++j) {
      if (j == i || used[j] || pairs[j].value.imag() <= 0.0) continue;
      if (std::abs(pairs[j].value - partner) <= 1e-8 * std::abs(partner)) {
        used[j] = true;
        drop[i] = true;
        break;
      }
    }
  }
  std::vector<RitzPair> kept;
  for (std::size_t i = 0; i < pairs.size(); ++i)
    if (!drop[i]) kept.push_back(std::move(pairs[i]));
  return kept;
}

// The member of a conjugate pair with Im lambda >= 0; real roots from real arithmetic may carry
// rounding-level imaginary parts, which are dropped.
Complex upper_root(Complex lambda) {
  Complex l = lambda.imag() < 0.0 ? std::conj(lambda) : lambda;
  if (std::abs(l.imag()) <= 1e-12 * std::abs(l)) l.imag(0.0);
  return l;
}

// Turns a state eigenvector and eigenvalue into a mode: x from the first block, or from the
// second block / lambda, whichever satisfies the quadratic equation better (for large |lambda|
// the second block carries more significant digits).
Mode make_mode(const QuadraticPencil& p, const Norms& norms, Complex lambda,
               const Eigen::VectorXcd& z) {
  const Eigen::Index n = p.size();
  const bool flip = lambda.imag() < 0.0;  // keep the member of the pair with Im lambda > 0
  auto orient = [flip](const Eigen::VectorXcd& v) -> Eigen::VectorXcd {
    return flip ? Eigen::VectorXcd(v.conjugate()) : v;
  };
  Mode m;
  m.lambda = upper_root(lambda);
  m.x = orient(z.head(n));
  // A zero block (the state eigenvector of a defective zero root can have one) is no mode shape,
  // whatever its residual.
  const double inf = std::numeric_limits<double>::infinity();
  m.residual = m.x.norm() > 0.0 ? backward_error(p, norms, m.lambda, m.x) : inf;
  if (std::abs(lambda) > 0.0) {
    const Eigen::VectorXcd alt = orient(z.tail(n) / lambda);
    const double r_alt = alt.norm() > 0.0 ? backward_error(p, norms, m.lambda, alt) : inf;
    if (r_alt < m.residual) {
      m.x = alt;
      m.residual = r_alt;
    }
  }
  Eigen::Index imax = 0;
  m.x.cwiseAbs().maxCoeff(&imax);
  if (std::abs(m.x[imax]) > 0.0) m.x /= m.x[imax];
  return m;
}

void finish(std::vector<Mode> modes, const QuadraticEigenOptions& options,
            QuadraticEigenResult& r) {
  std::stable_sort(modes.begin(), modes.end(),
                   [](const Mode& a, const Mode& b) { return a.distance < b.distance; });
  if (modes.size() > static_cast<std::size_t>(options.n_modes))
    modes.resize(static_cast<std::size_t>(options.n_modes));
  std::stable_sort(modes.begin(), modes.end(), [](const Mode& a, const Mode& b) {
    const double fa = std::abs(a.lambda), fb = std::abs(b.lambda);
    if (fa != fb) return fa < fb;
    return a.lambda.imag() < b.lambda.imag();
  });
  const Eigen::Index m = static_cast<Eigen::Index>(modes.size());
  const Eigen::Index n = modes.empty() ? 0 : modes.front().x.size();
  r.eigenvalues.resize(m);
  r.eigenvectors.resize(n, m);
  r.residuals.resize(m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const auto& mode = modes[static_cast<std::size_t>(k)];
    r.eigenvalues[k] = mode.lambda;
    r.eigenvectors.col(k) = mode.x;
    r.residuals[k] = mode.residual;
  }
  r.requested = options.n_modes;
  r.converged = static_cast<int>(m);
}

Complex upper(Complex z) { return {z.real(), std::abs(z.imag())}; }

// ---------------------------------------------------------------------------------------------
// Dense

void solve_dense(const QuadraticPencil& p, const QuadraticEigenOptions& options, Complex target,
                 QuadraticEigenResult& r) {
  const Eigen::Index n = p.size();
  r.method_used = Method::Dense;
  r.factorization = "dense_lu";
  r.factorizations = 1;
  // A real shift of the order of the lowest natural frequency keeps T = (A - sigma B)^{-1} B
  // well scaled; all eigenvalues are computed, so the target only selects afterwards.
  const double sigma =
      std::isnan(options.dense_shift) ? -std::sqrt(lowest_ratio(p.K, p.M)) : options.dense_shift;
  r.shift_used = sigma;
  const Eigen::MatrixXd Md(p.M), Kd(p.K), Dd = p.damping_dense();
  const Eigen::MatrixXd P = Kd + sigma * Dd + sigma * sigma * Md;
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(P);
  if (!(lu.rcond() > 1e-15)) {
    r.status = Status::Singular;
    const std::string scaling = scaling_diagnosis(p.K, p.M);
    r.message = fmt::format(
        "K + sigma D + sigma^2 M is singular at sigma = {:.6g} (rcond {:.2e}): {}", sigma,
        lu.rcond(),
        scaling.empty()
            ? "the model has a mechanism without mass, damping or stiffness; check supports"
            : scaling);
    return;
  }
  const Norms norms = pencil_norms(p);
  const double s = velocity_scale(norms);
  const Eigen::MatrixXd X = lu.solve(Dd + sigma * Md);
  const Eigen::MatrixXd Y = lu.solve(Md);
  // S^{-1} T S with S = diag(I, s I): the operator on scaled states [x; lambda x / s].
  Eigen::MatrixXd T(2 * n, 2 * n);
  T.topLeftCorner(n, n) = -X;
  T.topRightCorner(n, n) = -s * Y;
  T.bottomLeftCorner(n, n) = (Eigen::MatrixXd::Identity(n, n) - sigma * X) / s;
  T.bottomRightCorner(n, n) = -sigma * Y;
  const Eigen::EigenSolver<Eigen::MatrixXd> es(T, true);
  if (es.info() != Eigen::Success) {
    r.status = Status::Failed;
    const std::string scaling = scaling_diagnosis(p.K, p.M);
    r.message = "dense eigen-solver (Hessenberg QR) did not converge" +
                (scaling.empty() ? std::string() : ": " + scaling);
    return;
  }
  const Eigen::VectorXcd nu = es.eigenvalues();
  Eigen::MatrixXcd Z = es.eigenvectors();
  Z.bottomRows(n) *= s;
  const double nu_max = nu.cwiseAbs().maxCoeff();
  std::vector<RitzPair> pairs;
  for (Eigen::Index i = 0; i < nu.size(); ++i)
    if (std::abs(nu[i]) > 1e-13 * nu_max) pairs.push_back({nu[i], Z.col(i)});  // else infinite
  pairs = one_of_each_pair(std::move(pairs));
  const std::size_t finite = pairs.size();
  // Only the n_modes nearest the target become modes (make_mode costs two residuals each):
  // the same choice finish() makes, on the same distances, in the same stable order.
  std::vector<double> distance(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
    distance[i] = std::abs(upper_root(sigma + 1.0 / pairs[i].value) - upper(target));
  std::vector<std::size_t> order(pairs.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
  order.resize(std::min(order.size(), static_cast<std::size_t>(options.n_modes)));
  std::sort(order.begin(), order.end());  // the solver's order, as finish() expects
  std::vector<Mode> modes;
  for (std::size_t i : order) {
    Mode m = make_mode(p, norms, sigma + 1.0 / pairs[i].value, pairs[i].z);
    m.distance = distance[i];
    modes.push_back(std::move(m));
  }
  finish(std::move(modes), options, r);
  r.status = Status::Ok;
  if (r.converged < r.requested) {
    r.status = Status::FewerModes;
    r.message =
        fmt::format("the system has only {} finite modes, {} were asked for", finite, r.requested);
  }
}

// ---------------------------------------------------------------------------------------------
// Sparse

// Solves P(sigma) y = r with P = P0 + U V^T, P0 sparse (LU), U = sigma B diag(c), V = B
// (Sherman-Morrison-Woodbury; Golub & Van Loan, Matrix Computations, 4th ed., 2.1.4).
template <class S>
class PencilSolver {
 public:
  using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;
  using Matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;

  Status factor(const QuadraticPencil& p, S sigma, std::string& message) {
    using SM = Eigen::SparseMatrix<S>;
    const SM P = p.K.cast<S>() + sigma * p.C.cast<S>() + (sigma * sigma) * p.M.cast<S>();
    const Status s = lu_.compute(P);
    if (s != Status::Ok) {
      message = lu_.message();
      return s;
    }
    if (p.low_rank_coefficients.size() > 0) {
      V_ = p.low_rank_basis.cast<S>();
      const Matrix U = sigma * V_ * p.low_rank_coefficients.cast<S>().asDiagonal();
      W_ = lu_.solve(U);
      const Matrix cap = Matrix::Identity(V_.cols(), V_.cols()) + V_.transpose() * W_;
      capacitance_.compute(cap);
      if (!(capacitance_.rcond() > 1e-14)) {
        message = "the Woodbury capacitance matrix of the modal damping term is singular";
        return Status::Singular;
      }
    }
    return Status::Ok;
  }

  Vector solve(const Vector& r) const {
    Vector z = lu_.solve(r);
    if (V_.cols() > 0) z -= W_ * capacitance_.solve(V_.transpose() * z);
    return z;
  }

 private:
  linalg::SparseLU<S> lu_;
  Matrix V_, W_;
  Eigen::PartialPivLU<Matrix> capacitance_;
};

// Spectra operator on state vectors (length 2n):
//   y = Re[(A - sigma B)^{-1} B x]  (for real sigma the real part is the whole result).
template <class S>
class StateShiftInvert {
 public:
  using Scalar = double;
  using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;

  /// `scale` s: the operator acts on scaled states [x; lambda x / s] (see velocity_scale).
  StateShiftInvert(const QuadraticPencil& p, const PencilSolver<S>& solver, S sigma, double scale)
      : p_(p), solver_(solver), sigma_(sigma), scale_(scale), n_(p.size()) {}
  Eigen::Index rows() const { return 2 * n_; }
  Eigen::Index cols() const { return 2 * n_; }

  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x1(x_in, n_), x2_scaled(x_in + n_, n_);
    const Eigen::VectorXd x2 = scale_ * x2_scaled;
    const Eigen::VectorXd Mx1 = p_.M * x1;
    Eigen::VectorXd Dx1 = p_.C * x1;
    if (p_.low_rank_coefficients.size() > 0)
      Dx1 += p_.low_rank_basis *
             (p_.low_rank_coefficients.array() * (p_.low_rank_basis.transpose() * x1).array())
                 .matrix();
    const Vector rhs = -((p_.M * x2).template cast<S>() + Dx1.template cast<S>() +
                         sigma_ * Mx1.template cast<S>());
    const Vector y1 = solver_.solve(rhs);
    const Vector y2 = x1.template cast<S>() + sigma_ * y1;
    Eigen::Map<Eigen::VectorXd> out1(y_out, n_), out2(y_out + n_, n_);
    out1 = y1.real();
    out2 = y2.real() / scale_;
    ++count_;
  }
  int count() const { return count_; }

 private:
  const QuadraticPencil& p_;
  const PencilSolver<S>& solver_;
  S sigma_;
  double scale_;
  Eigen::Index n_;
  mutable int count_ = 0;
};

template <class S>
void solve_sparse_with(const QuadraticPencil& p, const QuadraticEigenOptions& options,
                       Complex target, S sigma, QuadraticEigenResult& r) {
  const Eigen::Index n = p.size(), N = 2 * n;
  r.method_used = Method::Sparse;
  r.shift_used = Complex(sigma);
  r.factorization = std::is_same_v<S, double> ? "umfpack_lu" : "umfpack_lu_complex";
  r.factorizations = 1;
  PencilSolver<S> solver;
  std::string why;
  const Status fs = solver.factor(p, sigma, why);
  if (fs != Status::Ok) {
    r.status = fs;
    r.message = fmt::format(
        "K + sigma D + sigma^2 M is singular at sigma = ({:.6g}, {:.6g}) ({}); sigma is an "
        "eigenvalue or the model has an unsupported mechanism: move the target or check supports",
        Complex(sigma).real(), Complex(sigma).imag(), why);
    return;
  }
  const Norms norms = pencil_norms(p);
  const double s = velocity_scale(norms);
  StateShiftInvert<S> op(p, solver, sigma, s);
  const Eigen::Index nev = std::min<Eigen::Index>(2 * options.n_modes + 1, N - 2);
  const Eigen::Index ncv =
      options.krylov.subspace_size > 0
          ? std::min<Eigen::Index>(N, std::max<Eigen::Index>(options.krylov.subspace_size, nev + 2))
          : std::min<Eigen::Index>(N, std::max<Eigen::Index>(2 * nev + 1, nev + 20));
  Spectra::GenEigsSolver<StateShiftInvert<S>> arnoldi(op, nev, ncv);
  if (options.start.size() == N && options.start.norm() > 0.0) {
    Eigen::VectorXd start = options.start;
    start.tail(n) /= s;
    arnoldi.init(start.data());
  } else
    arnoldi.init();
  arnoldi.compute(Spectra::SortRule::LargestMagn, options.krylov.max_restarts,
                  options.krylov.tolerance, Spectra::SortRule::LargestMagn);
  r.iterations = static_cast<int>(arnoldi.num_iterations());
  r.operations = op.count();
  const Eigen::VectorXcd nu = arnoldi.eigenvalues();
  Eigen::MatrixXcd Z = arnoldi.eigenvectors();
  Z.bottomRows(n) *= s;
  const int ritz_converged = static_cast<int>(nu.size());

  const double nu_max = nu.size() > 0 ? nu.cwiseAbs().maxCoeff() : 0.0;
  std::vector<RitzPair> pairs;
  for (Eigen::Index i = 0; i < nu.size(); ++i)
    if (std::abs(nu[i]) > 1e-13 * nu_max) pairs.push_back({nu[i], Z.col(i)});
  pairs = one_of_each_pair(std::move(pairs));
  std::vector<Mode> modes;
  for (const auto& pr : pairs) {
    Complex lambda;
    if constexpr (std::is_same_v<S, double>) {
      lambda = sigma + 1.0 / pr.value;
    } else {
      // Parlett-Saad: the real operator's eigenvalue does not determine lambda uniquely; the
      // state eigenvector does, through z2 = lambda z1.
      Complex numerator(0.0, 0.0);
      double denominator = 0.0;
      for (Eigen::Index i = 0; i < n; ++i) {
        numerator += std::conj(pr.z[i]) * pr.z[n + i];
        denominator += std::norm(pr.z[i]);
      }
      lambda = numerator / denominator;
    }
    Mode m = make_mode(p, norms, lambda, pr.z);
    m.distance = std::abs(m.lambda - upper(target));
    modes.push_back(std::move(m));
  }
  finish(std::move(modes), options, r);
  r.status = Status::Ok;
  if (r.converged < r.requested) {
    r.status = Status::FewerModes;
    r.message = fmt::format(
        "shift-invert Arnoldi converged {} of {} Ritz values ({} modes of {} asked) in {} "
        "restarts; increase krylov.max_restarts or krylov.subspace_size{}",
        ritz_converged, nev, r.converged, r.requested, options.krylov.max_restarts,
        nev >= N - 2 ? ", or use the dense method (the system is too small for Arnoldi)" : "");
  }
}

[[noreturn]] void throw_options(const std::vector<std::string>& problems) {
  std::string found;
  for (const auto& pr : problems) found += (found.empty() ? "" : "; ") + pr;
  throw InputError({}, "eig.QuadraticEigenOptions", "valid eigen-solver options", found);
}

}  // namespace

namespace {

void check_sizes(const QuadraticPencil& p) {
  const Eigen::Index n = p.size();
  auto square = [n](const SparseMatrix& A) { return A.rows() == n && A.cols() == n; };
  if (n == 0 || !square(p.M) || !square(p.C) || !square(p.K) ||
      p.low_rank_basis.cols() != p.low_rank_coefficients.size() ||
      (p.low_rank_coefficients.size() > 0 && p.low_rank_basis.rows() != n))
    throw InputError(
        {}, "eig.solve_quadratic",
        "non-empty square M, C, K of one size and B (n x m) with m coefficients",
        fmt::format("M {}x{}, C {}x{}, K {}x{}, B {}x{}, c {}", p.M.rows(), p.M.cols(), p.C.rows(),
                    p.C.cols(), p.K.rows(), p.K.cols(), p.low_rank_basis.rows(),
                    p.low_rank_basis.cols(), p.low_rank_coefficients.size()));
}

// The solve on a pencil whose every DOF has mass or damping.
QuadraticEigenResult solve_pencil(const QuadraticPencil& p, const QuadraticEigenOptions& options) {
  const Eigen::Index n = p.size();
  QuadraticEigenResult r;
  Method method = options.method;
  // Auto: dense for small systems, and whenever Arnoldi could not return the modes asked for
  // (it needs 2 n_modes + 1 Ritz values of the 2n state operator, at most 2n - 2).
  if (method == Method::Auto)
    method = n <= options.dense_limit || (2 * options.n_modes + 3 > 2 * n && n <= kDenseHardLimit)
                 ? Method::Dense
                 : Method::Sparse;
  check_dense_size(method, n);
  if (method == Method::Sparse && n < 3) method = Method::Dense;  // Arnoldi needs 2n > 4

  const Complex target =
      std::isnan(options.target.real()) ? Complex(automatic_target(p), 0.0) : options.target;
  if (method == Method::Dense) {
    solve_dense(p, options, target, r);
  } else if (target.imag() == 0.0) {
    solve_sparse_with<double>(p, options, target, target.real(), r);
  } else {
    solve_sparse_with<Complex>(p, options, target, upper(target), r);
  }
  if (r.status == Status::Ok && r.max_residual() > options.residual_limit) {
    r.status = Status::NotConverged;
    r.message =
        fmt::format("largest backward error {:.3e} exceeds residual_limit {:.1e}: {}",
                    r.max_residual(), options.residual_limit, conditioning_advice(p.K, p.M));
  }
  return r;
}

}  // namespace

double automatic_target(const QuadraticPencil& pencil) {
  return -1e-3 * std::sqrt(lowest_ratio(pencil.K, pencil.M));
}

Eigen::VectorXd backward_errors(const QuadraticPencil& pencil, const Eigen::VectorXcd& eigenvalues,
                                const Eigen::MatrixXcd& vectors) {
  const Norms norms = pencil_norms(pencil);
  Eigen::VectorXd eta(eigenvalues.size());
  for (Eigen::Index k = 0; k < eigenvalues.size(); ++k)
    eta[k] = backward_error(pencil, norms, eigenvalues[k], vectors.col(k));
  return eta;
}

Eigen::VectorXd backward_errors_from_residuals(const QuadraticPencil& pencil,
                                               const Eigen::VectorXcd& eigenvalues,
                                               const Eigen::MatrixXcd& vectors,
                                               const Eigen::MatrixXcd& residuals) {
  const Norms norms = pencil_norms(pencil);
  Eigen::VectorXd eta(eigenvalues.size());
  for (Eigen::Index k = 0; k < eigenvalues.size(); ++k) {
    const double a = std::abs(eigenvalues[k]), r = residuals.col(k).norm();
    const double scale = (a * a * norms.M + a * norms.D + norms.K) * vectors.col(k).norm();
    eta[k] = scale > 0.0 ? r / scale : r;
  }
  return eta;
}

QuadraticEigenResult solve_quadratic(const QuadraticPencil& p,
                                     const QuadraticEigenOptions& options) {
  if (auto problems = options.validate(); !problems.empty()) throw_options(problems);
  check_sizes(p);
  const MasslessCondensation condensation(p);
  if (!condensation.active()) return solve_pencil(p, options);
  QuadraticEigenResult r;
  if (!condensation.ok()) {
    r.status = Status::Singular;
    r.message = condensation.message();
    return r;
  }
  // DOFs without mass or damping are condensed out exactly (massless_condensation.hpp); the
  // start vector, if any, belongs to the full state space and is not used.
  QuadraticEigenOptions reduced_options = options;
  reduced_options.start = Eigen::VectorXd();
  r = solve_pencil(condensation.reduced(), reduced_options);
  if (r.eigenvectors.cols() == 0) return r;
  r.eigenvectors = condensation.expand(r.eigenvectors);
  const Norms norms = pencil_norms(p);
  for (Eigen::Index k = 0; k < r.eigenvectors.cols(); ++k) {
    Eigen::Index imax = 0;
    r.eigenvectors.col(k).cwiseAbs().maxCoeff(&imax);
    const Complex top = r.eigenvectors(imax, k);
    if (std::abs(top) > 0.0) r.eigenvectors.col(k) /= top;
    r.residuals[k] = backward_error(p, norms, r.eigenvalues[k], r.eigenvectors.col(k));
  }
  if (r.status == Status::Ok && r.max_residual() > options.residual_limit) {
    r.status = Status::NotConverged;
    r.message =
        fmt::format("largest backward error {:.3e} exceeds residual_limit {:.1e}: {}",
                    r.max_residual(), options.residual_limit, conditioning_advice(p.K, p.M));
  }
  return r;
}

}  // namespace geardyn::eig
