#pragma once
// solid_modal: the natural frequencies and mode shapes of a solid component, the mesh as given
// or the replicated full wheel of a cyclic sector.
//
// Modes of the mesh as given (or of the replicated full wheel), VTU + Gmsh views: run_solid_modal
// solves (the component from context.solid), solid_modal_output writes the table, plot, notes and
// mode-shape files. Numerical failures throw NumericalError (the caller reports the analysis as
// failed); bad input throws InputError.
#include <memory>
#include <string>
#include <vector>

#include "geardyn/analyses/context.hpp"
#include "geardyn/assembly/solid_component.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/eig/symmetric_eigen.hpp"
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

/// The modes, and the mesh and system they live on.
struct SolidModalResult {
  eig::SymmetricEigenResult modes;
  std::vector<double> frequency_hz;  ///< natural frequencies, ascending
  /// The replicated full wheel (full_wheel of a cyclic mesh), else null: the component's own.
  std::shared_ptr<const solid::Mesh> wheel_mesh;
  std::shared_ptr<const solid::SolidSystem> wheel_system;
  int merged_nodes = 0;          ///< interface nodes merged in the replication
  double worst_merge_gap = 0.0;  ///< [m]
};

SolidModalResult run_solid_modal(const model::Model& model, const SolidModalSettings& settings,
                                 const Context& context);

AnalysisOutput solid_modal_output(const model::Model& model, const SolidModalSettings& settings,
                                  const SolidModalResult& result, const Context& context);

}  // namespace geardyn::analyses
