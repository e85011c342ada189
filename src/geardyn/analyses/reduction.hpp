#pragma once
// reduction: how well a Craig-Bampton (or Guyan) reduction of a solid reproduces its full-model
// frequencies, and the reduced component file to use in place of the mesh.
//
// Craig-Bampton / Guyan reduction: reduced vs full frequencies, convergence as modes are added,
// the reduced-component file (.h5): run_reduction reduces the solid (from context.solid) and
// solves the full-model reference modes, reduction_output writes tables, plots, notes and the
// file. Numerical failures throw NumericalError (the caller reports the analysis as failed); bad
// input throws InputError.
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/solid_common.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/reduce/craig_bampton.hpp"

namespace geardyn::analyses {

/// Craig-Bampton (or Guyan) reduction of a solid: reduced vs full frequencies, a convergence
/// table, and the reduced component file.
struct ReductionSettings : model::SettingsOf<ReductionSettings> {
  std::string solid;
  ReductionMethod method = ReductionMethod::CraigBampton;
  std::vector<std::string> master_sets;
  int n_modes = 20;              ///< fixed-interface modes kept
  double f_max = model::kNaN;    ///< ... or all up to this [rad/s]
  int compare_modes = 10;        ///< full-model modes compared
  std::vector<int> convergence;  ///< mode counts of the convergence table (empty: automatic)
  bool save = true;              ///< write <analysis>.h5
};

/// The reduced component and how well it reproduces the full model's frequencies.
struct ReductionResult {
  std::shared_ptr<const reduce::ReducedComponent> reduced;
  int master_dofs = 0;                  ///< physical master DOFs (of the master sets)
  eig::SymmetricEigenResult full;       ///< the full-model reference modes
  Eigen::VectorXd reduced_eigenvalues;  ///< of the reduced model [rad^2/s^2], ascending
  /// Per compared mode (the first min(compare_modes, reduced size)): full and reduced
  /// frequency [Hz] and error 100 (reduced - full) / full [%].
  std::vector<double> full_hz, reduced_hz, error_pct;
  double max_error_pct = 0.0;  ///< largest |error_pct|
  /// Fixed-interface modes asked for (reduced_modes) beyond the interior DOFs: all interior
  /// modes are kept instead; 0 when the request fitted.
  int modes_asked_beyond_interior = 0;
};

ReductionResult run_reduction(const model::Model& model, const ReductionSettings& settings,
                              const Context& context);

AnalysisOutput reduction_output(const model::Model& model, const ReductionSettings& settings,
                                const ReductionResult& result, const Context& context);

}  // namespace geardyn::analyses
