#include "geardyn/assembly/modal_damping.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "geardyn/core/error.hpp"
#include "geardyn/eig/rigid_body.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/fe/dof_map.hpp"

namespace geardyn::assembly {

double modal_damping_ratio(const model::Damping& damping, int elastic_index, double omega) {
  if (elastic_index >= 0 && static_cast<std::size_t>(elastic_index) < damping.modal_ratios.size())
    return damping.modal_ratios[static_cast<std::size_t>(elastic_index)];
  for (const auto& band : damping.bands)
    if (omega >= band.f_min && omega < band.f_max) return band.ratio;
  return damping.modal_ratio;
}

namespace {

void check_ratio(double ratio, const std::string& key) {
  if (!(std::isfinite(ratio) && ratio >= 0.0))
    throw InputError({}, key, "a finite damping ratio >= 0", fmt::format("{}", ratio));
}

}  // namespace

ModalDampingSummary apply_modal_damping(const model::Model& model, fe::LinearSystem& system,
                                        const ModalDampingOptions& options) {
  system.modal_basis.resize(0, 0);
  system.modal_coefficients.resize(0);
  ModalDampingSummary summary;
  const model::Damping& damping = model.damping;
  if (!damping.any_modal() || system.size() == 0) return summary;
  check_ratio(damping.modal_ratio, "damping.modal_ratio");
  for (std::size_t i = 0; i < damping.modal_ratios.size(); ++i)
    check_ratio(damping.modal_ratios[i], fmt::format("damping.modal_ratios[{}]", i));
  for (std::size_t i = 0; i < damping.bands.size(); ++i)
    check_ratio(damping.bands[i].ratio, fmt::format("damping.bands[{}].ratio", i));

  int wanted = options.n_modes;
  if (wanted <= 0) wanted = damping.modal_modes;
  if (wanted <= 0) wanted = std::max(20, 2 * static_cast<int>(damping.modal_ratios.size()));
  // A singular M (massless DOFs, e.g. a massless shaft) has only rank(M) finite modes: as many
  // as the DOFs whose row of M is not zero.
  std::vector<bool> has_mass(static_cast<std::size_t>(system.size()), false);
  for (int k = 0; k < system.M.outerSize(); ++k)
    for (fe::SparseMatrix::InnerIterator it(system.M, k); it; ++it)
      if (it.value() != 0.0) has_mass[static_cast<std::size_t>(it.row())] = true;
  const int finite = static_cast<int>(std::count(has_mass.begin(), has_mass.end(), true));
  const int limit = std::max(1, finite);
  wanted = std::min(wanted, limit);

  eig::SymmetricEigenOptions eo;
  eo.n_modes = wanted;
  eo.method = options.method;
  const auto K0 = system.K_at(0.0);
  const eig::SymmetricEigenResult modes = solve_symmetric(K0, system.M, eo);
  // The sparse solver returns at most n - 1 pairs; that is enough when all were asked for.
  const bool all_but_one =
      modes.status == Status::FewerModes && wanted == limit && modes.converged == limit - 1;
  if (modes.status != Status::Ok && modes.status != Status::NotConverged && !all_but_one)
    throw NumericalError("modal damping",
                         fmt::format("the {} undamped modes at zero speed that carry the modal "
                                     "damping could not be computed: {} ({}); reduce "
                                     "damping.modal_modes or check supports",
                                     wanted, modes.message, to_string(modes.status)));
  if (modes.status == Status::NotConverged)
    throw NumericalError(
        "modal damping",
        fmt::format("undamped modes at zero speed are inaccurate: {}", modes.message));

  // Rigid-body modes carry no damping. Decided by the mode's shape (its kinetic energy in the
  // space of rigid motions K leaves unstrained, eig/rigid_body.hpp), not by a limit on omega^2:
  // the rounding of a zero eigenvalue grows with mesh refinement and would pass real modes of a
  // fine mesh, which then got no damping at all.
  const eig::RigidBodySpace rigid =
      eig::rigid_body_space(K0, system.M, fe::rigid_body_candidates(system.dofs));
  constexpr double kRigidEnergyFraction = 0.99;  // as the modal analysis labels modes rigid

  const Eigen::Index m = modes.eigenvalues.size();
  system.modal_coefficients.resize(m);
  int elastic = 0;
  for (Eigen::Index r = 0; r < m; ++r) {
    const double lambda = modes.eigenvalues[r];
    const Eigen::VectorXcd shape = modes.eigenvectors.col(r).cast<std::complex<double>>();
    if (lambda <= 0.0 || eig::rigid_body_fraction(rigid, system.M, shape) >= kRigidEnergyFraction) {
      system.modal_coefficients[r] = 0.0;
      ++summary.rigid_body_modes;
      continue;
    }
    const double omega = std::sqrt(lambda);
    system.modal_coefficients[r] = 2.0 * modal_damping_ratio(damping, elastic, omega) * omega;
    ++elastic;
  }
  system.modal_basis = system.M * modes.eigenvectors;
  summary.modes = static_cast<int>(m);
  summary.highest_frequency =
      m > 0 ? std::sqrt(std::max(modes.eigenvalues[m - 1], 0.0)) : eig::kNaN;
  summary.max_residual = modes.max_residual();
  return summary;
}

void apply_modal_damping(const model::Model& model, fe::LinearSystem& system) {
  apply_modal_damping(model, system, ModalDampingOptions{});
}

}  // namespace geardyn::assembly
