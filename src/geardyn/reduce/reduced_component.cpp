#include "geardyn/reduce/reduced_component.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "geardyn/core/error.hpp"

namespace geardyn::reduce {

std::vector<solid::DofInfo> ReducedComponent::reduced_dofs() const {
  std::vector<solid::DofInfo> out = masters;
  for (int k = 0; k < n_modal; ++k) {
    solid::DofInfo d;
    d.node_id = k + 1;
    d.component = -1;
    out.push_back(d);
  }
  return out;
}

Eigen::MatrixXd expand(const ReducedComponent& rc, const Eigen::MatrixXd& q) {
  if (q.rows() != rc.size())
    throw InputError({}, "reduce.expand.q",
                     fmt::format("{} rows (masters + modal coordinates)", rc.size()),
                     fmt::format("{} rows", q.rows()));
  const Eigen::Index nb = rc.n_masters();
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(rc.n_full(), q.cols());
  const Eigen::MatrixXd qb = q.topRows(nb);
  Eigen::MatrixXd xi = rc.Psi * qb;
  if (rc.n_modal > 0) xi += rc.Phi * q.bottomRows(rc.n_modal);
  for (Eigen::Index k = 0; k < nb; ++k)
    x.row(rc.master_index[static_cast<std::size_t>(k)]) = qb.row(k);
  for (Eigen::Index j = 0; j < xi.rows(); ++j)
    x.row(rc.interior_index[static_cast<std::size_t>(j)]) = xi.row(j);
  return x;
}

Eigen::MatrixXd recovery_matrix(const ReducedComponent& rc) {
  return expand(rc, Eigen::MatrixXd::Identity(rc.size(), rc.size()));
}

ReducedComponent truncate(const ReducedComponent& rc, int n_modes) {
  if (n_modes < 0 || n_modes > rc.n_modal)
    throw InputError({}, "reduce.truncate.n_modes", fmt::format("0 .. {}", rc.n_modal),
                     std::to_string(n_modes));
  ReducedComponent out = rc;
  const Eigen::Index m = rc.n_masters() + n_modes;
  out.K = rc.K.topLeftCorner(m, m);
  out.M = rc.M.topLeftCorner(m, m);
  out.n_modal = n_modes;
  out.fixed_interface_hz = rc.fixed_interface_hz.head(n_modes);
  out.Phi = rc.Phi.leftCols(n_modes);
  if (n_modes == 0) out.provenance.method = "guyan";
  return out;
}

Eigen::VectorXd reduced_eigenvalues(const ReducedComponent& rc,
                                    const std::vector<int>& fixed_masters) {
  std::vector<bool> fixed(static_cast<std::size_t>(rc.size()), false);
  for (int f : fixed_masters) {
    if (f < 0 || f >= rc.n_masters())
      throw InputError({}, "reduce.reduced_eigenvalues.fixed_masters",
                       fmt::format("master indices 0 .. {}", rc.n_masters() - 1),
                       std::to_string(f));
    fixed[static_cast<std::size_t>(f)] = true;
  }
  std::vector<Eigen::Index> keep;
  for (Eigen::Index k = 0; k < rc.size(); ++k)
    if (!fixed[static_cast<std::size_t>(k)]) keep.push_back(k);
  const auto n = static_cast<Eigen::Index>(keep.size());
  Eigen::MatrixXd K(n, n), M(n, n);
  for (Eigen::Index c = 0; c < n; ++c)
    for (Eigen::Index r = 0; r < n; ++r) {
      K(r, c) = rc.K(keep[static_cast<std::size_t>(r)], keep[static_cast<std::size_t>(c)]);
      M(r, c) = rc.M(keep[static_cast<std::size_t>(r)], keep[static_cast<std::size_t>(c)]);
    }
  if (n == 0) return {};
  const Eigen::LLT<Eigen::MatrixXd> mass_llt(M);
  if (mass_llt.info() != Eigen::Success)
    throw NumericalError("reduced_eigenvalues",
                         "the reduced mass matrix is not positive definite (a master or modal "
                         "coordinate without mass); check the masters and the model's mass");
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(K, M, Eigen::EigenvaluesOnly);
  if (ges.info() != Eigen::Success)
    throw NumericalError("reduced_eigenvalues",
                         "dense symmetric eigen-solver (QR iteration) did not converge on the "
                         "reduced pair");
  return ges.eigenvalues();
}

}  // namespace geardyn::reduce
