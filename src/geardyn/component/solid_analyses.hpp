#pragma once
// Analyses of solid components: (component, settings) -> AnalysisOutput (tables, plots, notes,
// mode-shape files). Numerical failures throw NumericalError (the caller reports the analysis
// as failed); bad input throws InputError.
//
//   solid_modal   modes of the mesh as given (or of the replicated full wheel), VTU + Gmsh views
//   cyclic_modal  modes per nodal diameter from one sector (DESIGN §4.3), optionally after
//                 Craig-Bampton reduction of the sector and interface-mode (Tran) reduction per
//                 nodal diameter (DESIGN §4.2), the nodal-diameter diagram, the rotating-frame
//                 Campbell diagram with its resonance table, full-wheel shapes, and optionally
//                 the check against the replicated 360 deg mesh
//   reduction     Craig-Bampton / Guyan reduction: reduced vs full frequencies, convergence as
//                 modes are added, the reduced-component file (.h5)
#include <string>

#include "geardyn/component/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::component {

AnalysisOutput run_solid_modal(const SolidComponent& component,
                               const model::SolidModalSettings& settings, const std::string& name,
                               Progress& progress = null_progress());

AnalysisOutput run_cyclic_modal(const SolidComponent& component,
                                const model::CyclicModalSettings& settings, const std::string& name,
                                Progress& progress = null_progress());

AnalysisOutput run_reduction(const SolidComponent& component,
                             const model::ReductionSettings& settings, const std::string& name,
                             Progress& progress = null_progress());

}  // namespace geardyn::component
