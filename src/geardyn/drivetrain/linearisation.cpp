#include "geardyn/drivetrain/linearisation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/eig/quadratic_eigen.hpp"
#include "geardyn/linalg/sparse_factorization.hpp"

namespace geardyn::drivetrain {
namespace {

/// The block of A over the free equations (rows and columns).
SparseMatrix free_block(const SparseMatrix& A, const std::vector<int>& position, int m) {
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < A.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(A, j); it; ++it) {
      const int r = position[static_cast<std::size_t>(it.row())];
      const int c = position[static_cast<std::size_t>(it.col())];
      if (r >= 0 && c >= 0) t.emplace_back(r, c, it.value());
    }
  SparseMatrix out(m, m);
  out.setFromTriplets(t.begin(), t.end());
  return out;
}

/// Eigenvalues closer than this, relative to |lambda|, form one cluster (a repeated root, e.g.
/// two equal planes of a symmetric shaft at rest): their left vectors are taken together.
constexpr double kClusterTolerance = 1e-6;
/// A left eigenvalue matches a right one within this, relative to |lambda|: both solves are
/// backward stable to the solver's residual limit (1e-8), so a simple root agrees to far less.
constexpr double kMatchTolerance = 1e-5;

/// P'(lambda) x = (2 lambda M + D) x over the free equations.
Eigen::VectorXcd derivative_times(const eig::QuadraticPencil& p, std::complex<double> l,
                                  const Eigen::VectorXcd& x) {
  return 2.0 * l * linalg::multiply(p.M, x) + p.apply_damping(x);
}

/// The left eigenvectors of lin.modes from the transposed pencil's modes (the same eigenvalues):
/// per cluster of equal right eigenvalues, the same number of nearest left ones; Y is scaled by
/// G^{-T}, G = Y^T P'(lambda) X, so that the left and right vectors are biorthonormal in P'.
void left_eigenvectors(Linearisation& lin, const eig::QuadraticPencil& pencil,
                       const eig::QuadraticEigenOptions& options, int n) {
  const SparseMatrix Mt = pencil.M.transpose(), Ct = pencil.C.transpose(),
                     Kt = pencil.K.transpose();
  const eig::QuadraticPencil transposed{Mt, Ct, Kt, pencil.low_rank_basis,
                                        pencil.low_rank_coefficients};
  const eig::QuadraticEigenResult r = eig::solve_quadratic(transposed, options);
  const auto m = static_cast<Eigen::Index>(lin.free.size());
  std::vector<bool> used(static_cast<std::size_t>(r.eigenvalues.size()), false);
  std::vector<bool> done(lin.modes.size(), false);
  for (std::size_t k0 = 0; k0 < lin.modes.size(); ++k0) {
    if (done[k0]) continue;
    const std::complex<double> l0 = lin.modes[k0].eigenvalue;
    const double tol = kClusterTolerance * std::abs(l0);
    std::vector<std::size_t> cluster;
    for (std::size_t k = k0; k < lin.modes.size(); ++k)
      if (!done[k] && std::abs(lin.modes[k].eigenvalue - l0) <= tol) {
        cluster.push_back(k);
        done[k] = true;
      }
    const auto c = static_cast<Eigen::Index>(cluster.size());
    std::vector<Eigen::Index> pick;
    for (Eigen::Index j = 0; j < c; ++j) {
      Eigen::Index best = -1;
      for (Eigen::Index i = 0; i < r.eigenvalues.size(); ++i)
        if (!used[static_cast<std::size_t>(i)] &&
            (best < 0 || std::abs(r.eigenvalues[i] - l0) < std::abs(r.eigenvalues[best] - l0)))
          best = i;
      if (best < 0 ||
          std::abs(r.eigenvalues[best] - l0) > std::max(kMatchTolerance * std::abs(l0), 2.0 * tol))
        break;
      used[static_cast<std::size_t>(best)] = true;
      pick.push_back(best);
    }
    Eigen::MatrixXcd X(m, c), Y(m, c), PX(m, c);
    for (Eigen::Index j = 0; j < c; ++j) {
      for (Eigen::Index i = 0; i < m; ++i)
        X(i, j) = lin.modes[cluster[static_cast<std::size_t>(j)]]
                      .shape[lin.free[static_cast<std::size_t>(i)]];
      PX.col(j) = derivative_times(pencil, l0, X.col(j));
    }
    bool ok = static_cast<Eigen::Index>(pick.size()) == c;
    Eigen::MatrixXcd Ys;
    if (ok) {
      for (Eigen::Index j = 0; j < c; ++j)
        Y.col(j) = r.eigenvectors.col(pick[static_cast<std::size_t>(j)]);
      const Eigen::MatrixXcd G = Y.transpose() * PX;
      const Eigen::FullPivLU<Eigen::MatrixXcd> lu(G);
      ok = lu.rank() == c;
      if (ok) Ys = Y * lu.inverse().transpose();
    }
    for (Eigen::Index j = 0; j < c; ++j) {
      LinearMode& mode = lin.modes[cluster[static_cast<std::size_t>(j)]];
      if (!ok) {
        ++lin.unmatched_left;
        continue;
      }
      mode.left = Eigen::VectorXcd::Zero(n);
      for (Eigen::Index i = 0; i < m; ++i)
        mode.left[lin.free[static_cast<std::size_t>(i)]] = Ys(i, j);
    }
  }
  lin.has_left = lin.unmatched_left == 0;
}

}  // namespace

void solve_linear_modes(Linearisation& lin, int n, int n_modes, bool left) {
  lin.equations = n;
  const int m = static_cast<int>(lin.free.size());
  if (m == 0) return;
  eig::QuadraticPencil pencil{lin.M, lin.C, lin.K, lin.low_rank_basis, lin.low_rank_coefficients};
  eig::QuadraticEigenOptions options;
  options.n_modes = std::min(std::max(1, n_modes), 2 * m);
  const eig::QuadraticEigenResult r = eig::solve_quadratic(pencil, options);
  lin.solver = r.brief_report();
  lin.max_residual = r.max_residual();
  if (r.status != Status::Ok && r.eigenvalues.size() == 0) {
    lin.status = r.status;
    lin.message = "linearisation: " + r.message;
    return;
  }
  double scale = 1.0;
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k)
    scale = std::max(scale, std::abs(r.eigenvalues[k]));
  for (Eigen::Index k = 0; k < r.eigenvalues.size(); ++k) {
    const std::complex<double> l = r.eigenvalues[k];
    const double mag = std::abs(l);
    // Rigid-body roots (a free spin not held by a driver): lambda = 0 to round-off.
    if (mag < 1e-6 * scale && mag < 1e-3) {
      ++lin.rigid_body_modes;
      continue;
    }
    LinearMode mode;
    mode.eigenvalue = l;
    mode.natural_frequency_hz = mag / (2.0 * M_PI);
    mode.damping_ratio = -l.real() / mag;
    mode.real_hz = l.real() / (2.0 * M_PI);
    mode.imag_hz = l.imag() / (2.0 * M_PI);
    if (l.real() > 1e-9 * mag) ++lin.unstable_modes;
    mode.shape = Eigen::VectorXcd::Zero(n);
    for (int i = 0; i < m; ++i)
      mode.shape[lin.free[static_cast<std::size_t>(i)]] = r.eigenvectors(i, k);
    lin.modes.push_back(std::move(mode));
  }
  if (left) left_eigenvectors(lin, pencil, options, n);
  if (r.status != Status::Ok) {
    lin.status = r.status;
    lin.message = "linearisation: " + r.message;
  } else if (lin.unstable_modes > 0) {
    lin.status = Status::Unstable;
    lin.message = fmt::format(
        "{} mode(s) of the linearised drivetrain have negative damping (Re lambda > 0): the "
        "operating point is unstable",
        lin.unstable_modes);
  }
}

Linearisation linearise(DrivetrainSystem& system, double t, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v, int n_modes, bool left) {
  Linearisation lin;
  const int n = system.size();
  std::vector<int> position(static_cast<std::size_t>(n), 0);
  for (int e : system.held_equations()) position[static_cast<std::size_t>(e)] = -1;
  for (int i = 0; i < n; ++i)
    if (position[static_cast<std::size_t>(i)] == 0) {
      position[static_cast<std::size_t>(i)] = static_cast<int>(lin.free.size());
      lin.free.push_back(i);
    }
  const int m = static_cast<int>(lin.free.size());
  SparseMatrix S;
  system.tangent(t, q, v, 0.0, 0.0, 1.0, S);
  lin.K = free_block(S, position, m);
  system.tangent(t, q, v, 0.0, 1.0, 0.0, S);
  lin.C = free_block(S, position, m);
  lin.M = free_block(system.mass(), position, m);
  Eigen::MatrixXd U;
  Eigen::VectorXd d;
  if (system.tangent_low_rank(t, q, v, 0.0, 1.0, 0.0, U, d)) {
    lin.low_rank_basis.resize(m, U.cols());
    for (int i = 0; i < m; ++i)
      lin.low_rank_basis.row(i) = U.row(lin.free[static_cast<std::size_t>(i)]);
    lin.low_rank_coefficients = d;
  }
  solve_linear_modes(lin, n, n_modes, left);
  return lin;
}

}  // namespace geardyn::drivetrain
