#include "geardyn/eig/projected_quadratic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geardyn/core/error.hpp"
#include "geardyn/eig/rigid_body.hpp"
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

// Row-major blocks: a sparse matrix times a row-major block is one pass over the sparse matrix
// for all columns (Eigen streams it once per column of a column-major block).
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Columns of the pencil residuals r_k = (lambda_k^2 M + lambda_k D + K) x_k, with one sparse
// product per matrix over the real and imaginary parts of all columns at once.
Eigen::MatrixXcd residual_vectors(const QuadraticPencil& p, const Eigen::VectorXcd& lambda,
                                  const RowMatrix& Xri) {
  const Eigen::Index k = lambda.size();
  const RowMatrix MX = p.M * Xri, KX = p.K * Xri;
  RowMatrix DX = p.C * Xri;
  if (p.low_rank_coefficients.size() > 0)
    DX += p.low_rank_basis *
          (p.low_rank_coefficients.asDiagonal() * (p.low_rank_basis.transpose() * Xri));
  // One pass over the rows (each a contiguous row of the row-major products), no temporaries.
  const Eigen::VectorXcd lambda2 = lambda.array().square().matrix();
  Eigen::MatrixXcd R(Xri.rows(), k);
  for (Eigen::Index i = 0; i < Xri.rows(); ++i)
    for (Eigen::Index j = 0; j < k; ++j)
      R(i, j) = lambda2[j] * Complex(MX(i, j), MX(i, k + j)) +
                lambda[j] * Complex(DX(i, j), DX(i, k + j)) + Complex(KX(i, j), KX(i, k + j));
  return R;
}

// Scales each column so that its largest entry is exactly 1 (QuadraticEigenResult's convention).
void normalise_columns(Eigen::MatrixXcd& X) {
  for (Eigen::Index k = 0; k < X.cols(); ++k) {
    Eigen::Index imax = 0;
    X.col(k).cwiseAbs2().maxCoeff(&imax);  // squared moduli: no hypot per entry
    const Complex top = X(imax, k);
    if (std::abs(top) > 0.0) X.col(k) /= top;
  }
}

SparseMatrix square_or_zero(const SparseMatrix& A, Eigen::Index n) {
  if (A.rows() == n && A.cols() == n) return A;
  SparseMatrix Z(n, n);
  return Z;
}

// The projected pencil at one speed, dense (m x m); D holds C + B diag(c) B^T.
struct ReducedPencil {
  Eigen::MatrixXd M, D, K;
};

// The wanted modes of the projected pencil: eigenvalues (Im >= 0, ascending |lambda|, the order
// of QuadraticEigenResult) and their vectors y.
struct ReducedModes {
  Status status = Status::Ok;
  std::string message;
  Complex shift = 0.0;
  Eigen::VectorXcd lambda;
  Eigen::MatrixXcd Y;
  /// Per column: -1 an elastic mode (x = V y), k >= 0 the deflated rigid-body motion R_k
  /// (lambda = 0, x = R_k; its column of Y is unused).
  std::vector<Eigen::Index> rigid;
};

double dense_norm1(const Eigen::MatrixXd& A) {
  return A.size() > 0 ? A.cwiseAbs().colwise().sum().maxCoeff() : 0.0;
}

Complex upper(Complex z) { return {z.real(), std::abs(z.imag())}; }

// The member of a conjugate pair with Im lambda >= 0, rounding-level imaginary parts dropped.
Complex upper_root(Complex lambda) {
  Complex l = lambda.imag() < 0.0 ? std::conj(lambda) : lambda;
  if (std::abs(l.imag()) <= 1e-12 * std::abs(l)) l.imag(0.0);
  return l;
}

// Indices of nu keeping one member of each conjugate pair (one-to-one, so that double
// eigenvalues both survive): the selection solve_quadratic's dense path makes.
std::vector<Eigen::Index> one_of_each_pair(const Eigen::VectorXcd& nu) {
  const auto n = static_cast<std::size_t>(nu.size());
  std::vector<bool> used(n, false), drop(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    if (nu[ii].imag() >= 0.0) continue;
    const Complex partner = std::conj(nu[ii]);
    for (std::size_t j = 0; j < n; ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      if (j == i || used[j] || nu[jj].imag() <= 0.0) continue;
      if (std::abs(nu[jj] - partner) <= 1e-8 * std::abs(partner)) {
        used[j] = drop[i] = true;
        break;
      }
    }
  }
  std::vector<Eigen::Index> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (!drop[i]) kept.push_back(static_cast<Eigen::Index>(i));
  return kept;
}

// Two steps of inverse iteration (J. H. Wilkinson, The Algebraic Eigenvalue Problem, 1965,
// ch. 9) from a fixed start with no structure of the modes: `solve(v)` overwrites v with
// (A - shift I)^{-1} v. The shift is an eigenvalue exact to rounding, so two steps give its
// vector to working precision when it is simple. False when the residual 1 / growth of the unit
// result is not at rounding level relative to `scale` (a defective or multiple root).
template <class Vector, class Solve>
bool inverse_iteration(Vector& v, double scale, const Solve& solve) {
  for (Eigen::Index k = 0; k < v.size(); ++k)
    v[k] = 1.0 + 0.5 * std::sin(1.0 + static_cast<double>(k));
  v.normalize();
  double growth = 0.0;
  for (int step = 0; step < 2; ++step) {
    solve(v);
    growth = v.norm();
    if (!(growth > 0.0) || !std::isfinite(growth)) return false;
    v /= growth;
  }
  // (A - shift I) v = v_previous / growth: the residual of the unit vector v is 1 / growth.
  return 1.0 / growth <= 1e-11 * scale;
}

// The shift-inverted state operator T = (A - sigma B)^{-1} B of the projected pencil on scaled
// states [y; lambda y / s] (the operator of solve_quadratic's dense path, so the eigenvalues are
// the same), kept in Hessenberg form T = Q H Q^T: its eigenvalues nu come from the QR iteration
// on H without Schur vectors (about a third of the cost with them), and each wanted vector from
// inverse iteration on H - nu I, O(m^2) per mode (LAPACK's xHSEIN does the same: E. Anderson et
// al., LAPACK Users' Guide, SIAM 1999, sec. 2.4.8), instead of an O(m^3) LU per mode.
struct StateOperator {
  double sigma = 0.0;
  Eigen::Index m = 0;
  Eigen::MatrixXd H;                                   // upper Hessenberg
  Eigen::HessenbergDecomposition<Eigen::MatrixXd> hd;  // its Q
};

// Eigenvalues of a real quasi-triangular Schur form: 1 x 1 blocks real, each 2 x 2 block a
// complex pair (a + d) / 2 +- i sqrt(-((a - d)^2 / 4 + b c)), computed scaled against overflow.
Eigen::VectorXcd schur_eigenvalues(const Eigen::MatrixXd& S) {
  const Eigen::Index n = S.rows();
  Eigen::VectorXcd nu(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i + 1 == n || S(i + 1, i) == 0.0) {
      nu[i] = S(i, i);
      continue;
    }
    const double half = 0.5 * (S(i, i) - S(i + 1, i + 1));
    const double big = std::max({std::abs(half), std::abs(S(i + 1, i)), std::abs(S(i, i + 1))});
    const double h = half / big, b = S(i, i + 1) / big, c = S(i + 1, i) / big;
    const double im = big * std::sqrt(std::abs(h * h + b * c));
    nu[i] = Complex(S(i + 1, i + 1) + half, im);
    nu[i + 1] = Complex(S(i + 1, i + 1) + half, -im);
    ++i;
  }
  return nu;
}

// Eigenvalues lambda = sigma + 1/nu of the projected pencil, the finite ones, one per conjugate
// pair, as upper roots; `op` keeps the Hessenberg form for the vectors.
std::vector<Complex> reduced_eigenvalues(const ReducedPencil& p, double sigma, StateOperator& op,
                                         ReducedModes& out) {
  const Eigen::Index m = p.M.rows();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(p.K + sigma * p.D + sigma * sigma * p.M);
  if (!(lu.rcond() > 1e-15)) {
    out.status = Status::Singular;
    out.message =
        fmt::format("projected K + sigma D + sigma^2 M is singular at sigma = {:.6g}", sigma);
    return {};
  }
  const double nk = dense_norm1(p.K), nm = dense_norm1(p.M);
  const double s0 = std::sqrt(nk / nm), s = std::isfinite(s0) && s0 > 0.0 ? s0 : 1.0;
  const Eigen::MatrixXd X = lu.solve(p.D + sigma * p.M), Y = lu.solve(p.M);
  Eigen::MatrixXd T(2 * m, 2 * m);
  T.topLeftCorner(m, m) = -X;
  T.topRightCorner(m, m) = -s * Y;
  T.bottomLeftCorner(m, m) = (Eigen::MatrixXd::Identity(m, m) - sigma * X) / s;
  T.bottomRightCorner(m, m) = -sigma * Y;
  op.sigma = sigma;
  op.m = m;
  op.hd.compute(T);
  op.H = op.hd.matrixH();
  Eigen::RealSchur<Eigen::MatrixXd> schur(2 * m);
  schur.computeFromHessenberg(op.H, Eigen::MatrixXd(), false);
  if (schur.info() != Eigen::Success) {
    out.status = Status::Failed;
    out.message = "projected eigen-solve (Hessenberg QR) did not converge";
    return {};
  }
  const Eigen::VectorXcd nu = schur_eigenvalues(schur.matrixT());
  double nu_max = 0.0;
  for (Eigen::Index i = 0; i < nu.size(); ++i) nu_max = std::max(nu_max, std::abs(nu[i]));
  Eigen::VectorXcd finite(nu.size());
  Eigen::Index n_finite = 0;
  for (Eigen::Index i = 0; i < nu.size(); ++i)
    if (std::abs(nu[i]) > 1e-13 * nu_max) finite[n_finite++] = nu[i];  // else infinite
  finite.conservativeResize(n_finite);
  std::vector<Complex> lambda;
  for (Eigen::Index i : one_of_each_pair(finite))
    lambda.push_back(upper_root(sigma + 1.0 / finite[i]));
  return lambda;
}

// y with P(lambda) y = 0 by inverse iteration on the Hessenberg form, nu = 1 / (lambda - sigma)
// the shift; y is the upper half of Q v. Gaussian elimination with partial pivoting on a
// Hessenberg matrix interchanges neighbouring rows only: O(m^2). Empty when the residual of v is
// not at rounding level (a defective root).
Eigen::VectorXcd null_vector(const StateOperator& op, Complex lambda) {
  const Eigen::Index n = op.H.rows();
  const Complex nu = 1.0 / (lambda - op.sigma);
  Eigen::MatrixXcd A = op.H.cast<Complex>();
  A.diagonal().array() -= nu;
  const double scale = dense_norm1(op.H) + std::abs(nu);
  const double tiny = 1e-14 * scale;  // a zero pivot is replaced by this (an exact eigenvalue)
  std::vector<Complex> factor(static_cast<std::size_t>(n));
  std::vector<bool> swapped(static_cast<std::size_t>(n), false);
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    if (std::abs(A(k + 1, k)) > std::abs(A(k, k))) {
      A.row(k).tail(n - k).swap(A.row(k + 1).tail(n - k));
      swapped[kk] = true;
    }
    if (A(k, k) == 0.0) A(k, k) = tiny;
    factor[kk] = A(k + 1, k) / A(k, k);
    A.row(k + 1).tail(n - k - 1) -= factor[kk] * A.row(k).tail(n - k - 1);
  }
  if (A(n - 1, n - 1) == 0.0) A(n - 1, n - 1) = tiny;
  Eigen::VectorXcd v(n);
  const bool ok = inverse_iteration(v, scale, [&](Eigen::VectorXcd& x) {
    for (Eigen::Index k = 0; k + 1 < n; ++k) {
      if (swapped[static_cast<std::size_t>(k)]) std::swap(x[k], x[k + 1]);
      x[k + 1] -= factor[static_cast<std::size_t>(k)] * x[k];
    }
    A.triangularView<Eigen::Upper>().solveInPlace(x);
  });
  if (!ok) return {};
  const Eigen::VectorXd zr = op.hd.matrixQ() * v.real(), zi = op.hd.matrixQ() * v.imag();
  const double norm = std::sqrt(zr.head(op.m).squaredNorm() + zi.head(op.m).squaredNorm());
  if (!(norm > 0.0)) return {};
  Eigen::VectorXcd y(op.m);
  y.real() = zr.head(op.m) / norm;
  y.imag() = zi.head(op.m) / norm;
  return y;
}

// Undamped gyroscopic pencils (the projected D skew-symmetric: D = W G only; K, M symmetric
// positive definite after the rigid-body deflation), the usual Campbell diagram: with states
// u = [x'; x], diag(M, K) u' = S u, S = [-D, -K; K, 0] skew-symmetric, and with the Cholesky
// factors M = Lm Lm^T, K = Lk Lk^T the operator S' = L^{-1} S L^{-T} is real skew-symmetric, so
// H = i S' is Hermitian, its eigenvalues mu real and lambda = -i mu imaginary to rounding
// (P. Lancaster, Linear Algebra Appl. 256 (1997) on gyroscopic systems; F. Tisseur & K. Meerbergen,
// SIAM Review 43 (2001) 235-286, sec. 3.5). Real Householder reflections bring S' to skew
// tridiagonal form T = Q^T S' Q (sub-diagonal t); H's tridiagonal iT is, after the diagonal
// phase scaling D (d_0 = 1, d_k+1 = i sign(t_k) d_k), the real symmetric tridiagonal J with zero
// diagonal and off-diagonal |t|: J = D^H (iT) D. Its QR (eigenvalues only) and the reduction
// cost a small part of the nonsymmetric Hessenberg QR; each wanted vector is one inverse
// iteration on J, O(m), then z = D u and the back-transformation Q z, O(m^2).
struct GyroscopicOperator {
  Eigen::Index m = 0;
  Eigen::LLT<Eigen::MatrixXd> lm, lk;
  Eigen::MatrixXd reflectors;  // column k: the Householder vector of step k (rows k+1..)
  Eigen::VectorXd beta;        // and its 2 / (v^T v) (0: no reflection)
  Eigen::VectorXd diagonal, off_diagonal;  // of J
  Eigen::VectorXd sign;                    // sign(t_k), for D
};

// Q^T S Q = T, skew tridiagonal, by Householder reflections P_k = I - beta v v^T (the scheme of
// the symmetric reduction, G. H. Golub & C. F. Van Loan, Matrix Computations, 4th ed. 2013,
// sec. 8.3.1): a reflection keeps a matrix skew, and for skew A, P A P = A + beta (v w^T - w v^T)
// with w = A v (v^T A v = 0). Returns the sub-diagonal t; S is overwritten.
Eigen::VectorXd skew_tridiagonalize(Eigen::MatrixXd& S, GyroscopicOperator& g) {
  const Eigen::Index n = S.rows();
  Eigen::VectorXd t(std::max<Eigen::Index>(n - 1, 0));
  g.reflectors.setZero(n, n);
  g.beta.setZero(n);
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const Eigen::Index len = n - k - 1;
    const Eigen::VectorXd x = S.col(k).tail(len);
    const double rest = len > 1 ? x.tail(len - 1).squaredNorm() : 0.0;
    if (rest == 0.0) {
      t[k] = x[0];
      continue;
    }
    const double alpha = -std::copysign(std::sqrt(x[0] * x[0] + rest), x[0]);
    const Eigen::VectorXd v = x - alpha * Eigen::VectorXd::Unit(len, 0);
    const double beta = 2.0 / v.squaredNorm();
    t[k] = alpha;
    auto A = S.bottomRightCorner(len, len);
    const Eigen::VectorXd w = A * v;
    A.noalias() += (beta * v) * w.transpose();  // two rank-1 updates, no temporary matrix
    A.noalias() -= (beta * w) * v.transpose();
    g.reflectors.col(k).tail(len) = v;
    g.beta[k] = beta;
  }
  return t;
}

// x <- Q x = P_0 P_1 ... x (the last reflection first).
void apply_q(const GyroscopicOperator& g, Eigen::VectorXd& x) {
  const Eigen::Index n = x.size();
  for (Eigen::Index k = n - 2; k >= 0; --k) {
    if (g.beta[k] == 0.0) continue;
    const auto v = g.reflectors.col(k).tail(n - k - 1);
    x.tail(n - k - 1) -= (g.beta[k] * v.dot(x.tail(n - k - 1))) * v;
  }
}

bool symmetric_to_rounding(const Eigen::MatrixXd& A, double sign) {
  const double scale = A.cwiseAbs().maxCoeff();
  return (A - sign * A.transpose()).cwiseAbs().maxCoeff() <= 1e-13 * scale;
}

// The upper roots lambda = i |mu| (mu < 0) of an undamped gyroscopic projected pencil; false
// when the pencil is not one (damping, a non-symmetric K, K or M not positive definite).
bool gyroscopic_eigenvalues(const ReducedPencil& p, GyroscopicOperator& g,
                            std::vector<Complex>& lambda) {
  if (!symmetric_to_rounding(p.D, -1.0) || !symmetric_to_rounding(p.K, 1.0) ||
      !symmetric_to_rounding(p.M, 1.0))
    return false;
  const Eigen::Index m = p.M.rows();
  g.m = m;
  g.lm.compute(p.M);
  g.lk.compute(p.K);
  if (g.lm.info() != Eigen::Success || g.lk.info() != Eigen::Success) return false;
  const Eigen::MatrixXd Lk = g.lk.matrixL();
  // S' = [-Lm^{-1} D Lm^{-T}, -Lm^{-1} Lk; Lk^T Lm^{-T}, 0].
  Eigen::MatrixXd top = g.lm.matrixL().solve(p.D);
  top = g.lm.matrixL().solve(top.transpose()).transpose();
  const Eigen::MatrixXd corner = g.lm.matrixL().solve(Lk);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(2 * m, 2 * m);
  S.topLeftCorner(m, m) = -top;
  S.topRightCorner(m, m) = -corner;
  S.bottomLeftCorner(m, m) = corner.transpose();
  const Eigen::VectorXd t = skew_tridiagonalize(S, g);
  g.diagonal.setZero(2 * m);
  g.off_diagonal = t.cwiseAbs();
  g.sign = t.unaryExpr([](double x) { return x < 0.0 ? -1.0 : 1.0; });
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
  es.computeFromTridiagonal(g.diagonal, g.off_diagonal, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) return false;
  lambda.clear();
  for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k)
    if (es.eigenvalues()[k] < 0.0) lambda.emplace_back(0.0, -es.eigenvalues()[k]);
  return static_cast<Eigen::Index>(lambda.size()) == m;  // one of each +-mu pair
}

// v with (T - mu I) v = 0 for the symmetric tridiagonal T (diagonal d, off-diagonal e) by inverse
// iteration, the solves by Gaussian elimination with partial pivoting (the upper factor gains a
// second superdiagonal; the scheme of LAPACK's xGTTRF / xGTTRS, Anderson et al. 1999). Empty
// when inverse_iteration fails.
Eigen::VectorXd tridiagonal_null_vector(const Eigen::VectorXd& d, const Eigen::VectorXd& e,
                                        double mu) {
  const Eigen::Index n = d.size();
  Eigen::VectorXd a = d.array() - mu, up = Eigen::VectorXd::Zero(n), up2 = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd low = Eigen::VectorXd::Zero(n);
  std::vector<bool> swapped(static_cast<std::size_t>(n), false);
  if (n > 1) up.head(n - 1) = e;
  const double scale =
      d.cwiseAbs().maxCoeff() + 2.0 * (n > 1 ? e.cwiseAbs().maxCoeff() : 0.0) + std::abs(mu);
  const double tiny = 1e-14 * scale;
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const double below = e[k];
    if (std::abs(a[k]) >= std::abs(below)) {
      if (a[k] == 0.0) a[k] = tiny;
      low[k] = below / a[k];
      a[k + 1] -= low[k] * up[k];
    } else {
      const double factor = a[k] / below;
      a[k] = below;
      low[k] = factor;
      const double next = a[k + 1];
      a[k + 1] = up[k] - factor * next;
      up[k] = next;
      if (k + 2 < n) {
        up2[k] = up[k + 1];
        up[k + 1] = -factor * up[k + 1];
      }
      swapped[static_cast<std::size_t>(k)] = true;
    }
  }
  if (a[n - 1] == 0.0) a[n - 1] = tiny;
  Eigen::VectorXd v(n);
  const bool ok = inverse_iteration(v, scale, [&](Eigen::VectorXd& x) {
    for (Eigen::Index k = 0; k + 1 < n; ++k) {
      if (swapped[static_cast<std::size_t>(k)]) std::swap(x[k], x[k + 1]);
      x[k + 1] -= low[k] * x[k];
    }
    for (Eigen::Index k = n - 1; k >= 0; --k) {
      double r = x[k];
      if (k + 1 < n) r -= up[k] * x[k + 1];
      if (k + 2 < n) r -= up2[k] * x[k + 2];
      x[k] = r / a[k];
    }
  });
  if (!ok) return {};
  return v;
}

// y of the upper root lambda = i omega: w = Q v (eigenvector of H for mu = -omega), the state
// u = L^{-T} w = [lambda y; y], so y = Lk^{-T} w_2.
Eigen::VectorXcd gyroscopic_vector(const GyroscopicOperator& g, Complex lambda) {
  const Eigen::VectorXd v = tridiagonal_null_vector(g.diagonal, g.off_diagonal, -lambda.imag());
  if (v.size() == 0) return {};
  // z = D u, d_k in {1, i, -1, -i}: real and imaginary parts, each taken through Q.
  const Eigen::Index n = v.size();
  Eigen::VectorXd zr = Eigen::VectorXd::Zero(n), zi = Eigen::VectorXd::Zero(n);
  Complex d(1.0, 0.0);
  for (Eigen::Index k = 0; k < n; ++k) {
    zr[k] = d.real() * v[k];
    zi[k] = d.imag() * v[k];
    if (k + 1 < n) d *= Complex(0.0, g.sign[k]);
  }
  apply_q(g, zr);
  apply_q(g, zi);
  Eigen::VectorXcd y(g.m);
  y.real() = zr.tail(g.m);
  y.imag() = zi.tail(g.m);
  g.lk.matrixU().solveInPlace(y);
  const Eigen::VectorXd moduli = y.cwiseAbs2();
  const double norm = std::sqrt(moduli.sum());
  if (!(norm > 0.0)) return {};
  return y / norm;
}

// Indices of the n_modes entries of `lambda` nearest the target, in the order of
// QuadraticEigenResult (ascending |lambda|, then Im): the choice of solve_quadratic's dense path.
std::vector<std::size_t> wanted(const std::vector<Complex>& lambda, Complex target, int n_modes) {
  std::vector<std::size_t> order(lambda.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> distance(lambda.size());
  for (std::size_t i = 0; i < lambda.size(); ++i) distance[i] = std::abs(lambda[i] - upper(target));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return distance[a] < distance[b]; });
  order.resize(std::min(order.size(), static_cast<std::size_t>(n_modes)));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const double fa = std::abs(lambda[a]), fb = std::abs(lambda[b]);
    if (fa != fb) return fa < fb;
    return lambda[a].imag() < lambda[b].imag();
  });
  return order;
}

// The n_modes eigenvalues nearest the target (the choice and the order of solve_quadratic's
// dense path), n_rigid deflated rigid-body motions counting as two roots at 0 each, with their
// vectors. Status NotConverged when a wanted eigenvalue lies within
// 1e-6 relative of another one (a double root, e.g. the two whirls of an isotropic rotor at
// rest, whose vectors inverse iteration cannot separate) or a vector fails: the caller then
// solves the projected pencil with solve_quadratic's vectors.
// The n_modes roots nearest the target among the elastic ones and 2 n_rigid exact zeros (two
// per deflated rigid-body motion, listed first), into out.lambda / Y / rigid in the order of
// QuadraticEigenResult; `vector_of(i)` gives the vector of elastic root i (empty: out.status
// becomes NotConverged and the selection stops). Returns the number of roots selected.
template <class VectorOf>
Eigen::Index select_roots(std::vector<Complex> elastic, Eigen::Index n_rigid, Complex target,
                          int n_modes, Eigen::Index m, const VectorOf& vector_of,
                          ReducedModes& out) {
  const auto n_zero = static_cast<std::size_t>(2 * n_rigid);
  elastic.insert(elastic.begin(), n_zero, Complex(0.0, 0.0));
  const std::vector<Complex>& lambda = elastic;
  const std::vector<std::size_t> order = wanted(lambda, target, n_modes);
  const auto k = static_cast<Eigen::Index>(order.size());
  out.lambda.resize(k);
  out.Y.setZero(m, k);
  out.rigid.assign(order.size(), -1);
  for (Eigen::Index j = 0; j < k; ++j) {
    const std::size_t i = order[static_cast<std::size_t>(j)];
    out.lambda[j] = lambda[i];
    if (i < n_zero) {
      out.rigid[static_cast<std::size_t>(j)] = static_cast<Eigen::Index>(i / 2);
      continue;
    }
    const Eigen::VectorXcd y = vector_of(i - n_zero);
    if (y.size() == 0) {
      out.status = Status::NotConverged;
      return j;
    }
    out.Y.col(j) = y;
  }
  return k;
}

ReducedModes solve_reduced(const ReducedPencil& p, double sigma, Complex target, int n_modes,
                           Eigen::Index n_rigid) {
  ReducedModes out;
  out.shift = sigma;
  StateOperator op;
  GyroscopicOperator gyro;
  std::vector<Complex> lambda;
  const bool gyroscopic = gyroscopic_eigenvalues(p, gyro, lambda);
  if (!gyroscopic) {
    lambda = reduced_eigenvalues(p, sigma, op, out);
    if (out.status != Status::Ok) return out;
  }
  const auto vector_of = [&](std::size_t i) -> Eigen::VectorXcd {
    for (std::size_t o = 0; o < lambda.size(); ++o)  // a double root: vectors not separable
      if (o != i && std::abs(lambda[o] - lambda[i]) <= 1e-6 * std::abs(lambda[i])) return {};
    return gyroscopic ? gyroscopic_vector(gyro, lambda[i]) : null_vector(op, lambda[i]);
  };
  const Eigen::Index k = select_roots(lambda, n_rigid, target, n_modes, p.M.rows(), vector_of, out);
  if (out.status != Status::Ok) return out;
  if (k < n_modes) {
    out.status = Status::FewerModes;
    out.message =
        fmt::format("the projected pencil has only {} finite modes, {} were asked for", k, n_modes);
  }
  return out;
}

}  // namespace

struct ProjectedQuadratic::Impl {
  SpeedPencilParts parts;
  ProjectedQuadraticOptions options;
  bool built = false;
  Status build_status = Status::Ok;
  std::string build_message;
  linalg::SymmetricFactorization factor;  // K0_sym - sigma_b M
  Eigen::MatrixXd V;                      // M-orthonormal basis, M-orthogonal to R
  Eigen::MatrixXd R;                      // deflated rigid-body motions, M-orthonormal
  Eigen::MatrixXd Mr, Kr, Cr, Gr, Br;     // V^T (.) V and V^T B
  int enrichments = 0;
  Eigen::Index max_basis = 0;
  Eigen::Index kept_columns = -1;  // keep_basis(); -1: the starting basis
  Eigen::Index start_columns = 0;

  void build(int n_modes);
  Eigen::MatrixXd deflated_rigid_space() const;
  bool rests(const SparseMatrix& A) const;
  int add_columns(const Eigen::MatrixXd& W);
  void project(Eigen::Index old = 0);
  ReducedPencil reduced(double speed, const SparseMatrix& dK, const SparseMatrix& dC) const;
  ReducedModes modes(const ReducedPencil& p, const QuadraticEigenOptions& qo) const;
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
  so.dense_limit = 100;  // measured: Lanczos beats the dense solve from ~100 DOFs
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
  R = deflated_rigid_space();
  V.resize(n, 0);
  add_columns(modes.eigenvectors);
  start_columns = V.cols();
}

// The candidate motions that K0, C0, G and B diag(c) B^T (and their transposes) all leave at
// rest, row by row to rounding (eig/rigid_body.hpp on the stacked matrices), M-orthonormal.
Eigen::MatrixXd ProjectedQuadratic::Impl::deflated_rigid_space() const {
  const Eigen::Index n = parts.M.rows();
  if (parts.rigid_candidates.cols() == 0 || parts.rigid_candidates.rows() != n)
    return Eigen::MatrixXd(n, 0);
  const Eigen::Index r = parts.low_rank_coefficients.size();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(2 * (parts.K0.nonZeros() + parts.C0.nonZeros()) +
                                     parts.G.nonZeros() + r * n));
  Eigen::Index row0 = 0;
  auto stack = [&](const SparseMatrix& A, bool transposed) {
    for (Eigen::Index j = 0; j < A.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(A, j); it; ++it)
        t.emplace_back(row0 + (transposed ? it.col() : it.row()), transposed ? it.row() : it.col(),
                       it.value());
    row0 += n;
  };
  stack(parts.K0, false);
  stack(parts.K0, true);
  stack(parts.C0, false);
  stack(parts.C0, true);
  stack(parts.G, false);
  for (Eigen::Index k = 0; k < r; ++k)  // rows c_k b_k^T
    for (Eigen::Index i = 0; i < n; ++i)
      if (parts.low_rank_basis(i, k) != 0.0)
        t.emplace_back(row0 + k, i, parts.low_rank_coefficients[k] * parts.low_rank_basis(i, k));
  SparseMatrix stacked(row0 + r, n);
  stacked.setFromTriplets(t.begin(), t.end());
  return rigid_body_space(stacked, parts.M, parts.rigid_candidates).basis;
}

// True when A leaves every deflated motion at rest (A R and A^T R zero to rounding, row-scaled
// as in deflated_rigid_space): the speed increments must, for the deflation to hold at a speed.
bool ProjectedQuadratic::Impl::rests(const SparseMatrix& A) const {
  if (R.cols() == 0 || A.nonZeros() == 0) return true;
  const Eigen::Index n = A.rows();
  SparseMatrix stacked(2 * n, n);
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      t.emplace_back(it.row(), it.col(), it.value());
      t.emplace_back(n + it.col(), it.row(), it.value());
    }
  stacked.setFromTriplets(t.begin(), t.end());
  return rigid_body_space(stacked, parts.M, R).dimension() == R.cols();
}

// Appends the parts of W M-orthogonal to R and V (classical Gram-Schmidt applied twice, which is
// orthogonal to working precision: Giraud et al., Numer. Math. 101 (2005) 87-100); drops
// columns that V already spans. Returns the number added and re-projects.
int ProjectedQuadratic::Impl::add_columns(const Eigen::MatrixXd& W) {
  int added = 0;
  for (Eigen::Index j = 0; j < W.cols() && V.cols() < max_basis; ++j) {
    Eigen::VectorXd w = W.col(j);
    const double norm0 = std::sqrt(std::max(0.0, w.dot(parts.M * w)));
    if (!(norm0 > 0.0)) continue;
    for (int pass = 0; pass < 2; ++pass) {
      if (R.cols() > 0) w -= R * (R.transpose() * (parts.M * w));
      w -= V * (V.transpose() * (parts.M * w));
    }
    const double norm = std::sqrt(std::max(0.0, w.dot(parts.M * w)));
    if (!(norm > 1e-10 * norm0)) continue;
    V.conservativeResize(Eigen::NoChange, V.cols() + 1);
    V.col(V.cols() - 1) = w / norm;
    ++added;
  }
  if (added > 0) project(V.cols() - added);
  return added;
}

// V^T A V after columns were appended to V (its first `old` columns projected before): only the
// new rows and columns, V^T (A V_new) and (A^T V_new)^T V_old, so an enrichment costs in
// proportion to the columns it adds.
void grow_projection(const SparseMatrix& A, const Eigen::MatrixXd& V, Eigen::Index old,
                     Eigen::MatrixXd& Ar) {
  const Eigen::Index m = V.cols(), added = m - old;
  const Eigen::MatrixXd AVnew = A * V.rightCols(added);
  const Eigen::MatrixXd AtVnew = A.transpose() * V.rightCols(added);
  Ar.conservativeResize(m, m);
  Ar.rightCols(added) = V.transpose() * AVnew;
  Ar.bottomLeftCorner(added, old) = AtVnew.transpose() * V.leftCols(old);
}

void ProjectedQuadratic::Impl::project(Eigen::Index old) {
  if (old > 0 && Mr.rows() == old) {
    grow_projection(parts.M, V, old, Mr);
    grow_projection(parts.K0, V, old, Kr);
    grow_projection(parts.C0, V, old, Cr);
    grow_projection(parts.G, V, old, Gr);
    if (parts.low_rank_coefficients.size() > 0) {
      Br.conservativeResize(V.cols(), Eigen::NoChange);
      Br.bottomRows(V.cols() - old) =
          V.rightCols(V.cols() - old).transpose() * parts.low_rank_basis;
    }
    return;
  }
  Mr = V.transpose() * (parts.M * V);
  Kr = V.transpose() * (parts.K0 * V);
  Cr = V.transpose() * (parts.C0 * V);
  Gr = V.transpose() * (parts.G * V);
  // No low-rank term: B stays 0 x 0, as in a pencil without one.
  Br = parts.low_rank_coefficients.size() > 0
           ? Eigen::MatrixXd(V.transpose() * parts.low_rank_basis)
           : Eigen::MatrixXd();
}

ReducedPencil ProjectedQuadratic::Impl::reduced(double speed, const SparseMatrix& dK,
                                                const SparseMatrix& dC) const {
  ReducedPencil p{Mr, Cr + speed * Gr, Kr};
  if (dK.nonZeros() > 0) p.K += V.transpose() * (dK * V);
  if (dC.nonZeros() > 0) p.D += V.transpose() * (dC * V);
  if (parts.low_rank_coefficients.size() > 0)
    p.D += Br * parts.low_rank_coefficients.asDiagonal() * Br.transpose();
  return p;
}

ReducedModes ProjectedQuadratic::Impl::modes(const ReducedPencil& p,
                                             const QuadraticEigenOptions& qo) const {
  ReducedModes out = solve_reduced(p, qo.dense_shift, qo.target, qo.n_modes, R.cols());
  if (out.status != Status::NotConverged) return out;
  // A double root: the vectors of the Schur form (solve_quadratic's dense path) separate it.
  QuadraticPencil full;
  full.M = p.M.sparseView();
  full.C = p.D.sparseView();
  full.K = p.K.sparseView();
  const QuadraticEigenResult red = solve_quadratic(full, qo);
  out = ReducedModes{};
  out.status = red.status;
  out.message = red.message;
  out.shift = red.shift_used;
  // With the deflated rigid-body roots, the wanted ones again.
  const std::vector<Complex> elastic(red.eigenvalues.begin(), red.eigenvalues.end());
  const Eigen::Index k = select_roots(
      elastic, R.cols(), qo.target, qo.n_modes, p.M.rows(),
      [&](std::size_t i) {
        return Eigen::VectorXcd(red.eigenvectors.col(static_cast<Eigen::Index>(i)));
      },
      out);
  if (out.status == Status::FewerModes && k == qo.n_modes) out.status = Status::Ok;
  return out;
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

void ProjectedQuadratic::keep_basis() { impl_->kept_columns = impl_->V.cols(); }

void ProjectedQuadratic::restore_basis() {
  Impl& s = *impl_;
  const Eigen::Index keep = s.kept_columns >= 0 ? s.kept_columns : s.start_columns;
  if (!s.built || s.V.cols() <= keep) return;
  // The projected matrices grow by new rows and columns only (grow_projection), so their
  // leading blocks are exactly those of the kept basis: the solves repeat bit for bit.
  s.V.conservativeResize(Eigen::NoChange, keep);
  s.Mr.conservativeResize(keep, keep);
  s.Kr.conservativeResize(keep, keep);
  s.Cr.conservativeResize(keep, keep);
  s.Gr.conservativeResize(keep, keep);
  if (s.Br.size() > 0) s.Br.conservativeResize(keep, Eigen::NoChange);
}

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
  if (!s.rests(dK) || !s.rests(dC)) {
    r.status = Status::NotConverged;
    r.message = fmt::format(
        "the speed-dependent bearing coefficients at this speed act on {} rigid-body motion(s) "
        "the projection deflates (free at the reference speed)",
        s.R.cols());
    return r;
  }
  for (int round = 0;; ++round) {
    const ReducedModes red = s.modes(s.reduced(speed, dK, dC), qo);
    r.iterations = round;
    r.shift_used = red.shift;
    r.factorization = fmt::format("projected({})", s.V.cols());
    if (red.status != Status::Ok && red.status != Status::FewerModes) {
      r.status = red.status;
      r.message = "projected solve: " + red.message;
      return r;
    }
    // x = V y for the real and imaginary parts in one product (V is real), then the largest
    // entry scaled to 1.
    const Eigen::Index k_modes = red.Y.cols();
    Eigen::MatrixXd Yri(red.Y.rows(), 2 * k_modes);
    Yri << red.Y.real(), red.Y.imag();
    const Eigen::MatrixXd VY = s.V * Yri;
    Eigen::MatrixXcd X(s.V.rows(), k_modes);
    X.real() = VY.leftCols(k_modes);
    X.imag() = VY.rightCols(k_modes);
    for (std::size_t j = 0; j < red.rigid.size(); ++j)
      if (red.rigid[j] >= 0) X.col(static_cast<Eigen::Index>(j)) = s.R.col(red.rigid[j]);
    normalise_columns(X);
    RowMatrix Xri(X.rows(), 2 * k_modes);
    Xri << X.real(), X.imag();
    const Eigen::MatrixXcd R = residual_vectors(full, red.lambda, Xri);
    r.eigenvalues = red.lambda;
    r.residuals = backward_errors_from_residuals(full, red.lambda, X, R);
    r.eigenvectors = std::move(X);
    r.converged = static_cast<int>(red.lambda.size());
    const bool complete = r.converged == options.n_modes || s.V.cols() + s.R.cols() == full.size();
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
    const RowMatrix Wr = W;
    const RowMatrix MW = s.parts.M * Wr, MX = s.parts.M * Xri;
    const Eigen::RowVectorXd wMw = Wr.cwiseProduct(MW).colwise().sum(),
                             xMx = Xri.cwiseProduct(MX).colwise().sum();
    std::vector<Eigen::Index> bad;
    double worst = 0.0;
    for (Eigen::Index k = 0; k < k_modes; ++k) {
      const Eigen::Index k2 = k_modes + k;
      const double wm = wMw[k] + wMw[k2], xm = xMx[k] + xMx[k2];
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
