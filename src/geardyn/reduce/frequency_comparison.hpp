#pragma once
// Reduced-versus-full checks as geardyn::Table (written as CSV and shown in the report).
#include <Eigen/Dense>
#include <vector>

#include "geardyn/core/table.hpp"
#include "geardyn/reduce/reduced_component.hpp"

namespace geardyn::reduce {

/// Natural frequency [Hz] of an eigenvalue lambda = omega^2 [rad^2/s^2]; negative round-off of a
/// rigid-body mode gives 0.
double frequency_hz(double lambda);

/// Signed relative error of a reduced frequency [%]: 100 (f_reduced - f_full) / max(f_full,
/// floor_hz). The floor keeps rigid-body modes (f_full = 0) finite: their "error" is the reduced
/// frequency over the floor.
double frequency_error_pct(double full_hz, double reduced_hz, double floor_hz);

/// Table "reduction_frequencies", columns mode (1-based), full_hz, reduced_hz, error_pct, one
/// row per mode up to the shorter of the two lists. Eigenvalues in rad^2/s^2, ascending.
/// Craig-Bampton is a Rayleigh-Ritz method, so its errors are >= 0 up to round-off.
Table compare_frequencies(const Eigen::VectorXd& full_eigenvalues,
                          const Eigen::VectorXd& reduced_eigenvalues, double floor_hz = 1e-3);

/// Convergence of Craig-Bampton as modes are added: for each count in `n_modes_list` (each
/// <= rc.n_modal), the component truncated to that many modes (nested mode sets, see
/// truncate()) is solved with the masters `fixed_masters` held, and its first `n_compare`
/// frequencies are compared with `full_eigenvalues` (the full model with the same masters held).
/// Table "reduction_convergence", columns n_modes, reduced_size, max_error_pct (largest |error|
/// over the first n_compare modes), worst_mode (the mode where it occurs, 1-based). Because the
/// mode sets are nested, each reduced eigenvalue can only fall as modes are added (Rayleigh-Ritz
/// on nested subspaces), so max_error_pct does not grow down the table.
/// Throws InputError when a count is out of range or n_compare exceeds what both sides have.
Table convergence_table(const ReducedComponent& rc, const Eigen::VectorXd& full_eigenvalues,
                        const std::vector<int>& n_modes_list, int n_compare,
                        const std::vector<int>& fixed_masters = {}, double floor_hz = 1e-3);

}  // namespace geardyn::reduce
