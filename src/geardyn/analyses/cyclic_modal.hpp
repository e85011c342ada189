#pragma once
// cyclic_modal: the natural frequencies of a cyclic solid per nodal diameter, computed on one
// sector, and the speeds at which engine orders meet them in the rotating frame.
//
// Modes per nodal diameter from one sector (DESIGN §4.3), optionally after Craig-Bampton
// reduction of the sector and interface-mode (Tran) reduction per nodal diameter (DESIGN §4.2),
// the nodal-diameter diagram, the rotating-frame Campbell diagram with its resonance table,
// full-wheel shapes, and optionally the check against the replicated 360 deg mesh:
// (component, settings) -> AnalysisOutput (tables, plots, notes, mode-shape files). Numerical
// failures throw NumericalError (the caller reports the analysis as failed); bad input throws
// InputError.
#include <string>
#include <vector>

#include "geardyn/analyses/solid_common.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// Modes per nodal diameter of a cyclic solid, optionally after Craig-Bampton reduction of the
/// sector and interface-mode reduction, and the rotating-frame Campbell diagram.
struct CyclicModalSettings : model::SettingsOf<CyclicModalSettings> {
  std::string solid;
  std::vector<int> nodal_diameters;  ///< empty: 0 .. sectors / 2
  int n_modes = 6;                   ///< per nodal diameter
  ReductionMethod reduction = ReductionMethod::None;
  int cb_modes = 40;                     ///< fixed-interface modes kept
  std::vector<std::string> master_sets;  ///< node sets kept physical besides the interfaces
  int interface_modes = 0;               ///< Tran interface modes per ND (0: interfaces kept)
  bool compare_full = false;             ///< also solve the replicated 360 deg mesh
  int shapes = 2;                        ///< expanded full-wheel shapes written per ND
  std::vector<double> speeds;            ///< Campbell speeds [rad/s] (empty: no Campbell)
  int max_engine_order = 0;              ///< 0: 2 x sectors
};

AnalysisOutput run_cyclic_modal(const assembly::SolidComponent& component,
                                const CyclicModalSettings& settings, const std::string& name,
                                Progress& progress = null_progress());

}  // namespace geardyn::analyses
