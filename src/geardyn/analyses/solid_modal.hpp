#pragma once
// solid_modal: the natural frequencies and mode shapes of a solid component, the mesh as given
// or the replicated full wheel of a cyclic sector.
//
// Modes of the mesh as given (or of the replicated full wheel), VTU + Gmsh views:
// (component, settings) -> AnalysisOutput (tables, plots, notes, mode-shape files). Numerical
// failures throw NumericalError (the caller reports the analysis as failed); bad input throws
// InputError.
#include <string>

#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Modes of a solid component (the mesh as given, or the whole wheel of a cyclic one).
struct SolidModalSettings : model::SettingsOf<SolidModalSettings> {
  std::string solid;
  int n_modes = 10;
  double f_max = model::kNaN;  ///< band mode: every mode up to this [rad/s] (n_modes ignored)
  bool full_wheel = false;     ///< cyclic solid: replicate the sector to 360 deg first
  int shapes = 10;             ///< mode shapes written to VTU / Gmsh files (0: none)
};

AnalysisOutput run_solid_modal(const assembly::SolidComponent& component,
                               const SolidModalSettings& settings, const std::string& name,
                               Progress& progress = null_progress());

}  // namespace geardyn::analyses
