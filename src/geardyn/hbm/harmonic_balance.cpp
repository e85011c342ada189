// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#include <complex>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include "geardyn/core/error.hpp"
#include "geardyn/hbm/condensed.hpp"
#include "geardyn/hbm/harmonic_balance.hpp"

namespace geardyn::hbm {

NonlinearForce cubic_spring(int dof, double alpha) {
  return [dof, alpha](const HarmonicBasis& b, const Eigen::VectorXd& X, Eigen::VectorXd& F,
                      Eigen::MatrixXd& J) {
    const int s = b.size();
    const Eigen::VectorXd q = b.to_time(X.segment(dof * s, s));
    const Eigen::VectorXd f = alpha * q.array().cube().matrix();
    F.segment(dof * s, s) += b.to_frequency(f);
    const Eigen::VectorXd slope = 3.0 * alpha * q.array().square().matrix();
    J.block(dof * s, dof * s, s, s) += b.projection() * slope.asDiagonal() * b.sampling();
  };
}

NonlinearForce jenkins_force(int dof_a, int dof_b, JenkinsElement element) {
  return [dof_a, dof_b, element](const HarmonicBasis& b, const Eigen::VectorXd& X,
                                 Eigen::VectorXd& F, Eigen::MatrixXd& J) {
    const int s = b.size();
    Eigen::VectorXd u = X.segment(dof_a * s, s);
    if (dof_b >= 0) u -= X.segment(dof_b * s, s);
    const JenkinsResponse r = jenkins_response(element, b, u);
    F.segment(dof_a * s, s) += r.coefficients;
    J.block(dof_a * s, dof_a * s, s, s) += r.jacobian;
    if (dof_b >= 0) {
      F.segment(dof_b * s, s) -= r.coefficients;
      J.block(dof_a * s, dof_b * s, s, s) -= r.jacobian;
      J.block(dof_b * s, dof_a * s, s, s) -= r.jacobian;
      J.block(dof_b * s, dof_b * s, s, s) += r.jacobian;
    }
  };
}

HarmonicBalance::HarmonicBalance(Eigen::MatrixXd M, Eigen::MatrixXd C, Eigen::MatrixXd K,
                                 HarmonicBasis basis, std::vector<NonlinearForce> forces,
                                 Eigen::VectorXd F_ext)
    : M_(std::move(M)),
      C_(std::move(C)),
      K_(std::move(K)),
      basis_(std::move(basis)),
      forces_(std::move(forces)),
      F_ext_(std::move(F_ext)) {
  const auto n = K_.rows();
  if (K_.cols() != n || M_.rows() != n || M_.cols() != n || C_.rows() != n || C_.cols() != n)
    throw InputError({}, "matrices", "square M, C, K of one size",
                     fmt::format("M {}x{}, C {}x{}, K {}x{}", M_.rows(), M_.cols(), C_.rows(),
                                 C_.cols(), K_.rows(), K_.cols()));
  if (F_ext_.size() != size())
    throw InputError({}, "F_ext", fmt::format("{} coefficients (n_dof (2H + 1))", size()),
                     std::to_string(F_ext_.size()));
}

Eigen::VectorXd HarmonicBalance::residual(const Eigen::VectorXd& X, double omega,
                                          Eigen::MatrixXd* J, Eigen::VectorXd* dR_domega) const {
  const int s = basis_.size(), nd = dofs();
  Eigen::VectorXd R = -F_ext_;
  if (J) J->setZero(size(), size());
  if (dR_domega) dR_domega->setZero(size());
  // Linear part, harmonic by harmonic.
  for (int i = 0; i < nd; ++i) {
    for (int j = 0; j < nd; ++j) {
      const double k = K_(i, j), m = M_(i, j), c = C_(i, j);
      if (k == 0.0 && m == 0.0 && c == 0.0) continue;
      const int a0i = i * s, a0j = j * s;
      R[a0i] += k * X[a0j];
      if (J) (*J)(a0i, a0j) += k;
      for (int n = 1; n <= basis_.harmonics(); ++n) {
        const int ci = a0i + HarmonicBasis::cos_index(n), si = a0i + HarmonicBasis::sin_index(n);
        const int cj = a0j + HarmonicBasis::cos_index(n), sj = a0j + HarmonicBasis::sin_index(n);
        const double w = n * omega;
        const double diag = k - w * w * m, off = w * c;
        R[ci] += diag * X[cj] + off * X[sj];
        R[si] += -off * X[cj] + diag * X[sj];
        if (J) {
          (*J)(ci, cj) += diag;
          (*J)(ci, sj) += off;
          (*J)(si, cj) -= off;
          (*J)(si, sj) += diag;
        }
        if (dR_domega) {
          const double ddiag = -2.0 * n * w * m, doff = n * c;
          (*dR_domega)[ci] += ddiag * X[cj] + doff * X[sj];
          (*dR_domega)[si] += -doff * X[cj] + ddiag * X[sj];
        }
      }
    }
  }
  if (!forces_.empty()) {
    Eigen::VectorXd F = Eigen::VectorXd::Zero(size());
    Eigen::MatrixXd Jn = Eigen::MatrixXd::Zero(size(), size());
    for (const auto& f : forces_) f(basis_, X, F, Jn);
    R += F;
    if (J) *J += Jn;
  }
  return R;
}

double HarmonicBalance::amplitude(const Eigen::VectorXd& X, int dof, int harmonic) const {
  const int base = dof * basis_.size();
  return std::hypot(X[base + HarmonicBasis::cos_index(harmonic)],
                    X[base + HarmonicBasis::sin_index(harmonic)]);
}

double HarmonicBalance::residual_scale(const Eigen::VectorXd&, double) const {
  return std::max(1.0, F_ext_.norm());
}

namespace {

// The problem in the scaled unknowns y = (X / x_scale, omega / omega_scale).
class Scaled {
 public:
  Scaled(const HarmonicSystem& hb, const ContinuationOptions& o)
      : hb_(hb), xs_(o.x_scale), ws_(o.omega_scale), tolerance_(o.tolerance) {}
  int size() const { return hb_.size(); }
  double x_scale() const { return xs_; }
  double omega_scale() const { return ws_; }
  double omega(const Eigen::VectorXd& y) const { return y[size()] * ws_; }
  Eigen::VectorXd X(const Eigen::VectorXd& y) const { return y.head(size()) * xs_; }
  Eigen::VectorXd pack(const Eigen::VectorXd& X, double omega) const {
    Eigen::VectorXd y(size() + 1);
    y << X / xs_, omega / ws_;
    return y;
  }
  // R and the Jacobian [dR/dy] (n x (n + 1)).
  Eigen::VectorXd residual(const Eigen::VectorXd& y, Eigen::MatrixXd* A) const {
    if (!A) return hb_.residual(X(y), omega(y));
    Eigen::MatrixXd J;
    Eigen::VectorXd dRw;
    Eigen::VectorXd R = hb_.residual(X(y), omega(y), &J, &dRw);
    A->resize(size(), size() + 1);
    A->leftCols(size()) = J * xs_;
    A->col(size()) = dRw * ws_;
    return R;
  }
  double tolerance(const Eigen::VectorXd& y) const {
    return tolerance_ * hb_.residual_scale(X(y), omega(y));
  }

 private:
  const HarmonicSystem& hb_;
  double xs_, ws_, tolerance_;
};

// The linear algebra of the continuation: R(y), and solves with the Jacobian A = dR/dy
// (n x (n + 1)) of the last point linearized, either alone with omega fixed (A_X d = rhs, border
// empty) or bordered by a row b ([A; b^T] d = rhs). `target` bounds the residual of the first n
// rows (units of R) that an iterative solver must reach; direct solvers ignore it.
class NewtonAlgebra {
 public:
  virtual ~NewtonAlgebra() = default;
  virtual Eigen::VectorXd residual(const Eigen::VectorXd& y, bool linearize) = 0;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& border, const Eigen::VectorXd& rhs,
                                double target) = 0;
  /// Sign of det [A; border^T] of the last bordered solve (the branch-point test function);
  /// 0 when the algebra does not know it (iterative solves).
  virtual int bordered_sign() const { return 0; }
  /// Whether the secant of the last two points may replace the tangent as predictor: where a
  /// tangent costs an iterative solve (condensed systems). A dense tangent costs one LU, and the
  /// secant's different point placement loses the grazing folds of contact laws (examples/
  /// gear_rattle), so the dense path keeps the tangent.
  virtual bool prefers_secant() const { return false; }
};

// Any HarmonicSystem: its dense Jacobian and a partial-pivoting LU per solve.
class DenseAlgebra final : public NewtonAlgebra {
 public:
  // `secant`: a condensed system solved densely (its fallback) keeps the condensed form's
  // predictor, so both trace the same points.
  DenseAlgebra(const Scaled& p, CondensedStatistics* statistics, bool secant)
      : p_(p), statistics_(statistics), secant_(secant) {}
  bool prefers_secant() const override { return secant_; }
  Eigen::VectorXd residual(const Eigen::VectorXd& y, bool linearize) override {
    return p_.residual(y, linearize ? &A_ : nullptr);
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& border, const Eigen::VectorXd& rhs,
                        double) override {
    const double started = statistics_ ? CondensedStatistics::now() : 0.0;
    const auto n = A_.rows();
    Eigen::VectorXd d;
    if (border.size() == 0) {
      d = A_.leftCols(n).partialPivLu().solve(rhs);
    } else {
      Eigen::MatrixXd B(n + 1, n + 1);
      B.topRows(n) = A_;
      B.bottomRows(1) = border.transpose();
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(B);
      d = lu.solve(rhs);
      // det = det(P) prod U_ii: its sign without the product's overflow.
      int sign = lu.permutationP().determinant() > 0 ? 1 : -1;
      for (Eigen::Index i = 0; i <= n; ++i) {
        const double u = lu.matrixLU()(i, i);
        sign = u > 0.0 ? sign : u < 0.0 ? -sign : 0;
      }
      sign_ = sign;
    }
    if (statistics_) {
      ++statistics_->linear_solves;
      ++statistics_->dense_factorizations;
      statistics_->linear_algebra_seconds += CondensedStatistics::now() - started;
    }
    return d;
  }
  int bordered_sign() const override { return sign_; }

 private:
  const Scaled& p_;
  CondensedStatistics* statistics_;
  Eigen::MatrixXd A_;
  int sign_ = 0;
  bool secant_ = false;
};

struct Krylov {
  bool converged = false;
  int iterations = 0;
  double initial = 0.0;   // ||b - A x|| at the start
  double residual = 0.0;  // and at the end
};

// Right-preconditioned GMRES (the flexible variant, which keeps the preconditioned vectors) on
// A x = b from the given x, until ||b - A x|| <= target or max_iterations, restarted every
// `restart` iterations. Right preconditioning makes the monitored residual the true one of
// A x = b (checked explicitly at the end of each cycle), which is what the Newton tolerance is
// about. Orthogonalisation: classical Gram-Schmidt applied twice (as stable as modified
// Gram-Schmidt, in matrix-vector products).
// Reference: Saad, "Iterative Methods for Sparse Linear Systems", 2nd ed., SIAM (2003), alg. 9.6.
template <class Operator, class Preconditioner>
Krylov gmres(const Operator& A, const Preconditioner& M, const Eigen::VectorXd& b,
             Eigen::VectorXd& x, double target, int max_iterations, int restart) {
  Krylov out;
  const auto n = b.size();
  Eigen::VectorXd r = x.isZero(0.0) ? b : Eigen::VectorXd(b - A(x));
  out.residual = out.initial = r.norm();
  while (out.residual > target && out.iterations < max_iterations && std::isfinite(out.residual)) {
    const int m = std::min(restart, max_iterations - out.iterations);
    Eigen::MatrixXd V(n, m + 1), Z(n, m), Hm = Eigen::MatrixXd::Zero(m + 1, m);
    Eigen::VectorXd cs(m), sn(m), g = Eigen::VectorXd::Zero(m + 1), w, h, h2;
    g[0] = out.residual;
    V.col(0) = r / out.residual;
    int j = 0;
    while (j < m) {
      Z.col(j) = M(V.col(j));
      w = A(Z.col(j));
      h.noalias() = V.leftCols(j + 1).transpose() * w;
      w.noalias() -= V.leftCols(j + 1) * h;
      h2.noalias() = V.leftCols(j + 1).transpose() * w;
      w.noalias() -= V.leftCols(j + 1) * h2;
      h += h2;
      const double next = w.norm();
      Hm.col(j).head(j + 1) = h;
      Hm(j + 1, j) = next;
      if (next > 0.0) V.col(j + 1) = w / next;
      for (int i = 0; i < j; ++i) {
        const double a = Hm(i, j), c = Hm(i + 1, j);
        Hm(i, j) = cs[i] * a + sn[i] * c;
        Hm(i + 1, j) = -sn[i] * a + cs[i] * c;
      }
      const double rho = std::hypot(Hm(j, j), Hm(j + 1, j));
      cs[j] = rho > 0.0 ? Hm(j, j) / rho : 1.0;
      sn[j] = rho > 0.0 ? Hm(j + 1, j) / rho : 0.0;
      Hm(j, j) = rho;
      Hm(j + 1, j) = 0.0;
      g[j + 1] = -sn[j] * g[j];
      g[j] *= cs[j];
      ++j;
      ++out.iterations;
      if (std::abs(g[j]) <= target || next == 0.0 || !(rho > 0.0)) break;
    }
    const Eigen::VectorXd y =
        Hm.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
    if (!y.allFinite()) break;
    x.noalias() += Z.leftCols(j) * y;
    r = b - A(x);
    const double previous = out.residual;
    out.residual = r.norm();
    if (!(out.residual < previous)) break;  // stagnation: no progress in a whole cycle
  }
  out.converged = out.residual <= target;
  return out;
}

// A CondensedHarmonicBalance built from LocalForce: J_X applied from its parts
// (CondensedJacobian), the (bordered) systems solved by GMRES, preconditioned by the
// Sherman-Morrison-Woodbury inverse of CondensedPreconditioner kept from an earlier Newton point
// (a chord-like reuse: the capacitance LU is the only factorisation, of the size of the modal
// basis, not of N). Rebuilt when the GMRES iterations spent beyond those a fresh preconditioner
// would have needed (from its convergence rate in its first solve) add up to the cost of a
// rebuild: the decision depends on iteration counts only, so the results do not depend on the
// machine or its load. When even a fresh one does not bring GMRES to the target (a residual
// flexibility strongly coupling the clusters), it falls back to the LU of the dense J, kept and
// reused the same way.
class CondensedAlgebra final : public NewtonAlgebra {
 public:
  bool prefers_secant() const override { return true; }
  CondensedAlgebra(const CondensedHarmonicBalance& hb, const Scaled& p) : hb_(hb), p_(p) {}

  Eigen::VectorXd residual(const Eigen::VectorXd& y, bool linearize) override {
    // The elements' march yields the Jacobian with the forces, so every residual is linearized:
    // the line search's accepted trial is the next Newton point and is not evaluated again.
    if (!(last_ && last_y_.size() == y.size() && last_y_ == y)) {
      last_ = std::make_shared<const CondensedJacobian>(hb_.linearize(p_.X(y), p_.omega(y)));
      last_y_ = y;
    }
    if (linearize && kept_ != last_) {
      kept_ = last_;
      ++kept_id_;
    }
    return last_->residual();
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& border, const Eigen::VectorXd& rhs,
                        double target) override {
    CondensedStatistics* stats = hb_.statistics();
    const double started = stats ? CondensedStatistics::now() : 0.0;
    const CondensedJacobian& J = *kept_;
    const int n = p_.size();
    const bool bordered = border.size() > 0;
    const double xs = p_.x_scale(), ws = p_.omega_scale();
    // The border row is weighted by x_scale, which puts its residual in the units of R.
    const double sigma = xs;
    const Eigen::VectorXd a = ws * J.omega_derivative();
    auto op = [&](const Eigen::VectorXd& v) {
      Eigen::VectorXd out(v.size());
      out.head(n) = xs * J.apply(v.head(n));
      if (bordered) {
        out.head(n) += a * v[n];
        out[n] = sigma * border.dot(v);
      }
      return out;
    };
    Eigen::VectorXd b = rhs;
    if (bordered) b[n] *= sigma;
    const double goal = std::max(target, kRelativeFloor * b.norm());

    if (!built_ || excess_ > rebuild_cost_) build();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
    Krylov k = run(op, b, x, border, a, goal);
    if (!k.converged && built_id_ != kept_id_) {
      build();
      k = run(op, b, x, border, a, goal);
    }
    if (!k.converged && !dense_) {
      dense_ = true;
      build();
      k = run(op, b, x, border, a, goal);
    }
    account(k);
    if (bordered) x += border * ((rhs[n] - border.dot(x)) / border.squaredNorm());
    if (stats) {
      ++stats->linear_solves;
      stats->linear_algebra_seconds += CondensedStatistics::now() - started;
    }
    return x;
  }

 private:
  // GMRES iterations of one attempt, and its restart length.
  static constexpr int kMaxIterations = 100;
  static constexpr int kRestart = 50;
  // No solve is asked to go below rounding.
  static constexpr double kRelativeFloor = 1e-13;

  // The convergence rate of the first solve after a build is the fresh preconditioner's; later
  // solves add the iterations beyond those it would have needed for their reduction.
  void account(const Krylov& k) {
    if (k.iterations == 0 || !(k.residual > 0.0) || !(k.initial > 0.0)) return;
    const double log_rate = std::log(k.residual / k.initial) / k.iterations;
    if (!(fresh_log_rate_ < 0.0)) {
      fresh_log_rate_ = log_rate;
      return;
    }
    const double needed = std::log(k.residual / k.initial) / fresh_log_rate_;
    excess_ += std::max(0.0, k.iterations - needed);
  }

  // M^{-1} r ~ J_X^{-1} r from the current preconditioner.
  Eigen::VectorXd inverse(const Eigen::VectorXd& r) const {
    return dense_ ? Eigen::VectorXd(dense_lu_.solve(r)) : woodbury_->solve(r);
  }

  void build() {
    CondensedStatistics* stats = hb_.statistics();
    if (!dense_) {
      woodbury_ = std::make_unique<CondensedPreconditioner>(hb_, *kept_);
      rebuild_cost_ = woodbury_->rebuild_cost();
      if (stats) ++stats->preconditioner_builds;
      if (woodbury_->status() != Status::Ok) dense_ = true;
    }
    if (dense_) {
      dense_lu_.compute(kept_->dense());
      // LU flops over those of a solve, 2/3 N^3 / 2 N^2; the solves run at memory speed once
      // the factor outgrows the cache, about 5 times slower per flop (measured at N = 2200).
      rebuild_cost_ = p_.size() / 15.0;
      if (stats) ++stats->dense_factorizations;
    }
    built_ = true;
    built_id_ = kept_id_;
    excess_ = 0.0;
    fresh_log_rate_ = 0.0;
  }

  // GMRES with the preconditioner of the bordered matrix [[A_X, a], [sigma b_X^T, sigma b_w]]
  // by block elimination with M in place of A_X: p = M^{-1} a, Schur complement
  // sigma (b_w - b_X . p).
  template <class Operator>
  Krylov run(const Operator& op, const Eigen::VectorXd& b, Eigen::VectorXd& x,
             const Eigen::VectorXd& border, const Eigen::VectorXd& a, double goal) {
    const int n = p_.size();
    const double xs = p_.x_scale(), sigma = xs;
    Krylov k;
    if (border.size() == 0) {
      k = gmres(
          op, [&](const Eigen::VectorXd& r) -> Eigen::VectorXd { return inverse(r) / xs; }, b, x,
          goal, kMaxIterations, kRestart);
    } else {
      const Eigen::VectorXd pa = inverse(a) / xs;
      const Eigen::VectorXd bx = border.head(n);
      const double bw = border[n];
      const double schur = sigma * (bw - bx.dot(pa));
      const bool usable = std::isfinite(schur) &&
                          std::abs(schur) > 1e-14 * sigma * (std::abs(bw) + bx.norm() * pa.norm());
      k = gmres(
          op,
          [&](const Eigen::VectorXd& r) -> Eigen::VectorXd {
            Eigen::VectorXd out(n + 1);
            const Eigen::VectorXd u = inverse(r.head(n)) / xs;
            if (usable) {
              out[n] = (r[n] - sigma * bx.dot(u)) / schur;
              out.head(n) = u - pa * out[n];
            } else {
              out.head(n) = u;
              out[n] = bw != 0.0 ? r[n] / (sigma * bw) : 0.0;
            }
            return out;
          },
          b, x, goal, kMaxIterations, kRestart);
    }
    if (CondensedStatistics* stats = hb_.statistics()) stats->krylov_iterations += k.iterations;
    return k;
  }

  const CondensedHarmonicBalance& hb_;
  const Scaled& p_;
  std::shared_ptr<const CondensedJacobian> last_, kept_;
  Eigen::VectorXd last_y_;
  long kept_id_ = 0, built_id_ = -1;
  bool built_ = false, dense_ = false;
  double rebuild_cost_ = 0.0, excess_ = 0.0, fresh_log_rate_ = 0.0;
  std::unique_ptr<CondensedPreconditioner> woodbury_;
  Eigen::PartialPivLU<Eigen::MatrixXd> dense_lu_;
};

std::unique_ptr<NewtonAlgebra> newton_algebra(const HarmonicSystem& hb, const Scaled& p) {
  const auto* condensed = dynamic_cast<const CondensedHarmonicBalance*>(&hb);
  if (condensed && condensed->has_local_forces())
    return std::make_unique<CondensedAlgebra>(*condensed, p);
  return std::make_unique<DenseAlgebra>(p, condensed ? condensed->statistics() : nullptr,
                                        condensed != nullptr);
}

// The secant of the last two points predicts the next one while it stays within about 6 degrees
// of the direction that led to it (cos 6 deg = 0.9945); where the curve bends more, the tangent
// is solved for.
constexpr double kSecantAlignment = 0.9945;

// Unit tangent of R(y) = 0 at the last point linearized, oriented along `previous`.
Eigen::VectorXd tangent(const Scaled& p, NewtonAlgebra& algebra, const Eigen::VectorXd& previous) {
  const auto n = previous.size() - 1;
  // |t| ~ 1 before normalising: a residual 1e-11 x_scale is 1e-11 of A t's terms.
  Eigen::VectorXd t = algebra.solve(previous, Eigen::VectorXd::Unit(n + 1, n), 1e-11 * p.x_scale());
  t.normalize();
  if (t.dot(previous) < 0.0) t = -t;
  return t;
}

struct Corrected {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;
};

// Newton on [R(z); t . (z - z0)] = 0 (t empty: omega fixed, X alone), with a backtracking line
// search on ||R|| (the constraint is linear, so every full or partial step keeps it satisfied
// once it holds). The algebra keeps the linearization at the final z.
Corrected correct_unguarded(const Scaled& p, NewtonAlgebra& algebra, Eigen::VectorXd& z,
                            const Eigen::VectorXd& t, const Eigen::VectorXd& z0,
                            int max_iterations) {
  const int n = p.size();
  Corrected c;
  Eigen::VectorXd R = algebra.residual(z, true);
  for (;; ++c.iterations) {
    const double arc = t.size() ? t.dot(z - z0) : 0.0;
    c.residual = R.norm();
    const double tolerance = p.tolerance(z);
    if (c.residual <= tolerance && std::abs(arc) <= 1e-12 * std::max(1.0, z.norm())) {
      c.converged = true;
      return c;
    }
    if (c.iterations >= max_iterations || !R.allFinite()) return c;
    // An iterative solve leaves at most 1 % of the tolerance in the linear residual, so the
    // Newton iterates, their count and the converged points are those of an exact solve.
    const double target = 0.01 * tolerance;
    Eigen::VectorXd delta = Eigen::VectorXd::Zero(n + 1);
    if (t.size()) {
      Eigen::VectorXd rhs(n + 1);
      rhs << R, arc;
      delta = algebra.solve(t, rhs, target);
    } else {
      delta.head(n) = algebra.solve(Eigen::VectorXd(), R, target);
    }
    if (!delta.allFinite()) return c;
    // The full step is evaluated with its linearization (it is usually taken, and is then the
    // next Newton point); the line search's halvings without, and the one taken is linearized.
    double alpha = 1.0;
    Eigen::VectorXd trial = z - delta;
    Eigen::VectorXd R_trial = algebra.residual(trial, true);
    int halvings = 0;
    for (; halvings < 4 && !(R_trial.norm() < c.residual); ++halvings) {
      alpha *= 0.5;
      trial = z - alpha * delta;
      R_trial = algebra.residual(trial, false);
    }
    z = trial;
    R = halvings == 0 ? std::move(R_trial) : algebra.residual(z, true);
  }
}

// A Newton iterate in a state the elements refuse (NumericalError: a squeeze-film journal at or
// beyond its clearance, a non-finite motion) is a failed correction, not a failed analysis: the
// continuation then halves its step, and a start point reports no solution.
Corrected correct(const Scaled& p, NewtonAlgebra& algebra, Eigen::VectorXd& z,
                  const Eigen::VectorXd& t, const Eigen::VectorXd& z0, int max_iterations) {
  try {
    return correct_unguarded(p, algebra, z, t, z0, max_iterations);
  } catch (const NumericalError&) {
    Corrected c;
    c.residual = std::numeric_limits<double>::infinity();
    return c;
  }
}

// Newton on [R(z); (|z - c|^2 - r^2) / (2 r)] = 0: the point of the curve at distance r from c
// (Crisfield's spherical constraint), bordered by the row (z - c)^T / r. Used where the plane
// constraint fails: a non-smooth fold (a contact that grazes) turns the curve back by more than
// 90 degrees, so the plane normal to the tangent misses the new branch while the sphere meets it.
Corrected correct_on_sphere(const Scaled& p, NewtonAlgebra& algebra, Eigen::VectorXd& z,
                            const Eigen::VectorXd& c, double r, int max_iterations) {
  const int n = p.size();
  Corrected out;
  Eigen::VectorXd R = algebra.residual(z, true);
  for (;; ++out.iterations) {
    const double g = ((z - c).squaredNorm() - r * r) / (2.0 * r);
    out.residual = R.norm();
    if (out.residual <= p.tolerance(z) && std::abs(g) <= 1e-12 * std::max(1.0, z.norm())) {
      out.converged = true;
      return out;
    }
    if (out.iterations >= max_iterations || !R.allFinite()) return out;
    Eigen::VectorXd rhs(n + 1);
    rhs << R, g;
    const Eigen::VectorXd delta = algebra.solve((z - c) / r, rhs, 0.01 * p.tolerance(z));
    if (!delta.allFinite()) return out;
    z -= delta;
    R = algebra.residual(z, true);
  }
}

// After the plane corrector failed at the smallest step from y (previous point y_before): the
// point at distance r (growing radii) on the sphere about y, searched from y + r t, that does
// not lie back along the segment y_before -> y. True and z set when found.
bool turn_sharp_fold(const Scaled& p, NewtonAlgebra& algebra, const Eigen::VectorXd& y,
                     const Eigen::VectorXd& y_before, const Eigen::VectorXd& t, int max_iterations,
                     double min_step, Eigen::VectorXd& z, double& radius, Corrected& used) {
  const Eigen::VectorXd back = (y_before - y).normalized();
  for (double r = 10.0 * min_step; r <= 1e-2; r *= 10.0) {
    for (const double side : {1.0, -1.0}) {
      // Start ahead along the tangent, or across it (the new branch may leave on either side).
      Eigen::VectorXd guess = y + r * t;
      if (side < 0.0) {
        Eigen::VectorXd normal = back - back.dot(t) * t;
        if (normal.norm() < 1e-12) continue;
        guess = y - r * normal.normalized();
      }
      z = guess;
      used = correct_on_sphere(p, algebra, z, y, r, max_iterations);
      if (used.converged && (z - y).normalized().dot(back) < 0.9) {
        radius = r;
        return true;
      }
    }
  }
  return false;
}

}  // namespace

ContinuationResult continue_in_frequency(const HarmonicSystem& hb, const Eigen::VectorXd& X0,
                                         const ContinuationOptions& o) {
  ContinuationResult out;
  const int n = hb.size();
  if (X0.size() != n)
    throw InputError({}, "X0", fmt::format("{} coefficients", n), std::to_string(X0.size()));
  if (!(o.step > 0.0 && o.min_step > 0.0 && o.max_step >= o.step && o.omega_end != o.omega_start &&
        o.x_scale > 0.0 && o.omega_scale > 0.0))
    throw InputError(
        {}, "continuation",
        "0 < min_step, 0 < step <= max_step, omega_end != omega_start and positive "
        "scales",
        fmt::format("step {}, min {}, max {}, omega {} .. {}, scales {} and {}", o.step, o.min_step,
                    o.max_step, o.omega_start, o.omega_end, o.x_scale, o.omega_scale));
  const double direction = o.omega_end > o.omega_start ? 1.0 : -1.0;
  const Scaled p(hb, o);
  const std::unique_ptr<NewtonAlgebra> algebra = newton_algebra(hb, p);

  // First point: Newton in X at omega_start.
  Eigen::VectorXd y = p.pack(X0, o.omega_start);
  Corrected c = correct(p, *algebra, y, Eigen::VectorXd(), y, o.max_iterations);
  if (!c.converged) {
    out.status = Status::NotConverged;
    out.message = fmt::format(
        "no periodic solution found at the start frequency {:.6g}: residual {:.3e} after {} "
        "Newton iterations; start from a better guess or a frequency away from resonance",
        o.omega_start, c.residual, c.iterations);
    return out;
  }
  out.points.push_back({o.omega_start, p.X(y), c.iterations, c.residual, 0});

  Eigen::VectorXd t_prev = Eigen::VectorXd::Unit(n + 1, n) * direction;
  Eigen::VectorXd t = tangent(p, *algebra, t_prev);
  bool t_is_tangent = true;  // false: t is the secant of the last two points
  double step = o.step;
  Eigen::VectorXd y_before = y - o.step * t;  // the previous point (a guess at the start)
  while (static_cast<int>(out.points.size()) < o.max_points) {
    const Eigen::VectorXd predicted = y + step * t;
    Eigen::VectorXd z = predicted;
    c = correct(p, *algebra, z, t, predicted, o.max_iterations);
    // A corrector that lands farther from its predictor than the step (more than 45 degrees off
    // the tangent) has left the branch for another part of the curve: a smaller step.
    if (c.converged && (z - predicted).norm() > step) c.converged = false;
    if (!c.converged) {
      step *= 0.5;
      if (!t_is_tangent) {  // a refused step from a secant: the tangent at y from now on
        algebra->residual(y, true);
        t = tangent(p, *algebra, t);
        t_is_tangent = true;
      }
      double radius = 0.0;
      Corrected turned;
      if (step < o.min_step && turn_sharp_fold(p, *algebra, y, y_before, t, o.max_iterations,
                                               o.min_step, z, radius, turned)) {
        t = tangent(p, *algebra, (z - y).normalized());
        t_is_tangent = true;
        y_before = y;
        y = z;
        out.points.push_back({p.omega(y), p.X(y), turned.iterations, turned.residual, 0});
        step = radius;
        if (direction * (p.omega(y) - o.omega_end) >= 0.0) break;
        continue;
      }
      if (step < o.min_step) {
        out.status = Status::NotConverged;
        out.message = fmt::format(
            "continuation stopped at frequency {:.8g}: the corrector did not converge at the "
            "smallest step {:.1e} (residual {:.3e} after {} iterations); a bifurcation or a "
            "non-smooth point is likely there -- lower min_step, raise max_iterations or the "
            "number of time samples",
            p.omega(y), o.min_step, c.residual, c.iterations);
        return out;
      }
      continue;
    }
    // The corrector's last bordered matrix [A(z); t^T] (t along the direction of travel) gives
    // the branch-point test function's sign at z; read before the tangent solve replaces it.
    const int corrected_sign = c.iterations > 0 ? algebra->bordered_sign() : 0;
    // Secant predictor: the chord just traced, unless it turned from the direction followed by
    // more than acos(kSecantAlignment) (the curve bends: near a turning point or a corner), where
    // the tangent at the new point (the algebra holds its linearization) is solved for.
    const Eigen::VectorXd chord = (z - y).normalized();
    if (algebra->prefers_secant() && chord.dot(t) >= kSecantAlignment) {
      t = chord;
      t_is_tangent = false;
    } else {
      t = tangent(p, *algebra, t);
      t_is_tangent = true;
    }
    y_before = y;
    y = z;
    out.points.push_back({p.omega(y), p.X(y), c.iterations, c.residual, corrected_sign});
    if (direction * (p.omega(y) - o.omega_end) >= 0.0) break;
    if (direction * (p.omega(y) - o.omega_start) < -0.1 * std::abs(o.omega_end - o.omega_start)) {
      out.status = Status::NotConverged;
      out.message = fmt::format(
          "the curve turned back and left the range below its start (at {:.8g}): it folds "
          "over the whole range, or a smaller max_step is needed to follow it",
          p.omega(y));
      return out;
    }
    if (c.iterations <= 3)
      step = std::min(1.5 * step, o.max_step);
    else if (c.iterations > 6)
      step *= 0.5;
  }
  if (direction * (p.omega(y) - o.omega_end) < 0.0) {
    out.status = Status::NotConverged;
    out.message = fmt::format("continuation reached max_points = {} at frequency {:.8g}",
                              o.max_points, p.omega(y));
  }
  out.branch_points = branch_points(out.points);
  return out;
}

std::vector<int> branch_points(const std::vector<ContinuationPoint>& points) {
  std::vector<int> found;
  int last = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int s = points[i].test_sign;
    if (s == 0) continue;
    if (last != 0 && s != last) found.push_back(static_cast<int>(i));
    last = s;
  }
  return found;
}

}  // namespace geardyn::hbm
