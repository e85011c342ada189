#pragma once
// mesh_force: how large the dynamic mesh force of a gear pair gets over a speed range, where
// the mesh resonance lies and where the teeth lose contact.
//
// The dynamic mesh model over a speed range of gear 1, swept up and/or down: dynamic factor, DTE
// and contact loss versus speed, the mesh resonance speed (f_n = sqrt(k_mean / m_e) / 2 pi), time
// histories at `detail_rpm` (DESIGN 4.4-4.5; issue [mesh-excitation]): (model, settings) ->
// AnalysisOutput with tables, plots and notes. Bad input throws InputError (call
// check_gear_analyses, pair_model.hpp, before running, so it shows before any result); a
// numerical failure throws NumericalError naming the analysis, or, where the rest of the result
// is still worth having (a speed sweep), comes back as a non-Ok status with every failed point
// listed in the message.
#include <string>
#include <vector>

#include "geardyn/analyses/gear_common.hpp"
#include "geardyn/core/progress.hpp"
#include "geardyn/core/table.hpp"
#include "geardyn/model/model.hpp"

namespace geardyn::analyses {

/// The direction(s) a mesh_force sweep runs through its speeds.
enum class SweepDirectionKind { Up, Down, Both };

/// The dynamic mesh force over a speed range of gear 1 (DESIGN 4.5).
struct MeshForceSettings : model::SettingsOf<MeshForceSettings> {
  std::string pair;            ///< empty: the model's only gear pair
  std::vector<double> speeds;  ///< speeds of gear 1 [rad/s], increasing
  SweepDirectionKind direction = SweepDirectionKind::Both;
  MeshForceModel model = MeshForceModel::Dynamic;
  bool contact_loss = true;           ///< false: linear mesh law for every x
  std::vector<double> detail_speeds;  ///< time histories at these speeds of gear 1 [rad/s]
};

AnalysisOutput run_mesh_force(const model::Model& model, const MeshForceSettings& settings,
                              const std::string& name, Progress& progress = null_progress());

}  // namespace geardyn::analyses
