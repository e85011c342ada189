#pragma once
// reduction: how well a Craig-Bampton (or Guyan) reduction of a solid reproduces its full-model
// frequencies, and the reduced component file to use in place of the mesh.
//
// Craig-Bampton / Guyan reduction: reduced vs full frequencies, convergence as modes are added,
// the reduced-component file (.h5): (component, settings) -> AnalysisOutput (tables, plots,
// notes, files). Numerical failures throw NumericalError (the caller reports the analysis as
// failed); bad input throws InputError.
#include <string>
#include <vector>

#include "geardyn/analyses/solid_common.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

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

AnalysisOutput run_reduction(const assembly::SolidComponent& component,
                             const ReductionSettings& settings, const std::string& name,
                             Progress& progress = null_progress());

}  // namespace geardyn::analyses
