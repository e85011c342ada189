#pragma once
// gear_pair: the geometry, tooth forces, ISO 6336 mesh stiffness and static transmission error
// of the [[gear_pairs]] of a model, before any dynamics.
//
// Geometry, tooth forces (drive and coast, both members), ISO 6336-1 stiffness, and the STE /
// mesh stiffness over one mesh cycle of each pair (DESIGN 4.4-4.5; issue [mesh-excitation]):
// (model, settings) -> AnalysisOutput with tables, plots and notes. Bad input throws InputError
// (call check_gear_analyses, pair_model.hpp, before running, so it shows before any result).
#include <string>

#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Geometry, tooth forces, ISO 6336 stiffness and the mesh stiffness / STE over one mesh cycle.
struct GearPairSettings : model::SettingsOf<GearPairSettings> {
  std::string pair;  ///< empty: every [[gear_pairs]] entry
};

AnalysisOutput run_gear_pair(const model::Model& model, const GearPairSettings& settings,
                             const std::string& name, Progress& progress = null_progress());

}  // namespace geardyn::analyses
