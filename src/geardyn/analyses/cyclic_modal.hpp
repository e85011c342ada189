#pragma once
// cyclic_modal: the natural frequencies of a cyclic solid per nodal diameter, computed on one
// sector, and the speeds at which engine orders meet them in the rotating frame.
//
// Modes per nodal diameter from one sector (docs/theory.md §10), optionally after Craig-Bampton
// reduction of the sector and interface-mode (Tran) reduction per nodal diameter (docs/theory.md
// §9), the nodal-diameter diagram, the rotating-frame Campbell diagram with its resonance table,
// full-wheel shapes, and optionally the check against the replicated 360 deg mesh:
// run_cyclic_modal solves (the component from context.solid), cyclic_modal_output writes tables,
// plots, notes and mode-shape files. Numerical failures throw NumericalError (the caller reports
// the analysis as failed); bad input throws InputError.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/analyses/solid_common.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/cyclic/cyclic_symmetry.hpp"
#include "geardyn/model/model.hpp"
#include "geardyn/reduce/craig_bampton.hpp"

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

/// compare_full: the cyclic frequencies (double modes counted twice) against the full wheel's.
struct CyclicFullComparison {
  bool done = false;  ///< false: not asked, no mesh, or not every nodal diameter solved
  int full_dofs = 0;  ///< of the replicated 360 deg model
  std::vector<double> full_hz, cyclic_hz, nodal_diameter;
  std::vector<double> relative_error;  ///< (cyclic - full) / max(full, 1e-3 Hz)
  double worst_error = 0.0;            ///< largest |relative_error|
};

/// The modes per nodal diameter, the sector they were solved on, and the full-wheel check.
struct CyclicModalResult {
  cyclic::SectorInterfaces mesh_interfaces;  ///< of the component's own (unreduced) sector
  std::size_t mesh_dofs = 0;                 ///< DOFs of that sector
  /// The Craig-Bampton (or Guyan) reduction of the sector (null: none).
  std::shared_ptr<const reduce::ReducedComponent> reduction;
  std::vector<int> nodal_diameters;  ///< solved
  cyclic::CyclicModesResult modes;
  /// Every natural frequency [Hz] of every nodal diameter, ascending; a double mode (a
  /// travelling-wave pair) is one entry.
  std::vector<double> frequency_hz;
  CyclicFullComparison full;
};

CyclicModalResult run_cyclic_modal(const model::Model& model, const CyclicModalSettings& settings,
                                   const Context& context);

AnalysisOutput cyclic_modal_output(const model::Model& model, const CyclicModalSettings& settings,
                                   const CyclicModalResult& result, const Context& context);

}  // namespace geardyn::analyses
