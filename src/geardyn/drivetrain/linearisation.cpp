#include "geardyn/drivetrain/linearisation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "geardyn/eig/quadratic_eigen.hpp"

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

}  // namespace

Linearisation linearise(DrivetrainSystem& system, double t, const Eigen::VectorXd& q,
                        const Eigen::VectorXd& v, int n_modes) {
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
  if (m == 0) return lin;
  eig::QuadraticPencil pencil{lin.M, lin.C, lin.K, lin.low_rank_basis, lin.low_rank_coefficients};
  eig::QuadraticEigenOptions options;
  options.n_modes = std::min(std::max(1, n_modes), 2 * m);
  const eig::QuadraticEigenResult r = eig::solve_quadratic(pencil, options);
  lin.solver = r.brief_report();
  lin.max_residual = r.max_residual();
  if (r.status != Status::Ok && r.eigenvalues.size() == 0) {
    lin.status = r.status;
    lin.message = "linearisation: " + r.message;
    return lin;
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
  return lin;
}

}  // namespace geardyn::drivetrain
