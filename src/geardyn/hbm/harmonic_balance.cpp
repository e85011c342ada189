// GCC's -Wnull-dereference false positive inside Eigen's inlined code (see
// linalg/sparse_factorization.cpp): the pragma must precede the first include of Eigen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <Eigen/Dense>
#pragma GCC diagnostic pop

#include <fmt/format.h>

#include <cmath>
#include <utility>

#include "geardyn/core/error.hpp"
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

namespace {

// Unit tangent of R(X, omega) = 0 at y, oriented along `previous`.
Eigen::VectorXd tangent(const Eigen::MatrixXd& J, const Eigen::VectorXd& dR_domega,
                        const Eigen::VectorXd& previous) {
  const auto n = J.rows();
  Eigen::MatrixXd A(n + 1, n + 1);
  A.topLeftCorner(n, n) = J;
  A.topRightCorner(n, 1) = dR_domega;
  A.bottomRows(1) = previous.transpose();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + 1);
  rhs[n] = 1.0;
  Eigen::VectorXd t = A.partialPivLu().solve(rhs);
  t.normalize();
  if (t.dot(previous) < 0.0) t = -t;
  return t;
}

}  // namespace

ContinuationResult continue_in_frequency(const HarmonicBalance& hb, const Eigen::VectorXd& X0,
                                         const ContinuationOptions& o) {
  ContinuationResult out;
  const int n = hb.size();
  if (X0.size() != n)
    throw InputError({}, "X0", fmt::format("{} coefficients", n), std::to_string(X0.size()));
  if (!(o.step > 0.0 && o.min_step > 0.0 && o.max_step >= o.step && o.omega_end != o.omega_start))
    throw InputError({}, "continuation",
                     "0 < min_step, 0 < step <= max_step and omega_end != omega_start",
                     fmt::format("step {}, min {}, max {}, omega {} .. {}", o.step, o.min_step,
                                 o.max_step, o.omega_start, o.omega_end));
  const double direction = o.omega_end > o.omega_start ? 1.0 : -1.0;
  const double tol = o.tolerance * std::max(1.0, hb.external_force().norm());

  // First point: Newton in X at omega_start.
  Eigen::VectorXd X = X0;
  Eigen::MatrixXd J;
  Eigen::VectorXd dRw;
  int it = 0;
  Eigen::VectorXd R = hb.residual(X, o.omega_start, &J, &dRw);
  while (R.norm() > tol && it < o.max_iterations) {
    X -= J.partialPivLu().solve(R);
    R = hb.residual(X, o.omega_start, &J, &dRw);
    ++it;
  }
  if (!(R.norm() <= tol)) {
    out.status = Status::NotConverged;
    out.message = fmt::format(
        "no periodic solution found at the start frequency {:.6g}: residual {:.3e} after {} "
        "Newton iterations; start from a better guess or a frequency away from resonance",
        o.omega_start, R.norm(), it);
    return out;
  }
  out.points.push_back({o.omega_start, X, it, R.norm()});

  Eigen::VectorXd y(n + 1);
  y << X, o.omega_start;
  Eigen::VectorXd t_prev = Eigen::VectorXd::Zero(n + 1);
  t_prev[n] = direction;
  Eigen::VectorXd t = tangent(J, dRw, t_prev);
  double step = o.step;
  while (static_cast<int>(out.points.size()) < o.max_points) {
    const Eigen::VectorXd predicted = y + step * t;
    Eigen::VectorXd z = predicted;
    bool converged = false;
    int iterations = 0;
    double res = 0.0;
    for (; iterations < o.max_iterations; ++iterations) {
      R = hb.residual(z.head(n), z[n], &J, &dRw);
      const double arc = t.dot(z - predicted);
      res = R.norm();
      if (res <= tol && std::abs(arc) <= 1e-12 * std::max(1.0, z.norm())) {
        converged = true;
        break;
      }
      Eigen::MatrixXd A(n + 1, n + 1);
      A.topLeftCorner(n, n) = J;
      A.topRightCorner(n, 1) = dRw;
      A.bottomRows(1) = t.transpose();
      Eigen::VectorXd rhs(n + 1);
      rhs << R, arc;
      z -= A.partialPivLu().solve(rhs);
      if (!z.allFinite()) break;
    }
    if (!converged) {
      step *= 0.5;
      if (step < o.min_step) {
        out.status = Status::NotConverged;
        out.message = fmt::format(
            "continuation stopped at frequency {:.8g}: the corrector did not converge at the "
            "smallest step {:.1e} (residual {:.3e} after {} iterations); a bifurcation or a "
            "non-smooth point is likely there -- lower min_step or raise max_iterations",
            y[n], o.min_step, res, iterations);
        return out;
      }
      continue;
    }
    const Eigen::VectorXd t_new = tangent(J, dRw, t);
    y = z;
    t = t_new;
    out.points.push_back({y[n], y.head(n), iterations, res});
    if (direction * (y[n] - o.omega_end) >= 0.0) break;
    if (iterations <= 3)
      step = std::min(1.5 * step, o.max_step);
    else if (iterations > 6)
      step *= 0.5;
  }
  if (direction * (y[n] - o.omega_end) < 0.0) {
    out.status = Status::NotConverged;
    out.message =
        fmt::format("continuation reached max_points = {} at frequency {:.8g}", o.max_points, y[n]);
  }
  return out;
}

}  // namespace geardyn::hbm
